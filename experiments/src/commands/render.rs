//! `grassbench render`: one frame of one technique to a PNG.

use std::path::PathBuf;

use anyhow::Context as _;
use grassbench::runner::Harness;
use grassbench::target::{Size, save_png};

use super::{GpuArgs, param_table};
use crate::{registry, scenes};

/// Arguments of `render`.
#[derive(Clone, Debug, clap::Args)]
pub struct RenderArgs {
    /// Technique id (see `grassbench list`).
    #[arg(long, short)]
    pub technique: String,
    /// Built-in scene name or path to a scene TOML.
    #[arg(long, short, default_value = "meadow")]
    pub scene: String,
    /// Frame index to render (earlier frames are simulated first).
    #[arg(long, short, default_value_t = 0)]
    pub frame: u64,
    /// Output PNG.
    #[arg(long, short)]
    pub out: PathBuf,
    /// Target size WxH (default: the scene's).
    #[arg(long)]
    pub size: Option<String>,
    /// 4x MSAA.
    #[arg(long)]
    pub msaa: bool,
    /// Debug view of the technique (1-based, see `grassbench list`; 0 = none).
    #[arg(long, default_value_t = 0)]
    pub debug_view: u32,
    /// Technique parameter override KEY=VALUE (repeatable).
    #[arg(long = "param", short = 'p')]
    pub params: Vec<String>,
    /// GPU options.
    #[command(flatten)]
    pub gpu: GpuArgs,
}

/// Renders the frame and writes the PNG.
pub fn render(args: &RenderArgs) -> anyhow::Result<()> {
    let entry = registry::find(&args.technique)?;
    let scene = scenes::load(&args.scene)?;
    let size = match &args.size {
        Some(s) => Size::parse(s)?,
        None => scene.resolution(),
    };
    let overrides = param_table(&args.params)?;
    let gpu = args
        .gpu
        .context_for(&super::needs([(entry, &scene, &overrides)])?)?;
    let mut harness = Harness::new(&gpu, scene, size, args.msaa)?;
    harness.view.debug_view = args.debug_view;
    let mut technique = harness.create(entry, &overrides)?;
    harness.catch_up(technique.as_mut(), 0, args.frame)?;
    let out = harness.frame(technique.as_mut(), args.frame, true)?;
    let image = out.image.context("the frame produced no image")?;
    save_png(&image, &args.out)?;
    eprintln!(
        "{} frame {} of `{}` → {} ({:.1} ms GPU wall, {} blades drawn, {} represented)",
        entry.info.id,
        args.frame,
        harness.world.scene.name(),
        args.out.display(),
        out.record.gpu_wall_ms,
        out.record.blades_drawn.unwrap_or_default(),
        out.record.blades_represented.unwrap_or_default()
    );
    Ok(())
}

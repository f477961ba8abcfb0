//! `grassbench compare`: LOD fidelity, the cross-technique matrix and temporal change for
//! every selected technique on every selected scene, as CSV and difference images.

use std::path::PathBuf;

use anyhow::Context as _;
use grassbench::compare::{self, CameraMotion, Scale};
use grassbench::metrics;
use grassbench::runner::{Provenance, write_atomic, write_csv};
use grassbench::target::{Size, save_png};
use grassbench::technique::{DEFAULT_VARIANT, NO_TRANSITIONS, NoGrass, TechniqueEntry, overlay};

use super::GpuArgs;
use super::out_dir::Progress;
use crate::{registry, scenes};

/// Arguments of `compare`.
#[derive(Clone, Debug, clap::Args)]
pub struct CompareArgs {
    /// Scene names or paths, comma-separated, or `default`.
    #[arg(long, short, default_value = "default")]
    pub scene: String,
    /// Technique ids, comma-separated, or `all`.
    #[arg(long, short, default_value = "all")]
    pub technique: String,
    /// Frame compared.
    #[arg(long, short, default_value_t = 30)]
    pub frame: u64,
    /// Target size WxH.
    #[arg(long, default_value = "640x360")]
    pub size: String,
    /// The operating point every technique is compared at: `default` (its defaults) or a
    /// variant name such as `paper` (each paper's own settings, `grassbench list` shows
    /// them). A technique without that variant is compared at its defaults, and `lod.csv`
    /// and `temporal.csv` say which it was.
    #[arg(long, default_value = DEFAULT_VARIANT)]
    pub variant: String,
    /// Frame steps along each camera motion for the temporal figures (0 skips them).
    #[arg(long, default_value_t = 24)]
    pub motion_frames: u32,
    /// Output folder.
    #[arg(long, short, default_value = "results/compare")]
    pub out: PathBuf,
    /// Replace a non-empty output folder (without it, the folder of an interrupted `compare`
    /// with the same arguments is resumed: its finished scenes are kept).
    #[arg(long)]
    pub force: bool,
    /// GPU options.
    #[command(flatten)]
    pub gpu: GpuArgs,
}

#[derive(serde::Serialize)]
struct LodRow {
    technique: String,
    /// The operating point (`default`, `paper`, …) the technique was rendered at.
    variant: String,
    scene: String,
    flip_mean: f64,
    flip_p95: f64,
    ssim: f64,
    psnr: f64,
}

/// One row of `temporal.csv`: a technique's change against a baseline's (the reference's, or
/// its own finest representation's) along one motion at one scale
/// (`grassbench::compare::temporal_change`); spurious and missing change in units of the
/// baseline's mean change per step (`baseline_change`, 0..1 of full scale).
#[derive(serde::Serialize)]
struct TemporalRow {
    technique: String,
    variant: String,
    scene: String,
    motion: String,
    /// What the change is compared with: `reference` (the reference's change on the same
    /// motion) or `finest` (the technique's own finest representation's: the change its
    /// levels of detail add, blade placement aside).
    baseline: String,
    scale: String,
    baseline_change: f64,
    technique_change: f64,
    spurious_mean: f64,
    spurious_p95: f64,
    spurious_peak: f64,
    missing_mean: f64,
    missing_p95: f64,
    missing_peak: f64,
}

/// The two motions every technique is followed along.
pub const MOTIONS: [CameraMotion; 2] = [CameraMotion::Dolly(0.25), CameraMotion::Pan(0.6)];

/// Runs the comparisons.
pub fn compare(args: &CompareArgs) -> anyhow::Result<()> {
    let entries = registry::select(&args.technique)?;
    let scenes = scenes::select(&args.scene)?;
    let size = Size::parse(&args.size)?;
    let scene_names: Vec<String> = scenes.iter().map(|s| s.name().to_owned()).collect();
    let mut arguments = super::out_dir::selection_arguments(&entries, &scene_names);
    arguments.extend([
        ("--frame".to_owned(), args.frame.to_string()),
        ("--size".to_owned(), size.to_string()),
        ("--variant".to_owned(), args.variant.clone()),
        ("--motion-frames".to_owned(), args.motion_frames.to_string()),
        (
            "--backend".to_owned(),
            format!("{:?}", args.gpu.choice()?).to_lowercase(),
        ),
    ]);
    // Every technique (and the reference) with its defaults and the variants drawn below.
    let mut variants = Vec::new();
    for entry in entries
        .iter()
        .copied()
        .chain([registry::find("reference")?])
    {
        let (_, base) = operating_point(entry, &args.variant)?;
        variants.push((entry, overlay(&base, &entry.finest()?)));
        if let Some(v) = entry.variant(NO_TRANSITIONS) {
            variants.push((entry, overlay(&base, &v?)));
        }
        variants.push((entry, base));
    }
    if args.variant != DEFAULT_VARIANT
        && !entries.iter().any(|e| e.variant(&args.variant).is_some())
    {
        anyhow::bail!(
            "--variant {}: none of the selected techniques offers it (`grassbench list` shows each technique's variants)",
            args.variant
        );
    }
    let needs = super::needs(
        scenes
            .iter()
            .flat_map(|s| variants.iter().map(move |(e, o)| (*e, s, o))),
    )?;
    let mut progress = Progress::open(&args.out, args.force, "compare", arguments, &scene_names)?;
    let gpu = args.gpu.context_for(&needs)?;
    write_atomic(&args.out.join("meta.toml"), |f| {
        std::io::Write::write_all(f, Provenance::collect(&gpu.summary).to_toml().as_bytes())
    })?;
    let reference = registry::find("reference")?;
    for scene in &scenes {
        let name = scene.name().to_owned();
        let dir = args.out.join(&name);
        if progress.done(&name).is_some() {
            eprintln!("{name}: already done in {}", dir.display());
            continue;
        }
        eprintln!(
            "{name}: rendering frame {} of {} techniques",
            args.frame,
            entries.len()
        );
        let background = {
            let mut h = grassbench::runner::Harness::new(&gpu, scene.clone(), size, false)?;
            compare::render_in(&mut h, &mut NoGrass, args.frame)?
        };
        save_png(&background, &dir.join("none.png"))?;
        // Steps: each technique's frame and LOD fidelity, the matrix, and per motion the
        // reference's frames and each technique's.
        let motions = if args.motion_frames > 0 {
            MOTIONS.len()
        } else {
            0
        };
        let steps = entries.len() + 1 + motions * (1 + entries.len());
        let bar = super::progress::bar(steps as u64, "steps", &name);
        let mut images = Vec::new();
        let mut lod_rows = Vec::new();
        for entry in &entries {
            let id = entry.info.id;
            let (variant, base) = operating_point(entry, &args.variant)?;
            bar.set_message(format!("{id}: frame and LOD fidelity"));
            let image = compare::render(&gpu, scene, entry, &base, args.frame, size)
                .with_context(|| format!("{id} ({variant}) on {name}"))?;
            save_png(&image, &dir.join(format!("{id}.png")))?;
            {
                let lod = compare::lod_fidelity(&gpu, scene, entry, &base, args.frame, size)?;
                save_png(
                    &metrics::flip(&lod.finest_image, &lod.default_image)?.heatmap,
                    &dir.join(format!("lod_{id}_flip.png")),
                )?;
                lod_rows.push(LodRow {
                    technique: id.into(),
                    variant: variant.into(),
                    scene: name.clone(),
                    flip_mean: lod.scores.flip_mean,
                    flip_p95: lod.scores.flip_p95,
                    ssim: lod.scores.ssim,
                    psnr: lod.scores.psnr,
                });
            }
            images.push((id.to_owned(), image));
            bar.inc(1);
        }
        bar.set_message("every pair of techniques");
        let matrix = compare::cross_compare(&images, &background)?;
        for pair in &matrix {
            let (a, b) = (
                &images
                    .iter()
                    .find(|(n, _)| *n == pair.a)
                    .context("image")?
                    .1,
                &images
                    .iter()
                    .find(|(n, _)| *n == pair.b)
                    .context("image")?
                    .1,
            );
            save_png(
                &metrics::flip(a, b)?.heatmap,
                &dir.join(format!("diff_{}_{}.png", pair.a, pair.b)),
            )?;
        }
        write_csv(&dir.join("matrix.csv"), &matrix)?;
        write_csv(&dir.join("lod.csv"), &lod_rows)?;
        bar.inc(1);
        if args.motion_frames > 0 {
            let mut rows = Vec::new();
            for motion in MOTIONS {
                bar.set_message(format!("{}: reference", motion.name()));
                let base = compare::motion_frames(
                    &gpu,
                    scene,
                    reference,
                    &toml::Table::new(),
                    motion,
                    args.motion_frames,
                    size,
                )?;
                bar.inc(1);
                for entry in &entries {
                    bar.set_message(format!("{}: {}", motion.name(), entry.info.id));
                    let (point, at) = operating_point(entry, &args.variant)?;
                    let mut variants = vec![(point.to_owned(), at.clone())];
                    if let Some(v) = entry.variant(NO_TRANSITIONS) {
                        let name = if point == DEFAULT_VARIANT {
                            NO_TRANSITIONS.to_owned()
                        } else {
                            format!("{point}+{NO_TRANSITIONS}")
                        };
                        variants.push((name, overlay(&at, &v?)));
                    }
                    let finest = overlay(&at, &entry.finest()?);
                    let own = if finest.is_empty() {
                        None
                    } else {
                        Some(compare::motion_frames(
                            &gpu,
                            scene,
                            entry,
                            &finest,
                            motion,
                            args.motion_frames,
                            size,
                        )?)
                    };
                    for (variant, overrides) in variants {
                        let frames = compare::motion_frames(
                            &gpu,
                            scene,
                            entry,
                            &overrides,
                            motion,
                            args.motion_frames,
                            size,
                        )?;
                        let mut baselines = vec![("reference", &base)];
                        if let Some(own) = &own {
                            baselines.push(("finest", own));
                        }
                        for (baseline, against) in baselines {
                            for scale in Scale::ALL {
                                let c = compare::temporal_change(motion, scale, &frames, against)?;
                                rows.push(TemporalRow {
                                    technique: entry.info.id.into(),
                                    variant: variant.clone(),
                                    scene: name.clone(),
                                    motion: c.motion.into(),
                                    baseline: baseline.into(),
                                    scale: scale.name().into(),
                                    baseline_change: c.reference_change,
                                    technique_change: c.technique_change,
                                    spurious_mean: c.spurious.mean,
                                    spurious_p95: c.spurious.p95,
                                    spurious_peak: c.spurious.peak,
                                    missing_mean: c.missing.mean,
                                    missing_p95: c.missing.p95,
                                    missing_peak: c.missing.peak,
                                });
                            }
                        }
                    }
                    bar.inc(1);
                }
            }
            write_csv(&dir.join("temporal.csv"), &rows)?;
        }
        bar.finish_and_clear();
        progress.scene_done(&name, Vec::new())?;
        eprintln!("{name}: wrote {}", dir.display());
    }
    super::write_html(&args.out).context("writing report.html")?;
    progress.finish()
}

/// The operating point `entry` is compared at for `--variant name`: the variant's name and
/// overrides where the technique offers it, `default` and none where it does not (or where
/// `name` is `default`).
fn operating_point(
    entry: &TechniqueEntry,
    name: &str,
) -> anyhow::Result<(&'static str, toml::Table)> {
    Ok(match entry.variants.iter().find(|v| v.name == name) {
        Some(v) => (v.name, entry.expand(&toml::toml! { variant = name })?),
        None => (DEFAULT_VARIANT, toml::Table::new()),
    })
}

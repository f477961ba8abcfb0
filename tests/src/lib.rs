//! Helpers shared by grassbench's integration tests: a GPU context, small versions of the
//! built-in scenes, rendering a frame, snapshot comparison with FLIP that writes the actual
//! and difference images on failure, and [`twin`]: WGSL functions run over generated inputs
//! to compare with their Rust twins.

#![cfg_attr(test, allow(clippy::unwrap_used, clippy::expect_used, clippy::panic))]

pub mod twin;

use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};
use grassbench::runner::{FrameRecord, Harness};
use grassbench::target::{Size, save_png};
use grassbench::technique::GrassTechnique;
use grassbench::{GpuContext, Scene};

/// Size most GPU tests render at (small: the rasteriser is software).
pub const TEST_SIZE: Size = Size {
    width: 320,
    height: 180,
};

/// The repository root.
pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// A GPU context on the backend `GRASSBENCH_BACKEND` names (default: auto).
pub fn gpu() -> anyhow::Result<GpuContext> {
    let choice = grassbench::gpu::BackendChoice::from_env()?;
    GpuContext::new(choice).context("tests need a GPU adapter (lavapipe is enough)")
}

/// A built-in scene with its grass density scaled by `density_scale` (tests use fewer blades).
pub fn scene(name: &str, density_scale: f32) -> anyhow::Result<Scene> {
    let base = grassbench_cli::scenes::load(name)?;
    let mut config = base.config.clone();
    config.grass.density *= density_scale;
    Ok(Scene::from_config(config, base.base_dir.clone())?)
}

/// Renders frame `frame` of technique `id` (with parameter overrides) on `scene`.
pub fn render(
    gpu: &GpuContext,
    id: &str,
    scene: Scene,
    frame: u64,
    size: Size,
    overrides: &toml::Table,
) -> anyhow::Result<image::RgbaImage> {
    let entry = grassbench_cli::registry::find(id)?;
    let mut harness = Harness::new(gpu, scene, size, false)?;
    let mut technique = harness.create(entry, overrides)?;
    render_with(&mut harness, technique.as_mut(), frame)
}

/// Renders frame `frame` of an existing technique in a harness (earlier frames caught up).
pub fn render_with(
    harness: &mut Harness<'_>,
    technique: &mut dyn GrassTechnique,
    frame: u64,
) -> anyhow::Result<image::RgbaImage> {
    Ok(render_record(harness, technique, frame)?.0)
}

/// [`render_with`], with the frame's record (the harness's counts: draw calls, timings).
pub fn render_record(
    harness: &mut Harness<'_>,
    technique: &mut dyn GrassTechnique,
    frame: u64,
) -> anyhow::Result<(image::RgbaImage, FrameRecord)> {
    harness.catch_up(technique, 0, frame)?;
    let out = harness.frame(technique, frame, true)?;
    Ok((out.image.context("no image captured")?, out.record))
}

/// Blades `technique` drew or stood for at its level `name` in its last frame; the error names
/// the levels it has.
pub fn level_blades(technique: &dyn GrassTechnique, name: &str) -> anyhow::Result<u64> {
    let levels = technique.levels();
    levels
        .iter()
        .find(|l| l.level == name)
        .map(|l| l.blades)
        .with_context(|| {
            format!(
                "`{}` has no level `{name}`; it has {levels:?}",
                technique.info().id
            )
        })
}

/// Where failing tests write their actual and difference images.
pub fn output_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("output")
}

/// Compares `actual` with `tests/snapshots/<name>.png` by mean FLIP (see
/// [`check_snapshot_flip`]).
pub fn check_snapshot(
    name: &str,
    actual: &image::RgbaImage,
    max_mean_flip: f32,
) -> anyhow::Result<f32> {
    check_snapshot_flip(name, actual, max_mean_flip, 1.0)
}

/// Compares `actual` with `tests/snapshots/<name>.png` by mean and 95th-percentile FLIP, the
/// way wgpu's image tests do. With `UPDATE_SNAPSHOTS=1` (or no snapshot yet, outside CI) the
/// snapshot is (re)written instead. On failure `tests/output/<name>-actual.png` and
/// `<name>-diff.png` (the FLIP heat map) are written.
pub fn check_snapshot_flip(
    name: &str,
    actual: &image::RgbaImage,
    max_mean_flip: f32,
    max_p95_flip: f32,
) -> anyhow::Result<f32> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("snapshots")
        .join(format!("{name}.png"));
    let update = std::env::var("UPDATE_SNAPSHOTS").is_ok_and(|v| v == "1");
    if update || (!path.exists() && std::env::var("CI").is_err()) {
        save_png(actual, &path)?;
        return Ok(0.0);
    }
    let expected = image::open(&path)
        .with_context(|| {
            format!(
                "missing snapshot {} (run with UPDATE_SNAPSHOTS=1 to create it)",
                path.display()
            )
        })?
        .to_rgba8();
    let flip = grassbench::metrics::flip(&expected, actual)?;
    if flip.mean > max_mean_flip || flip.p95 > max_p95_flip {
        let out = output_dir();
        save_png(actual, &out.join(format!("{name}-actual.png")))?;
        save_png(&flip.heatmap, &out.join(format!("{name}-diff.png")))?;
        bail!(
            "snapshot `{name}`: FLIP mean {:.4} (limit {max_mean_flip}), p95 {:.4} (limit {max_p95_flip}); actual and FLIP heat map written to {}",
            flip.mean,
            flip.p95,
            out.display()
        );
    }
    Ok(flip.mean)
}

/// Pixels of `a` and `b` (the same size) where any channel differs by more than `tolerance`
/// of 255.
pub fn pixels_differing(a: &image::RgbaImage, b: &image::RgbaImage, tolerance: u8) -> usize {
    a.pixels()
        .zip(b.pixels())
        .filter(|(x, y)| x.0.iter().zip(y.0).any(|(p, q)| p.abs_diff(q) > tolerance))
        .count()
}

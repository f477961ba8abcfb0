//! The image-difference suite: three kinds of comparison, as library functions used by the
//! tests, `grassbench compare`, sweeps and the UI.
//!
//! 1. [`lod_fidelity`]: a technique against itself forced to its finest representation
//!    (same blades, wind and frame): per-pixel FLIP, SSIM and PSNR are meaningful here.
//! 2. [`cross_compare`]: techniques against each other and the reference. Blade placement
//!    legitimately differs, so besides full-resolution FLIP they are compared after
//!    downsampling (1/4, 1/16), by mean colour, by grass coverage per screen tile and by the
//!    height of the grass silhouette against the sky.
//! 3. [`motion_frames`] / [`temporal_change`]: along slow dolly and pan paths with the wind
//!    calm, a technique's frame-to-frame change against the reference's on the same path, pixel
//!    by pixel: change the reference does not show (spurious: popping, shimmer) apart from
//!    change it shows that the technique does not (missing: blur, frozen impostors).

mod cross;
mod temporal;

pub use cross::{PairScores, cross_compare, silhouette_rows, tile_coverage};
pub use temporal::{
    CameraMotion, Scale, Series, StepMaps, TemporalChange, frame_differences, motion_frames,
    spurious_and_missing, temporal_change,
};

use crate::metrics;
use crate::runner::Harness;
use crate::target::Size;
use crate::technique::{GrassTechnique, TechniqueEntry};
use crate::{GpuContext, Result, Scene};

/// Per-pixel scores of an image against a reference image.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ImageScores {
    /// Mean FLIP.
    pub flip_mean: f64,
    /// 95th percentile FLIP.
    pub flip_p95: f64,
    /// Mean SSIM.
    pub ssim: f64,
    /// PSNR, dB (infinite when identical).
    pub psnr: f64,
}

/// FLIP, SSIM and PSNR of `test` against `reference`.
pub fn scores(reference: &image::RgbaImage, test: &image::RgbaImage) -> Result<ImageScores> {
    let f = metrics::flip(reference, test)?;
    Ok(ImageScores {
        flip_mean: f64::from(f.mean),
        flip_p95: f64::from(f.p95),
        ssim: metrics::ssim(reference, test)?,
        psnr: metrics::psnr(reference, test)?,
    })
}

/// Renders frame `frame` of `entry` (with `overrides`) on `scene`, simulating earlier frames.
pub fn render(
    gpu: &GpuContext,
    scene: &Scene,
    entry: &TechniqueEntry,
    overrides: &toml::Table,
    frame: u64,
    size: Size,
) -> Result<image::RgbaImage> {
    let mut harness = Harness::new(gpu, scene.clone(), size, false)?;
    let mut technique = harness.create(entry, overrides)?;
    render_in(&mut harness, technique.as_mut(), frame)
}

/// Renders frame `frame` of a technique already in `harness`.
pub fn render_in(
    harness: &mut Harness<'_>,
    technique: &mut dyn GrassTechnique,
    frame: u64,
) -> Result<image::RgbaImage> {
    harness.catch_up(technique, 0, frame)?;
    harness
        .frame(technique, frame, true)?
        .image
        .ok_or_else(|| crate::Error::Technique {
            technique: technique.info().id.to_owned(),
            message: "the frame produced no image".into(),
        })
}

/// A technique's default rendering against its finest representation.
pub struct LodFidelity {
    /// Scores of the default against the finest.
    pub scores: ImageScores,
    /// The default rendering.
    pub default_image: image::RgbaImage,
    /// The finest rendering.
    pub finest_image: image::RgbaImage,
}

/// LOD fidelity of `entry` at `frame`: its rendering with `base` overrides (empty for its
/// defaults, or a variant such as `paper`) against the same with its finest variant laid on
/// top (every technique has one: the type of [`crate::technique::Variants`] requires it).
pub fn lod_fidelity(
    gpu: &GpuContext,
    scene: &Scene,
    entry: &TechniqueEntry,
    base: &toml::Table,
    frame: u64,
    size: Size,
) -> Result<LodFidelity> {
    let finest = crate::technique::overlay(base, &entry.finest()?);
    let default_image = render(gpu, scene, entry, base, frame, size)?;
    let finest_image = render(gpu, scene, entry, &finest, frame, size)?;
    Ok(LodFidelity {
        scores: scores(&finest_image, &default_image)?,
        default_image,
        finest_image,
    })
}

//! Temporal stability: how much a technique's picture changes from one frame to the next
//! along a slow camera motion with the wind frozen, relative to the reference's change on the
//! same motion. Blades that appear, vanish or switch representation all at once (popping)
//! show up as peaks in that ratio.

use glam::Vec3;

use crate::runner::{Harness, Percentiles};
use crate::target::Size;
use crate::technique::TechniqueEntry;
use crate::wind::WindConfig;
use crate::{GpuContext, Result, Scene};

/// A slow camera motion starting from the scene camera's pose at frame 0.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub enum CameraMotion {
    /// Moving forward along the view direction, metres per frame.
    Dolly(f32),
    /// Turning about the vertical axis, degrees per frame.
    Pan(f32),
}

impl CameraMotion {
    /// `dolly` or `pan`.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Dolly(_) => "dolly",
            Self::Pan(_) => "pan",
        }
    }

    fn pose(&self, start: (Vec3, Vec3), k: u32) -> (Vec3, Vec3) {
        let (eye, forward) = start;
        match *self {
            Self::Dolly(step) => {
                let horizontal = Vec3::new(forward.x, 0.0, forward.z).normalize_or(Vec3::X);
                (eye + horizontal * step * k as f32, forward)
            }
            Self::Pan(degrees) => {
                let q = glam::Quat::from_rotation_y((degrees * k as f32).to_radians());
                (eye, q * forward)
            }
        }
    }
}

/// Mean absolute 8-bit RGB difference between consecutive frames of `entry` along `motion`
/// (`frames` differences), with the wind replaced by calm air.
pub fn frame_differences(
    gpu: &GpuContext,
    scene: &Scene,
    entry: &TechniqueEntry,
    overrides: &toml::Table,
    motion: CameraMotion,
    frames: u32,
    size: Size,
) -> Result<Vec<f64>> {
    let mut harness = Harness::new(gpu, scene.clone(), size, false)?;
    harness.set_wind(WindConfig::Calm)?;
    let start = {
        let cam = scene.camera_at(0, size);
        (cam.eye, cam.forward)
    };
    let mut technique = harness.create(entry, overrides)?;
    let mut previous: Option<image::RgbaImage> = None;
    let mut diffs = Vec::with_capacity(frames as usize);
    for k in 0..=frames {
        harness.view.camera_override = Some(motion.pose(start, k));
        // Frame 0 every time: with the wind frozen only the camera moves.
        let img = harness
            .frame(technique.as_mut(), 0, true)?
            .image
            .unwrap_or_default();
        if let Some(p) = &previous {
            let sum: u64 = p
                .as_raw()
                .iter()
                .zip(img.as_raw())
                .map(|(a, b)| u64::from(a.abs_diff(*b)))
                .sum();
            diffs.push(sum as f64 / (f64::from(size.width * size.height) * 4.0));
        }
        previous = Some(img);
    }
    Ok(diffs)
}

/// A technique's frame-to-frame change over the reference's, along one motion.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct TemporalStability {
    /// `dolly` or `pan`.
    pub motion: &'static str,
    /// Ratio per frame step.
    pub ratios: Vec<f64>,
    /// Largest ratio.
    pub peak: f64,
    /// 95th percentile ratio.
    pub p95: f64,
}

/// Divides a technique's frame differences by the reference's along the same motion.
pub fn temporal_stability(
    motion: CameraMotion,
    technique: &[f64],
    reference: &[f64],
) -> TemporalStability {
    let ratios: Vec<f64> = technique
        .iter()
        .zip(reference)
        .map(|(t, r)| t / r.max(1e-3))
        .collect();
    TemporalStability {
        motion: motion.name(),
        peak: ratios.iter().copied().fold(0.0, f64::max),
        p95: Percentiles::of(ratios.iter().copied()).map_or(0.0, |p| p.p95),
        ratios,
    }
}

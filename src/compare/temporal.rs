//! Temporal fidelity: a technique's frame-to-frame change compared with the reference's change
//! on the same camera motion, pixel by pixel, so that popping and blur are told apart.
//!
//! Along a slow motion with the wind calm, only the camera moves. Per pixel and per pair of
//! consecutive frames, `t` is how much the technique's picture changed and `r` how much the
//! reference's did (mean absolute RGB difference, 0..1). Then
//! - **spurious change** `max(t − r, 0)`: change the technique shows that the reference does
//!   not: blades or impostors switching level (popping), shimmer, flicker;
//! - **missing change** `max(r − t, 0)`: change the reference shows that the technique does
//!   not: a blurred or bare picture, frozen or flattened impostors.
//!
//! Dividing the two totals (the metric this replaces) rewarded blur: a picture that loses its
//! detail changes less than the reference and scored as "steadier". Here losing detail is
//! missing change, and popping is spurious change; neither cancels the other.
//!
//! Each step's figure is the mean over the image of the per-pixel map, divided by the
//! reference's mean change over the whole motion (so 1 is as much change as the reference
//! shows in an average step); over the steps of a motion the report gives its mean, 95th
//! percentile and peak (a level switching at one step shows as a peak). Both are measured at
//! full resolution and after 4 x 4 box averaging ([`Scale::Quarter`]): where blades stand
//! elsewhere than the reference's (every impostor technique), the full-resolution maps hold
//! both techniques' blade edges, and the quarter scale compares coverage and colour instead.

use glam::Vec3;

use crate::runner::{Harness, Percentiles};
use crate::target::Size;
use crate::technique::TechniqueEntry;
use crate::wind::WindConfig;
use crate::{Error, GpuContext, Result, Scene};

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

    /// The camera's eye and forward direction after `k` steps from `start`.
    pub fn pose(&self, start: (Vec3, Vec3), k: u32) -> (Vec3, Vec3) {
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

/// The `frames + 1` images of `entry` along `motion` (wind replaced by calm air, frame 0's
/// time throughout, so only the camera moves).
pub fn motion_frames(
    gpu: &GpuContext,
    scene: &Scene,
    entry: &TechniqueEntry,
    overrides: &toml::Table,
    motion: CameraMotion,
    frames: u32,
    size: Size,
) -> Result<Vec<image::RgbaImage>> {
    let mut harness = Harness::new(gpu, scene.clone(), size, false)?;
    harness.set_wind(WindConfig::Calm)?;
    let start = {
        let cam = scene.camera_at(0, size);
        (cam.eye, cam.forward)
    };
    let mut technique = harness.create(entry, overrides)?;
    let mut out = Vec::with_capacity(frames as usize + 1);
    for k in 0..=frames {
        harness.view.camera_override = Some(motion.pose(start, k));
        let image = harness
            .frame(technique.as_mut(), 0, true)?
            .image
            .ok_or_else(|| Error::Technique {
                technique: entry.info.id.to_owned(),
                message: "the frame produced no image".into(),
            })?;
        out.push(image);
    }
    Ok(out)
}

/// Mean absolute 8-bit difference per colour channel (red, green, blue: a frame's alpha is
/// not part of the picture) between consecutive frames of `entry` along `motion` (`frames`
/// differences; [`motion_frames`]'s images): a technique's own change, for tests that look at
/// one technique's steps without a reference.
pub fn frame_differences(
    gpu: &GpuContext,
    scene: &Scene,
    entry: &TechniqueEntry,
    overrides: &toml::Table,
    motion: CameraMotion,
    frames: u32,
    size: Size,
) -> Result<Vec<f64>> {
    let images = motion_frames(gpu, scene, entry, overrides, motion, frames, size)?;
    Ok(images
        .windows(2)
        .map(|w| {
            let sum: u64 = w[0]
                .pixels()
                .zip(w[1].pixels())
                .flat_map(|(a, b)| (0..3).map(move |c| u64::from(a.0[c].abs_diff(b.0[c]))))
                .sum();
            let channels = 3 * u64::from(w[0].width()) * u64::from(w[0].height());
            sum as f64 / channels.max(1) as f64
        })
        .collect())
}

/// The resolution at which change is compared.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Scale {
    /// Pixel by pixel.
    Full,
    /// After averaging 4 x 4 blocks.
    Quarter,
}

impl Scale {
    /// Both scales, full first.
    pub const ALL: [Scale; 2] = [Scale::Full, Scale::Quarter];

    /// `full` or `quarter`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Full => "full",
            Self::Quarter => "quarter",
        }
    }

    fn factor(self) -> u32 {
        match self {
            Self::Full => 1,
            Self::Quarter => 4,
        }
    }
}

/// Mean, 95th percentile and peak of a per-step series.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Series {
    /// Mean over the steps.
    pub mean: f64,
    /// 95th percentile over the steps.
    pub p95: f64,
    /// Largest step.
    pub peak: f64,
}

impl Series {
    fn of(values: &[f64]) -> Self {
        Self {
            mean: values.iter().sum::<f64>() / values.len().max(1) as f64,
            p95: Percentiles::of(values.iter().copied()).map_or(0.0, |p| p.p95),
            peak: values.iter().copied().fold(0.0, f64::max),
        }
    }
}

/// A technique's change against the reference's along one motion, at one scale.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct TemporalChange {
    /// `dolly` or `pan`.
    pub motion: &'static str,
    /// The scale compared.
    pub scale: Scale,
    /// The reference's mean per-pixel change per step (0..1 of full scale): the unit of
    /// `spurious` and `missing`.
    pub reference_change: f64,
    /// The technique's mean per-pixel change per step, in units of `reference_change`.
    pub technique_change: f64,
    /// Spurious change per step, in units of `reference_change`.
    pub spurious_steps: Vec<f64>,
    /// Missing change per step, in units of `reference_change`.
    pub missing_steps: Vec<f64>,
    /// Summary of `spurious_steps`.
    pub spurious: Series,
    /// Summary of `missing_steps`.
    pub missing: Series,
}

/// An RGB image in floating point, 0..1, for change maps at any scale.
#[derive(Clone, Debug, PartialEq)]
struct Linear {
    width: u32,
    height: u32,
    rgb: Vec<[f32; 3]>,
}

impl Linear {
    /// `image` averaged over `factor x factor` blocks (a partial last block is dropped).
    fn of(image: &image::RgbaImage, factor: u32) -> Self {
        let (width, height) = (image.width() / factor, image.height() / factor);
        let mut rgb = vec![[0.0f32; 3]; (width * height) as usize];
        let scale = 1.0 / (255.0 * (factor * factor) as f32);
        for y in 0..height * factor {
            for x in 0..width * factor {
                let p = image.get_pixel(x, y).0;
                let cell = &mut rgb[((y / factor) * width + x / factor) as usize];
                for c in 0..3 {
                    cell[c] += f32::from(p[c]) * scale;
                }
            }
        }
        Self { width, height, rgb }
    }
}

/// Per-pixel change between two images: mean absolute RGB difference.
fn change(a: &Linear, b: &Linear) -> Vec<f32> {
    a.rgb
        .iter()
        .zip(&b.rgb)
        .map(|(p, q)| ((p[0] - q[0]).abs() + (p[1] - q[1]).abs() + (p[2] - q[2]).abs()) / 3.0)
        .collect()
}

/// Per-pixel spurious and missing change of one step: the technique's change map `t` against
/// the reference's `r`.
pub fn spurious_and_missing(t: &[f32], r: &[f32]) -> (Vec<f32>, Vec<f32>) {
    t.iter()
        .zip(r)
        .map(|(t, r)| ((t - r).max(0.0), (r - t).max(0.0)))
        .unzip()
}

/// The spurious and missing change of one step, per pixel (full resolution): what the
/// window's difference view shows.
#[derive(Clone, Debug, PartialEq)]
pub struct StepMaps {
    /// Width of the maps, pixels.
    pub width: u32,
    /// Height of the maps, pixels.
    pub height: u32,
    /// Spurious change per pixel, 0..1 of full scale.
    pub spurious: Vec<f32>,
    /// Missing change per pixel, 0..1 of full scale.
    pub missing: Vec<f32>,
    /// The reference's mean change over the step, 0..1 of full scale.
    pub reference_change: f64,
}

impl StepMaps {
    /// One step: the technique's frames `technique` = (before, after) against the
    /// reference's `reference` over the same step.
    pub fn of(
        technique: (&image::RgbaImage, &image::RgbaImage),
        reference: (&image::RgbaImage, &image::RgbaImage),
    ) -> Result<Self> {
        for (a, b) in [
            (technique.0, technique.1),
            (reference.0, reference.1),
            (technique.0, reference.0),
        ] {
            crate::metrics::same_size(a, b)?;
        }
        let l = |i| Linear::of(i, 1);
        let dt = change(&l(technique.0), &l(technique.1));
        let dr = change(&l(reference.0), &l(reference.1));
        let reference_change =
            dr.iter().map(|&x| f64::from(x)).sum::<f64>() / dr.len().max(1) as f64;
        let (spurious, missing) = spurious_and_missing(&dt, &dr);
        Ok(Self {
            width: technique.0.width(),
            height: technique.0.height(),
            spurious,
            missing,
            reference_change,
        })
    }

    /// Mean spurious and missing change over the image, in units of the reference's change
    /// over the step (absolute, 0..1, when the reference did not change).
    pub fn means(&self) -> (f64, f64) {
        let mean = |v: &[f32]| v.iter().map(|&x| f64::from(x)).sum::<f64>() / v.len().max(1) as f64;
        let unit = if self.reference_change > 0.0 {
            self.reference_change
        } else {
            1.0
        };
        (mean(&self.spurious) / unit, mean(&self.missing) / unit)
    }

    /// A picture of the maps: spurious change in red, missing change in cyan, times `gain`,
    /// on black (no disagreement).
    pub fn image(&self, gain: f32) -> image::RgbaImage {
        let level = |x: f32| (x * gain * 255.0).round().clamp(0.0, 255.0) as u8;
        image::RgbaImage::from_fn(self.width, self.height, |x, y| {
            let k = (y * self.width + x) as usize;
            let (s, m) = (level(self.spurious[k]), level(self.missing[k]));
            image::Rgba([s, m, m, 255])
        })
    }
}

/// Compares the frame-to-frame change of `technique`'s frames with `reference`'s (the same
/// motion's frames, as [`motion_frames`] renders them) at `scale`.
pub fn temporal_change(
    motion: CameraMotion,
    scale: Scale,
    technique: &[image::RgbaImage],
    reference: &[image::RgbaImage],
) -> Result<TemporalChange> {
    if technique.len() != reference.len() || technique.len() < 2 {
        return Err(Error::Image {
            path: "temporal change".into(),
            message: format!(
                "needs as many technique frames as reference frames, at least 2; got {} and {}",
                technique.len(),
                reference.len()
            ),
        });
    }
    for (a, b) in technique.iter().zip(reference) {
        crate::metrics::same_size(a, b)?;
    }
    let factor = scale.factor();
    let t: Vec<Linear> = technique.iter().map(|i| Linear::of(i, factor)).collect();
    let r: Vec<Linear> = reference.iter().map(|i| Linear::of(i, factor)).collect();
    let mean = |v: &[f32]| v.iter().map(|&x| f64::from(x)).sum::<f64>() / v.len().max(1) as f64;
    let (mut spurious, mut missing, mut t_total, mut r_total) = (Vec::new(), Vec::new(), 0.0, 0.0);
    for k in 1..t.len() {
        let (dt, dr) = (change(&t[k - 1], &t[k]), change(&r[k - 1], &r[k]));
        let (s, m) = spurious_and_missing(&dt, &dr);
        t_total += mean(&dt);
        r_total += mean(&dr);
        spurious.push(mean(&s));
        missing.push(mean(&m));
    }
    let steps = (t.len() - 1) as f64;
    let reference_change = r_total / steps;
    // A reference that does not change at all has no unit; 1e-6 of full scale stands in so
    // any change of the technique's is still reported (as a very large figure).
    let unit = reference_change.max(1e-6);
    for v in spurious.iter_mut().chain(missing.iter_mut()) {
        *v /= unit;
    }
    Ok(TemporalChange {
        motion: motion.name(),
        scale,
        reference_change,
        technique_change: t_total / steps / unit,
        spurious: Series::of(&spurious),
        missing: Series::of(&missing),
        spurious_steps: spurious,
        missing_steps: missing,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Frames of a bright square sliding one pixel a step over a dark field, with a
    /// checkerboard of period 2 moving with it (detail that blur removes).
    fn sliding(steps: u32, blur: bool) -> Vec<image::RgbaImage> {
        sliding_with(steps, blur, true)
    }

    /// [`sliding`], with the checkerboard fixed in the image instead when `!attached`.
    fn sliding_with(steps: u32, blur: bool, attached: bool) -> Vec<image::RgbaImage> {
        (0..=steps)
            .map(|k| {
                let sharp = image::RgbaImage::from_fn(64, 32, |x, y| {
                    let inside = (8 + k..40 + k).contains(&x) && (8..24).contains(&y);
                    // `x + y + k` has the parity of `x − k + y` (the pattern moving with the patch)
                    // without underflowing left of it.
                    let phase = if attached { x + y + k } else { x + y };
                    let v = if inside && phase % 2 == 0 { 240 } else { 20 };
                    image::Rgba([v, v, v, 255])
                });
                if blur {
                    image::imageops::blur(&sharp, 1.5)
                } else {
                    sharp
                }
            })
            .collect()
    }

    #[test]
    fn the_reference_against_itself_has_neither() {
        let r = sliding(6, false);
        for scale in Scale::ALL {
            let c = temporal_change(CameraMotion::Pan(1.0), scale, &r, &r).unwrap();
            assert!(c.reference_change > 0.0);
            assert_eq!((c.spurious.peak, c.missing.peak), (0.0, 0.0));
            assert!((c.technique_change - 1.0).abs() < 1e-9);
        }
    }

    #[test]
    fn blur_is_missing_change_and_popping_is_spurious() {
        let r = sliding(6, false);
        let blurred = sliding(6, true);
        let c = temporal_change(CameraMotion::Pan(1.0), Scale::Full, &blurred, &r).unwrap();
        // The old ratio of totals: blur changes less, so it looked "steadier".
        assert!(c.technique_change < 0.6, "{c:?}");
        assert!(c.missing.mean > 3.0 * c.spurious.mean, "{c:?}");
        // A frame where a block of pixels switches (a level popping in) is a spurious peak.
        let mut popping = r.clone();
        for (x, y) in (44..56).flat_map(|x| (4..28).map(move |y| (x, y))) {
            popping[3].put_pixel(x, y, image::Rgba([200, 120, 60, 255]));
        }
        let p = temporal_change(CameraMotion::Pan(1.0), Scale::Full, &popping, &r).unwrap();
        assert!(p.spurious.peak > 0.2, "{p:?}");
        let peak_step = p
            .spurious_steps
            .iter()
            .enumerate()
            .max_by(|a, b| a.1.total_cmp(b.1))
            .map(|(k, _)| k);
        // Step k compares frames k and k + 1: the switched frame is in steps 2 and 3.
        assert!(matches!(peak_step, Some(2 | 3)), "{p:?}");
    }

    #[test]
    fn quarter_scale_forgives_detail_that_averages_alike() {
        // Fine detail that does not move with the surface it is on (a texture fixed to the
        // screen) misses the reference's change pixel by pixel; averaged over 4 x 4 blocks both
        // pictures are the same grey there and agree.
        let r = sliding(4, false);
        let fixed = sliding_with(4, false, false);
        let full = temporal_change(CameraMotion::Dolly(1.0), Scale::Full, &fixed, &r).unwrap();
        let quarter =
            temporal_change(CameraMotion::Dolly(1.0), Scale::Quarter, &fixed, &r).unwrap();
        assert!(full.missing.mean > 0.5, "{full:?}");
        assert!(
            quarter.missing.mean + quarter.spurious.mean
                < 0.5 * (full.missing.mean + full.spurious.mean),
            "{quarter:?} vs {full:?}"
        );
    }

    #[test]
    fn step_maps_agree_with_the_series_and_colour_each_kind() {
        let r = sliding(2, false);
        let blurred = sliding(2, true);
        let maps = StepMaps::of((&blurred[0], &blurred[1]), (&r[0], &r[1])).unwrap();
        let c =
            temporal_change(CameraMotion::Pan(1.0), Scale::Full, &blurred[..2], &r[..2]).unwrap();
        let (s, m) = maps.means();
        assert!((s - c.spurious.mean).abs() < 1e-9 && (m - c.missing.mean).abs() < 1e-9);
        let picture = maps.image(4.0);
        let k = maps
            .missing
            .iter()
            .position(|&x| x > 0.1)
            .expect("blur misses change somewhere");
        let p = picture
            .get_pixel(k as u32 % maps.width, k as u32 / maps.width)
            .0;
        assert!(p[1] > 0 && p[1] == p[2], "{p:?}");
    }

    #[test]
    fn mismatched_frames_are_refused() {
        let r = sliding(3, false);
        assert!(temporal_change(CameraMotion::Pan(1.0), Scale::Full, &r[..2], &r).is_err());
        let small = vec![image::RgbaImage::new(8, 8); 4];
        let e = temporal_change(CameraMotion::Pan(1.0), Scale::Full, &small, &r)
            .unwrap_err()
            .to_string();
        assert!(e.contains("size"), "{e}");
    }
}

//! Comparing images: FLIP (NVIDIA's perceptual difference, crate `nv-flip`), SSIM and PSNR,
//! grass coverage, and difference images.
//!
//! Per-pixel metrics are meaningful between a technique and its own finest level of detail;
//! across techniques blade placement differs by design, so compare at reduced scales
//! ([`downsample`]) and by coverage as well.

mod coverage;
mod flip;
mod psnr;
#[cfg(test)]
mod reference;
mod ssim;

pub use coverage::{coverage_mask, grass_coverage};
pub use flip::{FlipResult, flip};
pub use psnr::psnr;
pub use ssim::ssim;

use crate::{Error, Result};

/// Errors unless both images have the same size.
pub(crate) fn same_size(a: &image::RgbaImage, b: &image::RgbaImage) -> Result<()> {
    if a.dimensions() == b.dimensions() {
        Ok(())
    } else {
        Err(Error::Image {
            path: "comparison".into(),
            message: format!(
                "images differ in size ({}x{} vs {}x{}); render both at the same --size",
                a.width(),
                a.height(),
                b.width(),
                b.height()
            ),
        })
    }
}

/// Box-filters an image down by an integer `factor` (averaging in the stored sRGB values).
pub fn downsample(img: &image::RgbaImage, factor: u32) -> image::RgbaImage {
    let f = factor.max(1);
    let (w, h) = ((img.width() / f).max(1), (img.height() / f).max(1));
    image::RgbaImage::from_fn(w, h, |x, y| {
        let mut sum = [0u32; 4];
        let mut n = 0;
        for dy in 0..f {
            for dx in 0..f {
                let (sx, sy) = (x * f + dx, y * f + dy);
                if sx < img.width() && sy < img.height() {
                    let p = img.get_pixel(sx, sy).0;
                    for c in 0..4 {
                        sum[c] += u32::from(p[c]);
                    }
                    n += 1;
                }
            }
        }
        image::Rgba(sum.map(|s| (s / n.max(1)) as u8))
    })
}

/// Absolute difference per channel, scaled by `gain` (alpha opaque).
pub fn abs_diff_image(
    a: &image::RgbaImage,
    b: &image::RgbaImage,
    gain: f32,
) -> Result<image::RgbaImage> {
    same_size(a, b)?;
    Ok(image::RgbaImage::from_fn(a.width(), a.height(), |x, y| {
        let (p, q) = (a.get_pixel(x, y).0, b.get_pixel(x, y).0);
        let d = |c: usize| ((f32::from(p[c]) - f32::from(q[c])).abs() * gain).min(255.0) as u8;
        image::Rgba([d(0), d(1), d(2), 255])
    }))
}

/// Mean colour (sRGB-encoded, 0..255 per channel) of an image.
pub fn mean_color(img: &image::RgbaImage) -> [f64; 3] {
    let n = f64::from(img.width() * img.height()).max(1.0);
    let mut sum = [0.0; 3];
    for p in img.pixels() {
        for (s, v) in sum.iter_mut().zip(p.0) {
            *s += f64::from(v);
        }
    }
    sum.map(|s| s / n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn downsample_averages_blocks() {
        let img = image::RgbaImage::from_fn(4, 2, |x, _| {
            image::Rgba([if x % 2 == 0 { 0 } else { 200 }, 0, 0, 255])
        });
        let d = downsample(&img, 2);
        assert_eq!(d.dimensions(), (2, 1));
        assert_eq!(d.get_pixel(0, 0).0, [100, 0, 0, 255]);
        assert_eq!(mean_color(&img)[0], 100.0);
    }
}

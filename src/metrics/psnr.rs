//! Peak signal-to-noise ratio over the RGB channels.

use super::same_size;
use crate::Result;

/// PSNR in dB between two images (RGB, 8-bit); infinite when identical.
pub fn psnr(a: &image::RgbaImage, b: &image::RgbaImage) -> Result<f64> {
    same_size(a, b)?;
    let mut sum = 0.0f64;
    for (p, q) in a.pixels().zip(b.pixels()) {
        for c in 0..3 {
            let d = f64::from(p.0[c]) - f64::from(q.0[c]);
            sum += d * d;
        }
    }
    let mse = sum / (3.0 * f64::from(a.width() * a.height()).max(1.0));
    Ok(if mse == 0.0 {
        f64::INFINITY
    } else {
        10.0 * (255.0f64 * 255.0 / mse).log10()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identical_is_infinite_and_known_error_matches() {
        let a = image::RgbaImage::from_pixel(8, 8, image::Rgba([100, 100, 100, 255]));
        let b = image::RgbaImage::from_pixel(8, 8, image::Rgba([110, 110, 110, 255]));
        assert!(psnr(&a, &a).unwrap().is_infinite());
        // MSE = 100 → 10 log10(65025 / 100) = 28.13 dB.
        assert!((psnr(&a, &b).unwrap() - 28.1308).abs() < 1e-3);
        assert!(psnr(&a, &image::RgbaImage::new(4, 4)).is_err());
    }
}

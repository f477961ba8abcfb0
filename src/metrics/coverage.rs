//! Grass coverage: the fraction of the image a technique's grass changed compared with the
//! same frame drawn without grass (the core's background only). Technique-agnostic: no colour
//! classification, just "did something get drawn here".

use super::same_size;
use crate::Result;

/// Per-pixel "grass here" mask: the summed absolute RGB difference exceeds `tolerance`.
pub fn coverage_mask(
    frame: &image::RgbaImage,
    background: &image::RgbaImage,
    tolerance: u32,
) -> Result<Vec<bool>> {
    same_size(frame, background)?;
    Ok(frame
        .pixels()
        .zip(background.pixels())
        .map(|(p, q)| {
            (0..3)
                .map(|c| u32::from(p.0[c].abs_diff(q.0[c])))
                .sum::<u32>()
                > tolerance
        })
        .collect())
}

/// Fraction of pixels in the mask.
pub fn grass_coverage(
    frame: &image::RgbaImage,
    background: &image::RgbaImage,
    tolerance: u32,
) -> Result<f64> {
    let mask = coverage_mask(frame, background, tolerance)?;
    Ok(mask.iter().filter(|&&m| m).count() as f64 / mask.len().max(1) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_changed_pixels() {
        let bg = image::RgbaImage::from_pixel(10, 10, image::Rgba([50, 60, 70, 255]));
        let mut f = bg.clone();
        for x in 0..10 {
            for y in 0..3 {
                f.put_pixel(x, y, image::Rgba([10, 90, 10, 255]));
            }
        }
        f.put_pixel(5, 5, image::Rgba([51, 60, 70, 255])); // below tolerance
        assert!((grass_coverage(&f, &bg, 6).unwrap() - 0.3).abs() < 1e-9);
    }
}

//! Comparing techniques whose blades stand in different places: at several scales, by mean
//! colour, by coverage per screen tile and by the silhouette against the sky.

use crate::Result;
use crate::metrics::{self, coverage_mask, downsample};

/// Summed RGB difference above which a pixel counts as changed by grass (8-bit values).
pub const COVERAGE_TOLERANCE: u32 = 6;
/// Screen tiles per side for the coverage comparison.
pub const TILES: u32 = 8;

/// How two images of the same scene and frame differ.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PairScores {
    /// First image's name (the reference when comparing with it).
    pub a: String,
    /// Second image's name.
    pub b: String,
    /// Mean FLIP at full resolution.
    pub flip_full: f64,
    /// Mean FLIP after 4x downsampling.
    pub flip_quarter: f64,
    /// Mean FLIP after 16x downsampling.
    pub flip_sixteenth: f64,
    /// Mean absolute difference of the mean colour (0..255) after 4x downsampling, per pixel.
    pub color_error_quarter: f64,
    /// Mean absolute difference of grass coverage per screen tile (0..1).
    pub coverage_tile_error: f64,
    /// Mean absolute difference of the silhouette height per column, as a fraction of the
    /// image height.
    pub silhouette_error: f64,
}

/// Fraction of each of `tiles x tiles` screen tiles covered by grass (row-major).
pub fn tile_coverage(mask: &[bool], width: u32, height: u32, tiles: u32) -> Vec<f64> {
    let mut covered = vec![0u32; (tiles * tiles) as usize];
    let mut total = vec![0u32; (tiles * tiles) as usize];
    for y in 0..height {
        for x in 0..width {
            let t = ((y * tiles / height) * tiles + x * tiles / width) as usize;
            total[t] += 1;
            covered[t] += u32::from(mask[(y * width + x) as usize]);
        }
    }
    covered
        .iter()
        .zip(&total)
        .map(|(&c, &t)| f64::from(c) / f64::from(t.max(1)))
        .collect()
}

/// Per column, the topmost row where grass covers the image (`None` where no grass).
pub fn silhouette_rows(mask: &[bool], width: u32, height: u32) -> Vec<Option<u32>> {
    (0..width)
        .map(|x| (0..height).find(|&y| mask[(y * width + x) as usize]))
        .collect()
}

/// Scores every pair of `images` (name, image) of one scene and frame; `background` is the same
/// frame without grass, for coverage and silhouettes.
pub fn cross_compare(
    images: &[(String, image::RgbaImage)],
    background: &image::RgbaImage,
) -> Result<Vec<PairScores>> {
    let (w, h) = background.dimensions();
    let masks = images
        .iter()
        .map(|(_, img)| coverage_mask(img, background, COVERAGE_TOLERANCE))
        .collect::<Result<Vec<_>>>()?;
    let mut out = Vec::new();
    for i in 0..images.len() {
        for j in i + 1..images.len() {
            let (a, b) = (&images[i].1, &images[j].1);
            let flip_at = |f: u32| -> Result<f64> {
                Ok(f64::from(
                    metrics::flip(&downsample(a, f), &downsample(b, f))?.mean,
                ))
            };
            let (qa, qb) = (downsample(a, 4), downsample(b, 4));
            let color = qa
                .pixels()
                .zip(qb.pixels())
                .map(|(p, q)| {
                    (0..3)
                        .map(|c| f64::from(p.0[c].abs_diff(q.0[c])))
                        .sum::<f64>()
                        / 3.0
                })
                .sum::<f64>()
                / f64::from(qa.width() * qa.height()).max(1.0);
            let (ta, tb) = (
                tile_coverage(&masks[i], w, h, TILES),
                tile_coverage(&masks[j], w, h, TILES),
            );
            let tiles = ta.iter().zip(&tb).map(|(x, y)| (x - y).abs()).sum::<f64>()
                / ta.len().max(1) as f64;
            let (sa, sb) = (
                silhouette_rows(&masks[i], w, h),
                silhouette_rows(&masks[j], w, h),
            );
            let sil = sa
                .iter()
                .zip(&sb)
                .map(|(x, y)| f64::from(x.unwrap_or(h).abs_diff(y.unwrap_or(h))) / f64::from(h))
                .sum::<f64>()
                / f64::from(w).max(1.0);
            out.push(PairScores {
                a: images[i].0.clone(),
                b: images[j].0.clone(),
                flip_full: flip_at(1)?,
                flip_quarter: flip_at(4)?,
                flip_sixteenth: flip_at(16)?,
                color_error_quarter: color,
                coverage_tile_error: tiles,
                silhouette_error: sil,
            });
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiles_and_silhouettes_of_a_known_mask() {
        // 4x4 image, bottom half covered.
        let mask: Vec<bool> = (0..16).map(|i| i >= 8).collect();
        assert_eq!(tile_coverage(&mask, 4, 4, 2), vec![0.0, 0.0, 1.0, 1.0]);
        assert_eq!(silhouette_rows(&mask, 4, 4), vec![Some(2); 4]);
        let none = vec![false; 16];
        assert_eq!(silhouette_rows(&none, 4, 4), vec![None; 4]);
    }
}

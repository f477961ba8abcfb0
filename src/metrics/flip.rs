//! FLIP (Andersson et al. 2020), through the `nv-flip` bindings to NVIDIA's reference code.

use super::same_size;
use crate::Result;

/// A FLIP comparison.
pub struct FlipResult {
    /// Mean FLIP error over the image, 0 (identical) to 1.
    pub mean: f32,
    /// 95th percentile of the per-pixel error (how bad the worst 5 % of the image is).
    pub p95: f32,
    /// The error map coloured with the magma palette, for difference images.
    pub heatmap: image::RgbaImage,
}

/// FLIP between a reference and a test image at the default viewing condition
/// (`nv_flip::DEFAULT_PIXELS_PER_DEGREE`, about 67: a 0.7 m viewing distance on a 24" 4K
/// monitor).
pub fn flip(reference: &image::RgbaImage, test: &image::RgbaImage) -> Result<FlipResult> {
    same_size(reference, test)?;
    let (w, h) = reference.dimensions();
    let rgb = |img: &image::RgbaImage| {
        let data: Vec<u8> = img
            .pixels()
            .flat_map(|p| [p.0[0], p.0[1], p.0[2]])
            .collect();
        nv_flip::FlipImageRgb8::with_data(w, h, &data)
    };
    let error = nv_flip::flip(
        rgb(reference),
        rgb(test),
        nv_flip::DEFAULT_PIXELS_PER_DEGREE,
    );
    let mean = nv_flip::FlipPool::from_image(&error).mean();
    let mut values = error.to_vec();
    values.sort_by(f32::total_cmp);
    let p95 = values.get(values.len() * 95 / 100).copied().unwrap_or(0.0);
    let colored = error.apply_color_lut(&nv_flip::magma_lut()).to_vec();
    let heatmap = image::RgbaImage::from_fn(w, h, |x, y| {
        let i = ((y * w + x) * 3) as usize;
        image::Rgba([colored[i], colored[i + 1], colored[i + 2], 255])
    });
    Ok(FlipResult { mean, p95, heatmap })
}

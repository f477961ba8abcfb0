//! Structural similarity (Wang et al. 2004) on luma, with the paper's 11x11 Gaussian window
//! (σ = 1.5), K1 = 0.01, K2 = 0.03.

use super::same_size;
use crate::Result;

/// Mean SSIM between two images, computed on Rec. 709 luma of the stored (sRGB) values.
pub fn ssim(a: &image::RgbaImage, b: &image::RgbaImage) -> Result<f64> {
    same_size(a, b)?;
    let (w, h) = (a.width() as usize, a.height() as usize);
    let luma = |img: &image::RgbaImage| -> Vec<f64> {
        img.pixels()
            .map(|p| {
                0.2126 * f64::from(p.0[0]) + 0.7152 * f64::from(p.0[1]) + 0.0722 * f64::from(p.0[2])
            })
            .collect()
    };
    let (x, y) = (luma(a), luma(b));
    let prod = |u: &[f64], v: &[f64]| u.iter().zip(v).map(|(p, q)| p * q).collect::<Vec<_>>();
    let kernel = gaussian(1.5, 5);
    let blur = |v: &[f64]| blur(v, w, h, &kernel);
    let (mx, my) = (blur(&x), blur(&y));
    let (sxx, syy, sxy) = (
        blur(&prod(&x, &x)),
        blur(&prod(&y, &y)),
        blur(&prod(&x, &y)),
    );
    let (c1, c2) = ((0.01f64 * 255.0).powi(2), (0.03f64 * 255.0).powi(2));
    let mut sum = 0.0;
    for i in 0..w * h {
        let (ux, uy) = (mx[i], my[i]);
        let vx = sxx[i] - ux * ux;
        let vy = syy[i] - uy * uy;
        let cxy = sxy[i] - ux * uy;
        sum +=
            ((2.0 * ux * uy + c1) * (2.0 * cxy + c2)) / ((ux * ux + uy * uy + c1) * (vx + vy + c2));
    }
    Ok(sum / (w * h).max(1) as f64)
}

fn gaussian(sigma: f64, radius: i32) -> Vec<f64> {
    let k: Vec<f64> = (-radius..=radius)
        .map(|i| (-f64::from(i * i) / (2.0 * sigma * sigma)).exp())
        .collect();
    let s: f64 = k.iter().sum();
    k.into_iter().map(|v| v / s).collect()
}

/// Separable blur with edge clamping.
fn blur(v: &[f64], w: usize, h: usize, k: &[f64]) -> Vec<f64> {
    let r = (k.len() / 2) as isize;
    let mut tmp = vec![0.0; v.len()];
    for y in 0..h {
        for x in 0..w {
            tmp[y * w + x] = k
                .iter()
                .enumerate()
                .map(|(i, kv)| {
                    kv * v[y * w + (x as isize + i as isize - r).clamp(0, w as isize - 1) as usize]
                })
                .sum();
        }
    }
    let mut out = vec![0.0; v.len()];
    for y in 0..h {
        for x in 0..w {
            out[y * w + x] = k
                .iter()
                .enumerate()
                .map(|(i, kv)| {
                    kv * tmp
                        [(y as isize + i as isize - r).clamp(0, h as isize - 1) as usize * w + x]
                })
                .sum();
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identical_is_one_noise_lowers_it() {
        let a = image::RgbaImage::from_fn(32, 32, |x, y| {
            image::Rgba([(x * 8) as u8, (y * 8) as u8, 50, 255])
        });
        assert!((ssim(&a, &a).unwrap() - 1.0).abs() < 1e-9);
        let b = image::RgbaImage::from_fn(32, 32, |x, y| {
            let n = if (x * 7 + y * 13) % 3 == 0 { 60 } else { 0 };
            image::Rgba([((x * 8) as u8).saturating_add(n), (y * 8) as u8, 50, 255])
        });
        let s = ssim(&a, &b).unwrap();
        assert!(s < 0.95 && s > 0.0, "{s}");
    }
}

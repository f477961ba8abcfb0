//! The billboard texture of Fig. 11, rendered at start-up from the single blade and petal
//! textures: blades of the scene's heights, widths and lean standing side by side, some with
//! a flower, as a wing of a billboard shows them.
//!
//! One layer per billboard step `s` (Eq. 8): a billboard stands for the `s²` plants of its
//! block and shows them on `(2 + √2)·s` spacings of wings, so a layer holds
//! `s / (2 + √2)` blades per spacing of width. A layer spans [`SPAN`] lattice spacings
//! horizontally (repeating) and the tallest blade vertically.
//!
//! Texels are not colours: R is the blade texture's luminance, G the blade's density
//! threshold (uniform in `[0, 1)`: the shader keeps a blade where it is below the density map,
//! the shared rule of `grassbench::grass`, and below the fade alpha of Sec. 6.1), B the blade's
//! colour variation mapped to `[0, 0.75]`, or `0.8 + 0.03·layer` for a petal of petal texture
//! `layer`, A the cut-out alpha. The shader colours them like single blades, so both agree.

use grassbench::grass::GrassConfig;
use grassbench::rng::hash_f32;

use crate::prairie::{FLOWER_HEIGHT, PETAL_TEXTURES};
use crate::textures::{BLADE_SIZE, PETAL_SIZE, blade_texture, petal_textures};

/// Texture size of one layer (u along a wing, v from the ground to the tallest blade).
pub const SIZE: (u32, u32) = (256, 128);
/// Lattice spacings one layer spans along a wing (`u` repeats after it).
pub const SPAN: f32 = 8.0;
/// Value of the B channel from which a texel is a petal.
pub const PETAL_CODE: f32 = 0.8;

/// What the composed blades look like (from the scene and the technique's parameters).
#[derive(Clone, Copy, Debug)]
pub struct Look<'a> {
    /// Scene grass ranges (height, width, lean).
    pub grass: &'a GrassConfig,
    /// Lattice spacing, m.
    pub spacing: f32,
    /// Fraction of blades with a flower.
    pub flower_fraction: f32,
    /// Petal side, m.
    pub petal_size: f32,
}

fn quantise(v: f32) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8
}

/// Blades composed into the layer of billboard step `step`.
pub fn blades_per_layer(step: u32) -> u32 {
    ((step as f32 / (2.0 + std::f32::consts::SQRT_2)) * SPAN)
        .round()
        .max(1.0) as u32
}

/// The layers for `steps`, one after the other, each `SIZE.0 x SIZE.1` RGBA8 texels, row-major
/// from the ground (`v = 0`) up.
pub fn billboard_texture(look: &Look<'_>, steps: &[u32], seed: u64) -> Vec<[u8; 4]> {
    let blade = blade_texture(seed);
    let petals = petal_textures();
    let (w, h) = SIZE;
    let tallest = look.grass.height[1].max(1e-3);
    // Metres per texel along u and v.
    let (mx, my) = (SPAN * look.spacing / w as f32, tallest / h as f32);
    let mut out = vec![[0u8; 4]; (w * h) as usize * steps.len()];
    for (layer, &step) in steps.iter().enumerate() {
        let texels = &mut out[(layer * (w * h) as usize)..((layer + 1) * (w * h) as usize)];
        for b in 0..blades_per_layer(step) {
            let r = |k: i64| hash_f32(seed ^ 0xb111_b0a2d, &[layer as i64, i64::from(b), k]);
            let lerp = |range: [f32; 2], t: f32| range[0] + (range[1] - range[0]) * t;
            let size = r(0);
            let height = lerp(look.grass.height, size);
            let width = lerp(look.grass.width, 0.5 * size + 0.5 * r(1));
            // Lean seen from the side: the tip moves by sin(lean)·height across the wing.
            let lean = look.grass.lean * r(2).sqrt() * (r(3) - 0.5) * 2.0;
            let x0 = r(4) * w as f32;
            let threshold = quantise(r(5));
            let variation = quantise((r(6) * 2.0 - 1.0 + 1.0) * 0.5 * 0.75);
            let rows = (height / my).round() as u32;
            let half = 0.5 * width / mx;
            let centre = |v: f32| x0 + lean.sin() * height * v * v / mx;
            for y in 0..rows.min(h) {
                let v = (y as f32 + 0.5) / rows as f32;
                let c = centre(v);
                let ty = ((v * BLADE_SIZE.1 as f32) as u32).min(BLADE_SIZE.1 - 1);
                for x in (c - half - 1.0).floor() as i32..=(c + half + 1.0).ceil() as i32 {
                    let u = (x as f32 + 0.5 - c) / (2.0 * half.max(0.5)) + 0.5;
                    if !(0.0..1.0).contains(&u) {
                        continue;
                    }
                    let tx = ((u * BLADE_SIZE.0 as f32) as u32).min(BLADE_SIZE.0 - 1);
                    let t = blade[(ty * BLADE_SIZE.0 + tx) as usize];
                    if t[3] < 128 {
                        continue;
                    }
                    let xi = x.rem_euclid(w as i32) as u32;
                    texels[(y * w + xi) as usize] = [t[0], threshold, variation, t[3]];
                }
            }
            // A flower on this blade (Sec. 3.3), seen from the side: a flattened petal.
            if r(7) < look.flower_fraction {
                let layer_id = ((r(8) * PETAL_TEXTURES as f32) as u32).min(PETAL_TEXTURES - 1);
                let code = quantise(PETAL_CODE + 0.03 * layer_id as f32);
                let py = height * FLOWER_HEIGHT * (0.9 + 0.2 * r(9)) / my;
                let px = centre(py * my / height);
                let (rx, ry) = (0.5 * look.petal_size / mx, 0.5 * 0.4 * look.petal_size / my);
                let p = &petals[(layer_id * PETAL_SIZE * PETAL_SIZE) as usize..];
                for y in (py - ry).floor() as i32..=(py + ry).ceil() as i32 {
                    for x in (px - rx).floor() as i32..=(px + rx).ceil() as i32 {
                        let (qx, qy) = ((x as f32 + 0.5 - px) / rx, (y as f32 + 0.5 - py) / ry);
                        if y < 0 || y >= h as i32 || qx.abs() >= 1.0 || qy.abs() >= 1.0 {
                            continue;
                        }
                        let s = PETAL_SIZE as f32;
                        let tx = (((qx * 0.5 + 0.5) * s) as u32).min(PETAL_SIZE - 1);
                        let ty = (((qy * 0.5 + 0.5) * s) as u32).min(PETAL_SIZE - 1);
                        let t = p[(ty * PETAL_SIZE + tx) as usize];
                        if t[3] < 128 {
                            continue;
                        }
                        let xi = x.rem_euclid(w as i32) as u32;
                        texels[(y as u32 * w + xi) as usize] = [255, threshold, code, t[3]];
                    }
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coarser_layers_hold_more_blades_and_cover_more() {
        let grass = GrassConfig::default();
        let look = Look {
            grass: &grass,
            spacing: 0.15,
            flower_fraction: 0.3,
            petal_size: 0.07,
        };
        let steps = [4, 8, 16];
        assert_eq!(blades_per_layer(4), 9);
        assert_eq!(blades_per_layer(16), 37);
        let t = billboard_texture(&look, &steps, 3);
        let n = (SIZE.0 * SIZE.1) as usize;
        assert_eq!(t.len(), 3 * n);
        let cover: Vec<f32> = t
            .chunks(n)
            .map(|l| l.iter().filter(|p| p[3] >= 128).count() as f32 / n as f32)
            .collect();
        assert!(
            cover[0] > 0.02 && cover[0] < cover[1] && cover[1] < cover[2],
            "{cover:?}"
        );
        // The top row is mostly sky, the bottom row mostly blades.
        let row = |l: usize, y: u32| {
            t[l * n + (y * SIZE.0) as usize..l * n + ((y + 1) * SIZE.0) as usize]
                .iter()
                .filter(|p| p[3] >= 128)
                .count()
        };
        assert!(row(2, 0) > row(2, SIZE.1 - 1));
        // Some petals, and thresholds spread over [0, 1).
        assert!(
            t.iter()
                .any(|p| p[3] >= 128 && f32::from(p[2]) / 255.0 >= PETAL_CODE - 0.01)
        );
        let g: Vec<u8> = t.iter().filter(|p| p[3] >= 128).map(|p| p[1]).collect();
        assert!(g.iter().any(|&v| v < 64) && g.iter().any(|&v| v > 192));
    }
}

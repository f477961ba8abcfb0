//! Procedural textures with alpha: the blade of Fig. 5b (a tapering blade with a midrib and
//! streaks; alpha cuts its outline out of the quad strip) and the six petal textures of
//! Fig. 9 (the thesis used photographs; these are drawn from petal count, shape and colour).
//!
//! Texels hold *linear* colour in `Rgba8Unorm`; the shader multiplies the blade's luminance
//! into the scene's grass colours and uses the petals' colour as albedo.

use grassbench::rng::hash_f32;

/// Blade texture size (u across the blade, v from root to tip).
pub const BLADE_SIZE: (u32, u32) = (32, 128);
/// Petal texture side.
pub const PETAL_SIZE: u32 = 64;

fn smoothstep(e0: f32, e1: f32, x: f32) -> f32 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

fn texel(rgb: [f32; 3], a: f32) -> [u8; 4] {
    let q = |v: f32| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
    [q(rgb[0]), q(rgb[1]), q(rgb[2]), q(a)]
}

/// Half-width of the blade outline at height `v` (0 root, 1 tip), as a fraction of the quad:
/// nearly full at the root, tapering to a point like the reference's `(1 − s)^0.7`.
pub fn blade_profile(v: f32) -> f32 {
    0.5 * (1.0 - v).max(0.0).powf(0.7)
}

/// The blade texture, row-major from `v = 0` (root) up, RGBA8. RGB is a luminance in about
/// `[0.55, 1]` (same in the three channels): lighter midrib, darker edges, faint streaks.
pub fn blade_texture(seed: u64) -> Vec<[u8; 4]> {
    let (w, h) = BLADE_SIZE;
    let mut out = Vec::with_capacity((w * h) as usize);
    for y in 0..h {
        let v = (y as f32 + 0.5) / h as f32;
        for x in 0..w {
            let u = (x as f32 + 0.5) / w as f32;
            let d = (u - 0.5).abs();
            let half = blade_profile(v);
            // One texel of soft edge so bilinear filtering gives a clean cut-out.
            let alpha = 1.0 - smoothstep(half - 0.5 / w as f32, half + 0.5 / w as f32, d);
            let across = if half > 0.0 { d / half } else { 1.0 };
            let midrib = (1.0 - across * 6.0).max(0.0) * 0.2;
            let edge = smoothstep(0.6, 1.0, across) * 0.2;
            let streak = (hash_f32(seed, &[i64::from(x)]) - 0.5) * 0.12;
            let l = (0.85 + midrib - edge + streak).clamp(0.0, 1.0);
            out.push(texel([l, l, l], alpha));
        }
    }
    out
}

/// The look of one petal texture.
struct Flower {
    petals: f32,
    /// Petal roundness: larger = narrower petals.
    sharpness: f32,
    petal: [f32; 3],
    centre: [f32; 3],
    centre_radius: f32,
}

const FLOWERS: [Flower; 6] = [
    // Daisy: many narrow white petals, yellow centre.
    Flower {
        petals: 14.0,
        sharpness: 3.0,
        petal: [0.85, 0.85, 0.80],
        centre: [0.80, 0.55, 0.03],
        centre_radius: 0.22,
    },
    // Buttercup: five round yellow petals.
    Flower {
        petals: 5.0,
        sharpness: 0.6,
        petal: [0.85, 0.65, 0.02],
        centre: [0.55, 0.40, 0.02],
        centre_radius: 0.15,
    },
    // Cornflower: eight ragged blue petals.
    Flower {
        petals: 8.0,
        sharpness: 1.5,
        petal: [0.10, 0.22, 0.75],
        centre: [0.10, 0.05, 0.30],
        centre_radius: 0.18,
    },
    // Pink campion: five notched pink petals.
    Flower {
        petals: 10.0,
        sharpness: 1.0,
        petal: [0.80, 0.25, 0.45],
        centre: [0.90, 0.80, 0.75],
        centre_radius: 0.12,
    },
    // Violet: six purple petals.
    Flower {
        petals: 6.0,
        sharpness: 1.0,
        petal: [0.40, 0.12, 0.60],
        centre: [0.85, 0.75, 0.10],
        centre_radius: 0.14,
    },
    // Poppy: four broad red petals, dark centre.
    Flower {
        petals: 4.0,
        sharpness: 0.4,
        petal: [0.80, 0.06, 0.03],
        centre: [0.04, 0.03, 0.03],
        centre_radius: 0.2,
    },
];

/// The six petal textures, layer after layer, each `PETAL_SIZE²` RGBA8 texels.
pub fn petal_textures() -> Vec<[u8; 4]> {
    let s = PETAL_SIZE;
    let mut out = Vec::with_capacity((s * s) as usize * FLOWERS.len());
    for f in &FLOWERS {
        for y in 0..s {
            for x in 0..s {
                let p = [
                    (x as f32 + 0.5) / s as f32 * 2.0 - 1.0,
                    (y as f32 + 0.5) / s as f32 * 2.0 - 1.0,
                ];
                let r = p[0].hypot(p[1]);
                let angle = p[1].atan2(p[0]);
                // Petal outline: radius modulated by |cos(petals·angle/2)|^sharpness.
                let lobe = (f.petals * angle * 0.5).cos().abs().powf(f.sharpness);
                let radius = 0.45 + 0.5 * lobe;
                let aa = 1.5 / s as f32;
                let alpha = 1.0 - smoothstep(radius - aa, radius + aa, r);
                let centre = 1.0 - smoothstep(f.centre_radius - aa, f.centre_radius + aa, r);
                // Petals darken a little towards their base.
                let shade = 0.75 + 0.25 * smoothstep(f.centre_radius, radius, r);
                let rgb: [f32; 3] = std::array::from_fn(|c| {
                    f.petal[c] * shade * (1.0 - centre) + f.centre[c] * centre
                });
                out.push(texel(rgb, alpha));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blade_is_opaque_in_the_middle_and_clear_outside() {
        let t = blade_texture(1);
        let (w, h) = BLADE_SIZE;
        let at = |x: u32, y: u32| t[(y * w + x) as usize];
        assert_eq!(at(w / 2, 2)[3], 255);
        assert_eq!(at(0, h / 2)[3], 0);
        // The top row keeps a sub-texel sliver (measured alpha 65), cut by the 0.5 alpha test.
        assert!(at(w / 2, h - 1)[3] < 128, "the tip is a point");
        let coverage = t.iter().map(|p| f32::from(p[3]) / 255.0).sum::<f32>() / t.len() as f32;
        // The reference's blade covers ∫(1−s)^0.7 ds = 0.588 of its quad.
        assert!((coverage - 0.588).abs() < 0.03, "{coverage}");
    }

    #[test]
    fn six_distinct_petal_textures_with_alpha() {
        let t = petal_textures();
        let n = (PETAL_SIZE * PETAL_SIZE) as usize;
        assert_eq!(t.len(), 6 * n);
        let layers: Vec<&[[u8; 4]]> = t.chunks(n).collect();
        for (i, l) in layers.iter().enumerate() {
            assert_eq!(l[0][3], 0, "layer {i}: corner must be transparent");
            assert_eq!(
                l[n / 2 + PETAL_SIZE as usize / 2][3],
                255,
                "layer {i}: centre opaque"
            );
            for other in &layers[i + 1..] {
                assert_ne!(l, other);
            }
        }
    }
}

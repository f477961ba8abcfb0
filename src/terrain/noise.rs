//! Seeded value noise and fractal sums of it, for procedural heightmaps and density maps.

use crate::rng::hash_f32;

/// Value noise in `[0, 1]` at `(x, y)` (lattice spacing 1), smoothly interpolated.
pub fn value_noise(seed: u64, x: f32, y: f32) -> f32 {
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (smooth(x - x0), smooth(y - y0));
    let (i, j) = (x0 as i64, y0 as i64);
    let n = |di: i64, dj: i64| hash_f32(seed, &[i + di, j + dj]);
    let a = n(0, 0) + (n(1, 0) - n(0, 0)) * fx;
    let b = n(0, 1) + (n(1, 1) - n(0, 1)) * fx;
    a + (b - a) * fy
}

/// Fractal Brownian motion: `octaves` layers of value noise, each at twice the frequency and
/// `gain` times the amplitude of the previous one; normalised to `[0, 1]`.
pub fn fbm(seed: u64, x: f32, y: f32, octaves: u32, gain: f32) -> f32 {
    let (mut sum, mut norm, mut amp, mut freq) = (0.0, 0.0, 1.0, 1.0);
    for octave in 0..octaves.max(1) {
        sum += amp
            * value_noise(
                seed.wrapping_add(u64::from(octave) * 7919),
                x * freq,
                y * freq,
            );
        norm += amp;
        amp *= gain;
        freq *= 2.0;
    }
    sum / norm
}

/// Quintic smoothstep (continuous second derivative, so normals have no creases).
fn smooth(t: f32) -> f32 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn noise_is_bounded_deterministic_and_continuous() {
        for k in 0..500 {
            let (x, y) = (k as f32 * 0.173, k as f32 * 0.091);
            let v = fbm(3, x, y, 4, 0.5);
            assert!((0.0..=1.0).contains(&v));
            assert_eq!(v.to_bits(), fbm(3, x, y, 4, 0.5).to_bits());
            assert!((value_noise(3, x, y) - value_noise(3, x + 1e-3, y)).abs() < 0.01);
        }
    }
}

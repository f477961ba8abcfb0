//! Seeded value noise and fractal sums of it, for procedural heightmaps and density maps.

use crate::rng::hash_f32;

/// Value noise in `[0, 1]` at `(x, y)` (lattice spacing 1), smoothly interpolated.
pub fn value_noise(seed: u64, x: f32, y: f32) -> f32 {
    ValueNoiseCache::new(seed).sample(x, y)
}

/// [`value_noise`] of one seed at many nearby points: remembers the last lattice cell and its
/// four corner hashes, so a point in the same cell as the one before skips the floors and the
/// hashing (a fresh cache is [`value_noise`] itself); worth it when consecutive points are
/// close compared with the lattice spacing.
#[derive(Clone, Copy, Debug)]
pub struct ValueNoiseCache {
    seed: u64,
    /// Lower corner of the cached cell (integral floats; NaN before the first sample).
    x0: f32,
    y0: f32,
    /// Corner values at `(0, 0)`, `(1, 0)`, `(0, 1)`, `(1, 1)` from the lower corner.
    corners: [f32; 4],
}

impl ValueNoiseCache {
    /// An empty cache for `seed`.
    pub fn new(seed: u64) -> Self {
        Self {
            seed,
            x0: f32::NAN,
            y0: f32::NAN,
            corners: [0.0; 4],
        }
    }

    /// `value_noise(seed, x, y)`.
    #[inline]
    pub fn sample(&mut self, x: f32, y: f32) -> f32 {
        // Inside the cached cell `floor` would return its corner (NaN fails both tests).
        if !(x >= self.x0 && x < self.x0 + 1.0 && y >= self.y0 && y < self.y0 + 1.0) {
            let (x0, y0) = (x.floor(), y.floor());
            let (i, j) = (x0 as i64, y0 as i64);
            let n = |di: i64, dj: i64| hash_f32(self.seed, &[i + di, j + dj]);
            self.corners = [n(0, 0), n(1, 0), n(0, 1), n(1, 1)];
            (self.x0, self.y0) = (x0, y0);
        }
        let (fx, fy) = (smooth(x - self.x0), smooth(y - self.y0));
        let [n00, n10, n01, n11] = self.corners;
        let a = n00 + (n10 - n00) * fx;
        let b = n01 + (n11 - n01) * fx;
        a + (b - a) * fy
    }
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

    #[test]
    fn the_cache_gives_exactly_value_noise() {
        let mut cache = ValueNoiseCache::new(11);
        // A walk that stays in cells, crosses them both ways, lands on integers, goes
        // negative and jumps far.
        let mut points: Vec<(f32, f32)> = (0..2000)
            .map(|k| {
                let s = k as f32;
                (0.013 * s - 7.0 + (0.3 * s).sin(), 2.5 - 0.007 * s)
            })
            .collect();
        points.extend([
            (0.0, 0.0),
            (-0.0, 1.0),
            (1.0, 1.0),
            (0.999_999_9, 0.999_999_9),
            (-1.0, -1e-8),
            (1e6 + 0.5, -3e5),
            (f32::NAN, 0.5),
            (0.5, 0.5),
        ]);
        for (x, y) in points {
            let direct = value_noise(11, x, y);
            let cached = cache.sample(x, y);
            assert!(
                direct.to_bits() == cached.to_bits() || (direct.is_nan() && cached.is_nan()),
                "({x}, {y}): {direct} vs {cached}"
            );
        }
    }
}

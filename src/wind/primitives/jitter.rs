//! The small stochastic oscillations around a prescribed posture (Sec. 3.3: "it is necessary
//! to add small oscillation of random direction and intensity around the prescribed
//! position"), and the seeded space-time noise they and the breeze's drift are made of.

use glam::Vec2;

use super::{JitterParams, WindSample};
use crate::rng::hash;
use crate::terrain::noise::value_noise;

/// Seeded value noise in `[−1, 1]` over the ground (feature size 1) and time (one new layer
/// per unit of `s`, blended smoothly): a pure function of its arguments.
pub(super) fn noise(seed: u64, q: Vec2, s: f32) -> f32 {
    let k = s.floor();
    let f = s - k;
    let f = f * f * (3.0 - 2.0 * f);
    let layer = |i: f32| value_noise(hash(seed, &[i as i64]), q.x, q.y);
    (layer(k) + (layer(k + 1.0) - layer(k)) * f) * 2.0 - 1.0
}

/// One primitive's oscillations, seeded.
#[derive(Clone, Debug)]
pub(super) struct Jitter {
    params: JitterParams,
    seed: u64,
}

impl Jitter {
    pub(super) fn new(params: JitterParams, seed: u64) -> Self {
        Self { params, seed }
    }

    /// `sample` turned by a random angle and its index scaled by a random factor near 1, so
    /// a blade at rest stays at rest; the index stays in `[−1, 1]`.
    pub(super) fn apply(&self, sample: WindSample, xz: Vec2, time: f32) -> WindSample {
        let p = &self.params;
        if p.angle == 0.0 && p.index == 0.0 {
            return sample;
        }
        let q = xz / p.scale;
        let s = time * p.frequency;
        let turn = p.angle * noise(self.seed, q, s);
        let gain = 1.0 + p.index * noise(self.seed ^ 0x4A49_5454, q, s);
        WindSample {
            direction: Vec2::from_angle(turn).rotate(sample.direction),
            posture: (sample.posture * gain).clamp(-1.0, 1.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn noise_is_bounded_continuous_and_seeded() {
        for k in 0..300 {
            let q = Vec2::new(k as f32 * 0.13, k as f32 * -0.07);
            let s = k as f32 * 0.021;
            let n = noise(5, q, s);
            assert!((-1.0..=1.0).contains(&n));
            assert!((n - noise(5, q, s + 1e-3)).abs() < 0.02);
            assert_eq!(n.to_bits(), noise(5, q, s).to_bits());
        }
        assert_ne!(
            noise(5, Vec2::splat(0.3), 0.4),
            noise(6, Vec2::splat(0.3), 0.4)
        );
    }
}

//! The gentle breeze primitive (Perbet & Cani 2001, Sec. 3.3): "an infinite mask ... motion
//! at two different scales: each blade experiences a succession of small stochastic
//! oscillations, of random angles and intensity, around rest angles and bent positions that
//! slowly vary over time".

use glam::Vec2;

use super::jitter::{Jitter, noise};
use super::{BreezeParams, WindSample};

/// A breeze: the slow scale is space-time noise of feature size `drift_scale` changing over
/// `drift_period`, turning the mean direction and shifting the mean bend; the fast scale is
/// the primitive's [`Jitter`].
#[derive(Clone, Debug)]
pub(super) struct Breeze {
    params: BreezeParams,
    direction: Vec2,
    seed: u64,
    jitter: Jitter,
}

impl Breeze {
    pub(super) fn new(params: BreezeParams, seed: u64) -> Self {
        Self {
            direction: Vec2::from(params.direction).normalize_or(Vec2::X),
            jitter: Jitter::new(params.jitter, seed ^ 0x4A49),
            params,
            seed,
        }
    }

    /// The infinite mask.
    pub(super) fn mask(&self, _xz: Vec2, _time: f32) -> f32 {
        1.0
    }

    pub(super) fn action(&self, xz: Vec2, time: f32) -> WindSample {
        let p = &self.params;
        let q = xz / p.drift_scale;
        let s = time / p.drift_period;
        let turn = p.drift_angle * noise(self.seed, q, s);
        let bend = p.bend + p.drift_bend * noise(self.seed ^ 0x4245_4E44, q, s);
        let slow = WindSample {
            direction: Vec2::from_angle(turn).rotate(self.direction),
            posture: bend.clamp(-1.0, 1.0),
        };
        self.jitter.apply(slow, xz, time)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn drifts_slowly_around_the_mean() {
        let b = Breeze::new(BreezeParams::default(), 3);
        let mean = Vec2::from(BreezeParams::default().direction).normalize();
        let (mut sum, mut changes) = (0.0, 0.0);
        for k in 0..400 {
            let xz = Vec2::new(k as f32 * 0.7 - 140.0, k as f32 * 0.3);
            let t = k as f32 * 0.1;
            assert_eq!(b.mask(xz, t), 1.0);
            let s = b.action(xz, t);
            assert!(s.direction.is_normalized());
            assert!(s.direction.dot(mean) > 0.75, "{s:?}");
            assert!((0.0..=0.5).contains(&s.posture), "{s:?}");
            sum += s.posture;
            changes += (b.action(xz, t + 0.05).posture - s.posture).abs();
        }
        assert!(
            (sum / 400.0 - 0.25).abs() < 0.06,
            "mean bend {}",
            sum / 400.0
        );
        // Small steps in time: small changes (the motion is smooth).
        assert!(changes / 400.0 < 0.02, "{}", changes / 400.0);
    }
}

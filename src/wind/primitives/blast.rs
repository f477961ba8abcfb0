//! The blast of air primitive (Perbet & Cani 2001, Sec. 3.3, Fig. 12): "a repelling blow
//! around a flying object ... It translates and rotates onto the prairie according to the
//! motion of an object under the user's control. Here, the main bending directions are radial
//! to the mask contour."
//!
//! The mask here is a disc (rotation changes nothing). With `follow_object = true` its centre
//! is the scene's moving object ([`crate::object::ObjectConfig`]); otherwise its path comes from
//! the configuration.

use glam::Vec2;

use super::jitter::Jitter;
use super::{BlastParams, WindSample};

/// A blast: at distance `r` from the object's ground position, bending away from it with index
/// `strength · (1 − r / radius)`.
#[derive(Clone, Debug)]
pub(super) struct Blast {
    params: BlastParams,
    jitter: Jitter,
}

impl Blast {
    pub(super) fn new(params: BlastParams, seed: u64) -> Self {
        Self {
            jitter: Jitter::new(params.jitter, seed ^ 0x4A49),
            params,
        }
    }

    /// The object's ground position at `time`: piecewise linear through the keyframes (held
    /// before the first and after the last), or `start + velocity · time` without any.
    pub(super) fn centre(&self, time: f32) -> Vec2 {
        let p = &self.params;
        crate::keyframes::track(p.start, p.velocity, &p.keyframes, time)
    }

    pub(super) fn mask(&self, xz: Vec2, time: f32) -> f32 {
        let p = &self.params;
        super::disc_mask(self.centre(time), p.radius, p.feather, xz)
    }

    pub(super) fn action(&self, xz: Vec2, time: f32) -> WindSample {
        let p = &self.params;
        let offset = xz - self.centre(time);
        let prescribed = WindSample {
            direction: offset.try_normalize().unwrap_or(Vec2::X),
            posture: p.strength * (1.0 - offset.length() / p.radius).max(0.0),
        };
        self.jitter.apply(prescribed, xz, time)
    }
}

#[cfg(test)]
mod tests {
    use super::super::JitterParams;
    use super::*;

    #[test]
    fn radial_from_a_moving_centre() {
        let b = Blast::new(
            BlastParams {
                start: [1.0, 2.0],
                velocity: [3.0, 0.0],
                jitter: JitterParams::NONE,
                ..Default::default()
            },
            1,
        );
        let c = b.centre(2.0);
        assert_eq!(c, Vec2::new(7.0, 2.0));
        let s = b.action(c + Vec2::new(0.0, -2.0), 2.0);
        assert!(s.direction.dot(-Vec2::Y) > 0.9999);
        assert!(s.posture > b.action(c + Vec2::new(0.0, -4.0), 2.0).posture);
        assert_eq!(b.mask(c + Vec2::new(5.5, 0.0), 2.0), 0.0);
        assert_eq!(b.mask(c + Vec2::new(1.0, 0.0), 2.0), 1.0);
    }

    #[test]
    fn keyframes_are_followed_and_held() {
        let b = Blast::new(
            BlastParams {
                keyframes: vec![[1.0, 0.0, 0.0], [3.0, 10.0, 0.0], [4.0, 10.0, 5.0]],
                ..Default::default()
            },
            1,
        );
        assert_eq!(b.centre(0.0), Vec2::ZERO);
        assert_eq!(b.centre(2.0), Vec2::new(5.0, 0.0));
        assert_eq!(b.centre(3.5), Vec2::new(10.0, 2.5));
        assert_eq!(b.centre(9.0), Vec2::new(10.0, 5.0));
    }
}

//! The whirlwind primitive (Perbet & Cani 2001, Sec. 3.3, Fig. 11): "a circular mask, the
//! bending direction at each point being tangent to the circle, and the amount of bending being
//! larger near the center ... The prescribed posture index slightly changes over time in a
//! circular way around the center of the mask."

use glam::Vec2;

use super::jitter::Jitter;
use super::{WhirlwindParams, WindSample};

/// A whirlwind: centre `centre + velocity · t`; at distance `r` the index is
/// `strength · (1 − r / radius) · (1 + swirl · sin(φ − spin · t))` (φ the point's angle around
/// the centre, so the pattern turns at `spin` rad/s), the direction tangent to the circle,
/// turning the way `spin`'s sign says.
#[derive(Clone, Debug)]
pub(super) struct Whirlwind {
    params: WhirlwindParams,
    jitter: Jitter,
}

impl Whirlwind {
    pub(super) fn new(params: WhirlwindParams, seed: u64) -> Self {
        Self {
            jitter: Jitter::new(params.jitter, seed ^ 0x4A49),
            params,
        }
    }

    /// The centre at `time`.
    pub(super) fn centre(&self, time: f32) -> Vec2 {
        Vec2::from(self.params.centre) + Vec2::from(self.params.velocity) * time
    }

    pub(super) fn mask(&self, xz: Vec2, time: f32) -> f32 {
        let p = &self.params;
        super::disc_mask(self.centre(time), p.radius, p.feather, xz)
    }

    pub(super) fn action(&self, xz: Vec2, time: f32) -> WindSample {
        let p = &self.params;
        let offset = xz - self.centre(time);
        let r = offset.length();
        let sense = if p.spin < 0.0 { -1.0 } else { 1.0 };
        let direction = (offset.perp() * sense).try_normalize().unwrap_or(Vec2::X);
        let angle = offset.y.atan2(offset.x);
        let falloff = (1.0 - r / p.radius).max(0.0);
        let posture = p.strength * falloff * (1.0 + p.swirl * (angle - p.spin * time).sin());
        let prescribed = WindSample {
            direction,
            posture: posture.clamp(-1.0, 1.0),
        };
        self.jitter.apply(prescribed, xz, time)
    }
}

#[cfg(test)]
mod tests {
    use super::super::JitterParams;
    use super::*;

    #[test]
    fn tangential_and_stronger_near_the_centre() {
        let params = WhirlwindParams {
            centre: [3.0, -2.0],
            velocity: [1.0, 0.5],
            radius: 10.0,
            jitter: JitterParams::NONE,
            ..Default::default()
        };
        let w = Whirlwind::new(params.clone(), 4);
        let t = 2.0;
        let c = w.centre(t);
        assert_eq!(c, Vec2::new(5.0, -1.0));
        for k in 0..16 {
            let radial = Vec2::from_angle(k as f32 * 0.39);
            let near = w.action(c + radial * 2.0, t);
            let far = w.action(c + radial * 8.0, t);
            assert!(near.direction.dot(radial).abs() < 1e-5, "{near:?}");
            // Positive spin turns from +x towards +z.
            assert!(radial.perp().dot(near.direction) > 0.999);
            assert!(
                near.posture > far.posture && far.posture > 0.0,
                "{near:?} {far:?}"
            );
            assert_eq!(w.mask(c + radial * 2.0, t), 1.0);
        }
        assert_eq!(w.mask(c + Vec2::new(10.5, 0.0), t), 0.0);
        let edge = w.mask(c + Vec2::new(9.5, 0.0), t);
        assert!(edge > 0.0 && edge < 1.0);
        let reverse = Whirlwind::new(
            WhirlwindParams {
                spin: -1.0,
                ..params
            },
            4,
        );
        let s = reverse.action(c + Vec2::X * 3.0, t);
        assert!(s.direction.dot(-Vec2::Y) > 0.999, "{s:?}");
    }
}

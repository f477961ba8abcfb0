//! A steady breeze with gust fronts travelling downwind and a little turbulence.

use glam::{Vec2, Vec3};

use super::{BreezeConfig, WindField};
use crate::rng::Rng;
use crate::terrain::noise::value_noise;

/// Three gust waves at slightly different headings and wavelengths (seeded), so fronts are
/// irregular but travel downwind at `gust_speed`; turbulence is space-time value noise.
#[derive(Clone, Debug)]
pub struct Breeze {
    config: BreezeConfig,
    direction: Vec2,
    waves: [(Vec2, f32); 3],
    seed: u64,
}

impl Breeze {
    /// A breeze; `seed` picks the gust pattern.
    pub fn new(config: BreezeConfig, seed: u64) -> Self {
        let direction = Vec2::from(config.direction).normalize_or(Vec2::X);
        let mut rng = Rng::new(seed ^ 0x4252_4545);
        let waves = [0.0f32, 1.0, 2.0].map(|k| {
            let heading = rng.range(-0.35, 0.35);
            let wavelength = config.gust_wavelength * (0.7 + 0.3 * k) * rng.range(0.85, 1.15);
            let dir = Vec2::from_angle(heading).rotate(direction);
            (
                dir * (std::f32::consts::TAU / wavelength),
                rng.range(0.0, std::f32::consts::TAU),
            )
        });
        Self {
            config,
            direction,
            waves,
            seed,
        }
    }

    /// Gust factor in about `[-1, 1]` at ground position `xz` and `time`.
    pub fn gust(&self, xz: Vec2, time: f32) -> f32 {
        let c = &self.config;
        let sum: f32 = self
            .waves
            .iter()
            .map(|(k, phase)| {
                let omega = k.length() * c.gust_speed;
                (k.dot(xz) - omega * time + phase).sin()
            })
            .sum();
        // Sharpen the crests: gusts are short pushes on a steady background.
        let s = sum / 3.0;
        s * s.abs()
    }
}

impl WindField for Breeze {
    fn name(&self) -> &'static str {
        "breeze"
    }

    fn advance(&mut self, _time: f32, _dt: f32) {}

    fn velocity(&self, p: Vec3, time: f32) -> Vec3 {
        let c = &self.config;
        let xz = Vec2::new(p.x, p.z);
        let along = 1.0 + c.gust_strength * self.gust(xz, time);
        // Turbulence: noise advected with the mean flow, 3 m features, changing over ~1.5 s.
        let q = (xz - self.direction * c.speed * time) / 3.0;
        let t = time / 1.5;
        let n1 = value_noise(self.seed, q.x + t, q.y) * 2.0 - 1.0;
        let n2 = value_noise(self.seed ^ 0xA5A5, q.x, q.y - t) * 2.0 - 1.0;
        let across = self.direction.perp();
        let v = self.direction * c.speed * along
            + (self.direction * n1 + across * n2) * c.speed * c.turbulence;
        Vec3::new(v.x, 0.0, v.y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deterministic_and_mostly_downwind() {
        let a = Breeze::new(BreezeConfig::default(), 9);
        let b = Breeze::new(BreezeConfig::default(), 9);
        let dir = Vec2::from(BreezeConfig::default().direction).normalize();
        let mut mean = Vec2::ZERO;
        for k in 0..400 {
            let p = Vec3::new(k as f32 * 0.37 - 70.0, 0.0, k as f32 * 0.11 - 20.0);
            let t = k as f32 * 0.05;
            let v = a.velocity(p, t);
            assert_eq!(v, b.velocity(p, t));
            assert!(v.is_finite() && v.y == 0.0);
            mean += Vec2::new(v.x, v.z);
        }
        mean /= 400.0;
        assert!(mean.normalize().dot(dir) > 0.95, "mean {mean}");
        assert!(
            (mean.length() - 3.0).abs() < 1.0,
            "mean speed {}",
            mean.length()
        );
        assert_ne!(
            Breeze::new(BreezeConfig::default(), 10).velocity(Vec3::ONE, 1.0),
            a.velocity(Vec3::ONE, 1.0)
        );
    }

    #[test]
    fn gust_fronts_travel_downwind() {
        let c = BreezeConfig {
            direction: [1.0, 0.0],
            turbulence: 0.0,
            ..Default::default()
        };
        let b = Breeze::new(c.clone(), 1);
        // The gust pattern at x + speed*dt, time + dt matches the pattern at x, time.
        let (x, t, dt) = (3.0, 2.0, 0.5);
        let here = b.gust(Vec2::new(x, 0.0), t);
        let later = b.gust(Vec2::new(x + c.gust_speed * dt, 0.0), t + dt);
        assert!((here - later).abs() < 0.15, "{here} vs {later}");
    }
}

//! A steady breeze with gust fronts travelling downwind and a little turbulence.

use glam::{Vec2, Vec3};

use super::{BreezeConfig, WindField};
use crate::rng::Rng;
use crate::terrain::noise::ValueNoiseCache;

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
        self.at(time).gust(xz)
    }

    /// What every sample at `time` shares.
    fn at(&self, time: f32) -> Instant<'_> {
        let c = &self.config;
        Instant {
            breeze: self,
            waves: self.waves.map(|(k, phase)| {
                let omega = k.length() * c.gust_speed;
                (k, omega * time, phase)
            }),
            drift: self.direction * c.speed * time,
            t: time / 1.5,
        }
    }
}

/// The breeze at one time: per wave the wave vector, `ω·time` and the phase; the turbulence's
/// drift and time coordinate.
struct Instant<'a> {
    breeze: &'a Breeze,
    waves: [(Vec2, f32, f32); 3],
    drift: Vec2,
    t: f32,
}

impl Instant<'_> {
    fn gust(&self, xz: Vec2) -> f32 {
        let sum: f32 = self
            .waves
            .iter()
            .map(|&(k, omega_time, phase)| (k.dot(xz) - omega_time + phase).sin())
            .sum();
        // Sharpen the crests: gusts are short pushes on a steady background.
        let s = sum / 3.0;
        s * s.abs()
    }

    /// The velocity at `p`; `noise` caches the two turbulence noises' lattice cells.
    #[inline]
    fn velocity(&self, p: Vec3, noise: &mut [ValueNoiseCache; 2]) -> Vec3 {
        let b = self.breeze;
        let c = &b.config;
        let xz = Vec2::new(p.x, p.z);
        let along = 1.0 + c.gust_strength * self.gust(xz);
        // Turbulence: noise advected with the mean flow, 3 m features, changing over ~1.5 s.
        let q = (xz - self.drift) / 3.0;
        let t = self.t;
        let n1 = noise[0].sample(q.x + t, q.y) * 2.0 - 1.0;
        let n2 = noise[1].sample(q.x, q.y - t) * 2.0 - 1.0;
        let across = b.direction.perp();
        let v = b.direction * c.speed * along
            + (b.direction * n1 + across * n2) * c.speed * c.turbulence;
        Vec3::new(v.x, 0.0, v.y)
    }

    fn noise(&self) -> [ValueNoiseCache; 2] {
        let seed = self.breeze.seed;
        [
            ValueNoiseCache::new(seed),
            ValueNoiseCache::new(seed ^ 0xA5A5),
        ]
    }
}

impl WindField for Breeze {
    fn name(&self) -> &'static str {
        "breeze"
    }

    fn advance(&mut self, _time: f32, _dt: f32) {}

    fn velocity(&self, p: Vec3, time: f32) -> Vec3 {
        let at = self.at(time);
        at.velocity(p, &mut at.noise())
    }

    /// The same values as [`WindField::velocity`], with the per-time constants computed once
    /// and the turbulence's lattice cells remembered from point to point (nearby points, such
    /// as a blade's control points and its neighbours', mostly share them).
    fn velocities(&self, points: &[Vec3], time: f32, out: &mut [Vec3]) {
        let at = self.at(time);
        let mut noise = at.noise();
        for (o, p) in out.iter_mut().zip(points) {
            *o = at.velocity(*p, &mut noise);
        }
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
    fn batched_velocities_are_exactly_the_single_ones() {
        let b = Breeze::new(BreezeConfig::default(), 4);
        // Blade-like clusters of points, then scattered ones.
        let mut points: Vec<Vec3> = (0..3000)
            .map(|k| {
                let (blade, i) = (k / 3, k % 3);
                Vec3::new(
                    0.16 * (blade % 40) as f32 - 3.0 + 0.05 * i as f32,
                    0.2 * i as f32,
                    0.16 * (blade / 40) as f32 - 40.0,
                )
            })
            .collect();
        points.extend((0..300).map(|k| Vec3::new(k as f32 * 7.31 - 900.0, 1.0, k as f32 * -3.7)));
        for time in [0.0, 1.0 / 30.0, 7.25, 123.4] {
            let mut out = vec![Vec3::NAN; points.len()];
            b.velocities(&points, time, &mut out);
            for (p, v) in points.iter().zip(&out) {
                let single = b.velocity(*p, time);
                assert_eq!(
                    single.to_array().map(f32::to_bits),
                    v.to_array().map(f32::to_bits)
                );
            }
        }
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

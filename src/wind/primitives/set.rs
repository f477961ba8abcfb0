//! Several primitives acting at once (Sec. 3.2–3.3): their masks decide who acts where, and
//! the mixing rule combines overlapping actions.

use std::cmp::Reverse;

use glam::{Vec2, Vec3};

use super::blast::Blast;
use super::breeze::Breeze;
use super::gust::Gust;
use super::whirlwind::Whirlwind;
use super::{BlastParams, Mixing, PrimitiveConfig, PrimitivesConfig, WindSample};
use crate::object::ObjectConfig;
use crate::rng::hash;
use crate::wind::WindField;
use crate::wind::posture::Postures;
use crate::{Error, Result};

/// One built primitive.
#[derive(Clone, Debug)]
enum Primitive {
    Breeze(Breeze),
    Gust(Gust),
    Whirlwind(Whirlwind),
    Blast(Blast),
}

impl Primitive {
    fn mask(&self, xz: Vec2, time: f32) -> f32 {
        match self {
            Self::Breeze(p) => p.mask(xz, time),
            Self::Gust(p) => p.mask(xz, time),
            Self::Whirlwind(p) => p.mask(xz, time),
            Self::Blast(p) => p.mask(xz, time),
        }
    }

    fn action(&self, xz: Vec2, time: f32) -> WindSample {
        match self {
            Self::Breeze(p) => p.action(xz, time),
            Self::Gust(p) => p.action(xz, time),
            Self::Whirlwind(p) => p.action(xz, time),
            Self::Blast(p) => p.action(xz, time),
        }
    }
}

/// The scene's primitives, their blade kind's postures and the mixing rule: what receivers
/// sample ([`PrimitiveSet::sample`]) and, as a [`WindField`], what drives other techniques.
/// Stateless: a pure function of (configuration, seed, position, time).
#[derive(Clone, Debug)]
pub struct PrimitiveSet {
    mixing: Mixing,
    postures: Postures,
    /// Front to back: highest priority first; equal priorities, later in the list first.
    primitives: Vec<Primitive>,
}

impl PrimitiveSet {
    /// Validates `config`, simulates its blade kind (a few milliseconds, plus one short run
    /// per gust) and builds every primitive; `seed` drives all their oscillations; blasts with
    /// `follow_object` take `object`'s path (an error without one).
    pub fn new(
        config: &PrimitivesConfig,
        seed: u64,
        object: Option<&ObjectConfig>,
    ) -> Result<Self> {
        config.validate()?;
        let postures = Postures::new(&config.blade)?;
        let mut primitives: Vec<(i32, Primitive)> = config
            .primitives
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let seed = hash(seed ^ 0x5052_494D, &[i as i64]);
                let built = match c {
                    PrimitiveConfig::Breeze(p) => Primitive::Breeze(Breeze::new(p.clone(), seed)),
                    PrimitiveConfig::Gust(p) => {
                        Primitive::Gust(Gust::new(p.clone(), &postures, seed))
                    }
                    PrimitiveConfig::Whirlwind(p) => {
                        Primitive::Whirlwind(Whirlwind::new(p.clone(), seed))
                    }
                    PrimitiveConfig::Blast(p) if p.follow_object => {
                        let o = object.ok_or_else(|| {
                            Error::param(
                                format!("wind.primitives[{i}].follow_object"),
                                true,
                                "an [object] in the scene for the blast to follow, or follow_object = false",
                            )
                        })?;
                        Primitive::Blast(Blast::new(
                            BlastParams {
                                start: o.start,
                                velocity: o.velocity,
                                keyframes: o.keyframes.clone(),
                                ..p.clone()
                            },
                            seed,
                        ))
                    }
                    PrimitiveConfig::Blast(p) => Primitive::Blast(Blast::new(p.clone(), seed)),
                };
                Ok((c.priority(), built))
            })
            .collect::<Result<_>>()?;
        primitives.reverse();
        primitives.sort_by_key(|(priority, _)| Reverse(*priority));
        Ok(Self {
            mixing: config.mixing,
            postures,
            primitives: primitives.into_iter().map(|(_, p)| p).collect(),
        })
    }

    /// Direction and posture index at ground point `xz` (x, z) and `time` (s);
    /// [`WindSample::REST`] where no mask covers.
    ///
    /// Priority mixing layers the actions front to back with the masks as opacities (with
    /// masks of 0 or 1: the highest-priority covering primitive alone); sum mixing adds the
    /// vectors weighted by mask values and clamps the index to 1. The result's direction stays
    /// on the side of the dominant primitive's direction (the top one, or the one with the
    /// largest mask), the index carrying the sign, so one primitive acting alone is returned
    /// as it is, backswing included.
    pub fn sample(&self, xz: Vec2, time: f32) -> WindSample {
        let mut v = Vec2::ZERO;
        let mut dominant: Option<(f32, Vec2)> = None;
        let mut through = 1.0;
        for p in &self.primitives {
            let m = p.mask(xz, time);
            if m.is_nan() || m <= 0.0 {
                continue;
            }
            let s = p.action(xz, time);
            match self.mixing {
                Mixing::Priority => {
                    dominant.get_or_insert((m, s.direction));
                    v += s.vector() * (m * through);
                    through *= 1.0 - m;
                    if through <= 0.0 {
                        break;
                    }
                }
                Mixing::Sum => {
                    if dominant.is_none_or(|(best, _)| m > best) {
                        dominant = Some((m, s.direction));
                    }
                    v += s.vector() * m;
                }
            }
        }
        let Some((_, reference)) = dominant else {
            return WindSample::REST;
        };
        let length = v.length();
        if length.is_nan() || length <= 1e-7 {
            return WindSample {
                direction: reference,
                posture: 0.0,
            };
        }
        let direction = v / length;
        let posture = length.min(1.0);
        if direction.dot(reference) >= 0.0 {
            WindSample { direction, posture }
        } else {
            WindSample {
                direction: -direction,
                posture: -posture,
            }
        }
    }

    /// The postures of the blade kind (what a receiver turns an index into).
    pub fn postures(&self) -> &Postures {
        &self.postures
    }

    /// Wind speed (m/s) that a posture index of 1 stands for in [`WindField::velocity`]: the
    /// blade kind's `wind_speed`.
    pub fn reference_speed(&self) -> f32 {
        self.postures.config().wind_speed
    }
}

impl WindField for PrimitiveSet {
    fn name(&self) -> &'static str {
        "primitives"
    }

    fn advance(&mut self, _time: f32, _dt: f32) {}

    /// Horizontal velocity `direction × index × reference_speed` at `p`'s ground point: the
    /// steady wind that would hold a blade near that posture (negative indices, a blade
    /// swinging back, point against the direction). Zero where no mask covers.
    fn velocity(&self, p: Vec3, time: f32) -> Vec3 {
        let v = self.sample(Vec2::new(p.x, p.z), time).vector() * self.reference_speed();
        Vec3::new(v.x, 0.0, v.y)
    }
}

#[cfg(test)]
mod tests {
    use super::super::{BlastParams, BreezeParams, GustParams, JitterParams, WhirlwindParams};
    use super::*;

    fn calm_breeze() -> PrimitiveConfig {
        PrimitiveConfig::Breeze(BreezeParams {
            priority: 0,
            direction: [1.0, 0.0],
            bend: 0.3,
            drift_angle: 0.0,
            drift_bend: 0.0,
            jitter: JitterParams::NONE,
            ..Default::default()
        })
    }

    fn still_whirlwind(priority: i32) -> PrimitiveConfig {
        PrimitiveConfig::Whirlwind(WhirlwindParams {
            priority,
            centre: [0.0, 0.0],
            velocity: [0.0, 0.0],
            radius: 10.0,
            strength: 0.9,
            swirl: 0.0,
            feather: 0.0,
            jitter: JitterParams::NONE,
            ..Default::default()
        })
    }

    fn set(mixing: Mixing, primitives: Vec<PrimitiveConfig>) -> PrimitiveSet {
        let config = PrimitivesConfig {
            mixing,
            primitives,
            ..Default::default()
        };
        PrimitiveSet::new(&config, 11, None).unwrap()
    }

    fn close(a: WindSample, b: WindSample) -> bool {
        a.direction.distance(b.direction) < 1e-5 && (a.posture - b.posture).abs() < 1e-5
    }

    #[test]
    fn priority_picks_the_higher_priority_where_masks_overlap() {
        let inside = Vec2::new(5.0, 0.0);
        let outside = Vec2::new(30.0, 0.0);
        let whirl = WindSample {
            direction: Vec2::Y,
            posture: 0.45,
        };
        let breeze = WindSample {
            direction: Vec2::X,
            posture: 0.3,
        };
        let s = set(Mixing::Priority, vec![calm_breeze(), still_whirlwind(2)]);
        assert!(
            close(s.sample(inside, 1.0), whirl),
            "{:?}",
            s.sample(inside, 1.0)
        );
        assert!(close(s.sample(outside, 1.0), breeze));
        // The list order does not matter, the priority does.
        let s = set(Mixing::Priority, vec![still_whirlwind(2), calm_breeze()]);
        assert!(close(s.sample(inside, 1.0), whirl));
        let s = set(Mixing::Priority, vec![still_whirlwind(-1), calm_breeze()]);
        assert!(close(s.sample(inside, 1.0), breeze));
        // Equal priorities: the later one is on top.
        let s = set(Mixing::Priority, vec![still_whirlwind(0), calm_breeze()]);
        assert!(close(s.sample(inside, 1.0), breeze));
        let s = set(Mixing::Priority, vec![calm_breeze(), still_whirlwind(0)]);
        assert!(close(s.sample(inside, 1.0), whirl));
    }

    #[test]
    fn sum_blends_by_mask_values() {
        let s = set(Mixing::Sum, vec![calm_breeze(), still_whirlwind(2)]);
        let got = s.sample(Vec2::new(5.0, 0.0), 1.0);
        let expected = Vec2::new(0.3, 0.45);
        assert!((got.posture - expected.length()).abs() < 1e-5, "{got:?}");
        assert!(
            got.direction.distance(expected.normalize()) < 1e-5,
            "{got:?}"
        );
        // Opposite directions partly cancel; the sign follows the dominant one.
        let got = s.sample(Vec2::new(0.0, 5.0), 1.0);
        assert!(close(
            got,
            WindSample {
                direction: -Vec2::X,
                posture: 0.15
            }
        ));
        assert!(close(
            s.sample(Vec2::new(30.0, 0.0), 1.0),
            WindSample {
                direction: Vec2::X,
                posture: 0.3
            }
        ));
    }

    #[test]
    fn a_lone_backswing_keeps_its_sign() {
        let gust = PrimitiveConfig::Gust(GustParams {
            direction: [1.0, 0.0],
            origin: [0.0, 0.0],
            interval: None,
            jitter: JitterParams::NONE,
            ..Default::default()
        });
        let s = set(Mixing::Priority, vec![gust]);
        let after = (0..400)
            .map(|i| s.sample(Vec2::ZERO, 1.5 + i as f32 * 0.01))
            .find(|w| w.posture < -0.2)
            .unwrap();
        assert_eq!(after.direction, Vec2::X);
    }

    fn everything() -> PrimitivesConfig {
        PrimitivesConfig {
            mixing: Mixing::Priority,
            primitives: vec![
                PrimitiveConfig::Breeze(BreezeParams::default()),
                PrimitiveConfig::Gust(GustParams::default()),
                PrimitiveConfig::Whirlwind(WhirlwindParams::default()),
                PrimitiveConfig::Blast(BlastParams::default()),
            ],
            ..Default::default()
        }
    }

    #[test]
    fn deterministic_for_a_seed_and_finite() {
        for mixing in [Mixing::Priority, Mixing::Sum] {
            let config = PrimitivesConfig {
                mixing,
                ..everything()
            };
            let a = PrimitiveSet::new(&config, 5, None).unwrap();
            let b = PrimitiveSet::new(&config, 5, None).unwrap();
            let c = PrimitiveSet::new(&config, 6, None).unwrap();
            let mut differs = false;
            for k in 0..2000 {
                let p = Vec3::new(
                    (k % 50) as f32 * 1.7 - 40.0,
                    0.3,
                    (k / 50) as f32 * 2.1 - 40.0,
                );
                let t = k as f32 * 0.013;
                let v = a.velocity(p, t);
                assert!(v.is_finite() && v.y == 0.0, "{v}");
                assert!(v.length() <= a.reference_speed() * 1.0001);
                assert_eq!(v, b.velocity(p, t));
                differs |= v != c.velocity(p, t);
                let s = a.sample(Vec2::new(p.x, p.z), t);
                assert!(s.direction.is_normalized() && s.posture.abs() <= 1.0);
            }
            assert!(differs);
        }
    }

    #[test]
    fn no_wind_where_no_mask_covers() {
        let s = set(Mixing::Priority, vec![still_whirlwind(0)]);
        assert_eq!(s.velocity(Vec3::new(20.0, 0.0, 0.0), 1.0), Vec3::ZERO);
        assert_eq!(s.sample(Vec2::new(20.0, 0.0), 1.0), WindSample::REST);
        // The very centre: finite, and a direction.
        let v = s.velocity(Vec3::ZERO, 1.0);
        assert!(v.is_finite() && v.length() > 0.0);
        assert!(s.velocity(Vec3::new(3.0, 0.0, 0.0), 1.0).length() > 0.0);
        assert_eq!(s.name(), "primitives");
    }
}

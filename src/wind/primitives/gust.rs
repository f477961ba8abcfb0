//! The gust of wind primitive (Perbet & Cani 2001, Sec. 3.3, Fig. 7–9): a strip-shaped mask
//! translating over the terrain perpendicular to its main axis; the posture index inside is
//! the pre-computed response of Fig. 8 read along the strip, since "blades of grass that are at
//! the front of the gust are just starting their motion, while those at its far end are just
//! finishing their oscillation, back at their rest position".

use glam::Vec2;

use super::jitter::Jitter;
use super::{GustParams, WindSample};
use crate::wind::posture::{Postures, ResponseCurve};

/// A gust: fronts perpendicular to `direction` pass `origin` at `start` (and every `interval`
/// after it, if set) and travel at `speed`. A point the front crossed `τ` seconds ago reads the
/// response curve at `τ`; the mask covers `0 ≤ τ ≤` the curve's duration (the windy width plus
/// the tail in which blades settle), softened at the strip's ends if it has a length.
#[derive(Clone, Debug)]
pub(super) struct Gust {
    params: GustParams,
    direction: Vec2,
    response: ResponseCurve,
    jitter: Jitter,
}

impl Gust {
    /// A gust whose blades respond like `postures`' blade to a wind of `width / speed` s.
    pub(super) fn new(params: GustParams, postures: &Postures, seed: u64) -> Self {
        Self {
            direction: Vec2::from(params.direction).normalize_or(Vec2::X),
            response: postures.response_for(params.width / params.speed),
            jitter: Jitter::new(params.jitter, seed ^ 0x4A49),
            params,
        }
    }

    /// Signed distance (m) along `direction` from `origin` to the most recent front at `time`
    /// (`speed · (time − start)` for a single gust; negative before it reaches `origin`).
    #[cfg(test)]
    pub(super) fn front(&self, time: f32) -> f32 {
        let p = &self.params;
        let mut since = time - p.start;
        if let Some(interval) = p.interval
            && since > 0.0
        {
            since = since.rem_euclid(interval);
        }
        p.speed * since
    }

    /// Seconds since the most recent front crossed `xz` (negative: not yet).
    fn since_front(&self, xz: Vec2, time: f32) -> f32 {
        let p = &self.params;
        let along = (xz - Vec2::from(p.origin)).dot(self.direction);
        let since = time - p.start - along / p.speed;
        match p.interval {
            Some(interval) if since > 0.0 => since.rem_euclid(interval),
            _ => since,
        }
    }

    pub(super) fn mask(&self, xz: Vec2, time: f32) -> f32 {
        let since = self.since_front(xz, time);
        if !(0.0..=self.response.duration()).contains(&since) {
            return 0.0;
        }
        let p = &self.params;
        match p.length {
            None => 1.0,
            Some(length) => {
                let across = (xz - Vec2::from(p.origin)).dot(self.direction.perp()).abs();
                let half = 0.5 * length;
                if p.feather <= 0.0 {
                    f32::from(across <= half)
                } else {
                    1.0 - smoothstep(half - p.feather, half, across)
                }
            }
        }
    }

    pub(super) fn action(&self, xz: Vec2, time: f32) -> WindSample {
        let since = self.since_front(xz, time);
        let prescribed = WindSample {
            direction: self.direction,
            posture: self.params.strength * self.response.index_at(since),
        };
        self.jitter.apply(prescribed, xz, time)
    }
}

/// Hermite step from 0 at `a` to 1 at `b`.
pub(super) fn smoothstep(a: f32, b: f32, x: f32) -> f32 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

#[cfg(test)]
mod tests {
    use super::super::JitterParams;
    use super::*;
    use crate::wind::posture::BladeConfig;

    fn gust(params: GustParams) -> Gust {
        Gust::new(params, &Postures::new(&BladeConfig::default()).unwrap(), 1)
    }

    /// The leading edge of the mask along the x axis at `time`, found by scanning.
    fn leading_edge(g: &Gust, time: f32) -> f32 {
        (0..20_000)
            .map(|i| 100.0 - i as f32 * 0.01)
            .find(|&x| g.mask(Vec2::new(x, 0.0), time) > 0.0)
            .unwrap()
    }

    #[test]
    fn the_strip_moves_at_its_speed() {
        let g = gust(GustParams {
            direction: [1.0, 0.0],
            origin: [-50.0, 0.0],
            speed: 7.0,
            interval: None,
            ..Default::default()
        });
        let (t1, t2) = (2.0, 5.5);
        assert!((g.front(t2) - g.front(t1) - 7.0 * (t2 - t1)).abs() < 1e-4);
        let (e1, e2) = (leading_edge(&g, t1), leading_edge(&g, t2));
        assert!((e1 - (-50.0 + 7.0 * t1)).abs() < 0.02, "{e1}");
        assert!((e2 - e1 - 7.0 * (t2 - t1)).abs() < 0.03, "{e1} {e2}");
        // Ahead of the front: nothing; far behind it: settled and uncovered.
        assert_eq!(g.mask(Vec2::new(e2 + 1.0, 0.0), t2), 0.0);
        let tail = g.response.duration() * 7.0;
        assert_eq!(g.mask(Vec2::new(e2 - tail - 1.0, 3.0), t2), 0.0);
        assert_eq!(g.mask(Vec2::new(e2 - 1.0, 300.0), t2), 1.0);
    }

    #[test]
    fn posture_along_the_strip_is_the_response() {
        let g = gust(GustParams {
            direction: [0.0, 1.0],
            origin: [0.0, 0.0],
            speed: 10.0,
            width: 20.0,
            interval: None,
            jitter: JitterParams::NONE,
            ..Default::default()
        });
        // At t = 3 the front is at z = 30: a point 10 m behind it felt the wind for 1 s.
        let s = g.action(Vec2::new(4.0, 20.0), 3.0);
        assert_eq!(s.direction, Vec2::Y);
        assert!((s.posture - g.response.index_at(1.0)).abs() < 1e-6);
        assert!(s.posture > 0.3);
        assert!(g.action(Vec2::new(0.0, 29.99), 3.0).posture.abs() < 0.01);
    }

    #[test]
    fn finite_strips_fade_at_their_ends_and_gusts_repeat() {
        let g = gust(GustParams {
            direction: [1.0, 0.0],
            origin: [0.0, 0.0],
            length: Some(20.0),
            feather: 2.0,
            interval: Some(30.0),
            ..Default::default()
        });
        let t = 1.0;
        assert_eq!(g.mask(Vec2::new(4.0, 0.0), t), 1.0);
        let edge = g.mask(Vec2::new(4.0, 9.0), t);
        assert!(edge > 0.0 && edge < 1.0, "{edge}");
        assert_eq!(g.mask(Vec2::new(4.0, 10.5), t), 0.0);
        assert_eq!(g.mask(Vec2::new(4.0, 0.0), t + 30.0), 1.0);
        assert!((g.front(t + 30.0) - g.front(t)).abs() < 1e-3);
    }
}

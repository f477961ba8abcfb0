//! The scene's blades as the compute pass reads them: one structure of arrays, each entry a
//! `vec4<f32>` (so no array passes the adapter's storage-binding limit before 8.4 M blades on
//! lavapipe's 128 MiB, where one 48-byte record would at 2.8 M).
//!
//! The paper packs a blade in four `vec4`s: `v0` + orientation, `v1` + height, `v2` + width,
//! `up` + stiffness. Here `v1` and `v2` are the simulated state (two copies, read one frame and
//! written the next); the up vector is the world's vertical for every blade, so its `vec4`
//! holds the rest tip instead; height, width and the colour variation share a third.

use grassbench::glam::{Vec2, Vec3};
use grassbench::grass::Blade;

use crate::sim::{self, BladeRest, UP};

/// Per-blade arrays, in the scene's blade order (the order `reference` draws them in).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BladeArrays {
    /// Root xyz; w: orientation (the angle of the width direction around the vertical).
    pub v0: Vec<[f32; 4]>,
    /// Rest tip xyz; w: stiffness.
    pub rest: Vec<[f32; 4]>,
    /// Height, width, colour variation, the blade's index in the scene (exact as an `f32`
    /// up to [`MAX_BLADES`]: the hashes that pick its distance bucket and whether the far
    /// level keeps it take this index, so they stay the scene's in any order).
    pub looks: Vec<[f32; 4]>,
}

/// The most blades whose scene indices an `f32` holds exactly (2^24).
pub const MAX_BLADES: usize = 1 << 24;

impl BladeArrays {
    /// The arrays of `blades`, in their order.
    pub fn new(blades: &[Blade]) -> Self {
        let order: Vec<u32> = (0..blades.len() as u32).collect();
        Self::in_order(blades, &order)
    }

    /// The arrays of the scene's `blades` taken in `order` (scene indices; each entry keeps
    /// its scene index in `looks`).
    pub fn in_order(blades: &[Blade], order: &[u32]) -> Self {
        let mut out = Self {
            v0: Vec::with_capacity(order.len()),
            rest: Vec::with_capacity(order.len()),
            looks: Vec::with_capacity(order.len()),
        };
        for &id in order {
            let Some(b) = blades.get(id as usize) else {
                continue;
            };
            out.v0.push(b.root.extend(b.facing).to_array());
            out.rest.push(rest_tip(b).extend(b.stiffness).to_array());
            out.looks.push([b.height, b.width, b.variation, id as f32]);
        }
        out
    }

    /// Blades held.
    pub fn len(&self) -> usize {
        self.v0.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.v0.is_empty()
    }

    /// What the simulation reads of blade `i` (for CPU mirrors and tests).
    pub fn rest_of(&self, i: usize) -> Option<BladeRest> {
        let (v0, rest, looks) = (self.v0.get(i)?, self.rest.get(i)?, self.looks.get(i)?);
        Some(BladeRest {
            v0: Vec3::new(v0[0], v0[1], v0[2]),
            orientation: v0[3],
            rest_tip: Vec3::new(rest[0], rest[1], rest[2]),
            stiffness: rest[3],
            height: looks[0],
        })
    }
}

/// Segments of `reference`'s blade walk (its default `segments`).
const REFERENCE_SEGMENTS: u32 = 5;
/// `reference`'s tilt profile exponent (its default `bend_profile`).
const REFERENCE_PROFILE: f32 = 1.5;
/// `reference`'s largest bend (its default `max_bend`).
const REFERENCE_MAX_BEND: f32 = 1.4;

/// Where `reference` puts the blade's tip in calm air: its rest lean walked up the blade in
/// segments of equal length tilted by `θ(s) = φ·s^p` (the reference's model, Bakay Sec. 3), so
/// in calm air the two techniques' blades end at the same point.
pub fn rest_tip(blade: &Blade) -> Vec3 {
    let lean = blade.lean.y * Vec2::new(blade.lean.x.cos(), blade.lean.x.sin());
    let amount = lean.length();
    let bend = amount.min(REFERENCE_MAX_BEND);
    let dir2 = if amount > 1e-5 {
        lean / amount
    } else {
        Vec2::X
    };
    let dir = Vec3::new(dir2.x, 0.0, dir2.y);
    let n = REFERENCE_SEGMENTS;
    let seg = blade.height / n as f32;
    let mut p = blade.root;
    for i in 0..n {
        let a = bend * ((i as f32 + 0.5) / n as f32).powf(REFERENCE_PROFILE);
        p += (dir * a.sin() + UP * a.cos()) * seg;
    }
    p
}

/// The curve a blade starts from: its rest tip, validated (Sec. 5.2) into a full curve.
pub fn rest_curve(rest: &BladeRest) -> sim::Curve {
    let v1 = sim::place_v1(rest.v0, rest.rest_tip, rest.height);
    sim::correct_length(rest.v0, v1, rest.rest_tip, rest.height)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn blade(lean: Vec2) -> Blade {
        Blade {
            root: Vec3::new(3.0, 1.0, -2.0),
            facing: 0.4,
            height: 0.5,
            width: 0.02,
            stiffness: 1.1,
            lean,
            variation: 0.3,
            threshold: 0.2,
        }
    }

    #[test]
    fn the_rest_tip_is_the_blade_height_away_and_leans_its_way() {
        let upright = blade(Vec2::new(1.0, 0.0));
        assert!((rest_tip(&upright) - (upright.root + UP * 0.5)).length() < 1e-6);
        let leaning = blade(Vec2::new(0.0, 0.6));
        let tip = rest_tip(&leaning);
        // The walk keeps each segment's length: the chord is a little under the height.
        let chord = tip.distance(leaning.root);
        assert!(chord < 0.5 && chord > 0.45, "{chord}");
        // It leans along +x (lean direction 0) and nowhere else.
        assert!(tip.x > leaning.root.x + 0.05 && (tip.z - leaning.root.z).abs() < 1e-6);
    }

    #[test]
    fn arrays_keep_the_population_in_order() {
        let blades = [blade(Vec2::new(0.0, 0.2)), blade(Vec2::new(2.0, 0.4))];
        let a = BladeArrays::new(&blades);
        assert_eq!(a.len(), 2);
        let r = a.rest_of(1).unwrap();
        assert_eq!(r.v0, blades[1].root);
        assert_eq!(r.orientation, blades[1].facing);
        assert_eq!(r.stiffness, blades[1].stiffness);
        assert_eq!(r.rest_tip, rest_tip(&blades[1]));
        assert!(a.rest_of(2).is_none());
        // In another order each entry keeps its scene index.
        let b = BladeArrays::in_order(&blades, &[1, 0]);
        assert_eq!(b.looks[0][3], 1.0);
        assert_eq!(b.v0[0], a.v0[1]);
        assert_eq!(a.looks[1][3], 1.0);
    }
}

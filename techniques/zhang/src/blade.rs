//! One blade of near grass (Sec. 3.1.1 and 3.2): four control points, the cubic Bezier
//! backbone (Eq. 5), Verlet integration (Eq. 7), the bottom-up length constraints (Sec. 3.2.4)
//! and the rotation of the segment points towards the wind (Sec. 3.2.5).

use grassbench::glam::{Vec2, Vec3};

/// Control points per blade (Sec. 3.1.1).
pub const CONTROL_POINTS: usize = 4;

/// Relative length error the constraint leaves alone (f32 rounding of the rest pose).
pub const CONSTRAINT_SLACK: f32 = 1e-6;

/// The length error below which a constraint leaves a point alone: `CONSTRAINT_SLACK` of the
/// length plus a few ulps of the coordinates (far from the origin f32 cannot place a point at
/// an exact distance; correcting ulp errors would keep a resting blade jittering).
pub fn slack(length: f32, a: Vec3, b: Vec3) -> f32 {
    CONSTRAINT_SLACK * length
        + 8.0 * f32::EPSILON * a.abs().max_element().max(b.abs().max_element())
}

/// A point on the backbone: the cubic Bezier curve of Eq. (5),
/// `p = P0(1−t)³ + 3P1t(1−t)² + 3P2t²(1−t) + P3t³`. The twin of `bezier` in
/// `shaders/blade.wgsl`, which the vertex shader draws with (tests/tests/twins.rs compares
/// the two).
pub fn bezier(p: &[Vec3; CONTROL_POINTS], t: f32) -> Vec3 {
    let s = 1.0 - t;
    p[0] * (s * s * s) + p[1] * (3.0 * t * s * s) + p[2] * (3.0 * t * t * s) + p[3] * (t * t * t)
}

/// The derivative `dp/dt` of Eq. (5),
/// `3(1−t)²(P1 − P0) + 6(1−t)t(P2 − P1) + 3t²(P3 − P2)`: the backbone's direction, which
/// the vertex shader turns into the blade's face normal. The twin of `bezier_tangent` in
/// `shaders/blade.wgsl`.
pub fn bezier_tangent(p: &[Vec3; CONTROL_POINTS], t: f32) -> Vec3 {
    let s = 1.0 - t;
    3.0 * s * s * (p[1] - p[0]) + 6.0 * s * t * (p[2] - p[1]) + 3.0 * t * t * (p[3] - p[2])
}

/// The constants of one animation step, shared by every blade and flower.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dynamics {
    /// Time step, s.
    pub dt: f32,
    /// Wind acceleration per m/s of wind per metre of blade height, 1/s.
    pub wind_response: f32,
    /// Pull back to the rest pose, 1/s² (times the blade's stiffness).
    pub spring: f32,
    /// `exp(−damping · dt)`: the fraction of last step's motion the Verlet step keeps.
    pub keep: f32,
}

impl Dynamics {
    /// The constants for a step of `dt` seconds.
    pub fn new(dt: f32, wind_response: f32, spring: f32, damping: f32) -> Self {
        Self {
            dt,
            wind_response,
            spring,
            keep: (-damping * dt).exp(),
        }
    }
}

/// A blade's animated state. `pos[0]` is the root: its inverse mass is 0 (Sec. 3.4), so no
/// step ever moves it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BladeState {
    /// Current control points `P0..P3`.
    pub pos: [Vec3; CONTROL_POINTS],
    /// Control points one step ago (`x''` of Eq. 7).
    pub old: [Vec3; CONTROL_POINTS],
    /// Rest pose (the blade's lean without wind).
    pub rest: [Vec3; CONTROL_POINTS],
    /// Length of each of the three control-polygon segments (`initSegmentLength` of
    /// Sec. 3.2.4: height / 3).
    pub segment: f32,
    /// Blade height, m.
    pub height: f32,
    /// Stiffness (1 = typical): scales the pull back to rest.
    pub stiffness: f32,
    /// Inverse mass of the moving control points (1 for a blade).
    pub inv_mass: f32,
    /// Direction of the width axis (the two bottom segment points), radians around y.
    pub facing: f32,
}

impl BladeState {
    /// A blade of `height` at `root`, leaning by `lean` radians towards direction `lean_dir`
    /// (radians around y) at rest: the control polygon is three segments of `height / 3` on a
    /// circular arc whose tilt grows linearly along the blade.
    pub fn new(
        root: Vec3,
        height: f32,
        facing: f32,
        lean_dir: f32,
        lean: f32,
        stiffness: f32,
    ) -> Self {
        let segment = height / 3.0;
        let dir = Vec3::new(lean_dir.cos(), 0.0, lean_dir.sin());
        let mut rest = [root; CONTROL_POINTS];
        for i in 1..CONTROL_POINTS {
            let tilt = lean * (i as f32 - 0.5) / 3.0;
            rest[i] = rest[i - 1] + (dir * tilt.sin() + Vec3::Y * tilt.cos()) * segment;
        }
        Self {
            pos: rest,
            old: rest,
            rest,
            segment,
            height,
            stiffness,
            inv_mass: 1.0,
            facing,
        }
    }

    /// One animation step: Verlet (Eq. 7) for `P1..P3` with the wind `wind[i − 1]` at `P_i`,
    /// then the length constraints bottom-up, keeping every point at or above the root's
    /// height `ground`.
    ///
    /// Acceleration `a = inv_mass · wind_response · height · w + spring · stiffness ·
    /// (rest − x)`; the step is `x' = x + keep·(x − x'') + a·dt²` (Eq. 7 with damping
    /// `keep = 1` is exactly the thesis' step). Like the thesis' `abs(y)`, a point pushed under
    /// the ground is reflected back above it.
    #[inline]
    pub fn step(&mut self, wind: &[Vec3; 3], k: &Dynamics, ground: f32) {
        let push = k.wind_response * self.height * self.inv_mass;
        let pull = k.spring * self.stiffness;
        let dt2 = k.dt * k.dt;
        for i in 1..CONTROL_POINTS {
            let x = self.pos[i];
            let a = wind[i - 1] * push + (self.rest[i] - x) * pull;
            let mut next = x + (x - self.old[i]) * k.keep + a * dt2;
            if next.y < ground {
                next.y = 2.0 * ground - next.y;
            }
            self.old[i] = x;
            self.pos[i] = next;
        }
        self.constrain(ground);
    }

    /// Sec. 3.2.4, bottom-up: each `P_i` moves along `P_i − P_{i−1}` back to distance
    /// `segment` from `P_{i−1}` (the thesis' `m_backbonePos[index] -= delta * diff`). If that
    /// leaves it under the ground it is moved, at the same distance, onto the ground plane in
    /// the same horizontal direction, so lengths hold exactly and no point goes under.
    #[inline]
    pub fn constrain(&mut self, ground: f32) {
        for i in 1..CONTROL_POINTS {
            let prev = self.pos[i - 1];
            let delta = self.pos[i] - prev;
            let len = delta.length();
            let mut p = if (len - self.segment).abs() <= slack(self.segment, prev, self.pos[i]) {
                // Already at length (to rounding): leave it, so a blade at rest stays
                // bit-for-bit at rest instead of jittering by an ulp per step.
                self.pos[i]
            } else if len > 1e-9 {
                self.pos[i] - delta * ((len - self.segment) / len)
            } else {
                prev + Vec3::Y * self.segment
            };
            if p.y < ground {
                let rise = (prev.y - ground).clamp(0.0, self.segment);
                let flat = Vec2::new(delta.x, delta.z).normalize_or(Vec2::X);
                let r = (self.segment * self.segment - rise * rise).max(0.0).sqrt();
                p = Vec3::new(prev.x + flat.x * r, ground, prev.z + flat.y * r);
            }
            self.pos[i] = p;
        }
    }

    /// Sec. 6.2, sphere-plant interaction, after a step: for a plant whose root lies inside the
    /// ground circle of the sphere (`centre`, `radius`), the first backbone point inside the
    /// sphere (from the bottom) is moved out to the sphere's surface along the ray from the
    /// centre, the length constraint of Sec. 3.2.4 brings it back to one segment from the point
    /// below, and the points above continue in that segment's direction, so the blade leans
    /// tangent to the sphere. Where that direction would leave a point inside the sphere or
    /// under the ground (a blade right under the centre: the thesis' push is straight down
    /// there), the rest of the blade points away from the centre instead, laid along the
    /// ground if that is down. Moved points lose their velocity (their previous positions are
    /// set to the new ones): the blade is held, and springs back once the sphere has passed.
    /// Returns whether the blade was touched.
    pub fn interact(&mut self, centre: Vec3, radius: f32, ground: f32) -> bool {
        let root = self.pos[0];
        if Vec2::new(root.x - centre.x, root.z - centre.z).length() > radius {
            return false;
        }
        let Some(i) = (1..CONTROL_POINTS).find(|&i| self.pos[i].distance(centre) < radius) else {
            return false;
        };
        let below = self.pos[i - 1];
        let out = centre + (self.pos[i] - centre).normalize_or(Vec3::Y) * radius;
        let remaining = (CONTROL_POINTS - i) as f32;
        let clear = |d: Vec3| {
            (1..=CONTROL_POINTS - i).all(|k| {
                (below + d * (self.segment * k as f32)).distance(centre) >= radius * (1.0 - 1e-5)
            }) && below.y + d.y * self.segment * remaining >= ground
        };
        let mut direction = (out - below).normalize_or(Vec3::Y);
        if !clear(direction) {
            let away = (below - centre).normalize_or(Vec3::Y);
            direction = if away.y >= 0.0 {
                away
            } else {
                Vec3::new(away.x, 0.0, away.z).normalize_or(Vec3::X)
            };
        }
        for j in i..CONTROL_POINTS {
            self.pos[j] = self.pos[j - 1] + direction * self.segment;
            self.old[j] = self.pos[j];
        }
        true
    }

    /// Sec. 3.2.5: the rotation θ (radians around y) of the top segment points, so that the
    /// blade's width axis ends up perpendicular to the "wind direction" (the horizontal
    /// direction from the bottom backbone point `P0` to the top one `P3`); the segment points
    /// of backbone point `i` of `n` turn by `θ·i/(n−1)` (done in the vertex shader).
    ///
    /// The thesis takes `θ = acos(wind · blade)`; a width axis perpendicular to the wind needs
    /// the complementary angle, and we take the signed angle to the nearer perpendicular
    /// (|θ| ≤ π/2). Blades that barely bend (tip displaced less than 10 % of the height) fade
    /// the rotation in linearly, so a blade standing upright does not spin as the direction
    /// of a tiny displacement flips.
    pub fn rotation(&self) -> f32 {
        let d = self.pos[3] - self.pos[0];
        let flat = Vec2::new(d.x, d.z);
        let len = flat.length();
        if len < 1e-6 {
            return 0.0;
        }
        let wind = flat / len;
        let blade = Vec2::from_angle(self.facing);
        let perp = wind.perp();
        let target = if blade.dot(perp) >= 0.0 { perp } else { -perp };
        let theta = blade.angle_to(target);
        theta * (len / (0.1 * self.height)).min(1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn dynamics() -> Dynamics {
        Dynamics::new(1.0 / 30.0, 5.0, 40.0, 4.0)
    }

    fn vec3() -> impl Strategy<Value = Vec3> {
        (-20.0f32..20.0, -5.0f32..5.0, -20.0f32..20.0).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    proptest! {
        /// Sec. 6.2: a sphere over a blade pushes it out: its points end outside the sphere,
        /// every segment keeps its length, the root stays, and nothing goes underground.
        #[test]
        fn a_blade_pushed_by_the_sphere_ends_outside_it_with_its_lengths(
            h in 0.2f32..1.0,
            lean in 0.0f32..0.8,
            lean_dir in 0.0f32..6.3,
            offset in (-0.9f32..0.9, -0.9f32..0.9),
            radius in 0.2f32..1.0,
            lift in 0.0f32..0.8,
        ) {
            let root = Vec3::new(2.0, 1.0, -1.0);
            let mut b = BladeState::new(root, h, 0.3, lean_dir, lean, 1.0);
            // The sphere's bottom `lift · h` above the ground, its centre within its own
            // radius of the root horizontally.
            let centre = root
                + Vec3::new(offset.0 * radius, lift * h + radius, offset.1 * radius);
            let touched = b.interact(centre, radius, root.y);
            prop_assert_eq!(b.pos[0], root);
            for i in 1..CONTROL_POINTS {
                let l = (b.pos[i] - b.pos[i - 1]).length();
                prop_assert!((l - b.segment).abs() < 1e-4, "segment {} = {} vs {}", i, l, b.segment);
                prop_assert!(b.pos[i].y >= root.y - 1e-5);
            }
            if touched {
                for p in &b.pos[1..] {
                    prop_assert!(p.distance(centre) >= radius - 1e-3 * radius.max(h), "{p} inside");
                }
            }
        }

        /// Eq. (5) passes through P0 at t = 0 and P3 at t = 1.
        #[test]
        fn bezier_passes_through_end_points(a in vec3(), b in vec3(), c in vec3(), d in vec3()) {
            let p = [a, b, c, d];
            prop_assert!((bezier(&p, 0.0) - a).length() < 1e-5);
            prop_assert!((bezier(&p, 1.0) - d).length() < 1e-4);
        }

        /// Between its end points the backbone is the thesis' cubic in Bernstein form,
        /// `Σ C(3, i) tⁱ (1 − t)³⁻ⁱ P_i` (Eq. 5), evaluated here in f64 with the binomial
        /// coefficients computed, and its tangent is that polynomial's derivative (central
        /// differences of it).
        #[test]
        fn bezier_is_the_bernstein_cubic_between_its_end_points(
            a in vec3(), b in vec3(), c in vec3(), d in vec3(), t in 0.01f32..0.99,
        ) {
            let p = [a, b, c, d];
            let bernstein = |t: f64| {
                let mut sum = [0.0f64; 3];
                for (i, point) in p.iter().enumerate() {
                    let binomial = (0..i).fold(1.0, |c, k| c * (3 - k) as f64 / (k + 1) as f64);
                    let weight = binomial * t.powi(i as i32) * (1.0 - t).powi(3 - i as i32);
                    for (s, x) in sum.iter_mut().zip(point.to_array()) {
                        *s += weight * f64::from(x);
                    }
                }
                sum
            };
            let t64 = f64::from(t);
            let expected = bernstein(t64);
            let got = bezier(&p, t).to_array();
            // f32 evaluation of coordinates up to 20 m (an ulp is 1.9e-6 m): measured 2.6e-6 m
            // over 256 cases; limit about ten ulps. P1 and P2 swapped is off by metres.
            for k in 0..3 {
                prop_assert!((f64::from(got[k]) - expected[k]).abs() < 2e-5, "t {t}: {got:?} vs {expected:?}");
            }
            let h = 1e-4;
            let (above, below) = (bernstein(t64 + h), bernstein(t64 - h));
            let tangent = bezier_tangent(&p, t).to_array();
            for k in 0..3 {
                let difference = (above[k] - below[k]) / (2.0 * h);
                // Central differences of a cubic are exact up to h² · |P‴| / 6 (< 1.6e-6 for
                // control points within 20 m); with the f32 tangent's rounding (components up
                // to 120, an ulp 7.6e-6) measured 1.3e-5 over 256 cases; limit 8x above. A
                // tangent with 3 for the middle term's 6 is off by metres a unit of t.
                prop_assert!((f64::from(tangent[k]) - difference).abs() < 1e-4, "t {t}: {tangent:?} vs {difference}");
            }
        }

        /// After any step in any wind, the root has not moved, each control-polygon segment
        /// has its rest length, and no point is under the ground.
        #[test]
        fn constraints_hold_and_root_never_moves(
            h in 0.05f32..2.0,
            facing in 0.0f32..6.3,
            lean_dir in 0.0f32..6.3,
            lean in 0.0f32..1.4,
            winds in proptest::collection::vec(vec3(), 1..40),
        ) {
            let root = Vec3::new(1.0, 2.0, -3.0);
            let mut b = BladeState::new(root, h, facing, lean_dir, lean, 1.0);
            let k = dynamics();
            for w in &winds {
                b.step(&[*w, *w * 1.1, *w * 1.2], &k, root.y);
                prop_assert_eq!(b.pos[0], root);
                for i in 1..CONTROL_POINTS {
                    let l = (b.pos[i] - b.pos[i - 1]).length();
                    prop_assert!((l - b.segment).abs() < 1e-4 * h.max(1.0), "segment {} = {} vs {}", i, l, b.segment);
                    prop_assert!(b.pos[i].y >= root.y);
                }
            }
        }

        /// With the blade bent in any direction, the rotated width axis at the top is
        /// perpendicular to the wind direction.
        #[test]
        fn rotation_follows_the_wind_direction(facing in -3.2f32..3.2, wind_dir in -3.2f32..3.2) {
            let mut b = BladeState::new(Vec3::ZERO, 0.5, facing, 0.0, 0.0, 1.0);
            let w = Vec3::new(wind_dir.cos(), 0.0, wind_dir.sin());
            for _ in 0..60 {
                b.step(&[w * 4.0; 3], &dynamics(), 0.0);
            }
            let axis = Vec2::from_angle(facing + b.rotation());
            let d = b.pos[3] - b.pos[0];
            let dir = Vec2::new(d.x, d.z).normalize();
            prop_assert!(dir.dot(Vec2::new(w.x, w.z)) > 0.99, "blade bent along {dir}, wind {w}");
            prop_assert!(axis.dot(dir).abs() < 1e-3, "axis {axis} vs wind {dir}");
            prop_assert!(b.rotation().abs() <= std::f32::consts::FRAC_PI_2 + 1e-4);
        }
    }

    #[test]
    fn zero_wind_keeps_blades_at_rest_and_restores_bent_ones() {
        let mut b = BladeState::new(Vec3::new(0.0, 1.0, 0.0), 0.5, 0.3, 1.0, 0.4, 1.0);
        let rest = b;
        for _ in 0..300 {
            b.step(&[Vec3::ZERO; 3], &dynamics(), 1.0);
        }
        for i in 0..CONTROL_POINTS {
            assert!(
                (b.pos[i] - rest.pos[i]).length() < 1e-5,
                "{i}: moved at rest"
            );
        }
        // Blown over, then calm: back at rest within a few seconds (damped spring).
        for _ in 0..30 {
            b.step(&[Vec3::X * 8.0; 3], &dynamics(), 1.0);
        }
        let bent = (b.pos[3] - rest.pos[3]).length();
        assert!(bent > 0.1, "wind did not bend the blade ({bent})");
        for _ in 0..150 {
            b.step(&[Vec3::ZERO; 3], &dynamics(), 1.0);
        }
        assert!((b.pos[3] - rest.pos[3]).length() < 0.01 * bent);
    }

    #[test]
    fn ground_reflects_and_clamps() {
        let mut b = BladeState::new(Vec3::ZERO, 0.5, 0.0, 0.0, 0.0, 1.0);
        // A wind pushing straight down and sideways lays the blade flat, never under.
        for _ in 0..200 {
            b.step(&[Vec3::new(3.0, -30.0, 0.0); 3], &dynamics(), 0.0);
            assert!(b.pos.iter().all(|p| p.y >= 0.0));
        }
        assert!(b.pos[3].y < 0.2, "blade not pressed down: {}", b.pos[3]);
    }
}

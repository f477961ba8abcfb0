//! One simulation step of one blade on the CPU: the twin of the shader's `simulate` (forces,
//! collision, validation), operation for operation, so the GPU's compute step can be checked
//! against it (`tests/tests/twins.rs`) and its properties tested here without a GPU.
//!
//! A blade is the paper's quadratic Bezier curve `v0` (root), `v1` (guide), `v2` (tip, where
//! forces act); its up vector is the world's vertical (see the crate essay). The step:
//! 1. **Forces** (Jahrmann & Wimmer Sec. 5.1): recovery `r = (I_v2 − v2)·s` (Hooke, towards
//!    the rest tip `I_v2`, `s` the blade's stiffness times [`Forces::recovery`]), gravity
//!    `g = g_E + g_F` with `g_E = (0, −G, 0)` and the front gravity `g_F = ¼·G·f`, and wind
//!    `w = k_w·h·w_i·θ` with the alignment `θ = f_d·f_r`: `f_d = 1 − |ŵ_i · (v2 − v0)/|v2 − v0||`
//!    (a blade already bent along the wind catches less of it) and `f_r = (v2 − v0)·up / h` (a
//!    blade bent low catches less). The paper moves `v2` by `(r + g + w)·Δt`; the recovery is
//!    taken implicitly here, `v2' = (v2 + Δt(s·I_v2 + g + w)) / (1 + s·Δt)`, which has the same
//!    rest state and the same small-step behaviour but stays stable for any `s·Δt` (the
//!    explicit step overshoots for `s·Δt > 1` and diverges beyond 2).
//! 2. **Collision** with the scene's sphere (Sec. 5.1's collisions): the tip is pushed out of
//!    the sphere, then the curve's midpoint `m = ¼v0 + ½v1 + ¼v2`, which moves a quarter as far
//!    as `v2` does, by moving `v2` four times its penetration.
//! 3. **Validation** (Sec. 5.2): the tip is kept above the ground; a tip pushed within half
//!    the height of its root is moved out along the ground ([`keep_chord`], not in the
//!    paper); `v1` is placed above `v0`
//!    from the tip's projection onto the ground plane,
//!    `v1 = v0 + h·up·max(1 − l_proj/h, 0.05·max(l_proj/h, 1))`; the curve is scaled about `v0`
//!    by `h / L` with `L = (2·L0 + L1)/3` the paper's estimate of a quadratic curve's length
//!    (`L0` the chord, `L1` the control polygon), so the blade keeps its length; the tip is
//!    checked against the ground once more where the scaling moved it.

use grassbench::glam::{Vec2, Vec3, Vec4};

/// The world's vertical: every blade's up vector.
pub const UP: Vec3 = Vec3::Y;

/// The force coefficients of [`crate::Params`], as the shader reads them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Forces {
    /// Recovery rate per unit of blade stiffness, 1/s.
    pub recovery: f32,
    /// Environmental gravity, m/s².
    pub gravity: f32,
    /// Wind force per metre of height per m/s of wind.
    pub wind_response: f32,
}

/// The front gravity's share of the environmental gravity (the paper's ¼).
pub const FRONT_GRAVITY: f32 = 0.25;

/// What the simulation reads of a blade that never changes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BladeRest {
    /// Root on the ground.
    pub v0: Vec3,
    /// Angle of the width direction around the vertical, radians.
    pub orientation: f32,
    /// The tip at rest (where recovery pulls it).
    pub rest_tip: Vec3,
    /// The scene's stiffness of the blade (1 = typical).
    pub stiffness: f32,
    /// Height (the curve's length), m.
    pub height: f32,
}

/// The simulated part of a blade: its guide and tip.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Curve {
    /// Guide point.
    pub v1: Vec3,
    /// Tip.
    pub v2: Vec3,
}

/// Unit width direction of a blade of `orientation`.
pub fn width_dir(orientation: f32) -> Vec3 {
    Vec3::new(orientation.cos(), 0.0, orientation.sin())
}

/// The blade's front: horizontal, perpendicular to its width, on the side it leans to at rest.
pub fn front_dir(orientation: f32, rest_offset: Vec3) -> Vec3 {
    let f = Vec3::new(-orientation.sin(), 0.0, orientation.cos());
    if f.dot(rest_offset) < 0.0 { -f } else { f }
}

/// The wind's force on the tip: the wind `wind` times the alignment `f_d·f_r`, times
/// `wind_response·h`.
pub fn wind_force(blade: &BladeRest, v2: Vec3, wind: Vec3, forces: &Forces) -> Vec3 {
    let speed = wind.length();
    let d = v2 - blade.v0;
    let len = d.length();
    if speed < 1e-6 || len < 1e-6 {
        return Vec3::ZERO;
    }
    let f_d = 1.0 - (wind / speed).dot(d / len).abs();
    let f_r = (d.dot(UP) / blade.height).max(0.0);
    wind * (forces.wind_response * blade.height * f_d * f_r)
}

/// The tip after the forces of one step of `dt` (recovery implicit, gravity and wind explicit).
pub fn apply_forces(blade: &BladeRest, v2: Vec3, wind: Vec3, forces: &Forces, dt: f32) -> Vec3 {
    let s = forces.recovery * blade.stiffness;
    let g_e = Vec3::new(0.0, -forces.gravity, 0.0);
    let g_f =
        front_dir(blade.orientation, blade.rest_tip - blade.v0) * (FRONT_GRAVITY * forces.gravity);
    let w = wind_force(blade, v2, wind, forces);
    (v2 + (blade.rest_tip * s + g_e + g_f + w) * dt) / (1.0 + s * dt)
}

/// The translation that moves `p` out of `sphere` (centre xyz, radius w; radius 0: none).
pub fn push_out(p: Vec3, sphere: Vec4) -> Vec3 {
    let d = p - sphere.truncate();
    let dist = d.length();
    if sphere.w <= 0.0 || dist >= sphere.w {
        return Vec3::ZERO;
    }
    let dir = if dist > 1e-6 { d / dist } else { UP };
    dir * (sphere.w - dist)
}

/// Shortest chord `|v2 − v0|` a blade may have, as a fraction of its height: a tip pushed
/// closer to its root (a sphere resting on the blade) is moved out along the ground, so the
/// blade folds over instead of into a hairpin, which the paper's length estimate cannot keep
/// at length (a hairpin's true length is 1.5 times its estimate).
pub const MIN_CHORD: f32 = 0.5;

/// The tip moved out horizontally, keeping its height above the root, until the chord is at
/// least [`MIN_CHORD`] of the height (along the blade's front where it stands straight up).
pub fn keep_chord(v0: Vec3, v2: Vec3, height: f32, front: Vec3) -> Vec3 {
    let d = v2 - v0;
    let least = MIN_CHORD * height;
    if d.length() >= least {
        return v2;
    }
    let flat = Vec3::new(d.x, 0.0, d.z);
    let dir = if flat.length() > 1e-6 * height {
        flat / flat.length()
    } else {
        front
    };
    let rise = d.y.min(least);
    v0 + dir * (least * least - rise * rise).max(0.0).sqrt() + UP * rise
}

/// The guide point placed from the tip (Sec. 5.2).
pub fn place_v1(v0: Vec3, v2: Vec3, height: f32) -> Vec3 {
    let d = v2 - v0;
    let l_proj = (d - UP * d.dot(UP)).length();
    let ratio = l_proj / height;
    v0 + UP * (height * (1.0 - ratio).max(0.05 * ratio.max(1.0)))
}

/// The curve scaled about `v0` so that the paper's length estimate is `height` (Sec. 5.2).
pub fn correct_length(v0: Vec3, v1: Vec3, v2: Vec3, height: f32) -> Curve {
    let l0 = v2.distance(v0);
    let l1 = v1.distance(v0) + v2.distance(v1);
    let l = (2.0 * l0 + l1) / 3.0;
    let r = height / l.max(1e-6);
    let c1 = v0 + (v1 - v0) * r;
    Curve {
        v1: c1,
        v2: c1 + (v2 - v1) * r,
    }
}

/// One step: forces, collision with `sphere`, validation against `ground` (height of the
/// ground at a point (x, z)). `v2` is the tip after the previous step, `wind` the wind at the
/// root.
pub fn step(
    blade: &BladeRest,
    v2: Vec3,
    wind: Vec3,
    sphere: Vec4,
    dt: f32,
    forces: &Forces,
    ground: impl Fn(Vec2) -> f32,
) -> Curve {
    let mut v2 = apply_forces(blade, v2, wind, forces, dt);
    v2 += push_out(v2, sphere);
    let m = blade.v0 * 0.25 + place_v1(blade.v0, v2, blade.height) * 0.5 + v2 * 0.25;
    v2 += push_out(m, sphere) * 4.0;
    v2.y = v2.y.max(ground(Vec2::new(v2.x, v2.z)));
    let front = front_dir(blade.orientation, blade.rest_tip - blade.v0);
    v2 = keep_chord(blade.v0, v2, blade.height, front);
    let v1 = place_v1(blade.v0, v2, blade.height);
    let mut c = correct_length(blade.v0, v1, v2, blade.height);
    c.v2.y = c.v2.y.max(ground(Vec2::new(c.v2.x, c.v2.z)));
    c
}

/// A point of the quadratic Bezier curve `v0, v1, v2` at parameter `t`.
pub fn bezier(v0: Vec3, v1: Vec3, v2: Vec3, t: f32) -> Vec3 {
    let u = 1.0 - t;
    v0 * (u * u) + v1 * (2.0 * u * t) + v2 * (t * t)
}

/// The curve's true length, by summing `segments` chords (for tests: what the paper's
/// estimate stands for).
pub fn arc_length(v0: Vec3, v1: Vec3, v2: Vec3, segments: u32) -> f32 {
    let n = segments.max(1);
    (0..n)
        .map(|i| {
            let a = bezier(v0, v1, v2, i as f32 / n as f32);
            let b = bezier(v0, v1, v2, (i + 1) as f32 / n as f32);
            a.distance(b)
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const FORCES: Forces = Forces {
        recovery: 30.0,
        gravity: 0.6,
        wind_response: 1.44,
    };

    fn blade(lean: Vec3, height: f32, stiffness: f32) -> BladeRest {
        BladeRest {
            v0: Vec3::new(1.0, 0.5, -2.0),
            orientation: 0.7,
            rest_tip: Vec3::new(1.0, 0.5, -2.0) + (UP + lean).normalize() * height,
            stiffness,
            height,
        }
    }

    fn flat(_: Vec2) -> f32 {
        0.5
    }

    /// At rest in calm air a blade settles where gravity and recovery balance, `g / s` below
    /// (and in front of) its rest tip before validation; the forces are exactly the paper's
    /// `r + g` there.
    #[test]
    fn calm_air_settles_where_recovery_balances_gravity() {
        let b = blade(Vec3::new(0.2, 0.0, 0.1), 0.5, 1.0);
        let mut v2 = b.rest_tip;
        for _ in 0..200 {
            v2 = apply_forces(&b, v2, Vec3::ZERO, &FORCES, 1.0 / 30.0);
        }
        let s = FORCES.recovery * b.stiffness;
        let g = Vec3::new(0.0, -FORCES.gravity, 0.0)
            + front_dir(b.orientation, b.rest_tip - b.v0) * (FRONT_GRAVITY * FORCES.gravity);
        let r = (b.rest_tip - v2) * s;
        assert!((r + g).length() < 1e-4, "net force {}", r + g);
    }

    /// The implicit step stays put at equilibrium and never overshoots, even for stiff blades
    /// whose explicit step (the paper's) would diverge.
    #[test]
    fn stiff_blades_do_not_overshoot() {
        let b = blade(Vec3::ZERO, 0.4, 50.0);
        let pushed = b.rest_tip + Vec3::new(0.2, -0.1, 0.0);
        let next = apply_forces(&b, pushed, Vec3::ZERO, &FORCES, 1.0 / 30.0);
        let before = (pushed - b.rest_tip).x;
        let after = (next - b.rest_tip).x;
        assert!(after > 0.0 && after < before, "{before} -> {after}");
    }

    /// The wind bends a blade along itself and less as it bends (f_d), a blade lying flat
    /// feels none (f_r), and calm air none at all.
    #[test]
    fn wind_alignment_weakens_the_force_as_the_blade_bends() {
        let b = blade(Vec3::ZERO, 0.5, 1.0);
        let wind = Vec3::new(5.0, 0.0, 0.0);
        let upright = wind_force(&b, b.v0 + UP * 0.5, wind, &FORCES);
        let bent = wind_force(&b, b.v0 + Vec3::new(0.35, 0.35, 0.0), wind, &FORCES);
        let flat = wind_force(&b, b.v0 + Vec3::new(0.5, 0.0, 0.0), wind, &FORCES);
        assert!(upright.x > bent.x && bent.x > 0.0, "{upright} {bent}");
        assert_eq!(flat, Vec3::ZERO);
        assert_eq!(
            wind_force(&b, b.v0 + UP * 0.5, Vec3::ZERO, &FORCES),
            Vec3::ZERO
        );
        // Upright and across the wind: f_d = f_r = 1, the whole of k_w·h·w.
        assert!((upright - wind * (FORCES.wind_response * 0.5)).length() < 1e-5);
    }

    #[test]
    fn the_sphere_pushes_tip_and_midpoint_out() {
        let b = blade(Vec3::ZERO, 0.5, 1.0);
        let tip = b.v0 + UP * 0.5;
        // A sphere just beside the tip pushes it away from its centre.
        let sphere = tip.extend(0.0) + Vec4::new(0.1, 0.0, 0.0, 0.2);
        let c = step(&b, tip, Vec3::ZERO, sphere, 1.0 / 30.0, &FORCES, flat);
        assert!(c.v2.x < tip.x - 0.05, "{}", c.v2);
        // No sphere (radius 0): nothing moves it but the forces.
        assert_eq!(push_out(tip, tip.extend(0.0)), Vec3::ZERO);
    }

    proptest! {
        /// Validation, over random states, winds, spheres and steps: the tip never ends below
        /// the ground, `v1` stands above the root, and the curve keeps its length to within
        /// what the paper's estimate `L = (2 L0 + L1) / 3` allows (see `LENGTH_TOLERANCE`).
        #[test]
        fn validation_keeps_tip_above_ground_and_length(
            lean in (-0.6f32..0.6, -0.6f32..0.6),
            h in 0.1f32..1.0,
            stiffness in 0.3f32..3.0,
            tip in (-1.5f32..1.5, -1.0f32..1.5, -1.5f32..1.5),
            wind in (-15.0f32..15.0, -3.0f32..3.0, -15.0f32..15.0),
            sphere in (-1.0f32..1.0, -0.5f32..1.5, -1.0f32..1.0, 0.0f32..0.8),
            dt in 0.001f32..0.2,
        ) {
            let b = blade(Vec3::new(lean.0, 0.0, lean.1), h, stiffness);
            let v2 = b.v0 + Vec3::new(tip.0, tip.1, tip.2) * h;
            let sphere = (b.v0 + Vec3::new(sphere.0, sphere.1, sphere.2) * h).extend(sphere.3 * h);
            let c = step(&b, v2, Vec3::new(wind.0, wind.1, wind.2), sphere, dt, &FORCES, flat);
            prop_assert!(c.v2.y >= 0.5, "tip {} below the ground", c.v2);
            prop_assert!(c.v1.y > b.v0.y, "v1 {} not above the root", c.v1);
            let len = arc_length(b.v0, c.v1, c.v2, 256);
            prop_assert!((len / h - 1.0).abs() < LENGTH_TOLERANCE, "length {len} of {h}");
        }
    }

    /// How far the true length of a validated curve may stray from the blade's height,
    /// relative. Measured over 200 000 random states (this test's ranges, each stepped once
    /// and again from the validated result): worst 7.26 %, 80 % of curves within 1 %. The
    /// paper's estimate errs most when the tip is pushed down straight over its root: `v1`
    /// then stands above the tip and the curve folds back on itself a little.
    pub(crate) const LENGTH_TOLERANCE: f32 = 0.075;
}

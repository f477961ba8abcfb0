//! Spherical barycentric interpolation of the BTF's five light directions (Boulanger
//! Appendix A, Eq. 8-13).
//!
//! The BTF of a slice is sampled for five light directions, in this order everywhere (CPU,
//! shader, texture channels): Y+, X+, Z+, X−, Z− ([`DIRECTIONS`]). A light direction `l` above
//! the ground lies in one quarter of the hemisphere, the spherical triangle `ABC` with
//! `A = ±X`, `B = Y+`, `C = ±Z` (signs of `l_x`, `l_z`), of area `π/2`. Its three weights are
//! the areas of the spherical triangles `LBC`, `LCA`, `LAB` over `π/2` (Eq. 9); the other two
//! weights are 0. Each area is its angle excess (Eq. 10), the angles from the spherical law of
//! cosines with the right angle between two axes (Eq. 11-12), which gives Eq. 13:
//!
//! `A(LBC) = acos(l_z / √(l_z² + l_x²)) + acos(l_y / √(l_x² + l_y²))
//!          + acos(−l_y l_z / (√(l_z² + l_x²) √(l_x² + l_y²))) − π`
//!
//! (the transcript's Eq. 13 drops the `√(l_z² + l_x²)` factor of the last denominator, which
//! Eq. 11 has). The three areas tile `ABC`, so the weights sum to 1 at a vertex; the shader
//! computes them per vertex (Appendix A: nine arc-cosines a vertex) and renormalises per pixel,
//! since interpolated weights of vertices in different quadrants no longer sum to 1. At a
//! quadrant border (`l_x = 0` say) `L` lies on the arc `BC`, `A(LBC) = 0`, so `X+` and `X−`
//! both weigh 0 there and the weights are continuous across it.
//!
//! A light below the horizon (`l_y < 0`, which the BTF does not sample: Y− is not defined,
//! Sec. 3.3) is taken at the horizon. The WGSL twin is `btf_weights` in `shaders/grass.wgsl`.

use glam::Vec3;

/// The five sampled light directions, in the BTF's order.
pub const DIRECTIONS: [Vec3; 5] = [Vec3::Y, Vec3::X, Vec3::Z, Vec3::NEG_X, Vec3::NEG_Z];

/// Area of the spherical triangle `L P Q` on the unit sphere, where `P` and `Q` are two
/// orthogonal axes and `lp = l·P`, `lq = l·Q`, `l` a unit vector in the octant they span with
/// the third axis (Eq. 10-13). Zero when `L` is on `P` or `Q` (degenerate triangle).
pub fn right_triangle_area(lp: f32, lq: f32) -> f32 {
    // Eq. 12: sin θ_P = |l × P| = √(1 − lp²), written with the other two components in the
    // paper; the same for Q.
    let sin_p = (1.0 - lp * lp).max(0.0).sqrt();
    let sin_q = (1.0 - lq * lq).max(0.0).sqrt();
    if sin_p < 1e-6 || sin_q < 1e-6 {
        return 0.0;
    }
    let acos = |x: f32| x.clamp(-1.0, 1.0).acos();
    // Eq. 11: the angles at P, at Q and at L; Eq. 10: the area is their excess over π.
    let at_p = acos(lq / sin_p);
    let at_q = acos(lp / sin_q);
    let at_l = acos(-lp * lq / (sin_p * sin_q));
    (at_p + at_q + at_l - std::f32::consts::PI).max(0.0)
}

/// Eq. 8-13: the weights of the five sampled directions ([`DIRECTIONS`]) for the light
/// direction `l` (need not be unit; zero gives straight up). Two of them are 0; the other three
/// sum to 1.
pub fn weights(l: Vec3) -> [f32; 5] {
    let l = Vec3::new(l.x, l.y.max(0.0), l.z).normalize_or(Vec3::Y);
    let (ax, ay, az) = (l.x.abs(), l.y, l.z.abs());
    let quarter = std::f32::consts::FRAC_PI_2;
    // A = ±X opposite the triangle L B C (B = Y, C = Z); B = Y opposite L C A; C = ±Z
    // opposite L A B.
    let wa = right_triangle_area(ay, az) / quarter;
    let wb = right_triangle_area(az, ax) / quarter;
    let wc = right_triangle_area(ax, ay) / quarter;
    let mut w = [0.0; 5];
    w[0] = wb;
    w[if l.x >= 0.0 { 1 } else { 3 }] = wa;
    w[if l.z >= 0.0 { 2 } else { 4 }] = wc;
    w
}

/// Per-pixel renormalisation (Appendix A, last paragraph): interpolated weights divided by
/// their sum (all zero gives straight up).
pub fn renormalise(w: [f32; 5]) -> [f32; 5] {
    let sum: f32 = w.iter().sum();
    if sum <= 1e-6 {
        return [1.0, 0.0, 0.0, 0.0, 0.0];
    }
    w.map(|x| x / sum)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Van Oosterom & Strackee's solid angle of a spherical triangle, an independent formula
    /// to check Eq. 13 against: `tan(E/2) = |a·(b×c)| / (1 + a·b + b·c + c·a)`.
    fn solid_angle(a: Vec3, b: Vec3, c: Vec3) -> f32 {
        let num = a.dot(b.cross(c)).abs();
        let den = 1.0 + a.dot(b) + b.dot(c) + c.dot(a);
        2.0 * num.atan2(den)
    }

    fn upper_direction() -> impl Strategy<Value = Vec3> {
        (-1.0f32..1.0, 0.0f32..1.0, -1.0f32..1.0)
            .prop_filter("not zero", |(x, y, z)| x * x + y * y + z * z > 1e-3)
            .prop_map(|(x, y, z)| Vec3::new(x, y, z).normalize())
    }

    #[test]
    fn weight_is_one_at_each_sampled_direction() {
        for (k, d) in DIRECTIONS.iter().enumerate() {
            let w = weights(*d);
            for (j, x) in w.iter().enumerate() {
                let expected = if j == k { 1.0 } else { 0.0 };
                assert!((x - expected).abs() < 1e-5, "direction {k}: {w:?}");
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]

        /// Eq. 13 agrees with the independent solid-angle formula, so the three weights are
        /// the areas of Eq. 9 and sum to 1 at a vertex.
        #[test]
        fn eq_13_matches_the_solid_angle(l in upper_direction()) {
            let w = weights(l);
            let (a, c) = (
                if l.x >= 0.0 { Vec3::X } else { Vec3::NEG_X },
                if l.z >= 0.0 { Vec3::Z } else { Vec3::NEG_Z },
            );
            let quarter = std::f32::consts::FRAC_PI_2;
            let expected = [
                solid_angle(l, c, a) / quarter,
                solid_angle(l, Vec3::Y, c) / quarter,
                solid_angle(l, a, Vec3::Y) / quarter,
            ];
            let got = [w[0], w[if l.x >= 0.0 { 1 } else { 3 }], w[if l.z >= 0.0 { 2 } else { 4 }]];
            for (g, e) in got.iter().zip(expected) {
                prop_assert!((g - e).abs() < 2e-3, "{l}: {got:?} vs {expected:?}");
            }
            let sum: f32 = w.iter().sum();
            prop_assert!((sum - 1.0).abs() < 3e-3, "{l}: sum {sum}");
            prop_assert!(w.iter().all(|x| (0.0..=1.0 + 1e-5).contains(x)));
        }

        /// Interpolating the weights of two vertices (possibly in different quadrants) and
        /// renormalising gives weights that sum to 1.
        #[test]
        fn renormalised_interpolation_sums_to_one(
            a in upper_direction(), b in upper_direction(), t in 0.0f32..=1.0,
        ) {
            let (wa, wb) = (weights(a), weights(b));
            let mixed: [f32; 5] = std::array::from_fn(|k| wa[k] * (1.0 - t) + wb[k] * t);
            let r = renormalise(mixed);
            let sum: f32 = r.iter().sum();
            prop_assert!((sum - 1.0).abs() < 1e-5, "{r:?}");
        }

        /// Continuity: a small turn of the light changes every weight a little, including
        /// across the quadrant borders `l_x = 0` and `l_z = 0` (the steps straddle them).
        #[test]
        fn weights_are_continuous_across_quadrant_borders(
            azimuth in 0.0f32..std::f32::consts::TAU, elevation in 0.02f32..1.55,
        ) {
            let h = 1e-3f32;
            let dir = |az: f32| {
                Vec3::new(elevation.cos() * az.cos(), elevation.sin(), elevation.cos() * az.sin())
            };
            let (w0, w1) = (weights(dir(azimuth)), weights(dir(azimuth + h)));
            for k in 0..5 {
                prop_assert!((w0[k] - w1[k]).abs() < 0.02, "{azimuth}: {w0:?} → {w1:?}");
            }
        }
    }

    #[test]
    fn quadrant_borders_give_zero_to_both_sides() {
        for &(l, zero) in &[
            (Vec3::new(0.0, 0.5, 0.8), [1usize, 3]),
            (Vec3::new(-0.6, 0.3, 0.0), [2, 4]),
        ] {
            let w = weights(l);
            for k in zero {
                assert!(w[k].abs() < 1e-4, "{l}: {w:?}");
            }
            let just = |e: f32| weights(l + Vec3::new(e, 0.0, e));
            for k in 0..5 {
                assert!((just(1e-4)[k] - just(-1e-4)[k]).abs() < 1e-2, "{l}");
            }
        }
        // Below the horizon: the horizon direction.
        let w = weights(Vec3::new(1.0, -0.5, 0.0));
        assert!((w[1] - 1.0).abs() < 1e-4, "{w:?}");
    }
}

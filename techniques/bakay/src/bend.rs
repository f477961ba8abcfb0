//! The length-preserving bend of Bakay Sec. 3 (their Fig. 6), on the CPU: the mirror of the
//! running sums `cs_bend` keeps in `shaders/bakay.wgsl` (tests/tests/twins.rs runs the shader's
//! `tilt`, `shell_segment` and `cs_bend` against these functions).
//!
//! A blade is a chain of segments of equal length `S` (the inter-shell distance). Segment `j`
//! leans away from the surface normal by the tilt
//! `θ_j = I · (π/2) · (j/N)^p`
//! (`I` the wind intensity at the vertex, `N` the number of shells, `p` the stiffness profile:
//! `p = 1` is the paper's constant increment per shell). Shell 0 is the ground (the base mesh);
//! shell `k` sits at the top of segments `0..k`, so it is moved
//! `n_k = Σ_{j<k} S·cos θ_j` along the normal and `w_k = Σ_{j<k} S·sin θ_j` along the wind
//! vector. These are the paper's sums for its "current shell" `i = k − 1` (it counts the shells
//! above the ground from 0), with one correction: the paper's `w_i` writes `sin(i/N …)` inside
//! the sum, which tilts every segment of a shell by the *shell's* angle and so stretches the
//! blade; with `j` (as in its `n_i`) every segment keeps the length `S` the text asks for.

use std::f32::consts::FRAC_PI_2;

/// Tilt (radians) of segment `j` of `shells` at wind intensity `intensity` with stiffness
/// profile exponent `stiffness`.
pub fn tilt(j: u32, shells: u32, intensity: f32, stiffness: f32) -> f32 {
    let x = j as f32 / shells.max(1) as f32;
    intensity * FRAC_PI_2 * x.powf(stiffness)
}

/// Segment `k` of a blade, `spacing` long and tilted by [`tilt`]: what it adds to the running
/// totals `(n, w)` (along the normal, along the wind vector). The twin of `shell_segment` in
/// `shaders/bakay.wgsl`.
pub fn segment(k: u32, shells: u32, spacing: f32, intensity: f32, stiffness: f32) -> (f32, f32) {
    let (s, c) = tilt(k, shells, intensity, stiffness).sin_cos();
    (spacing * c, spacing * s)
}

/// Offsets `(n_k, w_k)` (along the normal, along the wind vector) of shells `k = 0..shells` for
/// inter-shell distance `spacing`, as running totals (shell 0 is the ground: `(0, 0)`), the
/// totals `cs_bend` keeps.
pub fn offsets(shells: u32, spacing: f32, intensity: f32, stiffness: f32) -> Vec<(f32, f32)> {
    let mut out = Vec::with_capacity(shells as usize);
    let (mut n, mut w) = (0.0f32, 0.0f32);
    for k in 0..shells {
        out.push((n, w));
        let (dn, dw) = segment(k, shells, spacing, intensity, stiffness);
        n += dn;
        w += dw;
    }
    out
}

/// The paper's `w_i` as printed (`sin(i/N …)` inside the sum over `j`), for comparison only:
/// it does not preserve segment lengths (see the module docs).
pub fn printed_wind_offset(i: u32, shells: u32, spacing: f32, intensity: f32) -> f32 {
    (0..=i)
        .map(|_| spacing * tilt(i, shells, intensity, 1.0).sin())
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn segment_lengths(o: &[(f32, f32)]) -> Vec<f32> {
        o.windows(2)
            .map(|p| (p[1].0 - p[0].0).hypot(p[1].1 - p[0].1))
            .collect()
    }

    proptest! {
        /// Every bent segment keeps the inter-shell distance, whatever the wind and shells.
        #[test]
        fn every_segment_keeps_its_length(
            shells in 2u32..=128,
            intensity in -2.0f32..2.0,
            stiffness in 0.1f32..8.0,
            spacing in 0.001f32..0.2,
        ) {
            let o = offsets(shells, spacing, intensity, stiffness);
            prop_assert_eq!(o.len(), shells as usize);
            prop_assert_eq!(o[0], (0.0, 0.0));
            for (k, len) in segment_lengths(&o).into_iter().enumerate() {
                prop_assert!((len - spacing).abs() <= 1e-4 * spacing.max(1e-3),
                    "segment {} has length {} for S = {}", k, len, spacing);
            }
            // The blade's tip is never further from the root than its length.
            let (n, w) = o[shells as usize - 1];
            prop_assert!(n.hypot(w) <= spacing * (shells - 1) as f32 * (1.0 + 1e-5));
        }
    }

    #[test]
    fn zero_wind_leaves_shells_straight() {
        for k in [1, 2, 16, 65, 128] {
            let o = offsets(k, 0.04, 0.0, 1.0);
            for (i, (n, w)) in o.iter().enumerate() {
                assert_eq!(*w, 0.0);
                assert!((n - 0.04 * i as f32).abs() < 1e-5);
            }
        }
    }

    #[test]
    fn printed_formula_stretches_blades_and_ours_does_not() {
        // With the printed `w_i`, the last segment of 16 shells at full wind is 1.32 S long
        // (15·sin 78.75° − 14·sin 73.1° along the wind, cos 78.75° along the normal): the
        // blade would grow as it bends.
        let (shells, s, intensity) = (16, 0.05, 1.0);
        let i = shells - 2;
        let o = offsets(shells, s, intensity, 1.0);
        let n_step = o[(i + 1) as usize].0 - o[i as usize].0;
        let printed_step = printed_wind_offset(i, shells, s, intensity)
            - printed_wind_offset(i - 1, shells, s, intensity);
        assert!(n_step.hypot(printed_step) > 1.3 * s);
        assert!((segment_lengths(&o)[i as usize] - s).abs() < 1e-6);
    }

    #[test]
    fn stiffness_moves_the_bend_up_the_blade() {
        let floppy = offsets(16, 0.04, 0.8, 0.5);
        let stiff = offsets(16, 0.04, 0.8, 3.0);
        // Half-way up, floppy grass has already moved further along the wind.
        assert!(floppy[8].1 > 2.0 * stiff[8].1);
        assert!(floppy[15].1 > stiff[15].1);
    }
}

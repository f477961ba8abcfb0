//! Level-of-detail weights and the share of each blade between geometry and slices
//! (Boulanger Sec. 3.4, Eq. 1-5).
//!
//! Every function here has a WGSL twin in `shaders/grass.wgsl`; the two are kept line for line
//! alike so the property tests below speak for the GPU too.
//!
//! ## Which method draws a blade
//! A blade with density threshold `dth` exists where the local density `ρ` exceeds it
//! (Sec. 3.4). Between two levels the paper splits the existing blades with the weights: the
//! slices compare `dth` with `ρ·w_s`, the geometry compares `1 − dth` with `ρ·w_g`, so that the
//! two take complementary sets. Taken literally this holds only for `ρ = 1` (for `ρ = 0.5` and
//! `w_g = 1`, `1 − dth < 0.5` would draw exactly the blades the density map removed), so the
//! comparison is made on the threshold normalised by the local density, `t = dth / ρ ∈ [0, 1)`
//! for every existing blade: geometry draws when `1 − t ≤ w_g`, the slices take the rest, which
//! is `t < 1 − w_g = w_hs` (Eq. 2 and Eq. 4 are complementary). At `ρ = 1` this is the paper's
//! rule unchanged.
//!
//! ## Smooth opacity (Eq. 5)
//! `opacity(density, dth) = clamp((density − dth + ω) / 2ω, 0, 1)`. Applied as written, a weight
//! of 1 would leave every blade with `1 − t < ω` half transparent even right in front of the
//! camera (the ramp is centred on the step), so the weight is first stretched to
//! `w·(1 + 2ω) − ω`: weight 1 draws every blade fully, weight 0 none, and the ramp of half-width
//! `ω` lies in between. The slices take `1 − opacity_g`, so the opacities of a blade's two
//! representations always sum to 1 and no blade is lost or doubled in a transition. `ω = 0`
//! gives the hard test of Fig. 14(a).
//!
//! ## Vertical slices (Eq. 3)
//! The vertical slices and the horizontal slice together are the volume representation of the
//! mid band (Sec. 3.3): both draw the slices' share `1 − opacity_g`. Beyond `min_btf` the
//! vertical slices fade out with the second factor of Eq. 3, `f(d)`, by the same smooth test on
//! the normalised threshold, `t` against `f` this time so the blades with the lowest thresholds
//! stay longest: a vertical slice texel has opacity `(1 − opacity_g)·fade(f, t)`. With the hard
//! test the fraction of blades in the vertical slices is `ρ·min(w_hs, f) = ρ·w_vs` (Eq. 3's
//! product equals the minimum because `max_geom ≤ min_btf`: one factor is always 1), and the
//! horizontal slice keeps `ρ·w_hs` (Eq. 4).
//!
//! ## Without transitions
//! With `transitions = false` (the `no_transitions` variant) nothing above is split: each
//! cell gets one of Sec. 3.1's three levels by the distance from the eye to its centre
//! ([`LodDistances::abrupt_level`], cut where Eq. 2's weight and Eq. 3's far fade cross one
//! half, so the bands keep their extent and cost), and its draws carry fixed weights
//! ([`CellWeights::Fixed`]): 1 or 0 for geometry, 1 or 0 for the vertical slices. Eq. 5 at a
//! weight of 1 or 0 is 1 or 0 for every blade whatever ω, so a cell is drawn entirely by one
//! representation and the seamless mechanism is all that the two variants differ by.

/// Eq. 1: `clamp(x, 0, 1)`; NaN maps to 0.
pub fn clamp01(x: f32) -> f32 {
    if x >= 1.0 {
        1.0
    } else if x > 0.0 {
        x
    } else {
        0.0
    }
}

/// The four user distances of Fig. 13 (metres from the eye).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LodDistances {
    /// Geometry at full weight up to here.
    pub min_geom: f32,
    /// No geometry beyond here.
    pub max_geom: f32,
    /// Vertical slices at full weight up to here.
    pub min_btf: f32,
    /// No vertical slices beyond here.
    pub max_btf: f32,
}

impl LodDistances {
    /// Eq. 2: weight of geometry at distance `d`.
    pub fn w_g(&self, d: f32) -> f32 {
        clamp01((d - self.max_geom) / (self.min_geom - self.max_geom))
    }

    /// Eq. 3: weight of the vertical slices at distance `d` (drawn in part 2, issue 9).
    pub fn w_vs(&self, d: f32) -> f32 {
        clamp01((d - self.min_geom) / (self.max_geom - self.min_geom))
            * clamp01((d - self.max_btf) / (self.min_btf - self.max_btf))
    }

    /// The second factor of Eq. 3: 1 up to `min_btf`, 0 from `max_btf`.
    pub fn vertical_fade(&self, d: f32) -> f32 {
        clamp01((d - self.max_btf) / (self.min_btf - self.max_btf))
    }

    /// Eq. 4: weight of the horizontal slice at distance `d`.
    pub fn w_hs(&self, d: f32) -> f32 {
        clamp01((d - self.min_geom) / (self.max_geom - self.min_geom))
    }

    /// Where levels switch without transitions: geometry up to the middle of its transition
    /// band (Eq. 2's weight is one half there), the vertical slices up to the middle of their
    /// far fade (Eq. 3's second factor is one half), the horizontal slice beyond.
    pub fn abrupt_level(&self, d: f32) -> Level {
        if d < 0.5 * (self.min_geom + self.max_geom) {
            Level::Geometry
        } else if d < 0.5 * (self.min_btf + self.max_btf) {
            Level::VerticalSlices
        } else {
            Level::HorizontalSlice
        }
    }
}

/// Sec. 3.1's three levels of detail, as a cell switched without transitions gets one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Level {
    /// Geometric blades only.
    Geometry,
    /// The vertical slices over the horizontal slice (the volume of the mid band).
    VerticalSlices,
    /// The horizontal slice only.
    HorizontalSlice,
}

/// The weights a cell's draws use (the shaders' `cell_weight_geometry` and
/// `cell_vertical_fade`): by distance per blade and per pixel (Eq. 2 and Eq. 3's far fade,
/// the seamless transitions), or one pair for the whole cell.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CellWeights {
    /// Eq. 2 and Eq. 3's far fade of each blade's or pixel's own distance.
    ByDistance,
    /// Fixed for the cell: geometry's weight `w_g` and the vertical slices' far fade.
    Fixed {
        /// Geometry's weight (the slices take `1 − opacity_g`).
        w_g: f32,
        /// The vertical slices' far fade.
        fade: f32,
    },
}

impl CellWeights {
    /// A cell drawn entirely at `level`: geometry alone at full weight, or the slices alone,
    /// the vertical ones in full or not at all.
    pub fn of_level(level: Level) -> Self {
        let (w_g, fade) = match level {
            Level::Geometry => (1.0, 0.0),
            Level::VerticalSlices => (0.0, 1.0),
            Level::HorizontalSlice => (0.0, 0.0),
        };
        Self::Fixed { w_g, fade }
    }

    /// Geometry's weight at distance `d`.
    pub fn w_g(self, lod: &LodDistances, d: f32) -> f32 {
        match self {
            Self::ByDistance => lod.w_g(d),
            Self::Fixed { w_g, .. } => w_g,
        }
    }

    /// The vertical slices' far fade at distance `d`.
    pub fn fade(self, lod: &LodDistances, d: f32) -> f32 {
        match self {
            Self::ByDistance => lod.vertical_fade(d),
            Self::Fixed { fade, .. } => fade,
        }
    }

    /// As the shaders read them (a cell's `mode`, a slice quad's `tess`, after their first
    /// component): `(0, 0, 0)` by distance, `(1, w_g, fade)` fixed.
    pub fn encode(self) -> [f32; 3] {
        match self {
            Self::ByDistance => [0.0; 3],
            Self::Fixed { w_g, fade } => [1.0, w_g, fade],
        }
    }
}

/// Eq. 5 for the geometric representation of a blade with normalised threshold `t = dth / ρ`,
/// at geometry weight `w_g`: compares `1 − t` with the stretched weight (see the module docs).
/// `omega = 0` is the hard test `1 − t ≤ w_g`.
pub fn geometry_opacity(w_g: f32, t: f32, omega: f32) -> f32 {
    let key = 1.0 - t;
    if omega <= 0.0 {
        return if key <= w_g { 1.0 } else { 0.0 };
    }
    clamp01((w_g * (1.0 + 2.0 * omega) - key) / (2.0 * omega))
}

/// Eq. 5 for the vertical slices' far fade: the opacity of a blade of normalised threshold `t`
/// at fade weight `f` (Eq. 3's second factor, [`LodDistances::vertical_fade`]), stretched like
/// [`geometry_opacity`] so weight 1 keeps every blade and 0 none.
pub fn fade_opacity(f: f32, t: f32, omega: f32) -> f32 {
    if omega <= 0.0 {
        return if t <= f { 1.0 } else { 0.0 };
    }
    clamp01((f * (1.0 + 2.0 * omega) - t) / (2.0 * omega))
}

/// Opacity of a blade of normalised threshold `t` in the vertical slices: the slices' share
/// of it times the far fade (module docs).
pub fn vertical_opacity(w_g: f32, f: f32, t: f32, omega: f32) -> f32 {
    (1.0 - geometry_opacity(w_g, t, omega)) * fade_opacity(f, t, omega)
}

/// The opacity of a slice texel with density threshold `dth` over local density `density`
/// (Sec. 3.4, Fig. 11): where the blade exists (`dth < ρ`) the slices draw its share
/// [`vertical_opacity`] at normalised threshold `t = dth / ρ` (with the far fade `f`, 1 for
/// the horizontal slice). Where one pixel covers many texels (`texels` per pixel) the one
/// averaged threshold means nothing, so from 2^0.5 to 2^1.5 texels a pixel the texel's own
/// share gives way to the expected share of uniformly spread thresholds,
/// `ρ · ∫₀¹ vertical_opacity(t) dt`, by the midpoint rule over 8 thresholds. The twin of
/// `slice_share` in `shaders/grass.wgsl`.
pub fn slice_share(dth: f32, density: f32, w_g: f32, f: f32, texels: f32, omega: f32) -> f32 {
    let fine = if dth < density {
        vertical_opacity(w_g, f, dth / density, omega)
    } else {
        0.0
    };
    let mean: f32 = (0..SHARE_SAMPLES)
        .map(|k| vertical_opacity(w_g, f, (k as f32 + 0.5) / SHARE_SAMPLES as f32, omega))
        .sum();
    let expected = density * mean / SHARE_SAMPLES as f32;
    let far = (texels.max(1e-6).log2() - 0.5).clamp(0.0, 1.0);
    fine * (1.0 - far) + expected * far
}

/// Thresholds [`slice_share`] averages over for a pixel that covers many texels.
pub const SHARE_SAMPLES: u32 = 8;

/// How much of one blade each method draws.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Share {
    /// Opacity of the blade drawn as geometry.
    pub geometry: f32,
    /// Opacity of the blade in the slices.
    pub slices: f32,
}

/// The share of a blade with threshold `dth` where the local density is `density`, at geometry
/// weight `w_g`: nothing where the blade does not exist (`dth ≥ ρ`, Sec. 3.4), otherwise
/// geometry by Eq. 5 on `1 − dth/ρ` and the slices the complement.
pub fn blade_share(density: f32, dth: f32, w_g: f32, omega: f32) -> Share {
    if dth >= density || density <= 0.0 {
        return Share {
            geometry: 0.0,
            slices: 0.0,
        };
    }
    let g = geometry_opacity(w_g, dth / density, omega);
    Share {
        geometry: g,
        slices: 1.0 - g,
    }
}

/// Smallest normalised threshold `t` whose Eq. 5 opacity as geometry reaches `min_opacity`
/// at geometry weight up to `w_g_max` (blades below it would be alpha-tested away entirely):
/// lets the CPU skip them per cell and the vertex shader collapse them.
pub fn geometry_min_t(w_g_max: f32, omega: f32, min_opacity: f32) -> f32 {
    if omega <= 0.0 {
        1.0 - w_g_max
    } else {
        1.0 - w_g_max * (1.0 + 2.0 * omega) + 2.0 * omega * min_opacity
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const LOD: LodDistances = LodDistances {
        min_geom: 2.0,
        max_geom: 5.0,
        min_btf: 12.0,
        max_btf: 30.0,
    };

    fn lods() -> impl Strategy<Value = LodDistances> {
        (0.1f32..20.0, 0.1f32..20.0, 0.0f32..50.0, 0.1f32..50.0).prop_map(|(a, b, c, e)| {
            LodDistances {
                min_geom: a,
                max_geom: a + b,
                min_btf: a + b + c,
                max_btf: a + b + c + e,
            }
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4000))]

        /// The property issue 8 asks for: for every distance and threshold, a blade under the
        /// local density is drawn by exactly one method (hard test), and a blade over it by
        /// none.
        #[test]
        fn exactly_one_method_draws_an_existing_blade(
            lod in lods(), d in 0.0f32..200.0, density in 0.0f32..=1.0, dth in 0.0f32..1.0,
        ) {
            let s = blade_share(density, dth, lod.w_g(d), 0.0);
            let geometry = s.geometry > 0.5;
            let slices = s.slices > 0.5;
            if dth < density {
                prop_assert!(geometry != slices, "d {d} ρ {density} dth {dth}: {s:?}");
            } else {
                prop_assert!(!geometry && !slices);
            }
        }

        /// With the smooth opacity the two representations of a blade always add up to one
        /// opaque blade, each share in [0, 1].
        #[test]
        fn smooth_shares_sum_to_one(
            lod in lods(), d in 0.0f32..200.0, density in 0.01f32..=1.0, dth in 0.0f32..1.0,
            omega in 0.0f32..1.0,
        ) {
            let s = blade_share(density, dth, lod.w_g(d), omega);
            prop_assert!((0.0..=1.0).contains(&s.geometry) && (0.0..=1.0).contains(&s.slices));
            let total = s.geometry + s.slices;
            if dth < density {
                prop_assert!((total - 1.0).abs() < 1e-6, "{s:?}");
            } else {
                prop_assert_eq!(total, 0.0);
            }
        }

        /// Eq. 2-4 stay in [0, 1], are continuous (Lipschitz with the steepest slope of the
        /// ramps), and the horizontal slice's weight is the complement of geometry's.
        #[test]
        fn weights_are_continuous_and_in_unit_range(lod in lods(), d in 0.0f32..200.0, h in 1e-4f32..0.05) {
            let slope = 1.0 / (lod.max_geom - lod.min_geom)
                + 1.0 / (lod.max_btf - lod.min_btf).max(1e-6);
            for w in [LodDistances::w_g, LodDistances::w_vs, LodDistances::w_hs] {
                let (a, b) = (w(&lod, d), w(&lod, d + h));
                prop_assert!((0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b));
                prop_assert!((a - b).abs() <= slope * h * 1.001 + 1e-5, "jump {a} → {b} over {h}");
            }
            prop_assert!((lod.w_g(d) + lod.w_hs(d) - 1.0).abs() < 1e-5);
        }

        /// Below the CPU's per-cell cut geometry's opacity stays under the alpha-test threshold
        /// (zero for a zero threshold), so skipping those blades changes no pixel.
        #[test]
        fn cpu_cut_is_conservative(
            w in 0.0f32..=1.0, t in 0.0f32..1.0, omega in 0.0f32..1.0, a in 0.0f32..0.5,
        ) {
            if t < geometry_min_t(w, omega, a) - 1e-4 {
                let o = geometry_opacity(w, t, omega);
                prop_assert!(if a > 0.0 { o < a } else { o == 0.0 }, "{o} vs {a}");
            }
        }
    }

    /// With the hard test the vertical slices draw the fraction `ρ·w_vs` of the blades (Eq. 3),
    /// never a blade geometry draws, and nothing beyond `max_btf`.
    #[test]
    fn vertical_slices_draw_eq_3s_share() {
        let n = 100_000;
        for d in [1.0, 2.5, 3.5, 4.2, 8.0, 12.0, 15.0, 21.0, 29.0, 31.0] {
            for density in [1.0, 0.6] {
                let (w_g, f) = (LOD.w_g(d), LOD.vertical_fade(d));
                let mut v = 0usize;
                for k in 0..n {
                    let dth = (k as f32 + 0.5) / n as f32;
                    if dth >= density {
                        continue;
                    }
                    let t = dth / density;
                    let o = vertical_opacity(w_g, f, t, 0.0);
                    assert!(
                        o == 0.0 || geometry_opacity(w_g, t, 0.0) == 0.0,
                        "drawn twice"
                    );
                    v += usize::from(o > 0.5);
                }
                let v = v as f32 / n as f32;
                assert!(
                    (v - density * LOD.w_vs(d)).abs() < 1e-3,
                    "d {d} ρ {density}: {v}"
                );
            }
        }
    }

    proptest! {
        /// The smooth vertical opacity stays in [0, 1], never exceeds the slices' share, and
        /// is continuous in the distance.
        #[test]
        fn vertical_opacity_is_bounded_and_continuous(
            d in 0.0f32..60.0, t in 0.0f32..1.0, omega in 0.01f32..1.0,
        ) {
            let o = |d: f32| vertical_opacity(LOD.w_g(d), LOD.vertical_fade(d), t, omega);
            let g = geometry_opacity(LOD.w_g(d), t, omega);
            prop_assert!((0.0..=1.0).contains(&o(d)) && o(d) <= 1.0 - g + 1e-6);
            let h = 1e-3;
            let slope = (1.0 + 2.0 * omega) / (2.0 * omega)
                * (1.0 / (LOD.max_geom - LOD.min_geom) + 1.0 / (LOD.max_btf - LOD.min_btf));
            prop_assert!((o(d) - o(d + h)).abs() <= slope * h * 1.01 + 1e-5);
        }
    }

    /// Seen from far away (many texels a pixel) a slice texel draws the expected share of the
    /// blades there, `ρ · ∫₀¹ vertical_opacity(t) dt` (Sec. 3.4: the fraction of uniformly
    /// spread thresholds the slices draw), which the 8-threshold midpoint rule meets closely;
    /// seen up close (one texel a pixel), exactly the share of its own blade, and nothing
    /// where that blade does not exist.
    #[test]
    fn slice_share_is_its_blades_share_near_and_the_expected_fraction_far() {
        let mut worst = 0.0f64;
        for omega in [0.25, 0.4, 0.8] {
            for d in [2.5, 3.1, 3.5, 4.4, 13.0, 18.0, 25.0] {
                let (w_g, f) = (LOD.w_g(d), LOD.vertical_fade(d));
                let n = 100_000;
                let integral = (0..n)
                    .map(|k| {
                        f64::from(vertical_opacity(w_g, f, (k as f32 + 0.5) / n as f32, omega))
                    })
                    .sum::<f64>()
                    / f64::from(n);
                for density in [0.3f32, 0.7, 1.0] {
                    for dth in [0.05f32, 0.35, 0.62, 0.9] {
                        let far = slice_share(dth, density, w_g, f, 8.0, omega);
                        worst = worst.max((f64::from(far) - f64::from(density) * integral).abs());
                        let near = slice_share(dth, density, w_g, f, 1.0, omega);
                        let own = if dth < density {
                            (1.0 - geometry_opacity(w_g, dth / density, omega))
                                * fade_opacity(f, dth / density, omega)
                        } else {
                            0.0
                        };
                        assert!(
                            (near - own).abs() < 1e-6,
                            "ω {omega} d {d} ρ {density} dth {dth}: {near} vs {own}"
                        );
                    }
                }
            }
        }
        // Measured 0.0025 (the midpoint rule's error at the ramps' kinks); limit 2x above. A
        // rule off by half a sample (k instead of k + 0.5) is off by 0.0625.
        assert!(
            worst < 0.005,
            "far share off the expected fraction by {worst}"
        );
    }

    #[test]
    fn weights_match_fig_13() {
        assert_eq!(LOD.w_g(0.0), 1.0);
        assert_eq!(LOD.w_g(2.0), 1.0);
        assert!((LOD.w_g(3.5) - 0.5).abs() < 1e-6);
        assert_eq!(LOD.w_g(5.0), 0.0);
        assert_eq!(LOD.w_vs(1.0), 0.0);
        assert!((LOD.w_vs(3.5) - 0.5).abs() < 1e-6);
        assert_eq!(LOD.w_vs(8.0), 1.0);
        assert!((LOD.w_vs(21.0) - 0.5).abs() < 1e-6);
        assert_eq!(LOD.w_vs(40.0), 0.0);
        assert_eq!(LOD.w_hs(40.0), 1.0);
    }

    /// With the hard test, the fraction of uniformly spread thresholds each method draws is its
    /// weight: geometry `w_g`, the horizontal slice `w_hs` (Eq. 4), at any density.
    #[test]
    fn hard_shares_are_the_weights() {
        let n = 100_000;
        for d in [0.0, 2.5, 3.1, 3.5, 4.2, 4.9, 6.0] {
            for density in [1.0, 0.6, 0.3] {
                let (mut g, mut s) = (0usize, 0usize);
                for k in 0..n {
                    let dth = (k as f32 + 0.5) / n as f32;
                    let share = blade_share(density, dth, LOD.w_g(d), 0.0);
                    g += usize::from(share.geometry > 0.5);
                    s += usize::from(share.slices > 0.5);
                }
                let (g, s) = (g as f32 / n as f32, s as f32 / n as f32);
                assert!((g - density * LOD.w_g(d)).abs() < 1e-3, "d {d}: {g}");
                assert!((s - density * LOD.w_hs(d)).abs() < 1e-3, "d {d}: {s}");
            }
        }
    }
}

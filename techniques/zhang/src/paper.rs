//! The thesis's own operating point: every value of the `paper` variant, named and cited.
//! The wind is the scene's: the thesis's is Stam's fluid on an 8³ grid with 20 Gauss–Seidel
//! sweeps and its own projection, tiled per grass grid (Sec. 5.1), which the built-in scene
//! `meadow_fluid` sets.

use crate::params::{Sorting, WingLighting};

/// Sec. 5.1: "we place 16x16 grass grids".
pub const GRIDS: u32 = 16;
/// Sec. 5.1 fixes the grids' count (16 x 16), not their size: `grid_size = 0` keeps the
/// count whatever the terrain (a size in metres is ours).
pub const GRID_SIZE: f32 = 0.0;
/// Sec. 5.2 draws every far grid on its own, at the billboard length of Eq. 8 (grouping far
/// grids is ours).
pub const FAR_GROUPS: u32 = 0;
/// Sec. 7, Fig. 22: "each grass grid contains 20x20 blades of grasses" (the prairie of the
/// results; Sec. 5.1's example grid holds 32 x 32).
pub const BLADES_PER_SIDE: u32 = 20;
/// Sec. 3.1.1 and Fig. 22: "Each blade of grass has 4 backbone points".
pub const BACKBONE_POINTS: u32 = 4;
/// Eq. (7) has no restoring force: blades return only when the zero-mean fluid pushes them
/// back.
pub const SPRING: f32 = 0.0;
/// Eq. (7) has no damping (`keep = 1`). Stable under the thesis's fluid, whose velocity
/// changes sign; under a steady breeze the blades lie down (see `README.md`).
pub const DAMPING: f32 = 0.0;
/// Ch. 4: billboard wings are whole rectangles (trimming them is ours).
pub const TRIM_WINGS: bool = false;
/// Ch. 4 lights billboards as the plants they stand for: every light per pixel (lighting
/// the wings per vertex is ours).
pub const WING_LIGHTING: WingLighting = WingLighting::Pixel;
/// Sec. 3.2 and 5.2: every animated blade stepped every frame with the wind at each control
/// point (stepping the hidden ones every other frame is ours).
pub const HIDDEN_HALF_RATE: bool = false;
/// Sec. 5.4: far-to-near sorting with blending (Eq. 10).
pub const SORTING: Sorting = Sorting::Sort;

/// The `paper` variant's overrides: exactly the constants above (tested).
pub const VARIANT: &str = r#"grids = 16
grid_size = 0.0
far_groups = 0
blades_per_side = 20
backbone_points = 4
spring = 0.0
damping = 0.0
trim_wings = false
wing_lighting = "pixel"
hidden_half_rate = false
sorting = "sort""#;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Params;
    use grassbench::technique::variant_differences;

    #[test]
    fn the_paper_variant_sets_exactly_the_cited_values() {
        let cited = Params {
            grids: GRIDS,
            grid_size: GRID_SIZE,
            far_groups: FAR_GROUPS,
            blades_per_side: BLADES_PER_SIDE,
            backbone_points: BACKBONE_POINTS,
            spring: SPRING,
            damping: DAMPING,
            trim_wings: TRIM_WINGS,
            wing_lighting: WING_LIGHTING,
            hidden_half_rate: HIDDEN_HALF_RATE,
            sorting: SORTING,
            ..Params::default()
        };
        assert_eq!(
            variant_differences("zhang", VARIANT, &cited, 11),
            Vec::<String>::new()
        );
    }
}

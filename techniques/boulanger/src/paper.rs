//! The paper's own operating point: every value of the `paper` variant, named and cited.
//! Boulanger et al. give no distances for the levels of detail (Fig. 13's `minGeom` …
//! `maxBTF` are "defined by the user"), so the variant keeps ours; `README.md` lists each
//! departure and its measured effect.

use crate::params::Transparency;

/// Sec. 5: "a football field with about 627 million virtual grass blades" (105 m x 68 m:
/// 87 800 blades/m², 21 950 a 0.5 m patch).
pub const BLADES_PER_M2: f32 = 87_800.0;
/// Sec. 5: "10 vertical slices are defined for each horizontal axis of a 0.5 meter wide
/// patch".
pub const PATCH_SIZE: f32 = 0.5;
/// Sec. 5: 10 vertical slices per horizontal axis.
pub const VERTICAL_SLICES: u32 = 10;
/// Sec. 5: "The resolution of the images for vertical slices is 512×64".
pub const VSLICE_WIDTH: u32 = 512;
/// Sec. 5: 512×64.
pub const VSLICE_HEIGHT: u32 = 64;
/// Sec. 5: "512×512 for the horizontal slice".
pub const SLICE_RESOLUTION: u32 = 512;
/// Sec. 4.2: multisampling with alpha to coverage ("The results we show in the figures of
/// this report make use of multisampling"; at least 6 samples). Needs `--msaa`: the harness
/// renders 4 samples, what every wgpu adapter offers (see `README.md`).
pub const TRANSPARENCY: Transparency = Transparency::AlphaToCoverage;
/// Sec. 6: "Animation could also be added": the paper's grass is static.
pub const ANIMATE: bool = false;

/// The `paper` variant's overrides: exactly the constants above (tested).
pub const VARIANT: &str = r#"blades_per_m2 = 87800.0
patch_size = 0.5
vertical_slices = 10
vslice_width = 512
vslice_height = 64
slice_resolution = 512
transparency = "alpha_to_coverage"
animate = false"#;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Params;
    use grassbench::technique::variant_differences;

    #[test]
    fn the_paper_variant_sets_exactly_the_cited_values() {
        let cited = Params {
            blades_per_m2: BLADES_PER_M2,
            patch_size: PATCH_SIZE,
            vertical_slices: VERTICAL_SLICES,
            vslice_width: VSLICE_WIDTH,
            vslice_height: VSLICE_HEIGHT,
            slice_resolution: SLICE_RESOLUTION,
            transparency: TRANSPARENCY,
            animate: ANIMATE,
            ..Params::default()
        };
        assert_eq!(
            variant_differences("boulanger", VARIANT, &cited, 8),
            Vec::<String>::new()
        );
        // 627 M blades on 105 m x 68 m, to 0.1 %.
        let blades = f64::from(BLADES_PER_M2) * 105.0 * 68.0;
        assert!((blades / 627.0e6 - 1.0).abs() < 1e-3, "{blades}");
    }
}

//! The paper's own operating point: every value of the `paper` variant, named and cited.
//! The wind is the scene's: Perbet & Cani's receivers play wind primitives (Sec. 3), so the
//! paper's scene is `meadow_primitives` (a breeze, repeated gusts, a whirlwind and a blast);
//! under another wind model the receivers read its velocity ([`crate::receiver`]).

use crate::params::{Density, Quality};

/// Sec. 5.1's middle row, the one the paper's figures use ("medium" quality).
pub const QUALITY: Quality = Quality::Medium;
/// Sec. 5.1: the table's blades per patch (320 at medium), not the scene's density.
pub const DENSITY: Density = Density::Preset;
/// Sec. 4.1: "patches of grass of 2.5 x 2.5 meters".
pub const PATCH_SIZE: f32 = 2.5;
/// Sec. 4.1: "we set the duration of a transition to twenty iterations".
pub const TRANSITION_STEPS: u32 = 20;
/// Sec. 4.1: hysteresis, "different limits going back and forth" (one patch: the paper gives
/// no width; ours).
pub const HYSTERESIS: u32 = 1;

/// The `paper` variant's overrides: exactly the constants above (tested).
pub const VARIANT: &str = r#"quality = "medium"
density = "preset"
patch_size = 2.5
transition_steps = 20
hysteresis = 1"#;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Params;
    use grassbench::technique::variant_differences;

    #[test]
    fn the_paper_variant_sets_exactly_the_cited_values() {
        let cited = Params {
            quality: QUALITY,
            density: DENSITY,
            patch_size: PATCH_SIZE,
            transition_steps: TRANSITION_STEPS,
            hysteresis: HYSTERESIS,
            ..Params::default()
        };
        assert_eq!(
            variant_differences("perbet", VARIANT, &cited, 5),
            Vec::<String>::new()
        );
        // The preset's blades per patch, whatever the scene's density (Sec. 5.1: 320).
        assert_eq!(cited.blades(90.0), 320);
    }
}

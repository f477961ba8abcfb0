//! The paper's own operating point: every value of the `paper` variant, named and cited.
//! Where Bakay et al. state nothing (texture size, tile size, blade shape) the variant keeps
//! our defaults; `README.md` lists each departure and its measured effect.

use crate::params::{Lod, Mipmaps, WindSource};

/// Shells, the ground shell included: Fig. 4, "Close view of grass rendered with 16 shells".
pub const SHELLS: u32 = 16;
/// The wind: Sec. 3, "For the examples in this paper we have used a simple point source for
/// the wind", with animation steps by distance from it ("waves moving across the field").
pub const WIND: WindSource = WindSource::PointSource;
/// Fig. 5: "The wind source is roughly in the centre of the images" (the terrain's centre).
pub const SOURCE_POSITION: [f32; 3] = [0.0, 0.0, 0.0];
/// Sec. 3: the intensity "should be periodic, continuous and vary between -1.0 and 1.0": no
/// bias, so the grass swings both ways.
pub const SOURCE_BIAS: f32 = 0.0;
/// Sec. 3: values beyond ±1 "over-bend"; the paper's range ends at 1.
pub const MAX_INTENSITY: f32 = 1.0;
/// Sec. 3: "We increment the tilt angle a constant amount between shells" (exponent 1).
pub const STIFFNESS: f32 = 1.0;
/// Sec. 5: mipmaps generated automatically (custom ones keeping representative blades are
/// the paper's future work).
pub const MIPMAPS: Mipmaps = Mipmaps::Box;
/// The sampler's own mip choice (the paper's hardware path; `minor_axis` is ours).
pub const LOD: Lod = Lod::Hardware;
/// No level of detail: every chunk in view gets all the shells. Sec. 5 names fewer shells for
/// far-off parts of the landscape as future work ("however doing so also reduces the density
/// of the grass").
pub const SHELL_LOD_PIXELS: f32 = 0.0;
/// One texture blade per scene blade: the issue's "shell texture whose density matches the
/// scene's" (the paper's texture is a photograph-like height map of unknown density).
pub const DENSITY_SCALE: f32 = 1.0;

/// The `paper` variant's overrides: exactly the constants above (tested).
pub const VARIANT: &str = r#"shells = 16
wind = "point_source"
source_position = [0.0, 0.0, 0.0]
source_bias = 0.0
max_intensity = 1.0
stiffness = 1.0
mipmaps = "box"
lod = "hardware"
density_scale = 1.0
shell_lod_pixels = 0.0"#;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Params;
    use grassbench::technique::variant_differences;

    #[test]
    fn the_paper_variant_sets_exactly_the_cited_values() {
        let cited = Params {
            shells: SHELLS,
            wind: WIND,
            source_position: SOURCE_POSITION,
            source_bias: SOURCE_BIAS,
            max_intensity: MAX_INTENSITY,
            stiffness: STIFFNESS,
            mipmaps: MIPMAPS,
            lod: LOD,
            density_scale: DENSITY_SCALE,
            shell_lod_pixels: SHELL_LOD_PIXELS,
            ..Params::default()
        };
        assert_eq!(
            variant_differences("bakay", VARIANT, &cited, 10),
            Vec::<String>::new()
        );
    }
}

//! Parameters of the technique (`[techniques.boulanger]` in scene files, `--param` on the
//! command line).

use grassbench::grass::GrassConfig;
use grassbench::params::{TechniqueParams, check, check_ranges};
use grassbench::{Error, Result};

use crate::patch::PatchSpec;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// How semi-transparent blades and slices are composited (Sec. 4.2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Transparency {
    /// Alpha test with a low threshold removes what is clearly outside a blade, blending
    /// smooths the one-pixel borders; no sorting.
    Blend,
    /// Alpha to coverage on a 4x MSAA target (needs `--msaa`).
    AlphaToCoverage,
}

/// Most blades one patch may hold (its instance buffer and the start-up bake grow with it).
pub const MAX_BLADES_PER_PATCH: u32 = 512 * 512;

/// The technique's parameters.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Params {
    /// Side of the base patch and of a grid cell, m (Sec. 3.1).
    #[schemars(range(min = 0.05, max = 16.0))]
    pub patch_size: f32,
    /// Blades per square metre in the patch, tiled over the whole terrain; 0 (the default)
    /// takes the scene's `[grass] density`, so the field is comparable with the other
    /// techniques'. 87 800 gives the paper's ~627 M virtual blades on the 105 x 68 m football
    /// field (`football_field_human` sets it). A scene without grass (`grass.density = 0`)
    /// has none whatever this says.
    #[schemars(range(min = 0.0, max = 1e7))]
    pub blades_per_m2: f32,
    /// Quads per blade strip (Sec. 3.2).
    #[schemars(range(min = 1, max = 16))]
    pub segments: u32,
    /// Geometry at full weight up to this distance, m (Fig. 13).
    #[schemars(range(min = 0.0, max = 1e4))]
    pub min_geom: f32,
    /// No geometry beyond this distance, m.
    #[schemars(range(min = 0.0, max = 1e4))]
    pub max_geom: f32,
    /// Vertical slices at full weight up to this distance, m.
    #[schemars(range(min = 0.0, max = 1e5))]
    pub min_btf: f32,
    /// No vertical slices beyond this distance, m.
    #[schemars(range(min = 0.0, max = 1e5))]
    pub max_btf: f32,
    /// Half width of the smooth opacity transition, Eq. 5's ω (0 = hard test).
    #[schemars(range(min = 0.0, max = 1.0))]
    pub omega: f32,
    /// Sec. 3.4's seamless transitions: between two levels both representations draw the
    /// cell, the blades split between them by Eq. 2-5. `false` switches Sec. 3.1's levels
    /// abruptly instead, per cell by the distance to its centre, where the weights cross one
    /// half (`(min_geom + max_geom) / 2`, `(min_btf + max_btf) / 2`): every cell is entirely
    /// geometry or entirely slices, nothing is split or blended (the `no_transitions`
    /// variant, so that comparing the two isolates the paper's mechanism).
    pub transitions: bool,
    /// A macro-cell is drawn whole only when at least this many times its side away.
    #[schemars(range(min = 0.25, max = 64.0))]
    pub macro_factor: f32,
    /// Semi-transparency: `blend` or `alpha_to_coverage` (Sec. 4.2).
    pub transparency: Transparency,
    /// Alpha-test threshold of the `blend` mode.
    #[schemars(range(min = 0.0, max = 0.99))]
    pub alpha_threshold: f32,
    /// Side of the horizontal slice texture, texels.
    #[schemars(range(min = 16, max = 4096))]
    pub slice_resolution: u32,
    /// Vertical slices across each horizontal axis of a patch (Sec. 3.3; the paper's 10).
    #[schemars(range(min = 1, max = 32))]
    pub vertical_slices: u32,
    /// Width of a vertical slice's BTF texture, texels (along the patch side). The paper's
    /// 512 would take the start-up bake far past 10 s on lavapipe, where it is bound by fill;
    /// 128 halves the vertical part of the bake but ties `compare`'s popping with and without
    /// transitions on the meadow, so 256 (2 mm texels on a 0.5 m patch).
    #[schemars(range(min = 8, max = 2048))]
    pub vslice_width: u32,
    /// Height of a vertical slice's BTF texture, texels (the paper's slices are 512 x 64).
    #[schemars(range(min = 8, max = 2048))]
    pub vslice_height: u32,
    /// Folder of the BTF disk cache: empty for `$XDG_CACHE_HOME/grassbench/boulanger` (or
    /// `~/.cache/...`), `off` to bake at every start ([`crate::cache`]).
    pub btf_cache: String,
    /// Height of the horizontal slice above the ground, as a fraction of the tallest blade.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub slice_height: f32,
    /// Largest launch angle of a blade's particle from the vertical, radians.
    #[schemars(range(min = 0.0, max = 1.5))]
    pub max_tilt: f32,
    /// Gravity on the blade's particle, relative to its launch speed (droop).
    #[schemars(range(min = 0.0, max = 1.9))]
    pub gravity: f32,
    /// Wind push on the particle per m/s of wind, relative to gravity's scale.
    #[schemars(range(min = 0.0, max = 2.0))]
    pub wind_response: f32,
    /// Blade-to-blade shadows through the shadow mask (Sec. 3.5), on the blades and baked
    /// into the slices.
    pub shadow_mask: bool,
    /// The blades' and the horizontal slices' shadows projected on the ground along the sun
    /// (Sec. 3.5, Fig. 15: a stencil pass, then a darkening cover).
    pub ground_shadows: bool,
    /// Ambient occlusion of the grass by the covering map's trees and stones (Sec. 3.5).
    pub external_ao: bool,
    /// Height given to the covering map's trees, m (for the occlusion map).
    #[schemars(range(min = 0.0, max = 100.0))]
    pub tree_height: f32,
    /// Height given to the covering map's stones, m.
    #[schemars(range(min = 0.0, max = 100.0))]
    pub stone_height: f32,
    /// Animation (beyond the paper): the shared wind bends the geometric blades and shears
    /// the vertical slices' tops with them; `false` gives the paper's static grass.
    pub animate: bool,
    /// Fraction of back-side sunlight passing through a blade.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub translucency: f32,
    /// Ambient occlusion at the root (1 at the tip, linear in height: Sec. 3.2).
    #[schemars(range(min = 0.0, max = 1.0))]
    pub ao_root: f32,
}

impl Default for Params {
    fn default() -> Self {
        Self {
            patch_size: 0.5,
            blades_per_m2: 0.0,
            segments: 3,
            min_geom: 2.5,
            max_geom: 3.5,
            min_btf: 12.0,
            max_btf: 30.0,
            omega: 0.4,
            transitions: true,
            macro_factor: 4.0,
            transparency: Transparency::Blend,
            alpha_threshold: 0.1,
            slice_resolution: 512,
            vertical_slices: 10,
            vslice_width: 256,
            vslice_height: 64,
            btf_cache: String::new(),
            slice_height: 0.2,
            max_tilt: 0.4,
            gravity: 0.6,
            wind_response: 0.12,
            animate: true,
            shadow_mask: true,
            ground_shadows: true,
            external_ao: true,
            tree_height: 6.0,
            stone_height: 0.5,
            translucency: 0.35,
            ao_root: 0.35,
        }
    }
}

impl Params {
    /// The patch density in use: `blades_per_m2`, or the scene's grass density when it is 0;
    /// none where the scene has no grass (`scene_density = 0`).
    pub fn effective_blades_per_m2(&self, scene_density: f32) -> f32 {
        if scene_density.is_nan() || scene_density <= 0.0 {
            0.0
        } else if self.blades_per_m2 == 0.0 {
            scene_density
        } else {
            self.blades_per_m2
        }
    }

    /// The patch the scene's grass gives with these parameters ([`PatchSpec::for_density`]):
    /// its side (near `patch_size`) and blade count; refused when it would hold more than
    /// [`MAX_BLADES_PER_PATCH`] blades or be wider than 16 m.
    pub fn patch_spec(&self, grass: &GrassConfig) -> Result<PatchSpec> {
        let spec =
            PatchSpec::for_density(self.patch_size, self.effective_blades_per_m2(grass.density));
        if spec.blades > MAX_BLADES_PER_PATCH || spec.side > 16.0 {
            return Err(Error::param(
                "boulanger.patch_size",
                self.patch_size,
                format!(
                    "a patch of at most {MAX_BLADES_PER_PATCH} blades and 16 m: at {} blades/m² it would hold {} blades on {:.3} m",
                    self.effective_blades_per_m2(grass.density),
                    spec.blades,
                    spec.side
                ),
            ));
        }
        Ok(spec)
    }

    /// These parameters as the scene's patch makes them: `patch_size` the side of the patch
    /// actually tiled ([`Self::patch_spec`]), `blades_per_m2` the density in use. Everything
    /// the technique builds uses these; [`crate::Boulanger`] still reports the parameters as
    /// given.
    pub fn for_scene(&self, grass: &GrassConfig) -> Result<Self> {
        let spec = self.patch_spec(grass)?;
        Ok(Self {
            patch_size: spec.side,
            blades_per_m2: self.effective_blades_per_m2(grass.density),
            ..self.clone()
        })
    }
}

impl TechniqueParams for Params {
    fn validate(&self) -> Result<()> {
        check_ranges("boulanger", self)?;
        // 0 takes the scene's density; anything else is at least one blade per m².
        if self.blades_per_m2 != 0.0 {
            check("boulanger.blades_per_m2", self.blades_per_m2, 1.0..=1e7)?;
        }
        let per_patch = f64::from(self.blades_per_m2) * f64::from(self.patch_size).powi(2);
        if per_patch > f64::from(MAX_BLADES_PER_PATCH) {
            return Err(Error::param(
                "boulanger.blades_per_m2",
                self.blades_per_m2,
                format!(
                    "at most {MAX_BLADES_PER_PATCH} blades per patch ({per_patch:.0} with boulanger.patch_size = {})",
                    self.patch_size
                ),
            ));
        }
        for (name, lo, hi) in [
            ("boulanger.max_geom", self.min_geom, self.max_geom),
            ("boulanger.min_btf", self.max_geom, self.min_btf),
            ("boulanger.max_btf", self.min_btf, self.max_btf),
        ] {
            // Eq. 2-4 divide by these differences.
            let strict = name != "boulanger.min_btf";
            if hi < lo || (strict && hi <= lo) {
                return Err(Error::param(
                    name,
                    hi,
                    format!(
                        "min_geom < max_geom <= min_btf < max_btf (Fig. 13); the previous one is {lo}"
                    ),
                ));
            }
        }
        if !self.slice_resolution.is_power_of_two() {
            return Err(Error::param(
                "boulanger.slice_resolution",
                self.slice_resolution,
                "a power of two (the mip chain halves it exactly)",
            ));
        }
        for (name, v) in [
            ("boulanger.vslice_width", self.vslice_width),
            ("boulanger.vslice_height", self.vslice_height),
        ] {
            if !v.is_power_of_two() {
                return Err(Error::param(
                    name,
                    v,
                    "a power of two (the mip chain halves it exactly)",
                ));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_bad_values_name_their_key() {
        Params::default().validate().unwrap();
        let bad = |f: &dyn Fn(&mut Params), key: &str| {
            let mut p = Params::default();
            f(&mut p);
            let e = p.validate().unwrap_err().to_string();
            assert!(e.contains(key), "{e}");
        };
        bad(&|p| p.omega = f32::NAN, "boulanger.omega");
        bad(&|p| p.max_geom = 1.0, "boulanger.max_geom");
        bad(&|p| p.max_btf = 5.0, "boulanger.max_btf");
        bad(&|p| p.blades_per_m2 = 9e6, "boulanger.blades_per_m2");
        bad(&|p| p.segments = 0, "boulanger.segments");
        bad(&|p| p.vertical_slices = 0, "boulanger.vertical_slices");
        bad(&|p| p.vslice_width = 100, "boulanger.vslice_width");
        bad(&|p| p.vslice_height = 1 << 20, "boulanger.vslice_height");
        let mut t = toml::Table::new();
        t.insert("transparency".into(), "alpha_to_coverage".into());
        let p: Params = grassbench::params::resolve("boulanger", &t).unwrap();
        assert_eq!(p.transparency, Transparency::AlphaToCoverage);
        t.insert("transparency".into(), "sorted".into());
        assert!(grassbench::params::resolve::<Params>("boulanger", &t).is_err());
    }

    /// Every key has a description, and `validate` accepts each end of the schema's ranges
    /// and refuses the values just past them (the schema is where the ranges are written).
    #[test]
    fn the_schema_describes_every_key_and_validate_keeps_its_ranges() {
        assert_eq!(
            grassbench::params::schema_problems::<Params>(
                "boulanger",
                &[
                    // Fig. 13's ordering and the blades a patch may hold narrow these.
                    "boulanger.blades_per_m2",
                    "boulanger.max_geom",
                    "boulanger.min_btf",
                    "boulanger.max_btf",
                ]
            ),
            Vec::<String>::new()
        );
    }
}

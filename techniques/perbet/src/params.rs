//! Parameters of the technique (`[techniques.perbet]` in scene files, `--param` on the command
//! line), with the paper's three quality presets (Sec. 5.1's table).

use grassbench::params::{TechniqueParams, check_int, check_ranges};
use grassbench::{Error, Result};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Perbet & Cani's quality instances (Sec. 5.1): blades per patch, segments per blade and the
/// discrete-distance range of the 2.5D representation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Quality {
    /// 160 blades a patch, 3 segments, 2.5D from distance 3 to 8.
    Low,
    /// 320 blades a patch, 4 segments, 2.5D from distance 2 to 12.
    Medium,
    /// 500 blades a patch, 8 segments, 2.5D from distance 3 to 20.
    High,
}

/// Where the number of blades in a patch comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Density {
    /// The scene's `[grass] density` times the patch area, so perbet shows the same population
    /// as the other techniques it is compared with.
    Scene,
    /// The quality preset's blades per patch (the paper's table).
    Preset,
}

/// What a [`Quality`] sets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Preset {
    /// Blades in one patch (all three representations show the same blades).
    pub blades_per_patch: u32,
    /// Line segments per 3D blade.
    pub segments: u32,
    /// First and last discrete distance drawn as 2.5D strips (3D below, 2D beyond).
    pub strip_range: [u32; 2],
}

impl Quality {
    /// The row of the paper's table.
    pub fn preset(self) -> Preset {
        match self {
            Self::Low => Preset {
                blades_per_patch: 160,
                segments: 3,
                strip_range: [3, 8],
            },
            Self::Medium => Preset {
                blades_per_patch: 320,
                segments: 4,
                strip_range: [2, 12],
            },
            Self::High => Preset {
                blades_per_patch: 500,
                segments: 8,
                strip_range: [3, 20],
            },
        }
    }
}

/// Most blades one patch may hold.
pub const MAX_BLADES_PER_PATCH: u32 = 4096;
/// Most segments a blade may have (the shader's loops are bounded by it).
pub const MAX_SEGMENTS: u32 = 12;
/// Largest discrete distance a range may name (beyond any terrain's patch count).
pub const MAX_DISTANCE: u32 = 100_000;

/// The technique's parameters. Zero in `segments` or `strip_range` means "from the quality
/// preset"; zero in `blades_per_patch` means "as `density` says".
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Params {
    /// `low`, `medium` or `high` (Sec. 5.1).
    pub quality: Quality,
    /// Where blades per patch come from when `blades_per_patch` is 0: `scene` (the scene's
    /// density, the default, for comparisons) or `preset` (the paper's table).
    pub density: Density,
    /// Blades in a patch; 0 = as `density` says.
    #[schemars(range(min = 0, max = MAX_BLADES_PER_PATCH))]
    pub blades_per_patch: u32,
    /// Line segments per blade; 0 = the preset's.
    #[schemars(range(min = 0, max = MAX_SEGMENTS))]
    pub segments: u32,
    /// First and last discrete (Chebyshev) distance, in patches, drawn as 2.5D strips; 3D
    /// below, 2D beyond; `[0, 0]` = the preset's.
    #[schemars(inner(range(min = 0, max = MAX_DISTANCE)))]
    pub strip_range: [u32; 2],
    /// Side of a patch, m (the paper's 2.5 m).
    #[schemars(range(min = 0.25, max = 50.0))]
    pub patch_size: f32,
    /// Different pre-computed patches tiled over the terrain (chosen per patch by a hash).
    #[schemars(range(min = 1, max = 16))]
    pub variants: u32,
    /// Kinds of grass (Sec. 3.2): the scene's height range cut into this many classes, each
    /// with its own simulated postures, so one wind bends tall grass further than short.
    #[schemars(range(min = 1, max = 4))]
    pub kinds: u32,
    /// Parallel strips per orientation in a patch (the number of polygons of the 2.5D
    /// representation, Sec. 2.1). Strips are what costs: a view across the 2.5D band crosses
    /// `strips / patch_size` semi-transparent layers per metre. On the meadow (medium preset,
    /// lavapipe, 640x360) 8 strips took 244 ms a frame and 4 took 139 ms for a picture hard to
    /// tell apart (each strip paints every blade of its slab, so coverage is the same).
    #[schemars(range(min = 1, max = 64))]
    pub strips: u32,
    /// Polygons along one strip; their vertical edges carry the receivers (Fig. 3).
    #[schemars(range(min = 1, max = 32))]
    pub strip_columns: u32,
    /// How far a strip reaches past the patch on each side, as a fraction of the patch, so
    /// blades leaning out of the patch are painted whole.
    #[schemars(range(min = 0.0, max = 0.5))]
    pub strip_margin: f32,
    /// Strip texture width in texels (its height follows at the same texel size).
    #[schemars(range(min = 16, max = 2048))]
    pub strip_texels: u32,
    /// 2D terrain texture side in texels (mipmapped).
    #[schemars(range(min = 8, max = 2048))]
    pub flat_texels: u32,
    /// Patches a level's outer limit is extended by before a patch moving away leaves it
    /// (Sec. 4.1: different limits going back and forth).
    #[schemars(range(min = 0, max = 8))]
    pub hysteresis: u32,
    /// Settled 2D patches are drawn by square blocks of `s x s` patches (up to 8) once the
    /// block is at least `flat_block_distance · s` patches from the camera's patch, so the 2D
    /// level costs about as much on a 400 m terrain as on an 80 m one; 0 draws every 2D patch
    /// on its own (as before the blocks).
    #[schemars(range(min = 0, max = 64))]
    pub flat_block_distance: u32,
    /// Frames a transition lasts (Sec. 4.1: twenty); 0 switches levels at once.
    #[schemars(range(min = 0, max = 600))]
    pub transition_steps: u32,
    /// Fraction at the end of a 3D ↔ 2.5D morph spent cross-fading the two (Sec. 4.2).
    #[schemars(range(min = 0.0, max = 1.0))]
    pub fade: f32,
    /// Largest random tilt of one blade segment from its predecessor, radians (Sec. 2.2:
    /// "random numbers set the orientation of each blade segment").
    #[schemars(range(min = 0.0, max = 0.6))]
    pub segment_jitter: f32,
    /// For winds other than primitives: the wind speed (m/s) that a posture index of 1 stands
    /// for, as in `PrimitiveSet`'s own velocity. At 8 m/s the meadow's 3.5 m/s breeze bends a
    /// blade's tip about 0.35 rad, as far as the reference's blades bend in it.
    #[schemars(range(min = 0.1, max = 100.0))]
    pub wind_speed: f32,
    /// Fraction of back-side sunlight passing through a blade.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub translucency: f32,
}

impl Default for Params {
    fn default() -> Self {
        Self {
            quality: Quality::Medium,
            density: Density::Scene,
            blades_per_patch: 0,
            segments: 0,
            strip_range: [0, 0],
            patch_size: 2.5,
            variants: 4,
            kinds: 2,
            strips: 4,
            strip_columns: 4,
            strip_margin: 0.12,
            strip_texels: 256,
            flat_texels: 128,
            hysteresis: 1,
            flat_block_distance: 4,
            transition_steps: 20,
            fade: 0.25,
            segment_jitter: 0.12,
            wind_speed: 8.0,
            translucency: 0.35,
        }
    }
}

impl Params {
    /// Blades per patch for a scene of `density` blades per m²: with `density = "scene"`,
    /// `density · patch_size²` rounded, so 0 when the scene has no grass (or less than half a
    /// blade a patch).
    pub fn blades(&self, density: f32) -> u32 {
        let from = match self.density {
            Density::Preset => self.quality.preset().blades_per_patch,
            Density::Scene => (density * self.patch_size * self.patch_size)
                .round()
                .clamp(0.0, MAX_BLADES_PER_PATCH as f32) as u32,
        };
        or_preset(self.blades_per_patch, from)
    }

    /// Segments per blade after the preset.
    pub fn blade_segments(&self) -> u32 {
        or_preset(self.segments, self.quality.preset().segments)
    }

    /// The 2.5D range after the preset.
    pub fn strips_from_to(&self) -> [u32; 2] {
        if self.strip_range == [0, 0] {
            self.quality.preset().strip_range
        } else {
            self.strip_range
        }
    }

    /// Edges (receivers) per strip.
    pub fn strip_edges(&self) -> u32 {
        self.strip_columns + 1
    }
}

fn or_preset(value: u32, preset: u32) -> u32 {
    if value == 0 { preset } else { value }
}

impl TechniqueParams for Params {
    fn validate(&self) -> Result<()> {
        check_ranges("perbet", self)?;
        let [from, to] = self.strip_range;
        if self.strip_range != [0, 0] {
            check_int("perbet.strip_range[0]", from, 1..=MAX_DISTANCE)?;
            check_int("perbet.strip_range[1]", to, 1..=MAX_DISTANCE)?;
            if to < from {
                return Err(Error::param(
                    "perbet.strip_range",
                    format!("[{from}, {to}]"),
                    "[first, last] with last >= first, e.g. [2, 12]",
                ));
            }
        }
        if !self.flat_texels.is_power_of_two() {
            return Err(Error::param(
                "perbet.flat_texels",
                self.flat_texels,
                "a power of two (it is mipmapped), e.g. 128",
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_are_the_papers_table() {
        let rows = [Quality::Low, Quality::Medium, Quality::High].map(|q| q.preset());
        assert_eq!(rows.map(|p| p.blades_per_patch), [160, 320, 500]);
        assert_eq!(rows.map(|p| p.segments), [3, 4, 8]);
        assert_eq!(rows.map(|p| p.strip_range), [[3, 8], [2, 12], [3, 20]]);
    }

    #[test]
    fn zero_means_preset_and_overrides_win() {
        let mut p = Params::default();
        // The scene's 90 blades/m² on 2.5 m patches; none without grass; the preset's 320
        // when asked for.
        assert_eq!(p.blades(90.0), 563);
        assert_eq!((p.blades(0.0), p.blades(0.07), p.blades(0.09)), (0, 0, 1));
        p.density = Density::Preset;
        assert_eq!(
            (p.blades(90.0), p.blade_segments(), p.strips_from_to()),
            (320, 4, [2, 12])
        );
        p.quality = Quality::High;
        p.segments = 5;
        p.strip_range = [4, 9];
        assert_eq!(
            (p.blades(90.0), p.blade_segments(), p.strips_from_to()),
            (500, 5, [4, 9])
        );
        p.validate().unwrap();
    }

    #[test]
    fn bad_values_name_the_key() {
        type Break = fn(&mut Params);
        let cases: [(Break, &str); 5] = [
            (|p| p.patch_size = f32::NAN, "perbet.patch_size"),
            (|p| p.strip_range = [8, 3], "perbet.strip_range"),
            (|p| p.flat_texels = 100, "perbet.flat_texels"),
            (|p| p.segments = 99, "perbet.segments"),
            (|p| p.fade = -1.0, "perbet.fade"),
        ];
        for (break_it, key) in cases {
            let mut p = Params::default();
            break_it(&mut p);
            let message = p.validate().unwrap_err().to_string();
            assert!(message.contains(key), "{message}");
        }
    }

    /// Every key has a description, and `validate` accepts each end of the schema's ranges
    /// and refuses the values just past them (the schema is where the ranges are written).
    #[test]
    fn the_schema_describes_every_key_and_validate_keeps_its_ranges() {
        assert_eq!(
            grassbench::params::schema_problems::<Params>("perbet", &[]),
            Vec::<String>::new()
        );
    }
}

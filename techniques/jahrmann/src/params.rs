//! Parameters (`[techniques.jahrmann]` in scene files, `--param` on the command line) and the
//! variants the comparison suite asks for.

use grassbench::Result;
use grassbench::params::{TechniqueParams, check_ranges};
use grassbench::technique::{NO_TRANSITIONS, Variant, Variants};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Every parameter of the technique. The defaults and where each came from are in the crate's
/// essay (`src/lib.rs`, "Parameters").
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Params {
    /// Recovery rate (Hooke, Sec. 5.1) of a blade of the scene's stiffness 1, per second: the
    /// tip returns to rest with time constant `1 / (stiffness × blade stiffness)`.
    #[schemars(range(min = 0.1, max = 10_000.0))]
    pub stiffness: f32,
    /// Magnitude of the environmental gravity, m/s² of tip displacement rate (Sec. 5.1; the
    /// model is first order, so this is not the physical 9.81: see the essay).
    #[schemars(range(min = 0.0, max = 100.0))]
    pub gravity: f32,
    /// Wind force on the tip per metre of blade height per m/s of wind, before the alignment
    /// term (Sec. 5.1).
    #[schemars(range(min = 0.0, max = 1000.0))]
    pub wind_response: f32,
    /// Cull blades seen edge-on (the paper's orientation test).
    pub orientation_culling: bool,
    /// `|view direction · width direction|` above which a blade is culled (the paper's 0.9).
    #[schemars(range(min = 0.0, max = 1.0))]
    pub orientation_threshold: f32,
    /// Cull blades whose root, midpoint and tip all lie outside the view frustum.
    pub frustum_culling: bool,
    /// How far outside a frustum plane a point may lie and still count as inside, m.
    #[schemars(range(min = 0.0, max = 100.0))]
    pub frustum_tolerance: f32,
    /// Drop blades progressively with distance by bucket (the paper's distance test).
    pub distance_culling: bool,
    /// Ground distance from the eye beyond which no blade is kept, m (the paper's `d_max`).
    #[schemars(range(min = 1.0, max = 100_000.0))]
    pub cull_distance: f32,
    /// Ground distance beyond which the distance test also thins blades as `(D / d)²` (about
    /// as many blades per pixel at any distance), widening those kept by `(d / D)²` so they
    /// cover what the others covered, m (not in the paper; 0: off, the paper's test alone).
    #[schemars(range(min = 0.0, max = 100_000.0))]
    pub thin_distance: f32,
    /// Distance buckets (the paper's `n`): blades of the first `cull_distance / buckets`
    /// metres are all kept, then one bucket's blades fewer per further bucket.
    #[schemars(range(min = 1, max = 64))]
    pub buckets: u32,
    /// Side of the square ground tiles the compute pass is dispatched over, m: each frame
    /// only the tiles that meet the view frustum are simulated and culled, and in each only
    /// the blades the distance test and the far level can still draw there (`tiles.rs`); 0
    /// dispatches every blade every frame (the paper).
    #[schemars(range(min = 0.0, max = 1000.0))]
    pub dispatch_tile: f32,
    /// Two levels of detail (Ghost of Tsushima): 15 vertices a blade near, 7 far.
    pub lod: bool,
    /// Side of the square ground tiles whose blades change level together, m (Ghost of
    /// Tsushima's tiles; 0 chooses each blade's level by its own root).
    #[schemars(range(min = 0.0, max = 1000.0))]
    pub tile_size: f32,
    /// Distance from the eye to a tile's centre where the far level begins, m.
    #[schemars(range(min = 0.0, max = 100_000.0))]
    pub lod_distance: f32,
    /// The far level keeps one blade in `far_keep`.
    #[schemars(range(min = 1, max = 64))]
    pub far_keep: u32,
    /// Width factor of the far level's blades, so the survivors cover what the dropped
    /// blades covered.
    #[schemars(range(min = 0.1, max = 64.0))]
    pub far_widen: f32,
    /// Blend the hand-overs (near to far, distance culling, orientation culling) instead of
    /// switching.
    pub transitions: bool,
    /// Depth of the near-to-far hand-over band, m: over it the near level's shapes morph to
    /// the far level's, the dropped blades narrow to nothing and the survivors widen.
    #[schemars(range(min = 0.0, max = 10_000.0))]
    pub band: f32,
    /// Distance over which a blade narrows to nothing before distance culling drops it, m.
    #[schemars(range(min = 0.0, max = 10_000.0))]
    pub distance_fade: f32,
    /// Range of `|view · width|` below the orientation threshold over which a blade narrows
    /// to nothing before orientation culling drops it.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub orientation_fade: f32,
    /// Fraction of back-side sunlight passing through a blade (as `reference`).
    #[schemars(range(min = 0.0, max = 1.0))]
    pub translucency: f32,
}

impl Default for Params {
    fn default() -> Self {
        Self {
            stiffness: 30.0,
            gravity: 0.6,
            wind_response: 1.44,
            orientation_culling: true,
            orientation_threshold: 0.9,
            frustum_culling: true,
            frustum_tolerance: 0.1,
            distance_culling: true,
            cull_distance: 240.0,
            buckets: 8,
            thin_distance: 40.0,
            dispatch_tile: 8.0,
            lod: true,
            tile_size: 4.0,
            lod_distance: 15.0,
            far_keep: 4,
            far_widen: 4.0,
            transitions: true,
            band: 5.0,
            distance_fade: 4.0,
            orientation_fade: 0.05,
            translucency: 0.35,
        }
    }
}

impl TechniqueParams for Params {
    fn validate(&self) -> Result<()> {
        check_ranges("jahrmann", self)
    }
}

/// `finest`: culling and levels of detail off, so every blade of the scene is drawn at the
/// near level, where the reference draws it; `no_transitions`: every hand-over switches at
/// once.
pub const VARIANTS: Variants = Variants {
    finest: "orientation_culling = false\nfrustum_culling = false\ndistance_culling = false\nlod = false",
    others: &[Variant {
        name: NO_TRANSITIONS,
        params: "transitions = false",
    }],
};

impl Params {
    /// Culling settings drawn from `rng` over the ranges the property tests sweep (the cull
    /// distance, buckets, hand-over distance, tile size and frustum tolerance), with the
    /// tests `switches` turns on: orientation, frustum, distance, levels, transitions. For the
    /// crate's tests and the GPU twins (`tests/tests/twins.rs`), which must draw alike.
    pub fn random_culling(rng: &mut grassbench::rng::Rng, switches: [bool; 5]) -> Self {
        Self {
            orientation_culling: switches[0],
            frustum_culling: switches[1],
            distance_culling: switches[2],
            lod: switches[3],
            transitions: switches[4],
            cull_distance: rng.range(20.0, 300.0),
            buckets: 1 + (rng.next_u64() % 12) as u32,
            lod_distance: rng.range(0.0, 40.0),
            tile_size: if rng.next_f32() < 0.3 {
                0.0
            } else {
                rng.range(1.0, 8.0)
            },
            frustum_tolerance: rng.range(0.0, 0.5),
            ..Self::default()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_pass_and_bad_values_name_their_key() {
        Params::default().validate().unwrap();
        let bad = Params {
            buckets: 0,
            ..Default::default()
        };
        assert!(
            bad.validate()
                .unwrap_err()
                .to_string()
                .contains("jahrmann.buckets")
        );
        let nan = Params {
            far_widen: f32::NAN,
            ..Default::default()
        };
        assert!(
            nan.validate()
                .unwrap_err()
                .to_string()
                .contains("jahrmann.far_widen")
        );
    }

    /// Every key has a description, and `validate` accepts each end of the schema's ranges
    /// and refuses the values just past them (the schema is where the ranges are written).
    #[test]
    fn the_schema_describes_every_key_and_validate_keeps_its_ranges() {
        assert_eq!(
            grassbench::params::schema_problems::<Params>("jahrmann", &[]),
            Vec::<String>::new()
        );
    }
}

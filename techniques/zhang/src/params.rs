//! The technique's parameters (`[techniques.zhang]` in scene files, `--param` on the command
//! line).

use grassbench::Result;
use grassbench::params::{TechniqueParams, check_ranges};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// How translucent plants are composited (Sec. 5.4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Sorting {
    /// The thesis: grids, billboards and single plants drawn far to near (quicksort and
    /// pre-computed orders) and blended with Eq. (10).
    Sort,
    /// No sorting: alpha test with depth writes (alpha to coverage under MSAA), so the cost
    /// of sorting can be measured against it.
    AlphaToCoverage,
}

/// Where the billboard wings are lit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum WingLighting {
    /// Ambient and sun per vertex (exact over a wing: only the ambient occlusion varies,
    /// affinely in height), the point light and nothing else per pixel (ours).
    Vertex,
    /// Every light per pixel, as the single blades are lit (the thesis lights its
    /// billboards no differently from its plants).
    Pixel,
}

/// Parameters of [`crate::Zhang`]. Defaults follow the thesis where it gives numbers.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Params {
    /// Grass grids along the terrain's longer side when `grid_size = 0` (Sec. 5.1: the
    /// thesis' fixed 16 x 16, whatever the terrain's size).
    #[schemars(range(min = 1, max = 256))]
    pub grids: u32,
    /// Side of a grass grid on the scene's strata, m (ours; issue 20 §7). Above 0 it replaces
    /// the thesis' count `grids`: a grid is the whole number of strata nearest this side, so
    /// the single-plant region (3 x 3 grids) stays the same size however large the terrain.
    /// 0: `grids` grids along the longer side, as the thesis. The thesis' lattice
    /// (`blades_per_side > 0`, the `paper` variant) always fits `grids x grids` grids over the
    /// terrain. The default 5.1 m keeps the meadow's 16 x 16 grids at 80 m (48 strata a side
    /// at 90 blades/m², 23 at 20).
    #[schemars(range(min = 0.0, max = 10_000.0))]
    pub grid_size: f32,
    /// Lattice points per grass-grid side. 0 (the default): the scene's blade strata
    /// (`grassbench::grass::BladeField`), as many a side as it takes `grids` grids to cover
    /// the terrain, so zhang draws the scene's population, the same blades as the reference.
    /// Above 0: the thesis' fixed lattice of that many jittered candidates a side per grid
    /// (Sec. 3.1.2 and 5.1: 32 x 32), whatever the scene's `grass.density` (paper-like
    /// figures; see [`crate::prairie`]).
    #[schemars(range(min = 0, max = 512))]
    pub blades_per_side: u32,
    /// On the thesis' lattice (`blades_per_side > 0`): random placement offset, as a fraction
    /// of the spacing (1 = anywhere in its cell). The scene's strata are jittered by the
    /// scene's blade field (anywhere in their cell).
    #[schemars(range(min = 0.0, max = 1.0))]
    pub jitter: f32,
    /// Backbone points per blade, `n` of Eq. (5) (Fig. 5 uses 4; segments = n − 1).
    #[schemars(range(min = 2, max = 16))]
    pub backbone_points: u32,
    /// Wind acceleration per m/s of wind, per metre of blade height, 1/s (Eq. 7's `a`).
    #[schemars(range(min = 0.0, max = 1000.0))]
    pub wind_response: f32,
    /// Pull of each control point back to its rest position, 1/s² (see the essay: an
    /// addition, the thesis has no restoring force).
    #[schemars(range(min = 0.0, max = 10_000.0))]
    pub spring: f32,
    /// Velocity damping of the Verlet step, 1/s (an addition, see the essay).
    #[schemars(range(min = 0.0, max = 1000.0))]
    pub damping: f32,
    /// Mass of a flower's petal point relative to a blade control point (Sec. 3.4: heavier
    /// moves slower and less).
    #[schemars(range(min = 0.01, max = 1000.0))]
    pub flower_mass: f32,
    /// Fraction of blade positions that also carry a flower (Sec. 3.3).
    #[schemars(range(min = 0.0, max = 1.0))]
    pub flower_fraction: f32,
    /// Petal quad side, m.
    #[schemars(range(min = 0.001, max = 10.0))]
    pub petal_size: f32,
    /// Fraction of back-side sunlight passing through a blade.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub translucency: f32,
    /// Alpha below which texels are discarded (alpha test).
    #[schemars(range(min = 0.01, max = 0.99))]
    pub alpha_cutoff: f32,
    /// View-frustum culling of grass grids (Sec. 5.3); off draws every grid every frame.
    pub culling: bool,
    /// Level of detail (Sec. 5.2): the camera grid and its eight neighbours as single plants,
    /// the other grids as billboards (Ch. 4). Off draws single plants everywhere (the
    /// `finest` variant).
    pub lod: bool,
    /// Far groups (ours, issue 20 §7; [`crate::billboard::GroupLevel`]): from this grid
    /// offset on, blocks of 2 x 2 grids (aligned on even grids) are drawn as one billboard
    /// each, from `⌈√2·far_groups⌉` on blocks of 4 x 4, then 8 x 8 from `2·far_groups`, ...
    /// (the side doubling every `√2` in offset), so the far billboards' count stays bounded
    /// however large the terrain. 0: every grid is drawn on its own at Eq. 8's steps, as the
    /// thesis does (the `paper` variant). The default 16 is past the meadow's 16 x 16 grids
    /// at 80 m (no group there).
    #[schemars(range(min = 0, max = 65_536))]
    pub far_groups: u32,
    /// Extra sway of billboards per grid of offset beyond 2 (Sec. 4.2: far billboards move
    /// more so their motion stays visible): a billboard `g` grids away moves its top by
    /// `1 + billboard_sway·(g − 2)` times its plants' displacement. 0 = exactly the plants'.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub billboard_sway: f32,
    /// Far-to-near sorting with blending (`"sort"`, Sec. 5.4) or alpha to coverage without
    /// sorting (`"alpha_to_coverage"`).
    pub sorting: Sorting,
    /// Radius of the transition sphere (Sec. 6.1) as a fraction of the grid size: within it
    /// of a grid border, grids that switch between billboards and single plants there are
    /// drawn both ways, fading. 0 switches at once (the `no_transitions` variant).
    #[schemars(range(min = 0.0, max = 0.5))]
    pub fade_radius: f32,
    /// Draw each billboard wing cut down to the texels it can show (the same image where a
    /// wing is planar, a quarter less fill; [`crate::wing_trim`]); off draws whole
    /// rectangles as the thesis does.
    pub trim_wings: bool,
    /// Billboard wing lighting: `"vertex"` (ambient and sun per vertex, the picture of per
    /// pixel for less fill work; ours) or `"pixel"` (every light per pixel, the thesis's).
    pub wing_lighting: WingLighting,
    /// Animated blades that are not drawn this frame (culled grids, grids two away, anchors
    /// beyond the drawn step's) take one step every other frame with one wind sample (ours,
    /// about a third of the meadow's CPU animation); `false` steps every animated blade every
    /// frame with the wind at each control point, as the thesis does (Sec. 3.2, 5.2).
    pub hidden_half_rate: bool,
}

impl Default for Params {
    fn default() -> Self {
        Self {
            grids: 16,
            grid_size: 5.1,
            blades_per_side: 0,
            jitter: 1.0,
            backbone_points: 5,
            wind_response: 2.5,
            spring: 40.0,
            damping: 4.0,
            flower_mass: 4.0,
            flower_fraction: 0.02,
            petal_size: 0.07,
            translucency: 0.35,
            alpha_cutoff: 0.5,
            culling: true,
            lod: true,
            far_groups: 16,
            billboard_sway: 0.05,
            sorting: Sorting::Sort,
            fade_radius: 0.25,
            trim_wings: true,
            wing_lighting: WingLighting::Vertex,
            hidden_half_rate: true,
        }
    }
}

/// Alpha cut-off while blending (Sec. 5.4): only the clear part of the textures is discarded.
pub const BLEND_CUTOFF: f32 = 0.05;

impl Params {
    /// The alpha cut-off the shaders and the wing trim use: `alpha_cutoff`, at most
    /// [`BLEND_CUTOFF`] when sorting blends (Sec. 5.4).
    pub fn effective_alpha_cutoff(&self) -> f32 {
        if self.sorting == Sorting::Sort {
            self.alpha_cutoff.min(BLEND_CUTOFF)
        } else {
            self.alpha_cutoff
        }
    }
}

impl TechniqueParams for Params {
    fn validate(&self) -> Result<()> {
        check_ranges("zhang", self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_validate_and_bad_values_name_the_key() {
        Params::default().validate().unwrap();
        let bad = |f: fn(&mut Params), key: &str| {
            let mut p = Params::default();
            f(&mut p);
            let e = p.validate().unwrap_err().to_string();
            assert!(e.contains(key), "{e}");
        };
        bad(|p| p.grids = 0, "zhang.grids");
        bad(|p| p.grid_size = -1.0, "zhang.grid_size");
        bad(|p| p.grid_size = f32::NAN, "zhang.grid_size");
        bad(|p| p.backbone_points = 1, "zhang.backbone_points");
        bad(|p| p.wind_response = f32::NAN, "zhang.wind_response");
        bad(|p| p.flower_fraction = 2.0, "zhang.flower_fraction");
        bad(|p| p.blades_per_side = 100_000, "zhang.blades_per_side");
        bad(|p| p.blades_per_side = 513, "zhang.blades_per_side");
        bad(|p| p.jitter = -0.1, "zhang.jitter");
        bad(|p| p.spring = f32::NAN, "zhang.spring");
        bad(|p| p.damping = -1.0, "zhang.damping");
        bad(|p| p.flower_mass = 0.0, "zhang.flower_mass");
        bad(|p| p.petal_size = 0.0, "zhang.petal_size");
        bad(|p| p.translucency = 1.5, "zhang.translucency");
        bad(|p| p.alpha_cutoff = 1.0, "zhang.alpha_cutoff");
        // 0 is the scene's strata, any count up to 512 the thesis' lattice.
        for n in [0, 1, 32, 512] {
            Params {
                blades_per_side: n,
                ..Params::default()
            }
            .validate()
            .unwrap();
        }
        bad(|p| p.billboard_sway = f32::INFINITY, "zhang.billboard_sway");
        bad(|p| p.fade_radius = 0.75, "zhang.fade_radius");
    }

    /// Every key has a description, and `validate` accepts each end of the schema's ranges
    /// and refuses the values just past them (the schema is where the ranges are written).
    #[test]
    fn the_schema_describes_every_key_and_validate_keeps_its_ranges() {
        assert_eq!(
            grassbench::params::schema_problems::<Params>("zhang", &[]),
            Vec::<String>::new()
        );
    }
}

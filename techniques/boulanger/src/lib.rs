//! # `boulanger`: geometry near, slices far, density thresholds in between
//!
//! Boulanger, Pattanaik and Bouatouch, *Rendering Grass in Real Time with Dynamic Light
//! Sources* (2006; the transcript is `shared/seeds/001_15b45c4dc11230fe.txt`). Part 1 (issue 8):
//! geometric blades, the tiled and mirrored patch, density management, the LOD weights with
//! their smooth transition, the quadtree terrain with macro-cells, the horizontal slice for far
//! grass and both semi-transparency modes. Part 2 (issue 9):
//! - the vertical slices of the mid band and the BTF pre-computation of every slice (five light
//!   directions x the slice's two view directions, K_d, alpha, density threshold), with its
//!   disk cache;
//! - Appendix A's spherical barycentric light interpolation; the scene's lights moving at run
//!   time (keyframes of the sun and of a point light with Sec. 3.3's attenuation, `[lights]`);
//! - Sec. 3.5's shadows: the blades' and the horizontal slices' shadows projected on the ground
//!   (stencil), the shadow-mask cylinder (blade-to-blade shadows on the blades, baked into the
//!   slices) and the ambient occlusion map (the covering map's trees and stones);
//! - the vertical slices sheared with the wind that bends the blades (beyond the paper).
//!
//! The UI moves the sun and the point light at run time (`grassbench ui`, panels "sun" and
//! "point light").
//!
//! ## Algorithm
//! - **One patch, tiled** (Sec. 3.1, [`patch`]). A square patch holds the scene's density
//!   exactly: `N = round(ρ·patch_size²)` blades on the side `√(N/ρ)`, within half a blade's
//!   area of `patch_size` ([`patch::PatchSpec`]; a deviation: the paper's side is the user's),
//!   one in each of `N` of the `⌈√N⌉²` strata (stratified sampling), each with a density
//!   threshold drawn uniformly in `[0, 1)`. It is laid on every cell of a uniform grid over the
//!   terrain; each cell uses one of four mirrored versions (x, z, both or none, from a hash of
//!   the cell), mirrored on the GPU as a sign flip about the patch centre. The virtual blade
//!   count is `cells x N`. By default the patch takes the scene's `[grass] density`, so the
//!   field is the reference's population at a different placement, and a scene without grass
//!   (`grass.density = 0`) gets an empty patch and draws nothing at all; with
//!   `blades_per_m2 = 87800` on 0.5 m patches (21 950 blades a patch) the 105 x 68 m football
//!   field holds 28 560 cells and **626.9 M virtual blades**, the paper's "about 627 million"
//!   (Sec. 5): the `football_field_human` scene sets that. The scene always gives the blades'
//!   heights, widths and colours. (Before issue 19 the patch held the square
//!   `round(√N)²`: 4 of the 5 blades a 0.5 m patch holds at 20 blades/m², 20 % short, and
//!   one blade a patch at `grass.density = 0`.)
//! - **Geometric blades** (Sec. 3.2, `shaders/grass.wgsl` `vs_blade`). A quadrilateral strip of
//!   `segments` quads along the trajectory of a particle launched from the root almost
//!   vertically (up to `max_tilt` from the vertical) under `gravity`; its positions at
//!   `segments + 1` evenly spaced times are the reference points, scaled so the standing blade
//!   peaks at its height. A procedural blade texture ([`texture`]) shapes the strip with its
//!   alpha and modulates its colour. Two-sided Lambert + ambient (the prelude's `shade_leaf`
//!   with the shadow mask and the occlusion map, `shade_blade`), per-blade colour variation,
//!   ambient occlusion linear in the vertex height, the scene's fog.
//! - **Density** (Sec. 3.4). The shared density map, bilinear; a blade exists where its
//!   threshold is under the local density, tested per blade in the vertex shader and per texel
//!   for the slice. The covering map removes blades where it says no grass. The same rule
//!   (the scene's, `BladeField::grows`) counts the blades that grow in every cell at start-up
//!   ([`population`]), which the frame's counts are made of.
//! - **LOD weights** (Eq. 1-5, [`lod`]). `w_g`, `w_vs`, `w_hs` from `min_geom`, `max_geom`,
//!   `min_btf`, `max_btf` of the 3D distance from the eye to the blade's root. Geometry compares
//!   `1 − dth` (normalised by the local density, see [`lod`] for why) with its weight, the
//!   slices take the complement, so no blade is drawn twice or lost; Eq. 5's smooth opacity with
//!   `omega` (0.4) cross-fades each blade between its two representations. With
//!   `transitions = false` (the `no_transitions` variant) there is no split and no fade: each
//!   cell is entirely geometry, entirely slices with the vertical ones, or entirely the
//!   horizontal slice, by the distance to its centre against the middles of the two
//!   transition bands (where the weights cross one half), so the variant differs from the
//!   default by Sec. 3.4's seamless mechanism alone. (Before issue 19 the variant was `ω = 0`:
//!   the same density split with a hard Eq. 5, which isolated only the smoothing.)
//! - **Quadtree** (Sec. 4.1, [`quadtree`]). Leaves are cells with bounding spheres (ground,
//!   blade height, lean), inner nodes macro-cells; each frame `update` walks it with the view
//!   frustum. Within `max_geom` it descends to single cells: those get geometry (per visible
//!   block of the patch, the blades whose thresholds can pass there, a contiguous range since
//!   each block is sorted by threshold; [`cells`] turns the ranges of all cells into instanced
//!   draws, merging those that meet, so a run of cells drawn whole is one draw) and, where
//!   geometry's weight is under 1, a horizontal slice. Within `max_btf` cells stay single cells
//!   and get the vertical slices too. Farther
//!   away a node at least `macro_factor` times its side away is drawn whole as one horizontal
//!   slice quad, tessellated to follow the ground.
//! - **BTF pre-computation** (Sec. 3.3, Fig. 6, 7, 10, [`btf`], [`cache`]). At start-up every
//!   slice is rendered from the geometric patch and its eight neighbours by an orthographic
//!   camera whose near and far planes bound the slice's slab, with the blades' own vertex shader
//!   in baking mode, 4x MSAA resolved into coverage: per layer (slice x view side) the colour
//!   without lighting (`K_d`) with coverage (alpha), the two-sided diffuse factor for each of
//!   the five light directions Y+, X+, Z+, X−, Z− (one pass: only the shading differs), the
//!   density threshold and the occlusion, in three `Rgba16Float` 2D arrays with box-filtered
//!   mips. The blades each vertical layer draws are listed on the CPU (those reaching its
//!   slab). The result is cached on disk under a hash of everything the bake reads
//!   (`$XDG_CACHE_HOME/grassbench/boulanger`, `btf_cache`); a damaged file is baked again.
//! - **Vertical slices** (Sec. 3.3, [`vertical`], `vs_vslice`/`fs_vslice`). `vertical_slices`
//!   (10) quads across x and as many across z per cell, static for any camera, one instanced
//!   draw for all cells (far to near; within a cell each axis back to front, since they are
//!   blended unsorted like the blades). The layer is chosen by the side the camera is on, in
//!   the cell's mirrored frame. They draw the slices' share of each texel's blade like the
//!   horizontal slice, times the far fade of Eq. 3 ([`lod`]), so the three representations
//!   share every blade through part 1's weights and per-pixel thresholds (Fig. 12's debug
//!   view shows them red, blue and green).
//! - **Lighting** (Sec. 3.3, Appendix A, [`barycentric`]). Lambert with the scene's
//!   directional sun and, if `[lights.point]` sets one, a point light with attenuation
//!   `1/(1 + βd²)`; both follow their keyframes (`sun_keys`, `point.keys`) at run time. Slice
//!   texels are lit `K_d I_a ao + Σ_lights (Σ α_i C_i) I_d`: the five diffuse samples weighted
//!   by the spherical barycentric coordinates of the direction towards each light in the
//!   patch's frame (Eq. 8-13, nine arc-cosines per light per vertex; for the point light they
//!   vary across a slice), renormalised per pixel, the point light's attenuation per pixel. A
//!   mirrored cell sees the light mirrored (X+ and X− swap, Z+ and Z−). The geometric blades
//!   use the two-sided Lambert of the prelude, which has the point light too.
//! - **Horizontal slice** (Sec. 3.3, [`slice`](mod@slice)). One BTF layer (below): an orthographic top
//!   view of the patch and its 8 neighbours. Drawn over cells and macro-cells by texture
//!   repetition with the
//!   patch orientation map of Eq. 6-7 so macro-cells keep each cell's mirror; lit per pixel
//!   from the BTF's baked, texel-averaged diffuse factors (averaging normals instead made far
//!   grass far too bright). Per pixel the texel's
//!   threshold is tested against the local density and geometry's share; where a pixel covers
//!   many texels (minified more than about 1.4x) the single averaged threshold would be
//!   meaningless, so the expected fraction `ρ · mean_t(1 − opacity_g)` of the uniformly spread
//!   thresholds is drawn instead. `lod` and `slice::orientation_texel` are the CPU twins of
//!   the shader's weights, opacities, share and orientation map (`tests/tests/twins.rs`).
//! - **Ground shadows** (Sec. 3.5, Fig. 15, [`ground_shadow`]). One pass before the grass: the
//!   geometric blades projected along the sun onto the ground (the plane tangent at each root)
//!   mark the stencil where they pass the depth test, a screen-covering triangle multiplies the
//!   marked pixels by the ground's shadowed-to-lit ratio (ambient over ambient + sun), and the
//!   horizontal slices, projected likewise, multiply the unmarked ground by their opacity. The
//!   vertical slices cast none (the paper). `ground_shadows = false` turns it off.
//! - **Shadow mask** (Sec. 3.5, Fig. 17, [`shadow`]). The coverage of a slab of the patch as
//!   thick as a cylinder of circumference `patch_size`, baked first, is the shadow image
//!   wrapped around every blade with its origin at the blade's inclination; per fragment the
//!   ray towards each light leaves the cylinder through its side (mask lookup, bilinear) or
//!   its top (lit). The geometric blades use it for the sun and the point light; the BTF bake
//!   for its five directions, so the slices carry the same shadows at no run-time cost.
//!   `shadow_mask = false` turns it off. About 12 % less light on the walker's view.
//! - **Ambient occlusion map** (Sec. 3.5, Fig. 18, [`occlusion`]). At start-up, per
//!   covering-map sample, the share of the sky hidden by the trees and stones around
//!   (heights `tree_height`, `stone_height`: the map has none); the blades multiply their
//!   ambient light by it at their root, the slices per pixel. `external_ao = false` turns it
//!   off.
//! - **Semi-transparency** (Sec. 4.2, `transparency`). `blend`: alpha test with a low threshold
//!   (`alpha_threshold`, 0.1) plus blending, no sorting of blades (geometry cells are drawn far
//!   to near, which costs nothing on the CPU and keeps Eq. 5's semi-transparent blades from
//!   hiding whole cells drawn after them); `alpha_to_coverage`: alpha to
//!   coverage on the 4x MSAA target (needs `--msaa`; refused without it).
//! - **Wind.** The paper has no wind; here the shared wind pushes each geometric blade's
//!   particle sideways (`wind_response` per m/s, plus a small per-blade flutter), so near blades
//!   sway with the same wind as every other technique, and the vertical slices' tops are
//!   sheared by the displacement a standing blade's tip would get at their height, per vertex
//!   from the same wind (`vs_vslice`), so the mid band sways with the blades it replaces (the
//!   flutter is not there, and the horizontal slice stays flat). `animate = false` turns both
//!   off: the paper's static grass.
//!
//! ## Counting blades
//! `blades_drawn` and `blades_represented` count blades that grow (above), each once
//! (`plan`): geometry the growing blades of the ranges it submits, whatever opacity Eq. 5
//! gives them; the slices every other growing blade of their cells and macro-cells, once
//! though the vertical and the horizontal slices both show the mid band. In a transition a
//! blade submitted as geometry counts as drawn, and the slices' complementary share of it is
//! not counted again. `levels()` gives the vertical slices' blades apart (weighted by Eq. 3's
//! far fade), though the horizontal slice under them stands for the same blades.
//!
//! ## Cost model
//! CPU per frame: the quadtree walk, `O(visible nodes)` sphere tests (a few thousand), and one
//! entry per selected cell; for the counts, nothing more for a cell submitted whole (its
//! population's count), else per submitted range a binary search in a cell of uniform ground
//! and one density and covering test per submitted blade elsewhere (a fraction of what
//! drawing them costs). Start-up: the population, `O(blocks · log N)` per cell of uniform
//! ground, one test per blade elsewhere (the 626.9 M blades of the uniform pitch: 28 560 x 16
//! binary searches). GPU: geometric blades `G x 2·segments` triangles, where `G` is the
//! blades in cells nearer than `max_geom` whose thresholds can pass (the CPU skips those Eq. 5
//! gives no opacity there), all other blades cost nothing; plus one textured quad per cell in
//! the transition and per macro-cell beyond (`tess²` quads each on uneven ground), whose cost is
//! fill: about one fragment per ground pixel; plus `4N` triangles per cell of the mid band
//! (20 quads at `N` = 10, one draw), whose cost is fill again: at a grazing view several slices
//! cover each pixel (depth complexity up to `2N` per cell crossed), which is why the paper's
//! low horizontal view is its slowest (Sec. 5). The ground shadows draw the geometric blades'
//! vertices and the horizontal slices' fill a second time, plus one screen of fill for the
//! cover. Start-up: the BTF bake, bound by fill (4x MSAA, three targets, hundreds of blade
//! fragments per texel of a side view), 4-8 s of wall time on lavapipe for the paper's patch
//! depending on what else runs on the two cores (measured with the 21 904 blades it held
//! before issue 19; it now holds 21 950), 0.1 s from the disk cache. Memory: 32 bytes per
//! patch blade; the BTFs, `3 x 8 x 4/3` bytes a texel: the horizontal slice's
//! `slice_resolution²` (8.4 MB at 512) and the vertical slices' `4N x vslice_width x
//! vslice_height` (21.0 MB at 40 layers of 256 x 64; the paper's 512 x 64 would be 42 MB),
//! under issue 9's 64 MB; one byte per cell for the orientation map and for the occlusion
//! map; the shadow mask, 128 x 64 (262 KB with its mips); on the CPU, 8 bytes per cell for the
//! population. Per blade fragment the shadow mask costs a ray-cylinder intersection, an
//! `atan2` and a texture lookup per light. The BTFs' `Rgba16Float` texels cost lavapipe more
//! to sample than an RGBA8 texture's, converted one by one: 3.8-4.0 ns a sample against 1.6
//! on the Xeon, and 1.5-1.9 more for the second mip level a trilinear one blends (a GPU filters
//! 64-bit texels at half rate, most of them); 42 % of what the cost model predicts for the
//! walker's meadow is the slices' samples and blends (185 of 437 ms at 320x180), which it prices
//! apart (`TEXTURE_FORMATS` in `pipelines.rs`; `results/cost_model/`, `3116f59`). Since the
//! model prices a sample's second mip level on its own (`texture_mip_blend`), the slices'
//! samples, which blend two levels, cost 2.7-3.1 ns plus
//! 1.8-2.2 for the blend on the 2.6 GHz EPYC, and the occlusion map's, read at level 0, 2.1-2.5
//! ns: on the meadow at 320x180 the slices' samples and blends are 160 ms and the occlusion
//! map's 25 of the 452 predicted, against 398.6 measured. Nothing grows with the virtual blade count except
//! the orientation map, the population and the quadtree (about 40 000 nodes on the football
//! field). Brute force for 626 M blades at the reference's measured ~3.4 µs per blade on this
//! rasteriser would take over half an hour a
//! frame.
//!
//! ## Known artifacts
//! - Beyond `max_btf` (30 m) grass is the flat horizontal slice: seen at grazing angles it
//!   reads as a carpet, and it is lighter than the vertical slices before it (a top view shows
//!   the lit tips, a side view the darker stems), so the `max_btf` band shows as a change of
//!   tone on the human-height views.
//! - Looking along a slice axis, the slices of that axis are seen edge on and only the other
//!   axis's remain: rows of cells aligned with the view show as darker lines converging to the
//!   vanishing point. Slices are blended unsorted across cells' axes, so where slices of the
//!   two axes cross some borders are wrong (like the blades', Sec. 4.2).
//! - Slices are brighter and softer than the geometry they replace (measured against geometry
//!   at a sampled light and view: mean FLIP 0.182 at 320x180, `gpu_boulanger_btf`): mip-mapped
//!   coverage and colour average the dark stems with the tips, and a slab has no parallax
//!   inside its 5 cm.
//! - Five light samples are coarse: a light between them is a blend of images, not the lighting
//!   of the blades in between (the paper's own approximation). Per-vertex weights for the point
//!   light are exact only where the slice is small against its distance to the light
//!   (Appendix A).
//! - One shadow mask for every blade (Sec. 3.5's own approximation): shadows are plausible, not
//!   cast by the actual neighbours, and a light straight above casts none (its ray leaves the
//!   cylinder through the top).
//! - Ground shadows are hard (a stencil bit) and take the sun's share of a flat ground's light
//!   (on a slope the ground's own sun term differs a little); the point light casts none, as the
//!   core lights the ground with the sun only. A horizontal slice's shadow lies almost under it
//!   (it is `slice_height` up), so beyond `max_geom` the ground darkens in the slice's gaps
//!   rather than beside the blades; blades fading out (Eq. 5) cast until their opacity falls
//!   under one half.
//! - The occlusion map sums its occluders' solid angles, so clumps of trees darken more than
//!   an exact visibility test would ([`occlusion`]).
//! - Neighbouring cells of different mirrors meet along seams where blades baked from unmirrored
//!   neighbours do not match; at the slice's distances they are not visible.
//! - Blending without sorting leaves wrong borders where blades cross (Sec. 4.2, Fig. 21c);
//!   `alpha_to_coverage` removes them at 2.5-3x the fill cost on this rasteriser.
//! - The particle model does not preserve blade length under strong wind (clamped push).
//!
//! ## Code
//! This file holds the registry entry and the [`GrassTechnique`] impl, which delegates:
//! [`shader`] is the shader with the mirrors of its structs (a leaf of the crate); `tiling` the
//! patch of a scene, the blades that grow in each cell ([`population`]) and the quadtree of
//! its cells, built once; `plan` the frame plan that
//! `update` refills every frame from the quadtree walk; `gpu` what is kept on the GPU, with
//! `pipelines` (bind group layouts, render pipelines) and `bakes` (the shadow mask, then the
//! BTFs through the cache, at start-up), and it uploads and draws the plan. The other modules
//! are the paper's parts, linked above.

#![cfg_attr(test, allow(clippy::unwrap_used, clippy::expect_used, clippy::panic))]

mod bakes;
pub mod barycentric;
pub mod btf;
pub mod cache;
pub mod cells;
mod gpu;
pub mod ground_shadow;
pub mod lod;
pub mod occlusion;
pub mod paper;
pub mod params;
pub mod patch;
mod pipelines;
mod plan;
pub mod population;
pub mod quadtree;
pub mod shader;
pub mod shadow;
pub mod slice;
pub mod texture;
mod tiling;
pub mod vertical;

use grassbench::gpu::GpuEstimate;
use grassbench::technique::{LevelBlades, Technique, TechniqueEntry, Variant, Variants};
use grassbench::{
    Error, FrameEncoder, FrameInputs, GpuContext, GrassTechnique, InitContext, Result,
    TechniqueInfo, TechniqueStats,
};

pub use gpu::params_uniform;
pub use ground_shadow::GroundShadows;
pub use lod::LodDistances;
pub use params::{Params, Transparency};
pub use patch::{Orientation, Patch, PatchBlade, PatchSpec};
pub use quadtree::{CellGrid, Quadtree, Selection, Walk};
pub use shader::{CellRecord, ParamsUniform, SHADER, SliceQuad};
pub use tiling::BLOCKS;

/// The registry line for this technique.
pub const ENTRY: TechniqueEntry = grassbench::technique::entry::<Boulanger>();

/// Most cells (patches) on one terrain: the quadtree and orientation map are per cell.
pub const MAX_CELLS: u64 = 4096 * 4096;

/// The technique.
pub struct Boulanger {
    /// The parameters as given (what results record); everything built from them used
    /// [`Params::for_scene`]'s.
    params: Params,
    /// The patch and the quadtree of its cells.
    tiling: tiling::Tiling,
    /// Pipelines, bind groups, buffers and textures.
    gpu: gpu::BoulangerGpu,
    /// How the BTFs were obtained at start-up.
    bakes: bakes::BakeReport,
    /// This frame's draws (update → prepare → encode).
    plan: plan::FramePlan,
}

impl Technique for Boulanger {
    type Params = Params;

    const INFO: TechniqueInfo = TechniqueInfo {
        id: "boulanger",
        name: "Boulanger et al. 2006 (geometry, slices, density thresholds)",
        paper: "Boulanger, Pattanaik, Bouatouch 2006: Rendering Grass in Real Time with Dynamic Light Sources",
        gpu_state: false,
        debug_views: &[
            "LOD false colours (Fig. 12): geometry red, vertical slices blue, horizontal slice green",
            "patch orientation: one colour per mirrored version",
        ],
    };

    const VARIANTS: Variants = Variants {
        // Geometry everywhere (Eq. 1-4 with every distance inside min_geom).
        finest: "min_geom = 9000.0\nmax_geom = 9001.0\nmin_btf = 9001.0\nmax_btf = 9002.0",
        // Sec. 3.1's levels switched per cell at the middle of each transition band, without
        // Sec. 3.4's density split or Eq. 5's blending: each cell entirely geometry or
        // entirely slices.
        others: &[
            Variant {
                name: grassbench::technique::NO_TRANSITIONS,
                params: "transitions = false",
            },
            Variant {
                name: grassbench::technique::PAPER,
                params: paper::VARIANT,
            },
        ],
    };

    /// GPU memory `new` will allocate: the patch, the horizontal and vertical BTF arrays, the
    /// orientation map (one byte per cell), the blade texture and the per-frame buffers at
    /// their first size.
    fn estimate(scene: &grassbench::Scene, params: &Params) -> Result<GpuEstimate> {
        let params = params.for_scene(&scene.config.grass)?;
        let grid = CellGrid::new(&scene.terrain, params.patch_size);
        let spec = PatchSpec::for_density(params.patch_size, params.blades_per_m2);
        let blade = std::mem::size_of::<PatchBlade>() as u64;
        Ok([
            // At least one record: an empty patch still binds a buffer.
            GpuEstimate::buffer(u64::from(spec.blades.max(1)).saturating_mul(blade)),
            GpuEstimate::textures(slice::texture_bytes(params.slice_resolution)),
            GpuEstimate::textures(btf::texture_bytes(
                shadow::WIDTH,
                shadow::HEIGHT,
                btf::array_layers(1),
            )),
            GpuEstimate::textures(if params.external_ao {
                let c = scene.terrain.covering();
                (c.width() * c.height()) as u64
            } else {
                1
            }),
            GpuEstimate::textures(btf::texture_bytes(
                params.vslice_width,
                params.vslice_height,
                4 * params.vertical_slices,
            )),
            GpuEstimate::buffer((gpu::INITIAL_QUADS * std::mem::size_of::<CellRecord>()) as u64),
            GpuEstimate::textures(u64::from(grid.nx) * u64::from(grid.nz)),
            GpuEstimate::textures(texture::BYTES_BOUND),
            GpuEstimate::buffer(std::mem::size_of::<ParamsUniform>() as u64),
            GpuEstimate::buffer(64 * cells::CELL_BYTES),
            GpuEstimate::buffer((gpu::INITIAL_QUADS * std::mem::size_of::<SliceQuad>()) as u64),
        ]
        .into_iter()
        .sum())
    }

    /// Builds the patch of the scene's grass, its population and the quadtree, then the GPU
    /// side (`gpu`), which bakes the shadow mask and the slices.
    fn new(ctx: &InitContext<'_>, given: Params) -> Result<Self> {
        let params = given.for_scene(&ctx.scene.config.grass)?;
        if params.transparency == Transparency::AlphaToCoverage && ctx.sample_count < 4 {
            return Err(Error::param(
                "boulanger.transparency",
                "alpha_to_coverage",
                "`blend` on a single-sample target (alpha to coverage needs --msaa)",
            ));
        }
        let scene = ctx.scene;
        let grid = CellGrid::new(&scene.terrain, params.patch_size);
        let max_side = ctx.gpu.device.limits().max_texture_dimension_2d;
        if grid.count() > MAX_CELLS || grid.nx > max_side || grid.nz > max_side {
            return Err(Error::param(
                "boulanger.patch_size",
                given.patch_size,
                format!(
                    "at most {MAX_CELLS} cells and {max_side} a side; the terrain needs {} x {}",
                    grid.nx, grid.nz
                ),
            ));
        }
        let patch = tiling::scene_patch(&params, scene);
        let uniform = gpu::params_uniform(&params, &scene.config.grass);
        let tiling = tiling::Tiling::new(&params, scene, grid, patch, uniform.lod[3]);
        let (gpu, bakes) = gpu::BoulangerGpu::new(ctx, &params, &uniform, &tiling)?;
        Ok(Self {
            params: given,
            tiling,
            gpu,
            bakes,
            plan: plan::FramePlan::default(),
        })
    }

    fn params(&self) -> &Params {
        &self.params
    }
}

impl Boulanger {
    /// Virtual blades tiled over the terrain: cells x blades per patch.
    pub fn virtual_blades(&self) -> u64 {
        self.tiling.virtual_blades()
    }

    /// Blades in one patch.
    pub fn blades_per_patch(&self) -> u32 {
        self.tiling.blades_per_patch()
    }

    /// Side of the patch actually tiled, m ([`PatchSpec::for_density`]: near `patch_size`, so
    /// that the patch holds a whole number of blades at the scene's density).
    pub fn patch_side(&self) -> f32 {
        self.tiling.patch.size
    }

    /// Blades of the tiling that grow (under the density map, on grass, on the terrain).
    pub fn growing_blades(&self) -> u64 {
        self.tiling.population.total()
    }

    /// The BTF cache keys (horizontal, vertical) `new` would use on `scene` with `overrides`
    /// (CPU only).
    pub fn bake_keys(scene: &grassbench::Scene, overrides: &toml::Table) -> Result<[u64; 2]> {
        let params: Params = grassbench::params::resolve(Self::INFO.id, overrides)?;
        let params = params.for_scene(&scene.config.grass)?;
        let patch = tiling::scene_patch(&params, scene);
        let uniform = gpu::params_uniform(&params, &scene.config.grass);
        Ok(bakes::keys(&params, &uniform, &patch))
    }

    /// How the BTFs were obtained at start-up (horizontal, vertical) and the seconds it took.
    pub fn btf_outcome(&self) -> (&[cache::Outcome; 2], f64) {
        (&self.bakes.outcome, self.bakes.seconds)
    }
}

impl GrassTechnique for Boulanger {
    fn update(&mut self, inputs: &FrameInputs<'_>) -> Result<()> {
        self.plan.update(
            &self.tiling,
            &inputs.scene.terrain,
            &inputs.camera,
            &self.gpu.paging,
        );
        Ok(())
    }

    fn prepare(&mut self, gpu: &GpuContext, _inputs: &FrameInputs<'_>) -> Result<()> {
        self.gpu.upload(gpu, &self.plan)
    }

    fn encode(&self, encoder: &mut FrameEncoder<'_>) {
        self.gpu.encode(encoder, &self.plan, &self.params);
    }

    fn stats(&self) -> TechniqueStats {
        let plan = &self.plan;
        let quad_triangles: u64 = plan
            .slice_quads
            .iter()
            .map(|q| 2 * (q.tess[0] as u64).pow(2))
            .sum();
        let blade_triangles = plan.lod_blades.geometry * u64::from(2 * self.params.segments);
        // Sec. 3.5's ground shadows draw the blades and the slices again, plus the cover.
        let shadow_triangles = match &self.gpu.ground_shadows {
            Some(_) if !plan.geometry.is_empty() => blade_triangles + 1 + quad_triangles,
            Some(_) => quad_triangles,
            None => 0,
        };
        TechniqueStats {
            // Growing blades whose geometry was submitted, in transitions too (`plan`).
            blades_drawn: plan.lod_blades.geometry,
            // Every other growing blade of a cell with slices, and every growing blade of a
            // macro-cell: the horizontal slice lies under all of them, and in the mid band the
            // vertical slices show the same blades again (Sec. 3.3), so they add none.
            blades_represented: plan.lod_blades.horizontal_slices,
            triangles: blade_triangles
                + quad_triangles
                + plan.vslice_records.len() as u64 * u64::from(4 * self.params.vertical_slices)
                + shadow_triangles,
            gpu_bytes: self.gpu.bytes(),
        }
    }

    /// Sec. 3.1's three levels; the vertical slices' blades are also the horizontal slice's.
    fn levels(&self) -> Vec<LevelBlades> {
        let l = &self.plan.lod_blades;
        [
            ("geometry", l.geometry),
            ("vertical_slices", l.vertical_slices),
            ("horizontal_slices", l.horizontal_slices),
        ]
        .into_iter()
        .map(|(level, blades)| LevelBlades { level, blades })
        .collect()
    }
}

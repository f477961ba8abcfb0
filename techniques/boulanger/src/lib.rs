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
//! - **One patch, tiled** (Sec. 3.1, [`patch`]). A square patch of side `patch_size` holds
//!   `strata²` blades, one per stratum of an `strata x strata` grid (stratified sampling), each
//!   with a density threshold drawn uniformly in `[0, 1)`. It is laid on every cell of a uniform
//!   grid over the terrain; each cell uses one of four mirrored versions (x, z, both or none,
//!   from a hash of the cell), mirrored on the GPU as a sign flip about the patch centre. The
//!   virtual blade count is `cells x strata²`. By default the patch takes the scene's
//!   `[grass] density`, so the field is comparable with the reference's; with
//!   `blades_per_m2 = 87800` on 0.5 m patches (148² = 21 904 blades a patch) the 105 x 68 m
//!   football field holds 28 560 cells and **626 M virtual blades**, the paper's "about 627
//!   million" (Sec. 5): the `football_field_human` scene sets that. The scene always gives
//!   the blades' heights, widths and colours.
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
//!   for the slice. The covering map removes blades where it says no grass.
//! - **LOD weights** (Eq. 1-5, [`lod`]). `w_g`, `w_vs`, `w_hs` from `min_geom`, `max_geom`,
//!   `min_btf`, `max_btf` of the 3D distance from the eye to the blade's root. Geometry compares
//!   `1 − dth` (normalised by the local density, see [`lod`] for why) with its weight, the
//!   slices take the complement, so no blade is drawn twice or lost; Eq. 5's smooth opacity with
//!   `omega` (0.4) cross-fades each blade between its two representations.
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
//!   thresholds is drawn instead.
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
//! ## Cost model
//! CPU per frame: the quadtree walk, `O(visible nodes)` sphere tests (a few thousand), and one
//! entry per selected cell. GPU: geometric blades `G x 2·segments` triangles, where `G` is the
//! blades in cells nearer than `max_geom` whose thresholds can pass (the CPU skips those Eq. 5
//! gives no opacity there), all other blades cost nothing; plus one textured quad per cell in
//! the transition and per macro-cell beyond (`tess²` quads each on uneven ground), whose cost is
//! fill: about one fragment per ground pixel; plus `4N` triangles per cell of the mid band
//! (20 quads at `N` = 10, one draw), whose cost is fill again: at a grazing view several slices
//! cover each pixel (depth complexity up to `2N` per cell crossed), which is why the paper's
//! low horizontal view is its slowest (Sec. 5). The ground shadows draw the geometric blades'
//! vertices and the horizontal slices' fill a second time, plus one screen of fill for the
//! cover. Start-up: the BTF bake, bound by fill (4x MSAA,
//! three targets, hundreds of blade fragments per texel of a side view), 4-8 s of wall time
//! on lavapipe for the paper's 21 904-blade patch depending on what else runs on the two
//! cores, 0.1 s from the disk cache. Memory: 32 bytes per patch
//! blade; the BTFs, `3 x 8 x 4/3` bytes a texel: the horizontal slice's `slice_resolution²`
//! (8.4 MB at 512) and the vertical slices' `4N x vslice_width x vslice_height` (21.0 MB at 40
//! layers of 256 x 64; the paper's 512 x 64 would be 42 MB), under issue 9's 64 MB; one byte
//! per cell for the orientation map and for the occlusion map; the shadow mask, 128 x 64 (262
//! KB with its mips). Per blade fragment the shadow mask costs a ray-cylinder intersection, an
//! `atan2` and a texture lookup per light. Nothing grows with the virtual blade count except
//! the orientation map and the quadtree (about 40 000 nodes on the football field). Brute force for 626 M blades at the
//! reference's measured ~3.4 µs per blade on this rasteriser would take over half an hour a
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
//!   at a sampled light and view: mean FLIP 0.181 at 320x180, `gpu_boulanger_btf`): mip-mapped
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

#![cfg_attr(test, allow(clippy::unwrap_used, clippy::expect_used, clippy::panic))]

pub mod barycentric;
pub mod btf;
pub mod cache;
pub mod cells;
pub mod ground_shadow;
pub mod lod;
pub mod occlusion;
pub mod params;
pub mod patch;
pub mod quadtree;
pub mod shadow;
pub mod slice;
pub mod texture;
pub mod vertical;

use glam::{Vec2, Vec3};
use grassbench::camera::Aabb;
use grassbench::technique::{
    LevelBlades, RenderPass, Technique, TechniqueEntry, Variant, Variants,
};
use grassbench::wgpu::util::DeviceExt as _;
use grassbench::{
    Error, FrameEncoder, FrameInputs, GpuContext, GrassTechnique, InitContext, Result,
    TechniqueInfo, TechniqueStats, bytemuck, shaders, target, wgpu,
};

pub use ground_shadow::GroundShadows;
pub use lod::LodDistances;
pub use params::{Params, Transparency};
pub use patch::{Orientation, Patch, PatchBlade};
pub use quadtree::{CellGrid, Quadtree, Selection, Walk};

use grassbench::shaders::{PipelineSpec, depth_less, render_pipeline};

/// The blade, bake and slice shader (without the prelude).
pub const SHADER: &str = include_str!("../shaders/grass.wgsl");

/// The registry line for this technique.
pub const ENTRY: TechniqueEntry = grassbench::technique::entry::<Boulanger>();

/// Blades each of Sec. 3.1's three levels drew or stood for in the last frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BandBlades {
    /// Blades drawn as geometry.
    pub geometry: u64,
    /// Blades represented by vertical (volume) slices.
    pub vertical_slices: u64,
    /// Blades represented by the horizontal slice.
    pub horizontal_slices: u64,
}

/// Most cells (patches) on one terrain: the quadtree and orientation map are per cell.
pub const MAX_CELLS: u64 = 4096 * 4096;

/// Mirror of the shader's `Params` uniform.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ParamsUniform {
    /// Root colour; w = colour variation.
    pub color_root: [f32; 4],
    /// Tip colour; w = translucency.
    pub color_tip: [f32; 4],
    /// Segments, gravity, wind response, ambient occlusion at the root.
    pub blade: [f32; 4],
    /// min_geom, max_geom, omega, alpha-test threshold.
    pub lod: [f32; 4],
    /// Patch size, slice height (m), slice texture side, bake top (m).
    pub tile: [f32; 4],
    /// Vertical slices per axis, min_btf, max_btf; w = 1 with the shadow mask (Sec. 3.5).
    pub btf: [f32; 4],
}

/// Mirror of the shader's `Cell` (one per geometry cell in a storage buffer, [`cells`]).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CellUniform {
    /// World (x, z) of the patch centre, mirror signs for x and z.
    pub center_signs: [f32; 4],
    /// x = 1 when baking; then y = projection (0 top, 1 across x, 2 across z), z = the
    /// slice's coordinate on its axis (m from the patch centre), w = side of the camera (±1).
    pub mode: [f32; 4],
}

impl CellUniform {
    /// As instance attributes (the vertical slices' vertex buffer).
    const LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<Self>() as u64,
        step_mode: wgpu::VertexStepMode::Instance,
        attributes: &wgpu::vertex_attr_array![0 => Float32x4, 1 => Float32x4],
    };
}

/// One horizontal slice quad (instance of the slice pipeline).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct SliceQuad {
    /// World min (x, z) and size (x, z), m.
    pub rect: [f32; 4],
    /// First cell (i, j) and cells covered (ni, nj).
    pub cells: [f32; 4],
    /// Quads per side; yzw unused.
    pub tess: [f32; 4],
}

impl SliceQuad {
    const LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<Self>() as u64,
        step_mode: wgpu::VertexStepMode::Instance,
        attributes: &wgpu::vertex_attr_array![0 => Float32x4, 1 => Float32x4, 2 => Float32x4],
    };
}

/// Blocks per side of the patch: geometry is culled and cut per block (Sec. 4.1's culling at a
/// finer grain than the cell, since a cell may hold 20 000 blades).
pub const BLOCKS: u32 = 4;

/// Slice quads (and cells with vertical slices) the buffers hold at first (they grow by powers
/// of two).
const INITIAL_QUADS: usize = 256;

/// Tessellations of slice quads (quads per side), one draw each.
const TESS_LEVELS: [u32; 4] = [1, 2, 4, 8];

/// A cell drawn with geometry this frame: its uniform and one blade range per visible block.
#[derive(Clone, Debug)]
struct GeometryCell {
    uniform: CellUniform,
    ranges: Vec<std::ops::Range<u32>>,
    near: f32,
}

/// The technique.
pub struct Boulanger {
    params: Params,
    lod: LodDistances,
    blades_per_patch: u32,
    seed: u64,
    tree: Quadtree,
    /// The patch (blades by block, sorted by threshold within a block), for per-block ranges.
    patch: Patch,
    blade_pipeline: wgpu::RenderPipeline,
    slice_pipeline: wgpu::RenderPipeline,
    vslice_pipeline: wgpu::RenderPipeline,
    /// Sec. 3.5's shadows on the ground, when `ground_shadows` is on.
    ground_shadows: Option<GroundShadows>,
    group1: wgpu::BindGroup,
    cell_layout: wgpu::BindGroupLayout,
    cell_group: wgpu::BindGroup,
    cell_buffer: wgpu::Buffer,
    cell_capacity: usize,
    paging: cells::Paging,
    /// This frame's blade draws, per page of cells.
    pages: Vec<cells::Page>,
    slice_group: wgpu::BindGroup,
    blades: wgpu::Buffer,
    quad_buffer: wgpu::Buffer,
    quad_capacity: usize,
    vcell_buffer: wgpu::Buffer,
    vcell_capacity: usize,
    btf_outcome: [cache::Outcome; 2],
    btf_seconds: f64,
    fixed_bytes: u64,
    // Per frame (update → prepare → encode).
    selection: Selection,
    geometry: Vec<GeometryCell>,
    quads: Vec<SliceQuad>,
    /// Cells with vertical slices this frame, far to near, with their nearest distance.
    vcells: Vec<(CellUniform, f32)>,
    vcell_uniforms: Vec<CellUniform>,
    quad_groups: Vec<(u32, std::ops::Range<u32>)>,
    lod_blades: BandBlades,
    /// Opacity under which a blade is alpha-tested away whatever its texture (the shader's
    /// threshold).
    alpha_floor: f32,
    /// How far blades reach past their root horizontally, and how high, m.
    overhang: f32,
    reach_up: f32,
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
        // Eq. 5 with ω = 0: a hard threshold test, blades switch representation at once.
        others: &[Variant {
            name: grassbench::technique::NO_TRANSITIONS,
            params: "omega = 0.0",
        }],
    };

    fn new(ctx: &InitContext<'_>, params: Params) -> Result<Self> {
        Self::build(ctx, params)
    }

    fn estimate(
        scene: &grassbench::Scene,
        params: &Params,
    ) -> Result<grassbench::gpu::GpuEstimate> {
        Self::estimate_memory(scene, params)
    }

    fn params(&self) -> &Params {
        &self.params
    }
}

impl Boulanger {
    /// GPU memory `new` will allocate: the patch, the horizontal and vertical BTF arrays, the
    /// orientation map (one byte per cell), the blade texture and the per-frame buffers at
    /// their first size.
    fn estimate_memory(
        scene: &grassbench::Scene,
        params: &Params,
    ) -> Result<grassbench::gpu::GpuEstimate> {
        use grassbench::gpu::GpuEstimate;
        let grid = CellGrid::new(&scene.terrain, params.patch_size);
        let density = params.effective_blades_per_m2(scene.config.grass.density);
        let strata = u64::from(Patch::strata_for(params.patch_size, density));
        let blade = std::mem::size_of::<patch::PatchBlade>() as u64;
        Ok([
            GpuEstimate::buffer((strata * strata).saturating_mul(blade)),
            GpuEstimate::textures(slice::texture_bytes(params.slice_resolution)),
            GpuEstimate::textures(btf::texture_bytes(shadow::WIDTH, shadow::HEIGHT, 1)),
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
            GpuEstimate::buffer((INITIAL_QUADS * std::mem::size_of::<CellUniform>()) as u64),
            GpuEstimate::textures(u64::from(grid.nx) * u64::from(grid.nz)),
            GpuEstimate::textures(texture::BYTES_BOUND),
            GpuEstimate::buffer(std::mem::size_of::<ParamsUniform>() as u64),
            GpuEstimate::buffer(64 * cells::CELL_BYTES),
            GpuEstimate::buffer((INITIAL_QUADS * std::mem::size_of::<SliceQuad>()) as u64),
        ]
        .into_iter()
        .sum())
    }

    /// Builds the patch, the quadtree and the pipelines, and bakes the horizontal slice.
    fn build(ctx: &InitContext<'_>, params: Params) -> Result<Self> {
        if params.transparency == Transparency::AlphaToCoverage && ctx.sample_count < 4 {
            return Err(Error::param(
                "boulanger.transparency",
                "alpha_to_coverage",
                "`blend` on a single-sample target (alpha to coverage needs --msaa)",
            ));
        }
        let device = &ctx.gpu.device;
        let scene = ctx.scene;
        let grass = &scene.config.grass;
        let seed = scene.config.seed;
        let grid = CellGrid::new(&scene.terrain, params.patch_size);
        let max_side = device.limits().max_texture_dimension_2d;
        if grid.count() > MAX_CELLS || grid.nx > max_side || grid.nz > max_side {
            return Err(Error::param(
                "boulanger.patch_size",
                params.patch_size,
                format!(
                    "at most {MAX_CELLS} cells and {max_side} a side; the terrain needs {} x {}",
                    grid.nx, grid.nz
                ),
            ));
        }
        let patch = build_patch(&params, scene);
        let tallest = grass.height[1];
        let (overhang, reach_up) = (1.5 * tallest, 1.2 * tallest);
        let tree = Quadtree::build(&scene.terrain, grid, overhang, reach_up);
        let lod = LodDistances {
            min_geom: params.min_geom,
            max_geom: params.max_geom,
            min_btf: params.min_btf,
            max_btf: params.max_btf,
        };

        let blades = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("boulanger patch blades"),
            contents: bytemuck::cast_slice(&patch.blades),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let a2c = params.transparency == Transparency::AlphaToCoverage;
        let uniform = params_uniform(&params, grass);
        let uniform_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("boulanger params"),
            contents: bytemuck::bytes_of(&uniform),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let (blade_texture, blade_texture_bytes) = texture::upload(device, &ctx.gpu.queue);
        let sampler = |label, address| {
            device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some(label),
                address_mode_u: address,
                address_mode_v: address,
                mag_filter: wgpu::FilterMode::Linear,
                min_filter: wgpu::FilterMode::Linear,
                mipmap_filter: wgpu::MipmapFilterMode::Linear,
                ..Default::default()
            })
        };
        let clamp_sampler = sampler("boulanger blade", wgpu::AddressMode::ClampToEdge);
        let repeat_sampler = sampler("boulanger slice", wgpu::AddressMode::Repeat);

        let vf = wgpu::ShaderStages::VERTEX_FRAGMENT;
        // A filterable float texture of `view_dimension` at `binding`.
        let texture_entry = |binding, view_dimension| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: vf,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: true },
                view_dimension,
                multisampled: false,
            },
            count: None,
        };
        let float_texture = |binding| texture_entry(binding, wgpu::TextureViewDimension::D2);
        let array_texture = |binding| texture_entry(binding, wgpu::TextureViewDimension::D2Array);
        let sampler_entry = |binding| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: vf,
            ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
            count: None,
        };
        let group1_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("boulanger (group 1)"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: vf,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
                float_texture(1),
                sampler_entry(2),
                sampler_entry(3),
                array_texture(4),
                float_texture(5),
            ],
        });
        // Sec. 3.5's ambient occlusion map (one white texel when it is off).
        let (ao_view, ao_bytes) = ao_texture(
            device,
            &ctx.gpu.queue,
            params.external_ao.then(|| {
                occlusion::visibility_map(&scene.terrain, params.tree_height, params.stone_height)
            }),
        );
        // Group 1 with a shadow mask: the mask's own bake sees a transparent one (no shadow).
        let make_group1 = |mask: &wgpu::TextureView| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("boulanger (group 1)"),
                layout: &group1_layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 4,
                        resource: wgpu::BindingResource::TextureView(mask),
                    },
                    wgpu::BindGroupEntry {
                        binding: 5,
                        resource: wgpu::BindingResource::TextureView(&ao_view),
                    },
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: uniform_buffer.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::TextureView(&blade_texture),
                    },
                    wgpu::BindGroupEntry {
                        binding: 2,
                        resource: wgpu::BindingResource::Sampler(&clamp_sampler),
                    },
                    wgpu::BindGroupEntry {
                        binding: 3,
                        resource: wgpu::BindingResource::Sampler(&repeat_sampler),
                    },
                ],
            })
        };
        let no_mask = btf::create_textures(device, 1, 1, 1);
        let no_mask_group1 = make_group1(&btf::wrap(no_mask, 1, 1, 1).color);
        let cell_layout = cells::layout(device);
        let slice_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("boulanger slices (group 2)"),
            entries: &[
                array_texture(1),
                array_texture(2),
                array_texture(5),
                array_texture(6),
                array_texture(7),
                array_texture(8),
                wgpu::BindGroupLayoutEntry {
                    binding: 3,
                    visibility: vf,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Uint,
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
            ],
        });

        let module = shaders::module(device, "boulanger grass", SHADER);
        let blade_layout = ctx.scene_gpu.pipeline_layout(
            device,
            "boulanger blades",
            &[&group1_layout, &cell_layout],
        );
        let slice_pipeline_layout = ctx.scene_gpu.pipeline_layout(
            device,
            "boulanger slice",
            &[&group1_layout, &slice_layout],
        );
        let blend = (!a2c).then_some(wgpu::BlendState::ALPHA_BLENDING);
        let color_target = [Some(wgpu::ColorTargetState {
            format: target::COLOR_FORMAT,
            blend,
            write_mask: wgpu::ColorWrites::ALL,
        })];
        let multisample = wgpu::MultisampleState {
            count: ctx.sample_count,
            alpha_to_coverage_enabled: a2c,
            ..Default::default()
        };
        let strip = wgpu::PrimitiveState {
            topology: wgpu::PrimitiveTopology::TriangleStrip,
            cull_mode: None,
            ..Default::default()
        };
        let spec = |label, layout, vertex, fragment, buffers| PipelineSpec {
            label,
            layout,
            module: &module,
            vertex,
            fragment,
            buffers,
            primitive: strip,
            depth: depth_less(target::DEPTH_FORMAT, true),
            multisample,
            targets: &color_target,
        };
        let blade_pipeline = render_pipeline(
            device,
            &spec(
                "boulanger blades",
                &blade_layout,
                "vs_blade",
                "fs_blade",
                &[],
            ),
        );
        let quad_buffers = [Some(SliceQuad::LAYOUT)];
        let slice_pipeline = render_pipeline(
            device,
            &PipelineSpec {
                primitive: wgpu::PrimitiveState {
                    cull_mode: None,
                    ..Default::default()
                },
                ..spec(
                    "boulanger horizontal slice",
                    &slice_pipeline_layout,
                    "vs_slice",
                    "fs_slice",
                    &quad_buffers,
                )
            },
        );
        let vslice_pipeline = render_pipeline(
            device,
            &PipelineSpec {
                primitive: wgpu::PrimitiveState {
                    cull_mode: None,
                    ..Default::default()
                },
                ..spec(
                    "boulanger vertical slices",
                    &slice_pipeline_layout,
                    "vs_vslice",
                    "fs_vslice",
                    &[Some(CellUniform::LAYOUT)],
                )
            },
        );
        let ground_shadows = params.ground_shadows.then(|| {
            GroundShadows::new(
                device,
                &module,
                [
                    &blade_layout,
                    &slice_pipeline_layout,
                    &ctx.scene_gpu
                        .pipeline_layout(device, "boulanger shadow cover", &[]),
                ],
                ctx.sample_count,
            )
        });
        // The BTF bake (Sec. 3.3): the blade shader in baking mode, three targets, 4x MSAA.
        let refs_layout = btf::refs_layout(device);
        let bake_layout = ctx.scene_gpu.pipeline_layout(
            device,
            "boulanger BTF bake",
            &[&group1_layout, &cell_layout, &refs_layout],
        );
        let bake_target = Some(wgpu::ColorTargetState::from(btf::FORMAT));
        let bake_targets = [bake_target.clone(), bake_target.clone(), bake_target];
        let bake_pipeline = render_pipeline(
            device,
            &PipelineSpec {
                depth: depth_less(wgpu::TextureFormat::Depth32Float, true),
                multisample: wgpu::MultisampleState {
                    count: 4,
                    ..Default::default()
                },
                targets: &bake_targets,
                ..spec(
                    "boulanger BTF bake",
                    &bake_layout,
                    "vs_bake",
                    "fs_bake",
                    &[],
                )
            },
        );
        // The shadow mask first (Sec. 3.5): the blades and the BTF bake are lit through it.
        let (mask_cells, mask_refs, mask_range) =
            shadow::bake_layer(params.patch_size, &patch.blades, params.gravity);
        let mask = btf::bake(
            ctx,
            &btf::BakeInputs {
                pipeline: &bake_pipeline,
                group1: &no_mask_group1,
                cell_layout: &cell_layout,
                refs_layout: &refs_layout,
                blades: &blades,
                vertices: 2 * params.segments + 2,
            },
            shadow::WIDTH,
            shadow::HEIGHT,
            &btf::Layers {
                cells: &mask_cells,
                refs: &mask_refs,
                ranges: std::slice::from_ref(&mask_range),
            },
        )?;
        let group1 = make_group1(&mask.color);
        let bake_inputs = btf::BakeInputs {
            pipeline: &bake_pipeline,
            group1: &group1,
            cell_layout: &cell_layout,
            refs_layout: &refs_layout,
            blades: &blades,
            vertices: 2 * params.segments + 2,
        };
        let started = std::time::Instant::now();
        let [h_key, v_key] = bake_keys_of(&params, &uniform, &patch);
        let [h_dims, v_dims] = btf_dims(&params);
        let folder = cache::folder(&params.btf_cache);
        let (horizontal, h_outcome) =
            cache::load_or_bake(ctx.gpu, folder.as_deref(), h_key, h_dims, || {
                let (cells, refs, range) =
                    slice::bake_layer(params.patch_size, &patch.blades, params.gravity);
                btf::bake(
                    ctx,
                    &bake_inputs,
                    h_dims.width,
                    h_dims.height,
                    &btf::Layers {
                        cells: &cells,
                        refs: &refs,
                        ranges: std::slice::from_ref(&range),
                    },
                )
            })?;
        let (verticals, v_outcome) =
            cache::load_or_bake(ctx.gpu, folder.as_deref(), v_key, v_dims, || {
                let layout = vertical::SliceLayout {
                    per_axis: params.vertical_slices,
                    patch_size: params.patch_size,
                };
                let (refs, ranges) = layout.bake_refs(&patch.blades, params.gravity);
                btf::bake(
                    ctx,
                    &bake_inputs,
                    v_dims.width,
                    v_dims.height,
                    &btf::Layers {
                        cells: &layout.bake_cells(),
                        refs: &refs,
                        ranges: &ranges,
                    },
                )
            })?;
        ctx.gpu.wait_idle("baking the BTFs")?;
        let btf_seconds = started.elapsed().as_secs_f64();
        let (orientation, orientation_bytes) =
            slice::orientation_map(device, &ctx.gpu.queue, &grid, seed);
        let view = |binding, view| wgpu::BindGroupEntry {
            binding,
            resource: wgpu::BindingResource::TextureView(view),
        };
        let slice_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("boulanger slice (group 2)"),
            layout: &slice_layout,
            entries: &[
                view(1, &horizontal.color),
                view(2, &horizontal.diffuse),
                view(5, &horizontal.extra),
                view(6, &verticals.color),
                view(7, &verticals.diffuse),
                view(8, &verticals.extra),
                view(3, &orientation),
            ],
        });
        let blade_bytes = std::mem::size_of_val(patch.blades.as_slice()) as u64;
        let paging = cells::Paging::new(patch.blades.len() as u32, &device.limits());
        let cell_capacity = paging.capacity(0);
        let (cell_buffer, cell_group) = cells::buffer(
            device,
            &cell_layout,
            &blades,
            cell_capacity,
            paging.binding_cells(cell_capacity),
        );
        let quad_capacity = INITIAL_QUADS;
        let quad_buffer = quad_buffer(device, quad_capacity);
        let vcell_capacity = INITIAL_QUADS;
        let vcell_buffer = vcell_buffer(device, vcell_capacity);
        Ok(Self {
            lod,
            blades_per_patch: patch.blades.len() as u32,
            seed,
            tree,
            patch,
            blade_pipeline,
            slice_pipeline,
            vslice_pipeline,
            ground_shadows,
            group1,
            cell_layout,
            cell_group,
            cell_buffer,
            cell_capacity,
            paging,
            pages: Vec::new(),
            slice_group,
            blades,
            quad_buffer,
            quad_capacity,
            vcell_buffer,
            vcell_capacity,
            btf_outcome: [h_outcome, v_outcome],
            btf_seconds,
            fixed_bytes: blade_bytes
                + mask.bytes
                + ao_bytes
                + horizontal.bytes
                + verticals.bytes
                + orientation_bytes
                + blade_texture_bytes
                + std::mem::size_of::<ParamsUniform>() as u64,
            params,
            selection: Selection::default(),
            geometry: Vec::new(),
            quads: Vec::new(),
            vcells: Vec::new(),
            vcell_uniforms: Vec::new(),
            quad_groups: Vec::new(),
            lod_blades: BandBlades::default(),
            alpha_floor: uniform.lod[3],
            overhang,
            reach_up,
        })
    }

    /// Virtual blades tiled over the terrain: cells x blades per patch.
    pub fn virtual_blades(&self) -> u64 {
        self.tree.grid().count() * u64::from(self.blades_per_patch)
    }

    /// Blades in one patch.
    pub fn blades_per_patch(&self) -> u32 {
        self.blades_per_patch
    }

    fn slice_quad(&self, s: &quadtree::Selected, tess: u32) -> SliceQuad {
        let grid = self.tree.grid();
        let min = grid.cell_min(s.rect.i0, s.rect.j0);
        SliceQuad {
            rect: [
                min.x,
                min.y,
                s.rect.ni as f32 * grid.cell,
                s.rect.nj as f32 * grid.cell,
            ],
            cells: [
                s.rect.i0 as f32,
                s.rect.j0 as f32,
                s.rect.ni as f32,
                s.rect.nj as f32,
            ],
            tess: [tess as f32, 0.0, 0.0, 0.0],
        }
    }

    /// Records this frame's geometric blades with the pass's pipeline (blade layout: the
    /// cells in group 2, one dynamic offset per page).
    fn draw_geometry(&self, pass: &mut RenderPass<'_>) {
        let vertices = self.vertices_per_blade();
        for page in &self.pages {
            // In range: `prepare` refuses a buffer over 4 GiB.
            let offset = (u64::from(page.first_cell) * cells::CELL_BYTES) as u32;
            pass.set_bind_group(2, &self.cell_group, &[offset]);
            for r in &page.draws {
                pass.draw(0..vertices, r.clone());
            }
        }
    }

    /// Records this frame's horizontal slice quads with the pass's pipeline (slice layout),
    /// one draw per tessellation.
    fn draw_quads(&self, pass: &mut RenderPass<'_>) {
        pass.set_vertex_buffer(0, self.quad_buffer.slice(..));
        for (tess, range) in &self.quad_groups {
            pass.draw(0..tess * tess * 6, range.clone());
        }
    }

    fn vertices_per_blade(&self) -> u32 {
        2 * self.params.segments + 2
    }
}

fn quad_buffer(device: &wgpu::Device, capacity: usize) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("boulanger slice quads"),
        size: (capacity * std::mem::size_of::<SliceQuad>()) as u64,
        usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// The patch of a scene (Sec. 3.1).
fn build_patch(params: &Params, scene: &grassbench::Scene) -> Patch {
    let grass = &scene.config.grass;
    let density = params.effective_blades_per_m2(grass.density);
    let strata = Patch::strata_for(params.patch_size, density);
    Patch::new(
        params.patch_size,
        strata,
        BLOCKS,
        grass,
        patch::BladeShape {
            max_tilt: params.max_tilt,
        },
        scene.config.seed,
    )
}

/// The shaders' uniform block.
fn params_uniform(params: &Params, grass: &grassbench::grass::GrassConfig) -> ParamsUniform {
    let a2c = params.transparency == Transparency::AlphaToCoverage;
    let tallest = grass.height[1];
    ParamsUniform {
        color_root: Vec3::from(grass.color_root)
            .extend(grass.color_variation)
            .to_array(),
        color_tip: Vec3::from(grass.color_tip)
            .extend(params.translucency)
            .to_array(),
        blade: [
            params.segments as f32,
            params.gravity,
            if params.animate {
                params.wind_response
            } else {
                0.0
            },
            params.ao_root,
        ],
        lod: [
            params.min_geom,
            params.max_geom,
            params.omega,
            if a2c {
                1.0 / 255.0
            } else {
                params.alpha_threshold
            },
        ],
        tile: [
            params.patch_size,
            params.slice_height * tallest,
            params.slice_resolution as f32,
            1.3 * tallest + 0.05,
        ],
        btf: [
            params.vertical_slices as f32,
            params.min_btf,
            params.max_btf,
            f32::from(u8::from(params.shadow_mask)),
        ],
    }
}

/// Sizes of the two BTFs: the horizontal slice's one layer, the vertical slices' `4N`.
fn btf_dims(params: &Params) -> [cache::Dims; 2] {
    [
        cache::Dims {
            width: params.slice_resolution,
            height: params.slice_resolution,
            layers: 1,
        },
        cache::Dims {
            width: params.vslice_width,
            height: params.vslice_height,
            layers: 4 * params.vertical_slices,
        },
    ]
}

/// Cache keys of the two bakes (horizontal, vertical): the uniform block with what the bake
/// does not read (LOD distances, alpha threshold, wind response, slice height) zeroed, and the
/// patch.
fn bake_keys_of(params: &Params, uniform: &ParamsUniform, patch: &Patch) -> [u64; 2] {
    let mut u = *uniform;
    u.lod = [0.0; 4];
    u.blade[2] = 0.0;
    u.tile[1] = 0.0;
    u.btf[1] = 0.0;
    u.btf[2] = 0.0;
    let blades = bytemuck::cast_slice(&patch.blades);
    let [h, v] = btf_dims(params);
    [
        cache::bake_key("horizontal", h, bytemuck::bytes_of(&u), blades),
        cache::bake_key("vertical", v, bytemuck::bytes_of(&u), blades),
    ]
}

impl Boulanger {
    /// The BTF cache keys (horizontal, vertical) `new` would use on `scene` with `overrides`
    /// (CPU only).
    pub fn bake_keys(scene: &grassbench::Scene, overrides: &toml::Table) -> Result<[u64; 2]> {
        let params: Params = grassbench::params::resolve(Self::INFO.id, overrides)?;
        let patch = build_patch(&params, scene);
        let uniform = params_uniform(&params, &scene.config.grass);
        Ok(bake_keys_of(&params, &uniform, &patch))
    }

    /// How the BTFs were obtained at start-up (horizontal, vertical) and the seconds it took.
    pub fn btf_outcome(&self) -> (&[cache::Outcome; 2], f64) {
        (&self.btf_outcome, self.btf_seconds)
    }
}

/// The ambient visibility map as an `R8Unorm` texture (a white texel without one) and its
/// bytes.
fn ao_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    map: Option<grassbench::terrain::Grid<f32>>,
) -> (wgpu::TextureView, u64) {
    let (w, h, data) = match map {
        Some(m) => (
            m.width() as u32,
            m.height() as u32,
            m.data()
                .iter()
                .map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
                .collect(),
        ),
        None => (1, 1, vec![255u8]),
    };
    let texture = device.create_texture_with_data(
        queue,
        &wgpu::TextureDescriptor {
            label: Some("boulanger ambient occlusion map"),
            size: wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::R8Unorm,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        &data,
    );
    (texture.create_view(&Default::default()), data.len() as u64)
}

fn vcell_buffer(device: &wgpu::Device, capacity: usize) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("boulanger vertical slice cells"),
        size: (capacity * std::mem::size_of::<CellUniform>()) as u64,
        usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

impl GrassTechnique for Boulanger {
    fn update(&mut self, inputs: &FrameInputs<'_>) -> Result<()> {
        let camera = inputs.camera;
        let walk = Walk {
            frustum: camera.frustum(),
            eye: camera.eye,
            // Cells (not macro-cells) wherever geometry or vertical slices may be drawn.
            cell_distance: self.params.max_geom.max(self.params.max_btf),
            macro_factor: self.params.macro_factor,
        };
        let mut selection = std::mem::take(&mut self.selection);
        self.tree.select(&walk, &mut selection);
        self.geometry.clear();
        self.quads.clear();
        self.vcells.clear();
        let grid = *self.tree.grid();
        let per_patch = f64::from(self.blades_per_patch);
        let (omega, lod) = (self.params.omega, self.lod);
        let mut geometry_blades = 0u64;
        let mut slice_blades = 0.0f64;
        let mut vertical_blades = 0.0f64;
        for s in &selection.cells {
            let (i, j) = (s.rect.i0, s.rect.j0);
            if s.near < lod.max_geom {
                let centre = grid.cell_min(i, j) + Vec2::splat(0.5 * grid.cell);
                let orientation = Orientation::of_cell(self.seed, i, j);
                let mut ranges = Vec::new();
                for k in 0..BLOCKS * BLOCKS {
                    // The block where this cell's mirror puts it, with the blades' reach.
                    let (c, half) = self.patch.block_center(k);
                    let c = centre + orientation.apply(c);
                    let reach = half + self.overhang;
                    let ground = Aabb {
                        min: Vec3::new(c.x - half, s.ground_y[0], c.y - half),
                        max: Vec3::new(c.x + half, s.ground_y[1], c.y + half),
                    };
                    let bounds = Aabb {
                        min: Vec3::new(c.x - reach, s.ground_y[0], c.y - reach),
                        max: Vec3::new(c.x + reach, s.ground_y[1] + self.reach_up, c.y + reach),
                    };
                    let near = quadtree::distance_to_box(camera.eye, &ground);
                    if near >= lod.max_geom || !walk.frustum.intersects_aabb(&bounds) {
                        continue;
                    }
                    // The blades Eq. 5 can give visible opacity here: normalised thresholds
                    // from `geometry_min_t` of the largest weight in the block, under the
                    // density.
                    // A cell wholly at full weight draws whole blocks (the shader still
                    // tests each threshold), so runs of such cells merge into one draw.
                    let t_min =
                        lod::geometry_min_t(lod.w_g(near), omega, self.alpha_floor).max(0.0);
                    let whole = s.far <= lod.min_geom;
                    let lo = if whole {
                        0.0
                    } else {
                        (t_min * s.density_range[0] - 1e-4).max(0.0)
                    };
                    let hi = if whole || s.density_range[1] >= 1.0 {
                        f32::INFINITY
                    } else {
                        s.density_range[1] + 1e-4
                    };
                    let r = self.patch.threshold_range(k, lo, hi);
                    if !r.is_empty() {
                        geometry_blades += u64::from(r.end - r.start);
                        ranges.push(r);
                    }
                }
                if !ranges.is_empty() {
                    let signs = orientation.signs();
                    self.geometry.push(GeometryCell {
                        uniform: CellUniform {
                            center_signs: [centre.x, centre.y, signs.x, signs.y],
                            mode: [0.0; 4],
                        },
                        ranges,
                        near: s.near,
                    });
                }
            }
            if s.far > lod.min_geom {
                self.quads.push(self.slice_quad(s, 1));
                let d = 0.5 * (s.near + s.far);
                slice_blades += f64::from(s.density) * per_patch * f64::from(lod.w_hs(d));
                // The vertical slices where Eq. 3 can give them a share (Sec. 3.3).
                if s.near < lod.max_btf {
                    let centre = grid.cell_min(i, j) + Vec2::splat(0.5 * grid.cell);
                    let signs = Orientation::of_cell(self.seed, i, j).signs();
                    self.vcells.push((
                        CellUniform {
                            center_signs: [centre.x, centre.y, signs.x, signs.y],
                            mode: [0.0; 4],
                        },
                        s.near,
                    ));
                    vertical_blades += f64::from(s.density) * per_patch * f64::from(lod.w_vs(d));
                }
            }
        }
        for s in &selection.macro_cells {
            let side = s.rect.ni.max(s.rect.nj).next_power_of_two();
            self.quads.push(self.slice_quad(s, side.min(8)));
            slice_blades += f64::from(s.density) * per_patch;
        }
        self.selection = selection;
        // Far to near. Blades are not sorted (Sec. 4.2), but cells are, for free: Eq. 5 leaves
        // many blades of the transition semi-transparent, and with cells drawn near to far
        // (18 % faster here, thanks to early depth rejection) faint near blades hid whole
        // cells drawn after them, which showed as cell-sized blotches.
        self.geometry.sort_by(|a, b| b.near.total_cmp(&a.near));
        self.vcells.sort_by(|a, b| b.1.total_cmp(&a.1));
        self.vcell_uniforms.clear();
        self.vcell_uniforms.extend(self.vcells.iter().map(|c| c.0));
        self.pages = self
            .paging
            .draws(self.geometry.iter().map(|c| c.ranges.as_slice()));
        self.quads.sort_by(|a, b| a.tess[0].total_cmp(&b.tess[0]));
        self.quad_groups.clear();
        let mut start = 0u32;
        for tess in TESS_LEVELS {
            let n = self
                .quads
                .iter()
                .filter(|q| q.tess[0] as u32 == tess)
                .count() as u32;
            if n > 0 {
                self.quad_groups.push((tess, start..start + n));
            }
            start += n;
        }
        self.lod_blades = BandBlades {
            geometry: geometry_blades,
            vertical_slices: vertical_blades.round() as u64,
            horizontal_slices: slice_blades.round() as u64,
        };
        Ok(())
    }

    fn prepare(&mut self, gpu: &GpuContext, _inputs: &FrameInputs<'_>) -> Result<()> {
        let device = &gpu.device;
        if self.geometry.len() > self.cell_capacity {
            let capacity = self.paging.capacity(self.geometry.len());
            if capacity as u64 * cells::CELL_BYTES > u64::from(u32::MAX) {
                return Err(Error::Technique {
                    technique: Self::INFO.id.to_owned(),
                    message: format!(
                        "{} geometry cells in one frame do not fit one buffer: lower max_geom or raise patch_size",
                        self.geometry.len()
                    ),
                });
            }
            self.cell_capacity = capacity;
            (self.cell_buffer, self.cell_group) = cells::buffer(
                device,
                &self.cell_layout,
                &self.blades,
                capacity,
                self.paging.binding_cells(capacity),
            );
        }
        if self.quads.len() > self.quad_capacity {
            self.quad_capacity = self.quads.len().next_power_of_two();
            self.quad_buffer = quad_buffer(device, self.quad_capacity);
        }
        if self.vcell_uniforms.len() > self.vcell_capacity {
            self.vcell_capacity = self.vcell_uniforms.len().next_power_of_two();
            self.vcell_buffer = vcell_buffer(device, self.vcell_capacity);
        }
        if !self.vcell_uniforms.is_empty() {
            gpu.queue.write_buffer(
                &self.vcell_buffer,
                0,
                bytemuck::cast_slice(&self.vcell_uniforms),
            );
        }
        if !self.geometry.is_empty() {
            let uniforms: Vec<CellUniform> = self.geometry.iter().map(|c| c.uniform).collect();
            gpu.queue
                .write_buffer(&self.cell_buffer, 0, bytemuck::cast_slice(&uniforms));
        }
        if !self.quads.is_empty() {
            gpu.queue
                .write_buffer(&self.quad_buffer, 0, bytemuck::cast_slice(&self.quads));
        }
        Ok(())
    }

    fn encode(&self, encoder: &mut FrameEncoder<'_>) {
        if let Some(shadows) = &self.ground_shadows
            && !(self.geometry.is_empty() && self.quads.is_empty())
        {
            // Sec. 3.5, before the grass: blades into the stencil, the cover, then the slices.
            let mut pass = encoder.render_pass("ground_shadows");
            pass.set_stencil_reference(ground_shadow::STENCIL_MARK);
            pass.set_bind_group(1, &self.group1, &[]);
            if !self.geometry.is_empty() {
                pass.set_pipeline(&shadows.blades);
                self.draw_geometry(&mut pass);
                pass.set_pipeline(&shadows.cover);
                pass.draw(0..3, 0..1);
            }
            if !self.quads.is_empty() {
                pass.set_pipeline(&shadows.slices);
                pass.set_bind_group(2, &self.slice_group, &[]);
                self.draw_quads(&mut pass);
            }
        }
        if !self.quads.is_empty() {
            let mut pass = encoder.render_pass("horizontal_slice");
            pass.set_pipeline(&self.slice_pipeline);
            pass.set_bind_group(1, &self.group1, &[]);
            pass.set_bind_group(2, &self.slice_group, &[]);
            self.draw_quads(&mut pass);
        }
        if !self.vcell_uniforms.is_empty() {
            let mut pass = encoder.render_pass("vertical_slices");
            pass.set_pipeline(&self.vslice_pipeline);
            pass.set_bind_group(1, &self.group1, &[]);
            pass.set_bind_group(2, &self.slice_group, &[]);
            pass.set_vertex_buffer(0, self.vcell_buffer.slice(..));
            pass.draw(
                0..12 * self.params.vertical_slices,
                0..self.vcell_uniforms.len() as u32,
            );
        }
        if !self.geometry.is_empty() {
            let mut pass = encoder.render_pass("geometry");
            pass.set_pipeline(&self.blade_pipeline);
            pass.set_bind_group(1, &self.group1, &[]);
            self.draw_geometry(&mut pass);
        }
    }

    fn stats(&self) -> TechniqueStats {
        let quad_triangles: u64 = self
            .quads
            .iter()
            .map(|q| 2 * (q.tess[0] as u64).pow(2))
            .sum();
        let blade_triangles = self.lod_blades.geometry * u64::from(2 * self.params.segments);
        // Sec. 3.5's ground shadows draw the blades and the slices again, plus the cover.
        let shadow_triangles = match &self.ground_shadows {
            Some(_) if !self.geometry.is_empty() => blade_triangles + 1 + quad_triangles,
            Some(_) => quad_triangles,
            None => 0,
        };
        TechniqueStats {
            blades: self.lod_blades.geometry
                + self.lod_blades.vertical_slices
                + self.lod_blades.horizontal_slices,
            triangles: blade_triangles
                + quad_triangles
                + self.vcell_uniforms.len() as u64 * u64::from(4 * self.params.vertical_slices)
                + shadow_triangles,
            gpu_bytes: self.fixed_bytes
                + self.cell_capacity as u64 * cells::CELL_BYTES
                + (self.quad_capacity * std::mem::size_of::<SliceQuad>()) as u64
                + (self.vcell_capacity * std::mem::size_of::<CellUniform>()) as u64,
        }
    }

    /// Sec. 3.1's three levels.
    fn levels(&self) -> Vec<LevelBlades> {
        let l = &self.lod_blades;
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

#[cfg(test)]
mod tests {
    use super::*;
    use grassbench::glam::Vec2;
    use grassbench::terrain::{CoveringSource, MapSource, Terrain, TerrainConfig};

    /// A density map of constant 0.6 draws 60 % of the blades, whatever the distance: the
    /// patch's thresholds are drawn uniformly, so the fraction under 0.6 is binomial with
    /// standard deviation sqrt(0.6·0.4/N) = 0.0033 for the N = 21 904 blades of the default
    /// patch. The tolerance, 0.015, is 4.5 standard deviations (a false failure about once in
    /// 150 000 seeds); a bias in the thresholds or in the LOD share of 1.5 % fails it.
    #[test]
    fn constant_density_of_0_6_draws_60_percent() {
        let config = TerrainConfig {
            size: [4.0, 4.0],
            max_height: 0.0,
            samples_per_metre: 1.0,
            height: MapSource::default(),
            density: MapSource::Constant { value: 0.6 },
            covering: CoveringSource::Grass,
        };
        let terrain = Terrain::build(&config, 1, std::path::Path::new(".")).unwrap();
        let p = Params {
            blades_per_m2: 87_800.0,
            ..Params::default()
        };
        let strata = Patch::strata_for(p.patch_size, p.blades_per_m2);
        for seed in [1, 2, 3] {
            let patch = Patch::new(
                p.patch_size,
                strata,
                BLOCKS,
                &grassbench::grass::GrassConfig::default(),
                patch::BladeShape { max_tilt: 0.4 },
                seed,
            );
            let lod = LodDistances {
                min_geom: p.min_geom,
                max_geom: p.max_geom,
                min_btf: p.min_btf,
                max_btf: p.max_btf,
            };
            for d in [0.5, 2.7, 3.2, 3.9, 10.0] {
                for omega in [0.0, 0.4] {
                    let drawn: f32 = patch
                        .blades
                        .iter()
                        .map(|b| {
                            let rho = terrain.density_at(Vec2::from(b.root));
                            let s = lod::blade_share(rho, b.threshold, lod.w_g(d), omega);
                            s.geometry + s.slices
                        })
                        .sum();
                    let fraction = drawn / patch.blades.len() as f32;
                    assert!(
                        (fraction - 0.6).abs() < 0.015,
                        "seed {seed}, d {d}, ω {omega}: {fraction}"
                    );
                }
            }
        }
    }
}

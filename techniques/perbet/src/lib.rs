//! # `perbet`: animated prairies with three levels of detail
//!
//! Perbet and Cani, *Animating Prairies in Real-Time* (I3D 2001; the transcript is
//! `shared/seeds/004_605c516a3655ba8a.txt`). The terrain is tiled into patches of grass; each
//! patch is drawn, by its discrete distance to the camera, as 3D blades, as 2.5D animated
//! texture strips or as a 2D texture; wind primitives act on every level through receivers
//! that carry a bending direction and a posture index; patches change level on the fly with
//! morphing transitions while everything keeps moving.
//!
//! ## Algorithm
//! - **Patches, finest to coarsest** (Sec. 2.2, [`patch`], [`paint`]). `variants` patches of
//!   `patch_size` (2.5 m) are built at start-up. First the 3D blades: chains of `segments`
//!   line segments (Fig. 2) with seeded segment orientations (a curved rest lean plus a random
//!   turn of each segment), heights, widths and colours from the scene's `[grass]`. Then, for
//!   both strip orientations (planes of constant z, planes of constant x), each of the `strips`
//!   strip textures is rendered orthographically from the blades whose roots lie between its
//!   two planes (Sec. 4.2, Fig. 13), and each blade's points are stored in that texture's
//!   coordinates (Fig. 14): the morph targets. Last the 2D textures ("coarse images of the 3D
//!   patch taken from different viewing angles"): for 10°, 30° and 60° above the horizon, the
//!   average of four views of the patch, projected on the surface it is drawn on, mipmapped;
//!   a pixel blends the two nearest to the angle it is seen at. The
//!   textures are rasterised on the CPU (supersampled), so they are the same on any adapter.
//!   Every texel keeps the density threshold of its blade, so the scene's density map thins
//!   strips and 2D texture like the 3D blades.
//! - **Tiling and culling** ([`tiling`]). Patches tile the terrain row by row, each showing a
//!   hashed variant; each frame the patches whose box (ground, blade height, lean) meets the
//!   view frustum are kept — the paper's 2D view-cone test generalised to any camera pitch.
//! - **Levels** (Sec. 2.2, 4.1, [`lod`]). The discrete distance of a patch is the Chebyshev
//!   distance, in patches, to the camera's patch. Distances below `strip_range[0]` are 3D, up
//!   to `strip_range[1]` 2.5D, beyond 2D. A patch moving away keeps its level `hysteresis`
//!   patches past the limit (going back uses the nominal limit), so a walker standing at a
//!   limit starts at most one transition. A patch entering the view takes its level at once.
//! - **Receivers** (Sec. 3.2, [`receiver`]). Each frame every 3D blade (at its root) and both
//!   vertical edges of every strip polygon (Fig. 3) ask the wind for a direction and a posture
//!   index in `[−1, 1]`. Under `[wind] model = "primitives"` that is
//!   [`PrimitiveSet::sample`](grassbench::wind::PrimitiveSet::sample) (breeze, gust,
//!   whirlwind, blast, mixed by priority, Sec. 3.3); any other wind model drives the receivers
//!   through its velocity (index = speed / `wind_speed`). The index selects a shape among the
//!   pre-computed postures of `grassbench::wind::posture` (a simulated chain, Fig. 6) of the
//!   blade's kind of grass (`kinds` height classes, each simulated at its mean height, so the
//!   same wind bends tall grass further), interpolated between the two nearest postures and
//!   resampled to the blade's segment count; the
//!   vertex shader adds each segment's posture angle towards the direction to its rest tilt.
//!   Strip edges bend the same way (as the middle kind), carrying the texture with them.
//! - **Drawing** (Sec. 2.2, `shaders/perbet.wgsl`). One render pass, three instanced draws:
//!   2D surfaces (a terrain-following grid at half the strip height above the ground, Sec.
//!   4.3, one per block of patches below), then strips (each patch's strips in the
//!   orientation the view is least parallel to, chosen per patch with a little hysteresis),
//!   then 3D blades. Patches are listed far to near and each patch's strips are drawn far to
//!   near, so alpha blending needs no polygon sorting ("we just need to process the prairie
//!   in the right order").
//! - **2D blocks** ([`blocks`]; ours, not the paper's). The 2D level is a texture on the
//!   ground, so the patches settled at it (in view, not in a transition) need not be drawn one
//!   by one: a quadtree over the tiling merges them into squares of `s x s` patches, one 2D
//!   surface each, once a square is at least `flat_block_distance · s` patches (default 4)
//!   from the camera's patch and holds no patch at another level; `s` doubles with distance
//!   up to 8. A block's fragments find their own patch, its variant (a per-patch buffer) and
//!   its texture coordinates, and read the density map themselves, so a block draws what its
//!   patches drew. Patches in a 2.5D ↔ 2D transition keep their own surface. Every settled 2D
//!   patch lies in exactly one block, and every block holds one in view (no block lies
//!   wholly out of view). From 32 patches away every block is 8 x 8 (clipped at the
//!   terrain's edges), one draw for 64 patches: the 2D level still grows with the area in
//!   view (which the far plane bounds), 64 times slower.
//! - **Transitions** (Sec. 4, [`frame`]). A transition lasts `transition_steps` frames (the
//!   paper's twenty). 3D ↔ 2.5D: both levels animate; each 3D blade is drawn at a linear blend
//!   between its own animated shape and the point its painted copy has on the animated strip
//!   ([`morph`], the CPU twin of the shader's strip surface and morph),
//!   then the last `fade` of the way cross-fades blades and strips ("an additional fade in -
//!   fade out", Sec. 4.2). 2.5D ↔ 2D: strips sink into (grow out of) the ground while the 2D
//!   texture fades in (out) on its offset surface (Sec. 4.3). A transition the camera turns back
//!   on runs backwards from where it is.
//! - **Counts** ([`population`]). A tiled patch shows the blades of its variant, but only those
//!   rooted on the terrain, on ground the covering map calls grass and under the density map
//!   grow (the vertex shader's rule per 3D blade; strips and 2D texels test the same
//!   thresholds). Those are counted per tiled patch at start-up, and a frame's
//!   `blades_drawn` sums them over the patches drawn as 3D blades (alone or morphing into their
//!   strips), `blades_represented` over the other patches drawn (strips, 2D, or both while one
//!   grows out of the other), so each blade counts once. A patch none of whose blades grows is
//!   not drawn at all. On the 12 x 12 m lawn of `tests/scenes/counts.toml` (2 875 blades,
//!   tiled by 5 x 5 patches reaching 0.5 m past two edges): 2 834 (−1.4 %; before issue 19,
//!   `patches x blades_per_patch` = 3 125, +8.7 %, counting the overhang).
//!
//! ## Quality presets (Sec. 5.1)
//! `quality = "low" | "medium" | "high"`: 160 / 320 / 500 blades a patch, 3 / 4 / 8 segments,
//! strips from distance 3-8 / 2-12 / 3-20. By default (`density = "scene"`) a patch holds the
//! scene's `[grass] density` times its area, rounded (so none at `grass.density = 0`: nothing
//! is drawn), instead of the preset's blade count, so perbet is compared with the other
//! techniques on the same population; `density = "preset"` takes the table's.
//! `blades_per_patch`, `segments` and `strip_range` override both (0 keeps them).
//! `experiments/perbet_quality.toml` reproduces the table.
//!
//! ## Cost model
//! CPU per frame: the level update of every patch (`O(patches)`), a sort of the visible ones,
//! and one wind sample per receiver: `B` per 3D patch and `strips · (columns + 1)` per 2.5D
//! patch. GPU: 3D patches `B · (2n − 1)` triangles each (at most `(2·(from + hysteresis) +
//! 1)²` such patches whatever the view, as the paper bounds it); strips `2 · S · C · n`
//! triangles a patch but much fill (semi-transparent, overlapping: on lavapipe the blended
//! strip layers, not triangles, set the frame time); 2D `2 · 4²` triangles a block. Memory:
//! the variants' blades and textures (about 7 MB, mostly the 32 strip layers and twelve 2D
//! layers with their mip chains) plus per-frame entries and receivers: 8 MB on the meadow
//! (`results/perbet_quality/`). Measured on the meadow with the medium preset (the default
//! comparison, `results/default/`, revision `fc2311d`): 56 ms of GPU time a frame against the
//! reference's 489 ms (8.7x), 0.9 ms of CPU update, on a 2-vCPU AMD EPYC virtual machine
//! (Zen 4, 2.6 GHz; at `5d8d609` on a 2-core Xeon: 51 against 482 ms, 9.5x, 0.7 ms);
//! pre-computation 136 ms (`benches/precompute.rs`, 2026-12-01). The frame's cost moves with
//! the host, and not by one factor: `results/perbet_quality/`, re-made on that EPYC at
//! `2dd4b96`, has perbet's frames 1.13-1.30 times the Xeon's and the reference's 1.08-1.15
//! times (that host prices a blended fragment at 1.13 times the Xeon's, a texture sample at
//! 1.30, a vertex at 1.75, a primitive at 0.77), so the speed-ups over the reference there are
//! 3.8-8.4x at the presets' own densities (4.1-8.9x on the Xeon); on a 2.0 GHz AMD EPYC
//! (`487fc0a`), whose frames took 2.8-4.9 times these, they were 3.3-6.8x. Against the
//! reference's vertex shader of `59a14de` and `68eb6f4`, whose frames are 0.52-0.61 as long,
//! they are 2.2-4.6x (`ab46b38`, a 2-vCPU Intel Xeon with AVX-512), and the high preset at
//! 25.6 blades/m² on the 80 m meadow costs as much as the reference (0.97x).
//!
//! The 2D level drawn patch by patch grew with the terrain where the view was already full
//! (`results/scaling/` at `493d788`, on the Xeon: 34 → 91 ms from 80 m to 400 m, 42 k → 249 k
//! triangles). With the blocks, on the meadow at 20 blades/m² (480x270, lavapipe, frame 6): at
//! 80 m 377 2D patches in 82 draws, 32.5 k triangles (42.0 k patch by patch), 85.6 k vertex
//! invocations (113.9 k); at 400 m 6 816 2D patches in 224 draws, 37.7 k triangles (248.6 k),
//! 99.6 k vertex invocations (732.4 k), 29.7 k primitives out of the clipper (237.7 k);
//! fragments hardly change (1.26 M / 1.24 M). So from 80 m to 400 m the triangles now grow
//! 1.16x instead of 5.9x, and the frame stays nearly flat: `results/scaling/` has perbet at
//! 32.9 → 35.9 ms (1.09x) on the Zen 4 EPYC at `2dd4b96`, 106.0 → 103.1 ms (0.97x) on the
//! 2.0 GHz EPYC at `487fc0a`, 28.5 → 30.1 ms (1.05x) on the Xeon at `00e5090`. The CPU's level
//! update still visits every patch (`O(patches)`).
//!
//! ## Deviations and known artifacts
//! - Blades are drawn as tapering quads of their width along the chain, not as GL lines (wgpu
//!   lines are one pixel wide on every backend); the strip textures paint the same quads.
//! - The density map is tested per blade (3D) and per texel (strips, 2D: the threshold of the
//!   painted blade; the 2D texel's is an average, so thinning there is approximate).
//! - A patch's strip orientation flips when the view direction to it crosses a diagonal: a
//!   small pop (not in the paper either). Strips reach `strip_margin` past their patch so leaning
//!   blades are painted whole; neighbouring patches' strips overlap there.
//! - Morphing moves blade roots (the paper notes it too); blades keep their width axis while
//!   morphing, so a blade seen edge-on narrows only when the fade replaces it.
//! - The 2D level is not animated (as in the paper) and its texture tiles per variant, which
//!   shows as a faint pattern in far fields seen from above.
//! - Far 2D patches are drawn by blocks, not one by one (the paper draws every patch). A
//!   block's grid is coarser than a patch's (cells of up to 5 m instead of 0.625 m), so its
//!   surface follows the ground less closely: on the 400 m meadow a 5 m grid lies at most
//!   0.21 m below the ground it follows, less than the surface's offset (half the strips'
//!   height), so it never sinks into the ground there. The picture against patch by patch:
//!   FLIP 0.0004 at 80 m (354 of 129 600 pixels differ) and 0.0012 at 400 m (1.3 k pixels),
//!   480x270. `flat_block_distance = 0` draws every 2D patch on its own.

#![cfg_attr(test, allow(clippy::unwrap_used, clippy::expect_used, clippy::panic))]

pub mod blocks;
pub mod frame;
pub mod gpu;
pub mod lod;
pub mod morph;
pub mod paint;
pub mod paper;
pub mod params;
pub mod patch;
pub mod population;
pub mod precompute;
pub mod receiver;
pub mod tiling;

use glam::{Vec2, Vec3};
use grassbench::gpu::GpuEstimate;
use grassbench::technique::{LevelBlades, Technique, TechniqueEntry, Variant, Variants};
use grassbench::{
    FrameEncoder, FrameInputs, GpuContext, GrassTechnique, InitContext, Result, Scene,
    TechniqueInfo, TechniqueStats,
};

pub use gpu::SHADER;
pub use params::{Density, Params, Quality};

use blocks::{Block, Blocks, Cover};
use frame::{Entry, FLAG_ORIENTATION, FLAG_REVERSED, Lists};
use gpu::{Draws, Gpu, ParamsUniform, Statics};
use lod::{LodGrid, Ranges};
use patch::{Layout, Patch};
use precompute::{Precomputed, Sizes};
use receiver::Receivers;
use tiling::Tiling;

/// The registry line for this technique.
pub const ENTRY: TechniqueEntry = grassbench::technique::entry::<Perbet>();

/// The technique.
pub struct Perbet {
    params: Params,
    layout: Layout,
    patches: Vec<Patch>,
    tiling: Tiling,
    lod: LodGrid,
    /// Strip orientation per patch (0: planes of constant z), kept while it is good enough.
    orientation: Vec<u8>,
    visible: Vec<bool>,
    /// Visible patches by distance, far first (reused every frame).
    order: Vec<(f32, usize)>,
    lists: Lists,
    /// The quadtree merging settled 2D patches into blocks ([`blocks`]).
    blocks: Blocks,
    /// What each patch needs from the 2D surface this frame (reused every frame).
    cover: Vec<Cover>,
    /// This frame's 2D blocks (reused every frame).
    block_list: Vec<Block>,
    /// Patches drawn at the 2D level this frame (in blocks or in a transition).
    patches_flat: u64,
    entries: Vec<Entry>,
    blade_receivers: Vec<[f32; 4]>,
    edge_receivers: Vec<[f32; 4]>,
    uniform: ParamsUniform,
    draws: Draws,
    gpu: Gpu,
    culled: u64,
    transitions: u64,
    frozen: Option<lod::PatchLod>,
    /// Blades that grow on each patch of the tiling ([`population`]).
    growing: Vec<u32>,
    /// Blades of the last frame: drawn as 3D blades, represented by impostors, and per level
    /// (3D, 2.5D, 2D; a patch between two levels counts in both).
    blades: FrameBlades,
}

/// Blades of one frame, summed over the patches it draws.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct FrameBlades {
    /// Blades of patches drawn as 3D blades (alone or in a transition).
    drawn: u64,
    /// Blades of the other patches drawn: strips and 2D textures stand for them.
    represented: u64,
    /// Blades per level: 3D, 2.5D, 2D.
    levels: [u64; 3],
}

impl Technique for Perbet {
    type Params = Params;

    const INFO: TechniqueInfo = TechniqueInfo {
        id: "perbet",
        name: "Perbet & Cani (3D / 2.5D / 2D patches, wind primitives)",
        paper: "Perbet & Cani 2001, Animating Prairies in Real-Time (I3D)",
        gpu_state: false,
        debug_views: &["level of detail (red 3D, green 2.5D strips, blue 2D)"],
    };

    const VARIANTS: Variants = Variants {
        finest: "strip_range = [100000, 100000]",
        others: &[
            Variant {
                name: grassbench::technique::NO_TRANSITIONS,
                params: "transition_steps = 0",
            },
            Variant {
                name: grassbench::technique::PAPER,
                params: paper::VARIANT,
            },
        ],
    };

    /// Builds the patches, paints their strip and 2D textures, simulates the postures and
    /// creates the pipelines.
    fn new(ctx: &InitContext<'_>, params: Params) -> Result<Self> {
        let scene = ctx.scene;
        let grass = &scene.config.grass;
        let precompute = Precomputed::new(scene, &params)?;
        let blades_per_patch = params.blades(grass.density);
        let arrays = precompute.arrays();
        let uniform = precompute.uniform(&params, grass);
        let Precomputed {
            layout,
            patches,
            strip_layers,
            flat_layers,
            ..
        } = precompute;
        let sizes = Sizes::new(scene, &params, layout.strip_height);
        let reach =
            params.strip_margin * params.patch_size + grass.height[1] * grass.lean.sin().abs();
        let tiling = Tiling::new(
            &scene.terrain,
            params.patch_size,
            params.variants,
            scene.config.seed,
            reach,
            layout.strip_height,
        );
        let mut uniform = uniform;
        uniform.tiling = [tiling.cols, tiling.rows, 0, 0];
        let gpu = Gpu::new(
            ctx,
            &Statics {
                blades: &arrays.blades,
                tilts: &arrays.tilts,
                painted: &arrays.painted,
                postures: &arrays.postures,
                strip_layers: &strip_layers,
                flat_layers: &flat_layers,
                variants: &tiling.variants,
                segments: layout.segments,
            },
            sizes.capacity,
        );
        let [from, to] = params.strips_from_to();
        let lod = LodGrid::new(
            tiling.cols,
            tiling.rows,
            Ranges {
                strips_from: from,
                strips_to: to,
                hysteresis: params.hysteresis,
            },
            params.transition_steps,
        );
        let n_patches = tiling.len();
        let blocks = Blocks::new(tiling.cols, tiling.rows);
        let growing = population::growing(&tiling, &patches, &scene.terrain);
        Ok(Self {
            draws: Draws {
                vertices: [
                    2 * layout.segments + 1,
                    6 * params.strip_columns * layout.segments,
                    6 * gpu::FLAT_CELLS * gpu::FLAT_CELLS,
                ],
                per_entry: [blades_per_patch, params.strips],
                ..Default::default()
            },
            params,
            layout,
            patches,
            tiling,
            lod,
            orientation: vec![0; n_patches],
            visible: vec![false; n_patches],
            order: Vec::new(),
            lists: Lists::default(),
            blocks,
            cover: vec![Cover::Empty; n_patches],
            block_list: Vec::new(),
            patches_flat: 0,
            entries: Vec::new(),
            blade_receivers: Vec::new(),
            edge_receivers: Vec::new(),
            uniform,
            gpu,
            culled: 0,
            transitions: 0,
            frozen: None,
            growing,
            blades: FrameBlades::default(),
        })
    }

    fn estimate(scene: &Scene, params: &Params) -> Result<GpuEstimate> {
        Ok(Sizes::new(scene, params, scene.config.grass.height[1]).estimate())
    }

    fn params(&self) -> &Params {
        &self.params
    }
}

impl FrameBlades {
    /// Adds a patch of `growing` blades drawn as `r`.
    fn count(&mut self, r: &frame::Representation, growing: u64) {
        if r.geometry.is_some() {
            self.drawn += growing;
        } else {
            self.represented += growing;
        }
        for (sum, drawn) in
            self.levels
                .iter_mut()
                .zip([r.geometry.is_some(), r.strips.is_some(), r.flat.is_some()])
        {
            *sum += growing * u64::from(drawn);
        }
    }
}

impl Perbet {
    /// Draws every visible patch in `state` instead of its own level from the next `update` on
    /// (`None` goes back to the levels): a tool to inspect one level, or the whole view frozen
    /// at one step of a transition. The patches' own levels keep being updated underneath.
    pub fn freeze(&mut self, state: Option<lod::PatchLod>) {
        self.frozen = state;
    }

    /// Keeps or flips patch `i`'s strip orientation for a view from `eye` (xz): strips of
    /// constant z face a view along z; the other orientation is taken only when the view is
    /// clearly (20 %) closer to x, and never during a transition (its morph targets).
    fn orient(&mut self, i: usize, eye: Vec2) -> u32 {
        let d = (self.tiling.centre(i) - eye).abs();
        let o = &mut self.orientation[i];
        if self.lod.state(i).transition.is_none() {
            if *o == 0 && d.x > 1.2 * d.y {
                *o = 1;
            } else if *o == 1 && d.y > 1.2 * d.x {
                *o = 0;
            }
        }
        u32::from(*o)
    }
}

impl GrassTechnique for Perbet {
    /// Levels, culling, far-to-near lists and the receivers' wind samples.
    fn update(&mut self, inputs: &FrameInputs<'_>) -> Result<()> {
        let camera = &inputs.camera;
        let frustum = camera.frustum();
        let eye = Vec2::new(camera.eye.x, camera.eye.z);
        for (v, b) in self.visible.iter_mut().zip(&self.tiling.bounds) {
            *v = frustum.intersects_aabb(b);
        }
        let visible = &self.visible;
        let camera_patch = self.tiling.patch_of(eye);
        self.lod
            .update(camera_patch, |i| visible.get(i).copied().unwrap_or(false));

        // Far to near (Sec. 2.2); the list's memory is kept from frame to frame.
        let mut order = std::mem::take(&mut self.order);
        order.clear();
        order.extend(
            (0..self.tiling.len())
                .filter(|i| self.visible[*i])
                .map(|i| (self.tiling.centre(i).distance_squared(eye), i)),
        );
        order.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
        self.culled = (self.tiling.len() - order.len()) as u64;
        self.transitions = 0;
        self.lists.clear();
        self.blades = FrameBlades::default();
        self.cover.fill(Cover::Empty);
        self.patches_flat = 0;
        for &(_, i) in &order {
            let growing = u64::from(self.growing.get(i).copied().unwrap_or(0));
            if growing == 0 {
                // No blade of this patch grows (off the grass, under a bare density map, or
                // `grass.density = 0`): it would draw nothing but discarded fragments.
                continue;
            }
            let state = self.frozen.unwrap_or_else(|| self.lod.state(i));
            self.transitions += u64::from(state.transition.is_some());
            let representation =
                frame::representation(state, self.params.transition_steps, self.params.fade);
            self.blades.count(&representation, growing);
            self.patches_flat += u64::from(representation.flat.is_some());
            let o = self.orient(i, eye);
            let centre = self.tiling.centre(i);
            // Strips are numbered along their normal; far to near is descending when the eye
            // is on the low side.
            let (eye_across, centre_across) = if o == 0 {
                (eye.y, centre.y)
            } else {
                (eye.x, centre.x)
            };
            let mut flags = o * FLAG_ORIENTATION;
            if eye_across < centre_across {
                flags |= FLAG_REVERSED;
            }
            let base = Entry {
                origin: self.tiling.corner(i).to_array(),
                variant: self.tiling.variants[i],
                flags,
                ..Default::default()
            };
            let settled_flat = representation
                == frame::Representation {
                    flat: Some(1.0),
                    ..Default::default()
                };
            if let Some(c) = self.cover.get_mut(i) {
                *c = if settled_flat {
                    Cover::Flat
                } else {
                    Cover::Other
                };
            }
            if settled_flat {
                // Drawn by its block below.
                continue;
            }
            self.lists.push(base, representation);
        }
        self.order = order;

        // The settled 2D patches, merged into blocks growing with distance; sorted far to near
        // with the 2D entries of the patches in a transition.
        self.block_list.clear();
        self.blocks.plan(
            &self.cover,
            camera_patch,
            self.params.flat_block_distance,
            &mut self.block_list,
        );
        for b in &self.block_list {
            let i = (b.first.1 * self.tiling.cols + b.first.0) as usize;
            self.lists.flat.push(Entry {
                origin: self.tiling.corner(i).to_array(),
                variant: self.tiling.variants.get(i).copied().unwrap_or(0),
                opacity: 1.0,
                link: frame::extent(b.extent.0, b.extent.1),
                ..Default::default()
            });
        }
        let size = self.tiling.size;
        let distance = |e: &Entry| {
            let extent = Vec2::new((e.link & 0xffff) as f32, (e.link >> 16) as f32);
            (Vec2::from(e.origin) + 0.5 * size * extent).distance_squared(eye)
        };
        self.lists
            .flat
            .sort_by(|a, b| distance(b).total_cmp(&distance(a)));
        let [strips_base, flat_base] = self.lists.concatenate(&mut self.entries);
        self.uniform.bases = [strips_base, flat_base, 0, 0];
        self.draws.geometry = self.lists.geometry.len() as u32;
        self.draws.strips = self.lists.strips.len() as u32;
        self.draws.flat = self.lists.flat.len() as u32;

        // Receivers (Sec. 3.2): every 3D blade, every strip edge.
        let receivers = Receivers::new(inputs.wind, self.params.wind_speed, inputs.time);
        let terrain = &inputs.scene.terrain;
        let ground = |xz: Vec2| Vec3::new(xz.x, terrain.height_at(xz), xz.y);
        self.blade_receivers.clear();
        for e in &self.lists.geometry {
            let origin = Vec2::from(e.origin);
            if let Some(patch) = self.patches.get(e.variant as usize) {
                self.blade_receivers.extend(
                    patch
                        .blades
                        .iter()
                        .map(|b| receivers.receive(ground(origin + b.root), b.height)),
                );
            }
        }
        self.edge_receivers.clear();
        let columns = self.layout.columns;
        for e in &self.lists.strips {
            let origin = Vec2::from(e.origin);
            let o = e.flags & FLAG_ORIENTATION;
            for k in 0..self.layout.strips {
                for j in 0..=columns {
                    let xz = origin + self.layout.strip_xz(o, k, j as f32 / columns as f32);
                    self.edge_receivers
                        .push(receivers.receive(ground(xz), self.layout.strip_height));
                }
            }
        }
        Ok(())
    }

    fn prepare(&mut self, gpu: &GpuContext, _inputs: &FrameInputs<'_>) -> Result<()> {
        self.gpu.upload(
            gpu,
            &self.uniform,
            &self.entries,
            &self.blade_receivers,
            &self.edge_receivers,
        )
    }

    fn encode(&self, encoder: &mut FrameEncoder<'_>) {
        self.gpu.encode(encoder, &self.draws);
    }

    fn stats(&self) -> TechniqueStats {
        let d = &self.draws;
        let blades = u64::from(d.per_entry[0]);
        let n = u64::from(self.layout.segments);
        let strip_triangles =
            2 * u64::from(self.layout.strips) * u64::from(self.layout.columns) * n;
        TechniqueStats {
            // A patch drawn as 3D blades (alone, or in a transition beside its strips) counts
            // its growing blades as geometry; every other patch drawn, its impostor's.
            blades_drawn: self.blades.drawn,
            blades_represented: self.blades.represented,
            // Every blade of a 3D patch is submitted (those that do not grow collapse in the
            // vertex shader).
            triangles: u64::from(d.geometry) * blades * (2 * n - 1)
                + u64::from(d.strips) * strip_triangles
                + u64::from(d.flat) * 2 * u64::from(gpu::FLAT_CELLS * gpu::FLAT_CELLS),
            gpu_bytes: self.gpu.bytes(),
        }
    }

    fn levels(&self) -> Vec<LevelBlades> {
        let [geometry, strips, flat] = self.blades.levels;
        let level = |level, blades| LevelBlades { level, blades };
        vec![
            level("3d", geometry),
            level("2_5d", strips),
            level("2d", flat),
        ]
    }

    fn counters(&self) -> Vec<(&'static str, f64)> {
        vec![
            ("patches_3d", f64::from(self.draws.geometry)),
            ("patches_2_5d", f64::from(self.draws.strips)),
            ("patches_2d", self.patches_flat as f64),
            ("draws_2d", f64::from(self.draws.flat)),
            ("patches_in_transition", self.transitions as f64),
            ("patches_culled", self.culled as f64),
            (
                "receivers",
                (self.blade_receivers.len() + self.edge_receivers.len()) as f64,
            ),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn meadow() -> Scene {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../experiments/scenes/meadow.toml");
        Scene::load(&path).unwrap()
    }

    #[test]
    fn each_kind_of_grass_has_its_postures_and_tall_grass_bends_further() {
        let scene = meadow();
        let params = Params {
            kinds: 3,
            ..Params::default()
        };
        let p = Precomputed::new(&scene, &params).unwrap();
        assert_eq!(p.postures.len(), 3);
        let tips: Vec<f32> = p
            .postures
            .iter()
            .map(|k| k.tip_displacement(k.count() - 1))
            .collect();
        assert!(tips.windows(2).all(|w| w[1] > w[0]), "{tips:?}");
        // Every blade is of a kind that exists, and all kinds are planted.
        let kinds: std::collections::BTreeSet<u32> = p
            .patches
            .iter()
            .flat_map(|v| &v.blades)
            .map(|b| b.kind)
            .collect();
        assert_eq!(kinds.into_iter().collect::<Vec<_>>(), vec![0, 1, 2]);
    }

    #[test]
    fn precomputation_is_deterministic() {
        let scene = meadow();
        let params = Params::default();
        let a = Precomputed::new(&scene, &params).unwrap();
        let b = Precomputed::new(&scene, &params).unwrap();
        assert_eq!(a.patches, b.patches);
        assert_eq!(a.strip_layers, b.strip_layers);
        assert_eq!(a.flat_layers, b.flat_layers);
    }
}

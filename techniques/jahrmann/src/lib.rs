//! # `jahrmann`: GPU-driven Bezier blades, with Ghost of Tsushima's levels of detail
//!
//! Jahrmann and Wimmer 2017, *Responsive Real-Time Grass Rendering for General 3D Scenes* (I3D),
//! the modern baseline: blades are simulated, culled and drawn on the GPU, the CPU does no
//! per-blade work each frame (it picks the ground tiles in view), and nothing is read back within a
//! frame. Its level of detail follows Sucker Punch's GDC 2021 talk on Ghost of Tsushima's
//! procedural grass. The paper itself was not in the corpus; each step below names the description
//! it follows:
//! - (A) `shared/ANCHORS.md`, what is publicly known of the paper and the talk;
//! - (C) the CIS 565 "Vulkan Grass Rendering" course description of the paper
//!   (`CIS5650-Fall-2024/Project5-Vulkan-Grass-Rendering`, `INSTRUCTION.md`): the four `vec4`s,
//!   `g_E`, `g_F = ¼·|g_E|·f`, `r = (I_v2 − v2)·s`, the translation `(r + g + w)·Δt`, the frustum
//!   test's three points, and the section number 5.2 for the validation;
//! - (R) a CIS 565 re-implementation's description (`rmurdock41/Project5-Vulkan-Grass-Rendering`,
//!   `README.md`): the wind's directional alignment `1 − |ŵ·(v2 − v0)/|v2 − v0||` and height ratio
//!   `(v2 − v0)·up / h`, and the length estimate `L = (2·L0 + L1) / 3`.
//!
//! ## Algorithm, step by step
//! - **Blades** ([`blades`]; (A), (C)): the scene's population from
//!   `grassbench::grass::BladeField`, the module `reference` draws, in the same order, so with
//!   culling and levels off every blade stands where the reference's stands. A blade is the paper's
//!   quadratic Bezier curve: root `v0`, guide `v1`, tip `v2` where forces act, with orientation,
//!   height, width and stiffness (the paper's four `vec4`s: `v0`+orientation, `v1`+height,
//!   `v2`+width, `up`+stiffness; here stored as arrays of `vec4` — structure of arrays, so no
//!   binding passes the adapter's storage-binding limit — with the simulated tip `v2` kept
//!   twice, read one frame and written the next; `v1` follows from `v2` each step and is kept
//!   only in the draw list). The arrays hold the blades grouped by ground tile ([`tiles`]): a permutation of the
//!   scene's, each blade keeping its scene index, which is what the hashes below take, so the same
//!   blades are bucketed, kept and widened in any order.
//! - **Dispatch by tile** ([`tiles`]; Ghost of Tsushima's work per tile in view, (A); not in the
//!   paper, which runs every blade; `dispatch_tile = 0` does that): the ground is cut into
//!   `dispatch_tile` = 8 m squares. Each frame `update` picks, on the CPU, the tiles whose box
//!   (roots' bounds grown by `2·h + 0.25` m for the curve) meets the view frustum, and in each only
//!   the blades that can still be drawn there: within a tile the far level's survivors come first,
//!   then the others, each sorted by their distance cutoff, so the blades within reach of the
//!   tile's nearest point are a prefix; a tile wholly beyond the far level's start dispatches its
//!   survivors only. The ranges (at most two a tile) go to the GPU as a small table, one after the
//!   other in invocation order (a far tile's few survivors share a workgroup with the next tile's:
//!   one workgroup per range made 941 workgroups of 64 for 28 k blades at 400 m); each invocation
//!   finds its range by a binary search of a fixed number of halvings (`SEARCH_STEPS`, ⌈log₂⌉ of
//!   the most ranges a frame holds, set by the pipeline: every invocation runs the same trips,
//!   and the cost model counts them). Every skip is one the per-blade tests would make (tested
//!   over random cameras and settings: `tiles::tests`), so the picture is the every-blade pass's:
//!   FLIP 0.00000 on the three suite scenes (`tests/tests/gpu_jahrmann.rs`).
//! - **Simulation** ([`sim`], the shader's `simulate`; forces (A), (C), alignment (R), validation
//!   (C) Sec. 5.2 with (R)'s length estimate), every frame for every blade dispatched (above) in
//!   one compute pass, `dt` from the frame inputs (the frame globals): recovery towards the rest
//!   pose by the stiffness (Hooke), gravity (environmental plus the front gravity ¼·|g|·f), wind
//!   sampled on the GPU from the scene's wind texture (`wind_at`: every wind model of the shared
//!   module is baked into it each frame, so breeze, point source, fluid and Perbet's primitives all
//!   drive these blades) times the paper's alignment term, collision with the scene's moving sphere
//!   (`globals.object`: tip and midpoint pushed out); then the paper's validation (Sec. 5.2): tip
//!   above the ground, `v1` placed from the tip's projection, the curve rescaled to keep its
//!   length. [`sim`]'s docs give every formula.
//! - **Culling** ([`cull`], the shader's `cull`; (A), (C)), in the same pass: orientation (seen
//!   edge-on, `|view · width| > 0.9`), view frustum (`v0`, the midpoint and `v2`, with a
//!   tolerance), distance (buckets by a hash of the blade: density falls by one bucket per `d_max /
//!   n` metres; beyond `thin_distance` = 40 m, not in the paper, a second hash also keeps only a
//!   share `(D / d)²` of them, widened by `(d / D)²`, so the blades per pixel and the far field's
//!   cost stay about constant however far the ground runs). Survivors are appended to a draw list
//!   with atomics, one global atomic per workgroup and level, each with the state the draw needs
//!   (root, looks, this step's `v1` and `v2`: 64 bytes, in two halves of 32 so each binding
//!   stays within the limit up to 4.2 M blades at the default 128 MiB), so the draw reads its
//!   list slot after slot; the two counts are the instance counts of the two `draw_indirect`
//!   calls: no read-back. (Appending the blade's index instead, as this crate did until
//!   2026-12-06, had the draw read each survivor by index out of arrays sized for the whole
//!   terrain: on the 400 m meadow its render pass took 3.3 ms more than at 80 m for the same
//!   fragments; with the state appended no more (-0.4 ms, medians of eight repetitions), the
//!   compute pass about 1 ms more for writing it: `results/scaling/jahrmann_growth/landed/`.)
//! - **Levels** (Ghost of Tsushima, (A)): no tessellation stage in wgpu, so the draws pull their
//!   vertices: each visible blade is an instance of a triangle strip whose vertex count is its
//!   level's, 15 near (7 segments), 7 far (3 segments), the vertex shader evaluating the curve at
//!   each vertex. Levels are chosen per square ground tile of `tile_size` = 4 m, by the distance of
//!   the tile's centre, so a tile's blades change level together as Ghost of Tsushima's tiles do.
//!   Far tiles (beyond `lod_distance` + the band) draw one blade in `far_keep` = 4, widened by
//!   `far_widen` = 4 so the survivors cover what the others covered (for blades thinner than a
//!   pixel, coverage grows with width); the others are not drawn and count as stood for
//!   (`blades_represented`). Ghost of Tsushima generates each tile's blades in compute every frame
//!   (far tiles twice the size); here blades are the scene's fixed population (to compare with the
//!   reference), so tiles only group the choice of level, and which blades survive comes from a
//!   hash of the blade's index.
//! - **Hand-overs** ((A): shapes "blended across the hand-over to hide popping"; the geomorph and
//!   the fades are this crate's; with `transitions`, the default): over the band (5 m) the near
//!   level's vertices move onto the far level's 3-segment strip (a geomorph), the blades the far
//!   level drops narrow to nothing and the survivors widen to `far_widen`, so the switch at the
//!   band's end changes nothing on screen. Likewise each blade narrows to nothing over the last
//!   `distance_fade` metres before the distance test drops it, and over the last `orientation_fade`
//!   of `|view · width|` before the orientation test does. `no_transitions` switches at once.
//!   Measured (`tests/tests/temporal.rs`, the meadow at a quarter of its blades, 320x180): along a
//!   dolly and a pan the blended hand-overs change the spurious change against the reference by 1-2
//!   % (peak x1.02 without them), short of the suite's 10 % rule: a tile switches in the 15-20 m
//!   band, a few rows of the picture, each blade's fade happens at its own distance (switches are
//!   spread over the frames anyway), and most of the spurious change is the Bezier blades' own
//!   parallax against the reference's.
//! - **Shading**: `reference`'s: two-sided `shade_leaf` with the prelude's lights, colour from root
//!   to tip with the blade's variation, ambient darkened towards the root, no shadows, the shared
//!   fog.
//!
//! ## Counts (`stats`, `levels`, `counters`)
//! The compute pass counts its verdicts in the buffer that holds the two indirect draws, so the
//! reported counts are the GPU's own, exact. The blades a frame does not dispatch are counted by
//! the CPU into the same buffer before the pass (the starting values of its counters): a tile
//! outside the frustum counts as culled by the frustum, the blades beyond their cutoff as culled by
//! distance, the non-survivors of a tile wholly beyond the far level's start as represented
//! (`represented_untested`: these no per-blade test saw, so some of them the orientation or frustum
//! test would have culled: on the 400 m meadow of `experiments/scaling.toml` 42 k of the 44 k
//! represented, where the every-blade pass counts 25 k). `simulated` = `considered` less the blades
//! not dispatched. They are copied into a small read-back ring ([`counts`]) and mapped the next
//! frame: `stats()` after frame `f` reports frame `f − 1`'s counts (`count_lag_frames` in
//! `counters()` says how old they are). `blades_drawn` = near + far; `blades_represented` = blades
//! beyond the hand-over the far level does not draw; blades culled by a test are neither (the
//! honest reading of `TechniqueStats`: culling removes blades from the picture). `levels()`:
//! `near`, and `far` (drawn and stood for). `counters()`: `considered` (every blade), `simulated`
//! (dispatched), `culled_orientation`, `culled_frustum`, `culled_distance` (each blade counted by
//! the first test that culls it), `drawn_near`, `drawn_far`, `represented_far`,
//! `represented_untested`, `in_band`, `count_lag_frames`.
//!
//! ## Cost model
//! Compute: per dispatched blade 64 bytes read, 16 written, 64 more for a survivor, two bilinear lookups of the terrain and
//! one of the wind; one global atomic per workgroup; on the CPU a pass over the tiles (`O(T)`, 2
//! 500 at 400 m) and a table of at most `2T` ranges uploaded. Blades dispatched: those within reach
//! in the tiles in view, which the thinning bounds — on the meadow at 20 blades/m²
//! (`experiments/scaling.toml`), 23 k at 80 m and 28 k at 400 m, against 97 k and 2.26 M for the
//! every-blade pass; triangles 75 k and 79 k (84 k and 239 k without the thinning). Geometry:
//! `13·B_near + 5·B_far` triangles, `15·B_near + 7·B_far` vertices, each vertex evaluating the
//! curve once (three times inside the band). Memory: `144·B` bytes (five `vec4` arrays and a
//! 64-byte draw list slot per blade) plus a few hundred bytes. On a software rasteriser the draw
//! dominates wherever many blades survive; the compute pass is timed by wall clock only (lavapipe's
//! compute timestamps are wrong: `shared/PLATFORM.md`).
//!
//! What a CPU rasteriser charges for the pulling: each vertex reads 16 words from storage buffers
//! (its slot of the draw list: root, looks and the two curve points) and each compute invocation
//! moves 69-72 as counted (four `vec4`s of the blade read, the tip and the 16 words of a
//! draw-list slot written — counted for every invocation, though only survivors write the slot —
//! the ranges' search of 8-11 halvings, the counters with their loop over the six verdicts), and
//! lavapipe moves them a lane at a time: 0.75-0.90 ns a word in the vertex stage and 0.35-0.43 in
//! compute (`grassbench calibrate` at 320x180 and 640x360, 2026-12-05), 5.0-6.0 and 2.5-3.1 ms of
//! the meadow's 320x180 frame (6.7 M and 7.3 M words), which
//! the cost model prices since its storage terms (`results/cost_model/README.md`). What the model
//! still misses is the price of the pass's other operations. lavapipe runs the whole shader for
//! every batch of 8 invocations whichever way their lanes branch: with every lane masked off
//! after a uniform's test the pass still costs 67-71 of its 89-94 ns an invocation (`perf` on
//! lavapipe's compute threads, the meadow at 320x180). Taken apart, its simulation costs 35 ns an
//! invocation, its culling tests 19 (13 of them its two integer remainders by a uniform's value,
//! a term of the model since), its range search 23, where the model prices the pieces' counted
//! operations at a fraction of that. Not for the kind of operation (a calibration chain of
//! comparisons, selections, conversions and square roots prices one as the multiply-adds do), nor
//! for the values live at once (a chain 16 `vec4`s wide prices one lower). Dependence raises the
//! price (a scalar chain whose every operation waits for the last prices one at nine to ten times
//! the side-by-side chains' rate), but measured by its longest chain in the naga IR this pass is
//! about as parallel as the calibration's side-by-side chains (3.4-3.6 operations a link against
//! their 5.1), and a cost-model term priced on that chain left its prediction where it was (a
//! probe, not landed). So what its pieces pay beyond their count is still unexplained. The model
//! prices the pass at 50-61 ns an invocation on the meadow.
//!
//! ## Known artifacts
//! - The far level's widened blades are coarser: beyond the hand-over, four times fewer blades four
//!   times wider show as larger patches of colour; inside the band, tile edges show where
//!   neighbouring tiles stand at different stages of the hand-over (everywhere between a near and a
//!   far tile without transitions).
//! - Distance culling thins the far field without compensation (the paper's): far grass is sparser
//!   and more of the ground shows through than in `reference`.
//! - The draw list's order changes from frame to frame (atomics), so blades at exactly equal depth
//!   may swap which one shows; images are otherwise the same run to run.
//! - Counts are one frame late (see above).
//! - Blades outside the view are not simulated: their state waits where it was when their tile left
//!   the view, and resumes from there when it comes back. The recovery is implicit with `stiffness
//!   · dt` = 1 at 30 fps (blade stiffness 1), so each step halves what stands between a blade and
//!   its forced pose: a returning tile's stale bend (at most the wind's bend, a few centimetres at
//!   the tip) is down to 1/8 in three frames and 1/32 in five, and the tile's box, grown by the
//!   curve margin, usually enters the frustum a little before its blades show. The sphere does not
//!   push blades out of view until they come back.
//! - The thinning's widened blades are coarser with distance (at 200 m about 25 times the far
//!   level's width, ~1 px at 480x270); FLIP against no thinning 0.0015 / 0.0035 / 0.013 on the
//!   meadow / football field / prairie fly-over (`gpu_jahrmann.rs`).
//!
//! ## Departures from the sources
//! - Up is the world's vertical for every blade, as `reference`'s blades (the paper uses the
//!   surface normal: general 3D scenes; here a height field). The ground test checks the height
//!   field under the tip (the prelude's `terrain_height`), before and after the length correction,
//!   rather than the plane through `v0`.
//! - The rest pose is the tip `reference` gives the blade's rest lean (its segment walk), not
//!   straight up, so the two techniques stand alike in calm air.
//! - Recovery is integrated implicitly (same rest state, stable for stiff blades); the model is
//!   first order (no mass), so gravity is a displacement rate whose only effect is a droop of `g /
//!   s`: the default 0.6 m/s² droops a blade of stiffness 1 by 2 cm, where 9.81 would lay the
//!   scenes' blades flat at any recovery that keeps them responsive.
//! - The wind force is scaled by the blade's height (`wind_response · h · w · θ`), so bend angles
//!   depend on stiffness as `reference`'s do; `wind_response` defaults to what gives the
//!   reference's bend for small winds (`0.12 rad per m/s`, tip displacement `≈ 0.048·h·v /
//!   stiffness`).
//! - Collisions have no memory: the sphere pushes the tip (and midpoint) out each frame and the
//!   recovery brings the blade back as soon as it has passed. (A) says only that collisions push
//!   `v2` and the midpoint out; any lasting trampling the paper adds is not reproduced.
//! - A tip pushed within half the blade's height of its root is moved out along the ground first
//!   ([`sim::keep_chord`]), so the blade folds over instead of into a hairpin, whose length the
//!   paper's estimate gets 50 % wrong.
//! - Distance buckets and the far level's survivors come from hashes of the blade's index (the
//!   paper uses the index modulo `n`, which stripes a field generated row by row).
//! - Hand-over blending for the paper's distance and orientation tests (they switch blades off at
//!   once in the paper); off with `transitions = false`.
//! - The compute pass runs only over the tiles in view and the blades within reach there
//!   (`dispatch_tile`; 0 = the paper's every blade every frame), and the distance test also thins
//!   as `(D / d)²` beyond `thin_distance` (0 = the paper's buckets alone). Both keep the far
//!   field's cost bounded as the terrain grows. Measured on `experiments/scaling.toml`'s meadow at
//!   80 m and 400 m (jahrmann alone, 4 repetitions, 480x270, 2026-12-03 at `8b91ee2`, lavapipe on
//!   the first host, a 2-core Intel Xeon that other processes kept 1.1-1.5 cores busy, so times are
//!   noisy): GPU wall ms, median of the repetitions' medians, 82.5 → 565.5 (6.9x) with both off,
//!   70.5 → 99.0 (1.40x) with both on (the least of the four: 72.3 → 523.2, 7.2x; 50.3 → 58.2,
//!   1.16x); the cost model's prediction 48.1 → 141.1 ms (2.9x) and 44.0 → 58.1 ms (1.32x), what
//!   still grows with both on being mostly the core's ground mesh (its vertex and primitive terms:
//!   the blades' triangles grow 5 %). Tiles alone took the 400 m frame from 2.26 M blades simulated
//!   to 79 k (triangles unchanged at 239 k: the far level then dominates); the thinning alone took
//!   triangles to 79 k (simulated unchanged). The CPU's pass over the tiles grows with the terrain:
//!   `update` 0.05 ms at 80 m, 0.5 ms at 400 m. On a quiet host, with both on (`results/scaling`,
//!   every technique, 2 repetitions, a 2-vCPU AMD EPYC at 2.6 GHz, revision `2dd4b96`, 2026-12-04):
//!   25.4 → 31.3 ms (1.24x by the means of the medians, 1.24 and 1.23 by repetition), the cost
//!   model's 19.6 → 21.1 ms (1.07x), `update` 0.06 → 0.67 ms.
//!
//! ## Parameters
//! See [`Params`]. Defaults and where they come from: `stiffness` 30/s (a 33 ms response at
//! stiffness 1: a frame at 30 fps), `gravity` 0.6 (a 2 cm droop), `wind_response` 1.44 (= 0.048 ×
//! 30: the reference's bend for small winds); the paper's orientation threshold 0.9; a 0.1 m
//! frustum tolerance (about a blade's width); `cull_distance` 240 m in 8 buckets (the first 30 m
//! keep every blade: at 640x360 a blade there is under a pixel wide); `dispatch_tile` 8 m (about 1
//! 300 blades a tile at 20 blades/m²; 2 500 tiles at 400 m); `thin_distance` 40 m (beyond the
//! hand-over and the first distance bucket); `lod_distance` 15 m with a 5 m band (a 0.5 m blade is
//! about 14 px tall at 15 m, where 3 segments follow its curve); `far_widen` 4 = `far_keep`:
//! measured against the reference on the comparison suite's meadow and prairie (coverage per screen
//! tile), widening 2x leaves 0.031 / 0.035 of the tiles' coverage off, 3x 0.021 / 0.024, 4x 0.015 /
//! 0.017.

#![cfg_attr(test, allow(clippy::unwrap_used, clippy::expect_used, clippy::panic))]

pub mod blades;
pub mod counts;
pub mod cull;
pub mod gpu;
mod params;
pub mod sim;
pub mod tiles;

pub use gpu::SHADER;
pub use params::{Params, VARIANTS};

use grassbench::gpu::GpuEstimate;
use grassbench::technique::{LevelBlades, Technique, TechniqueEntry, Variants};
use grassbench::{
    FrameEncoder, FrameInputs, GpuContext, GrassTechnique, InitContext, Result, Scene,
    TechniqueInfo, TechniqueStats,
};

use crate::blades::BladeArrays;
use crate::counts::{GpuCounts, Readback};
use crate::cull::{CullSettings, Verdict};
use crate::gpu::{BladeGpu, ParamsUniform};
use crate::tiles::{Selection, TileGrid};

/// The registry line for this technique.
pub const ENTRY: TechniqueEntry = grassbench::technique::entry::<Jahrmann>();

/// Triangles of a near-level blade (15 vertices in a strip).
pub const NEAR_TRIANGLES: u64 = 13;
/// Triangles of a far-level blade (7 vertices in a strip).
pub const FAR_TRIANGLES: u64 = 5;

/// How this frame's step relates to the last one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Step {
    /// The next frame: read the copy the last step wrote.
    Advance,
    /// The same frame again: read what the last step read, so it writes the same.
    Repeat,
    /// A first frame, or time went backwards: start from the rest pose.
    Reset,
}

/// The technique.
pub struct Jahrmann {
    params: Params,
    gpu: BladeGpu,
    readback: Readback,
    blades: u32,
    /// The copy of the tips this frame's step reads.
    parity: usize,
    /// Whether this frame starts from the rest pose.
    reset: bool,
    last_frame: Option<u64>,
    uniform: ParamsUniform,
    /// The blades by dispatch tile (`None`: every blade every frame).
    grid: Option<TileGrid>,
    /// This frame's dispatched ranges and skipped blades.
    selection: Selection,
    /// The counters' starting values this frame (the skipped blades' verdicts).
    start: GpuCounts,
    /// Workgroups of this frame's compute pass.
    groups: (u32, u32),
    gpu_bytes: u64,
}

impl Technique for Jahrmann {
    type Params = Params;

    const INFO: TechniqueInfo = TechniqueInfo {
        id: "jahrmann",
        name: "Jahrmann & Wimmer 2017 (GPU-driven Bezier blades, Ghost of Tsushima's levels)",
        paper: "Jahrmann, Wimmer 2017, Responsive Real-Time Grass Rendering for General 3D Scenes (I3D); levels after Sucker Punch, Procedural Grass in Ghost of Tsushima (GDC 2021)",
        gpu_state: true,
        debug_views: &[
            "level of detail (near blue, hand-over green, far red)",
            "tilt of the tip from the vertical",
        ],
    };

    const VARIANTS: Variants = VARIANTS;

    /// Takes the scene's blades and uploads them; builds the pipelines.
    fn new(ctx: &InitContext<'_>, params: Params) -> Result<Self> {
        let scene = ctx.scene;
        let blades = scene.blades.all_blades(&scene.terrain);
        if blades.len() > blades::MAX_BLADES {
            return Err(grassbench::Error::Technique {
                technique: "jahrmann".into(),
                message: format!(
                    "{} blades: at most {} (a blade's scene index is kept in an f32); lower grass.density",
                    blades.len(),
                    blades::MAX_BLADES
                ),
            });
        }
        let grid = (params.dispatch_tile > 0.0)
            .then(|| TileGrid::new(&blades, params.dispatch_tile, &CullSettings::of(&params)));
        let arrays = match &grid {
            Some(g) => BladeArrays::in_order(&blades, &g.order),
            None => BladeArrays::new(&blades),
        };
        let max_ranges = grid.as_ref().map_or(1, |g| 2 * g.tiles.len());
        let gpu = BladeGpu::new(ctx, &arrays, max_ranges)?;
        let count = arrays.len() as u64;
        let groups = gpu.groups();
        Ok(Self {
            params,
            gpu,
            readback: Readback::new(&ctx.gpu.device),
            blades: u32::try_from(count).unwrap_or(u32::MAX),
            parity: 0,
            reset: true,
            last_frame: None,
            uniform: ParamsUniform::default(),
            grid,
            selection: Selection::default(),
            start: GpuCounts::default(),
            groups,
            gpu_bytes: gpu::bytes(count) + gpu::ranges_bytes(max_ranges),
        })
    }

    fn estimate(scene: &Scene, params: &Params) -> Result<GpuEstimate> {
        // At most one blade per candidate (fewer where the density map thins them); two
        // ranges per dispatch tile holding blades, at most one tile per blade or per cell of
        // the terrain (one more each way for the grid's offset).
        let candidates = scene.blades.candidate_count(&scene.terrain);
        let ranges = if params.dispatch_tile > 0.0 {
            let cells = (scene.terrain.size() / params.dispatch_tile).ceil() + 1.0;
            2 * candidates.min((cells.x * cells.y) as u64)
        } else {
            1
        };
        Ok(GpuEstimate {
            bytes: gpu::bytes(candidates) + gpu::ranges_bytes(ranges as usize),
            largest_buffer: gpu::largest_buffer(candidates),
        })
    }

    /// Each half of the draw list (32 bytes a blade) is bound whole as one storage buffer:
    /// beyond the default 128 MiB binding (4.2 M blades) the device must allow a larger one.
    /// The scene's candidates bound its blades from above without generating them; where that
    /// bound passes the default, the blades are counted, so a scene whose blades fit (the
    /// meadow keeps about three candidates in four) is not refused for the bound.
    fn required_limits(scene: &Scene, _params: &Params) -> grassbench::wgpu::Limits {
        let defaults = grassbench::wgpu::Limits::default();
        let mut array = gpu::largest_buffer(scene.blades.candidate_count(&scene.terrain));
        if array > defaults.max_storage_buffer_binding_size {
            array = gpu::largest_buffer(scene.blades.count(&scene.terrain));
        }
        grassbench::wgpu::Limits {
            max_storage_buffer_binding_size: defaults.max_storage_buffer_binding_size.max(array),
            ..defaults
        }
    }

    fn params(&self) -> &Params {
        &self.params
    }
}

impl Jahrmann {
    /// Records only the frame's compute pass (simulation and culling) and the counts' copy,
    /// as [`GrassTechnique::encode`] records them before its draws: for timing the compute
    /// pass by wall clock (`benches/compute.rs`), lavapipe's compute timestamps being wrong.
    pub fn encode_compute(&self, encoder: &mut FrameEncoder<'_>) {
        self.gpu.encode_compute(
            encoder,
            self.parity,
            self.reset,
            self.groups,
            self.readback.target(),
        );
    }

    /// The GPU's counts of the newest frame delivered, and how many frames old they are.
    fn counts(&self) -> (GpuCounts, u64) {
        self.readback.latest().unwrap_or_default()
    }
}

impl GrassTechnique for Jahrmann {
    /// Chooses which copy of the state the step reads, and the frame's uniform: no per-blade
    /// work.
    fn update(&mut self, inputs: &FrameInputs<'_>) -> Result<()> {
        let step = match self.last_frame {
            Some(last) if inputs.frame == last => Step::Repeat,
            Some(last) if inputs.frame > last => Step::Advance,
            _ => Step::Reset,
        };
        match step {
            Step::Advance => {
                self.parity ^= 1;
                self.reset = false;
            }
            Step::Repeat => {}
            Step::Reset => {
                self.parity = 0;
                self.reset = true;
            }
        }
        self.last_frame = Some(inputs.frame);
        self.readback.begin_frame();
        self.selection = match &self.grid {
            Some(grid) => grid.select(
                inputs.camera.eye,
                &inputs.camera.frustum().planes,
                &CullSettings::of(&self.params),
            ),
            None => Selection::default(),
        };
        let tiled = self.grid.is_some();
        self.groups = if tiled {
            self.gpu.split(self.selection.groups)
        } else {
            self.gpu.groups()
        };
        self.uniform = gpu::uniform(
            &self.params,
            &inputs.scene.config.grass,
            &inputs.camera,
            self.blades,
            self.groups.0,
        );
        self.uniform.counts[3] = u32::from(tiled);
        let sel = &self.selection;
        let count = |n: u64| u32::try_from(n).unwrap_or(u32::MAX);
        let mut start = GpuCounts::default();
        start.verdicts[Verdict::Frustum as usize] = count(sel.frustum);
        start.verdicts[Verdict::Distance as usize] = count(sel.distance);
        start.verdicts[Verdict::Represented as usize] = count(sel.represented);
        start.skipped = count(sel.frustum + sel.distance + sel.represented);
        start.represented_untested = count(sel.represented);
        start.ranges = u32::try_from(sel.ranges.len()).unwrap_or(u32::MAX);
        self.start = start;
        Ok(())
    }

    fn prepare(&mut self, gpu: &GpuContext, _inputs: &FrameInputs<'_>) -> Result<()> {
        self.gpu
            .upload(gpu, &self.uniform, &self.start, &self.selection.ranges);
        Ok(())
    }

    fn encode(&self, encoder: &mut FrameEncoder<'_>) {
        self.encode_compute(encoder);
        self.gpu.encode_draw(encoder, self.params.lod);
    }

    fn stats(&self) -> TechniqueStats {
        let (c, _) = self.counts();
        let near = u64::from(c.of(Verdict::Near));
        let far = u64::from(c.of(Verdict::Far));
        TechniqueStats {
            blades_drawn: near + far,
            blades_represented: u64::from(c.of(Verdict::Represented)),
            triangles: near * NEAR_TRIANGLES + far * FAR_TRIANGLES,
            gpu_bytes: self.gpu_bytes,
        }
    }

    fn levels(&self) -> Vec<LevelBlades> {
        let (c, _) = self.counts();
        vec![
            LevelBlades {
                level: "near",
                blades: u64::from(c.of(Verdict::Near)),
            },
            LevelBlades {
                level: "far",
                blades: u64::from(c.of(Verdict::Far)) + u64::from(c.of(Verdict::Represented)),
            },
        ]
    }

    fn counters(&self) -> Vec<(&'static str, f64)> {
        let (c, lag) = self.counts();
        let n = |v: Verdict| f64::from(c.of(v));
        vec![
            ("considered", c.considered() as f64),
            ("simulated", (c.considered() - u64::from(c.skipped)) as f64),
            ("culled_orientation", n(Verdict::Orientation)),
            ("culled_frustum", n(Verdict::Frustum)),
            ("culled_distance", n(Verdict::Distance)),
            ("drawn_near", n(Verdict::Near)),
            ("drawn_far", n(Verdict::Far)),
            ("represented_far", n(Verdict::Represented)),
            ("represented_untested", f64::from(c.represented_untested)),
            ("in_band", f64::from(c.in_band)),
            ("count_lag_frames", lag as f64),
        ]
    }
}

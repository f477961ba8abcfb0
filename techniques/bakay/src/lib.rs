//! # `bakay`: animated transparent shells
//!
//! Bakay, Lalonde and Heidrich 2002, *Real-Time Animated Grass* (transcript:
//! `shared/seeds/002_b07b405ffc789326.txt`). Grass is not geometry here but a volume: `N`
//! copies of the ground mesh ("Russian-doll style transparent shells", Sec. 3, Fig. 2), each
//! pushed out along the surface normal and textured with one grass texture whose alpha holds
//! the height of the grass. A shell at height `k/N` keeps only the texels whose blade reaches
//! it, so stacking the shells builds blades out of cross-sections. Wind moves the shells'
//! vertices, not blades: every vertex slides along its wind vector by an amount that grows up
//! the blade while keeping each segment's length.
//!
//! ## Algorithm, section by section
//! - **Shells (Sec. 3, Fig. 2).** The core's ground mesh (`TerrainGpu::ground_vertices`,
//!   position + normal, about one vertex a metre) is drawn `shells` times as instances; instance
//!   `k` is shell `k`, so shells go bottom to top as the paper draws them. Shell 0 is the base
//!   mesh; the inter-shell distance is `S = H / N` with `H` the **maximum** of the scene's
//!   `grass.height` range (the tallest blades reach the top; shorter ones have lower alpha).
//!   Shells follow the heightmap because they are the ground mesh.
//! - **Alpha test (Sec. 3).** Shell `k` discards texels with alpha below `k/N` (the paper's
//!   compare value rising `255/N` per shell), so opaque shells need no sorting. The paper's
//!   shell 0 is the whole texture including bare ground (alpha ≥ 0); here the core already drew
//!   that ground, identically for every technique, so shell 0 keeps only the blades' roots
//!   (alpha > 0) and lets the shared ground show between them.
//! - **Fewer shells far away (ours; Sec. 5 names it future work; [`lod`]).** The paper draws
//!   all `N` shells everywhere; "in a multiple level of detail setup, it would be advantageous
//!   to reduce the number of shells for far off portions of the landscape, however doing so
//!   also reduces the density of the grass" (Sec. 5). Here every ground chunk in view
//!   ([`chunks`]) gets a level `L` from its nearest depth `z`: it draws every `2^L`-th shell
//!   down from the top one, `L` the coarsest level whose drawn shells stay at most
//!   `shell_lod_pixels` (default 1) apart on screen, `2^L · S · f / z ≤ pixels` (`f` the focal
//!   length in pixels), so the grass keeps its height. Against the paper's loss of density each
//!   drawn shell alpha-tests at the lowest of the `2^L` shells it stands for, the widest of
//!   their sections. A chunk whose whole stack is that many pixels tall or less,
//!   `H · f / z ≤ pixels`, draws no shell: its grass is the core's ground. On the meadow's
//!   walker at 480x270 (`H` = 0.7 m, `f` = 259 px) the levels change at nearest depths of 23,
//!   45 and 91 m, and chunks from 181 m on draw no shell; at 640x360 a third farther.
//!   `shell_lod_pixels = 0` draws every shell everywhere, as the paper (the `paper` variant
//!   sets it).
//! - **Texture (Sec. 3, Fig. 3; [`texture`]).** One seeded, tileable texture: colour in RGB,
//!   height in alpha, 0 on the ground; blades from the scene's population: a tile of
//!   `tile_size` holds `round(grass.density · tile_size²)` blades (so the tiled texture has the
//!   scene's density to half a blade a tile; none at `grass.density = 0`), with the scene's
//!   height range (skewed by `height_skew`), widths and colours, each attribute stratified over
//!   the tile's blades so every tile has the scene's distribution of them. Each blade is an
//!   elliptic section that tapers to a point with height (alpha falls from the blade's height
//!   at its centre to 0 at its rim), so upper shells cut thinner sections. A second plane holds
//!   each blade's density threshold and facing. `density_scale` (default 1) multiplies the
//!   texture's density: any other value departs from the scene's population (see Known
//!   artifacts for what the earlier 9 was for).
//! - **Mipmaps (Sec. 5; [`texture`]).** `custom` (default): representative blades, each coarse
//!   texel is one of its children (those with the most blade children become blade texels) and
//!   the blade texels take the base level's height quantiles, so every shell keeps the base
//!   level's coverage at every level, exactly to half a texel a tile; `box`: the automatic
//!   average the paper warns about; `none`: base level only. The paper only asks for custom
//!   levels "likely retaining representative blades"; until issue 19 each coarse texel was a
//!   child picked by a hash, which kept coverage in expectation only: with the scene's
//!   density a tile holds few blades, every tile repeats the same draw, and the 8 blades/m²
//!   lawn of `tests/scenes/counts.toml` seen from 25 m showed no grass at all.
//! - **Wind vectors (Sec. 3; [`wind`]).** `V_w = W − (W·N)N`, normalised. With
//!   `wind = "point_source"`, `W` points to the technique's own source, the vertex's animation
//!   step is its distance band from the source and the intensity is the periodic function
//!   delayed by the step, `I = sin(2π(t − step·delay)/period) + bias` (the core's
//!   `grassbench::wind::PointSource`, mirrored), so gusts travel as waves (Fig. 8). With
//!   `wind = "scene"` (default), `W` is the scene's wind (any `WindField`, read through the
//!   prelude's `wind_at`), and `I = |W_t| / reference_speed` from its tangential part, so bakay
//!   bends in the same wind as every other technique. `|I|` is clamped to `max_intensity` (Sec.
//!   3: beyond 1 the grass "over-bends").
//! - **Length-preserving bend (Sec. 3, Fig. 6; [`bend`]).** Segment `j` of every blade tilts by
//!   `θ_j = I·(π/2)·(j/N)^p` (`p = stiffness`: 1 is the paper's constant increment, below 1
//!   floppy, above 1 stiff), and shell `k` moves `n_k = Σ_{j<k} S cos θ_j` along the normal and
//!   `w_k = Σ_{j<k} S sin θ_j` along `V_w`. The paper prints `sin(i/N …)` in `w_i`'s sum, which
//!   stretches blades as they bend; with `j` every segment keeps the length `S` (tested).
//!   Running totals (Sec. 3: "a running total is kept") are kept per vertex in a compute pass
//!   (`cs_bend`), once per frame, instead of the paper's per-animation-step registers: it
//!   serves the point source and any scene wind alike, `O(vertices · N)` over the vertices of
//!   the chunks drawn that frame ([`chunks::Plan::bent`]). [`wind`] and
//!   [`bend`] are its CPU twins: `tests/tests/twins.rs` runs `cs_bend` over generated ground
//!   vertices against them and checks that every segment it leaves is `S` long.
//! - **Density, covering (Boulanger Sec. 3.4, Zhang Sec. 5.5.2).** A texel is drawn only where
//!   the covering map says grass and where the density map exceeds its blade's threshold, the
//!   rule the scene's blade field (and so `reference`) uses per blade.
//! - **Counts.** `blades_represented` is the number of the tiled texture's blades whose centre
//!   lies on grass-covered terrain under the density map (counted once at start-up; none is
//!   geometry, so `blades_drawn` is 0). On the 12 x 12 m lawn of `tests/scenes/counts.toml`:
//!   2 880 against the scene's 2 875 blades; on the meadow 433 827 against the reference's
//!   433 720. With no blade in the texture (`grass.density = 0`) no shell is drawn.
//! - **Shading.** The prelude's `shade_leaf` with the normal of a flat blade (its facing from
//!   the texture, its direction bent by the wind), colour from root to tip along the blade with
//!   the scene's colours, ambient darkened towards the root, the shared fog: as `reference`.
//!
//! ## Cost model
//! Geometry: `N` x the ground mesh in view (meadow: 12 800 triangles a shell for the whole
//! mesh; the shells are drawn only over the 16 x 16-cell chunks whose box meets the view
//! frustum, [`chunks`]), fewer with distance ([`lod`]): a chunk's shells halve each time its
//! depth doubles past the first level's, and end where the stack is a pixel tall, so the
//! shells in view are bounded by that distance, not by the terrain. Vertex work `O(V·N)` in the
//! bend pass and the shells, both over the chunks drawn (the bend pass ran over every vertex
//! of the terrain until it too took the plan's chunks: 6.6 k → 66 k invocations a frame from
//! an 80 m terrain to a 400 m one on the meadow's walker at 480x270, now 5.8 k on the default
//! meadow, 4.2 k on the pitch and 53 k on the flyover, each shared chunk edge moved twice,
//! the pictures byte for byte the same). Where nearly every chunk of a small terrain is drawn
//! the chunked pass does more than one over the whole mesh would: a chunk's 17² vertices run as
//! five 64-wide workgroups (320 invocations) and its edges are shared, so the paper's point on
//! the pitch, which draws 31 chunks, runs 9 920 invocations for the terrain's 7 360 vertices
//! (0.13 ms a frame of its 128.5 ms model, `results/papers/`). Fill: every
//! shell covers the terrain's screen area, so fragment work is `N x covered pixels` near the
//! camera (two texture samples each), whatever the number of blades: the method is fill-rate
//! bound (Sec. 4), and blade density is free. GPU memory: the texture (`6 bytes · size² · 4/3`
//! with mips: 2 MiB at 512²) plus `16·V + 8·V·N` bytes of per-vertex wind and offsets.
//!
//! The shell count `N` reaches the shader as a pipeline-overridable constant (`SHELLS`), not
//! in the uniform: the bend pass loops over the shells, and lavapipe re-specialises a shader
//! whose loop a uniform bounds every time its pipeline is bound, unrolling the loop on the
//! CPU outside every timestamped pass ([`grassbench::shaders::uniform_bound_loops`]). On the
//! football field at 320x180 (12 frames after 3, lavapipe, quiet host) a frame took 11.2-13.6
//! ms with the count in the uniform and 5.9-6.2 ms with it a constant; the frame's time
//! outside its passes' timestamps fell from 5.0-5.6 ms to 0.6-1.5. Dispatching the bend pass
//! five times in one pass added 0.33 ms for each extra dispatch (the work itself), and 32
//! shells, a loop the driver leaves rolled, cost 0.5-1.7 ms outside the passes: the 5 ms were
//! the driver's, which no GPU pays.
//!
//! The way a lookup picks its mip level (`lod`) picks the fragment entry point when the
//! pipeline is made (`fs_shell_minor_axis`, `fs_shell_hardware`), for the same reason: one
//! entry point branching on the mode in the uniform made every fragment on lavapipe take both
//! kinds of lookup, 4 filtered samples where 2 are kept, since a SIMD rasteriser runs both
//! sides of a branch even when every invocation agrees. The same pictures, byte for byte, and
//! on the meadow at 320x180 (8 frames after 8, alternating builds, 2026-12-05) frames of
//! 47.8-48.7 ms against 51.4-52.2 (46.8-47.6 against 53.7-56.6 in a first pair of runs of
//! three); the flyover's frames moved between 61 and 96 ms with either build. The cost model
//! had priced the four samples, 13 ms of a 55 ms meadow frame for the two no pixel keeps.
//! Each lookup filters one mip level at the default custom levels, whose sampler's mipmap
//! filter is `Nearest` (blending two representative levels would average two different
//! blades): the module says so when it is made (`shaders::module_with_bindings`), so the cost
//! model prices no second level for them. Priced as trilinear samples, as every sample was
//! until `7c6575e`, they had bakay over-predicted on every run (0.68-0.95 of the model on the
//! 2.6 GHz EPYC; 0.85-1.26 since: `results/cost_model/`).
//! With 4x MSAA the model under-predicts it instead (in one process at 320x180, 1.14-1.68
//! against 0.91-1.06 single-sampled: `results/cost_model/coverage/sweep/`): nearly all of its
//! counted fragments are discarded or hidden (0.1-0.7 % of them kept), and such an alpha-tested
//! fragment costs what a shaded one does with MSAA (0.92-1.17 of its price in the calibration's
//! coverage checks) but a third to a half of it single-sampled (0.32-0.61), which the model,
//! pricing every counted fragment as shaded, does not tell apart.
//!
//! The level of detail on the scaling sweep's points (the meadow at 20 blades/m², terrain 80
//! and 400 m a side, 480x270, 5 frames after 2, lavapipe on the 2-core Intel Xeon on 2026-12-03
//! while another build ran; per-frame counts, the same in every run and, with the level of
//! detail, in `results/scaling/` on all three hosts): triangles 147 k → 696 k with every shell,
//! 111 k → 146 k with the level of detail; clipped primitives 110 k → 605 k against 73 k
//! → 100 k; fragment invocations 3.46 M → 4.07 M against 3.24 M → 2.86 M; vertex invocations
//! 89 k → 1 416 k against 66 k → 298 k (lavapipe shades about 2 vertices a triangle on the
//! 400 m terrain's mesh and 0.6 on the 80 m one, with or without the level of detail: its
//! vertex cache, keyed by `index % 256`, missed on that 257-wide mesh, 241 wide since `ee6c9e6`
//! (`grassbench::terrain::MAX_GROUND_SIDE`); 29 draws at 400 m against 10). GPU wall time, seven
//! interleaved repetitions with other processes taking 0.9-1.4 of the 2 cores (so every time is
//! several times the 101 and 209 ms with every shell of that host's quiet scaling sweep at
//! `493d788`): medians 466 → 1 277 ms (2.7x) with every shell, 437 → 555 ms (1.27x; 0.95-1.70x
//! within a repetition, median 1.11x) with the level of detail, whose 400 m runs took 0.43x the
//! time of every shell's. By the timestamps (medians over the frames) the technique's render
//! pass (the shells) goes 360 → 421 ms (1.17x) with the level of detail and 467 → 1 117 ms
//! without, while the core's background pass, the same for every technique, grows 25 → 64 ms
//! (its ground mesh was then drawn whole; the core now draws it in chunks culled to the view,
//! coarser far away). In `results/scaling/` (revision `2dd4b96`, a 2-vCPU AMD EPYC virtual
//! machine at 2.6 GHz, no other process busy in bakay's runs at these sizes) that pass goes
//! 4.7 → 5.8 ms there (5.5 and 6.1 ms at 400 m by repetition) and bakay's frame 71.4 → 84.0 ms,
//! 1.18x (1.17-1.19x by repetition); in its previous versions, on the 2.0 GHz EPYC at
//! `487fc0a`, 11.0 → 17.6 ms and 201.6 → 250.2 ms, 1.24x (1.04-1.47x by repetition), and on the
//! Xeon at `00e5090`, 4.2 → 4.8 ms and 78.1 → 88.6 ms, 1.13x. The picture: mean FLIP
//! 0.0001-0.0003 between the two (frames 2 and 6, 80 and 400 m), against 0.0153 between every
//! shell and no shell at 400 m; on the default meadow (90 blades/m², 640x360, frames 2 and 6)
//! 0.0008-0.0009, against 0.0526, with 147 k → 123 k triangles.
//!
//! Measured (lavapipe, `results/bakay_table2/`, revision `2dd4b96`, a 2-vCPU AMD EPYC at 2.6
//! GHz, at the `paper` variant: every shell everywhere, box mipmaps, the point source; the
//! reference in the same group): (736.9 − 21.7) / 64 = 11.2 ms per added shell at 640x480 and
//! 23.4 ms at 1024x768, 2.10x for 2.56x the pixels (the paper: 2.2 and 4.6 ms on a GeForce3,
//! 2.1x); the cells of Table 2 5.1-5.4x the paper's time from 9 to 65 shells and 6.4 and 5.9x
//! at 1 shell, where the rest of the frame weighs more: time grows with shells x pixels as in
//! the paper, at a software rasteriser's scale; faster than `reference` up to 33 shells at
//! 640x480 (0.79x its time) and 17 at 1024x768 (0.88x), slower at 65 shells by 1.51x and
//! 3.08x, because a software rasteriser has no cheap fill rate. On the 2.0 GHz EPYC at
//! `e1e5cb1`: 14.7-17.9x the paper's time, 32.6 and 73.7 ms a shell (2.26x), faster than
//! `reference` up to the same 33 and 17 shells; on the Xeon at `cfbfa08`: 6.0-6.6x, 13.2 and
//! 27.7 ms a shell (2.1x), faster than `reference` up to 17 shells at 640x480 and 9 at
//! 1024x768. Against the reference's vertex shader of `59a14de` and `68eb6f4` (its frames
//! about half as long), at `ab46b38` on a 2-vCPU Intel Xeon with AVX-512: 4.5-4.9x the paper's
//! time from 9 shells on, 9.8 and 20.7 ms a shell (2.11x), faster than `reference` up to 17
//! shells at 640x480 (0.71x) and 9 at 1024x768 (0.73x), 2.50x and 4.59x its time at 65. (On 2026-12-01, before issue 19, at our defaults then and with the texture
//! 9 times the scene's density, the same table read 8.0 and 17.3 ms a shell on average from 1
//! to 65 shells.)
//! 3.0 MB of GPU memory on the meadow (unchanged: the texture's size does not depend on its
//! blades).
//!
//! ## Known artifacts
//! - Shells seen edge-on at grazing angles (the walker's horizon) show as separate layers with
//!   gaps between them, and blades lose their silhouette there (Sec. 5 proposes vertical
//!   slices for such views); more shells close the gaps at proportional cost.
//! - Blades are quantised to `S`: a blade ends at the last shell below its tip. Far away
//!   (level `L`) a drawn shell shows every blade reaching the lowest shell it stands for, so a
//!   blade can stand up to `(2^L − 1)·S` taller than it is, by construction at most
//!   `shell_lod_pixels` on screen; where neighbouring chunks sit at different levels their
//!   shells differ by as much, and beyond the last level the sparse grass the shells showed
//!   there (tips a pixel tall) is gone.
//! - The texture repeats every `tile_size` metres; the wind moves whole shells, so neighbouring
//!   blades of one vertex neighbourhood sway together.
//! - At a distance blades alias with `mipmaps = "none"`, turn into short felt with `box`;
//!   `custom` keeps every shell's coverage but blade shapes become single texels. The sampler's
//!   own mip choice (`lod = "hardware"`) follows the footprint's major axis, many levels too
//!   coarse at grazing angles, and smears custom levels into blotches; the default
//!   `lod = "minor_axis"` picks the level anisotropic filtering would, with one tap.
//! - **Grazing views show the scene's population sparsely.** A shell shows a blade only where
//!   it cuts it, so seen edge-on a blade is a dotted column of sections, not a silhouette.
//!   On the meadow's walker view (frame 3, 640x360, lavapipe) 16 shells at the scene's
//!   density cover 0.068 of the frame against `reference`'s 0.463; 64 shells 0.195. Seen from
//!   above it is sparser too: on the meadow at half its density from 8 m up, looking 70° down
//!   (frame 30, 320x180), 0.035 against 0.108 (the texture's blades stand straight while the
//!   reference's lean, and a coarse texel shows one blade of the several it covers). Until
//!   issue 19 the texture held 9 times the scene's blades (`density_scale = 9`, measured to
//!   match the reference's coverage on the walker view: 0.454 there now; 0.250 at 4 times):
//!   the paper's own remedy ("making the grass more dense on textures", Sec. 5), kept as an
//!   override, but a different population from the scene's, and it made the counts 9 times
//!   the scene's blades.
//! - **Sparse tiles at a distance.** A tile holds few blades at the scene's density (14 at
//!   3.5 blades/m² on 2 m tiles), and a custom level keeps a tile's coverage only to half a
//!   texel: where a tile's grass covers less than half a texel of a coarse level (the prairie
//!   flyover's far field) that level shows none of it, while the reference's sub-pixel blades
//!   still hit pixels here and there.

#![cfg_attr(test, allow(clippy::unwrap_used, clippy::expect_used, clippy::panic))]

pub mod bend;
pub mod chunks;
mod gpu;
pub mod lod;
pub mod paper;
pub mod params;
pub mod texture;
pub mod wind;

use grassbench::glam::Vec2;
use grassbench::gpu::GpuEstimate;
use grassbench::technique::{Technique, TechniqueEntry, Variant, Variants};
use grassbench::terrain::{Terrain, covering};
use grassbench::{
    FrameEncoder, FrameInputs, GpuContext, GrassTechnique, InitContext, Result, TechniqueInfo,
    TechniqueStats,
};

pub use gpu::{BEND_WORKGROUPS_PER_CHUNK, ParamsUniform, SHADER};
pub use params::{Lod, Mipmaps, Params, WindSource};

/// The registry line for this technique.
pub const ENTRY: TechniqueEntry = grassbench::technique::entry::<Bakay>();

/// The shell technique.
pub struct Bakay {
    params: Params,
    gpu: gpu::ShellGpu,
    /// The ground mesh in chunks with their bounds.
    chunks: chunks::Chunks,
    /// This frame's draws (the chunks in view, each at its level of detail) and the chunks
    /// the bend pass moves, from `update`.
    plan: chunks::Plan,
    /// Shells per chunk by distance.
    lod: lod::ShellLod,
    /// Blades the tiled texture puts on grass-covered terrain under the density map.
    blades: u64,
    /// Blades in one tile of the texture.
    texture_blades: usize,
}

impl Technique for Bakay {
    type Params = Params;

    const INFO: TechniqueInfo = TechniqueInfo {
        id: "bakay",
        name: "Bakay et al. 2002 (animated transparent shells)",
        paper: "Bakay, Lalonde, Heidrich 2002, Real-Time Animated Grass",
        gpu_state: false,
        debug_views: &[],
    };

    // The approximations are the number of shells (the volume's vertical sampling, Sec. 3),
    // their thinning with distance (`shell_lod_pixels`, ours) and the texture's mip chain
    // (Sec. 5), so the finest representation is many shells, all of them everywhere, sampling
    // the base level at every distance.
    const VARIANTS: Variants = Variants {
        finest: "shells = 64\nshell_lod_pixels = 0.0\nmipmaps = \"none\"",
        others: &[Variant {
            name: grassbench::technique::PAPER,
            params: paper::VARIANT,
        }],
    };

    /// Generates the grass texture and builds the passes.
    fn new(ctx: &InitContext<'_>, params: Params) -> Result<Self> {
        let scene = ctx.scene;
        let texture = texture::GrassTexture::new(&texture_spec(&params, scene), params.mipmaps);
        let uniform = uniform(&params, scene, ctx.scene_gpu.terrain.ground_side);
        // A shell moves at most the tallest blade's height along the normal and the wind.
        let chunks = chunks::Chunks::new(
            &scene.terrain,
            ctx.scene_gpu.terrain.ground_side,
            scene.config.grass.height[1],
        );
        let gpu = gpu::ShellGpu::new(ctx, &chunks, &uniform, &texture, &params)?;
        Ok(Self {
            blades: count_blades(&texture, params.tile_size, &scene.terrain),
            texture_blades: texture.blades.len(),
            plan: chunks::Plan {
                draws: Vec::with_capacity(chunks.len()),
                bent: Vec::with_capacity(chunks.len()),
            },
            lod: lod::ShellLod {
                shells: params.shells,
                height: scene.config.grass.height[1],
                pixels: params.shell_lod_pixels,
            },
            chunks,
            params,
            gpu,
        })
    }

    fn estimate(scene: &grassbench::Scene, params: &Params) -> Result<GpuEstimate> {
        // The ground mesh's vertices, each with a wind vector and one offset per shell, its
        // triangles re-indexed in chunks, and the first cell of each chunk the bend pass moves.
        let (nx, nz) = grassbench::terrain::TerrainGpu::ground_side_for(&scene.terrain);
        let vertices = u64::from(nx) * u64::from(nz);
        let cells = u64::from(nx.saturating_sub(1)) * u64::from(nz.saturating_sub(1));
        Ok(GpuEstimate::buffer(vertices * 16)
            .plus(GpuEstimate::buffer(cells * 6 * 4))
            .plus(GpuEstimate::buffer(
                chunks::Chunks::count_for((nx, nz)).max(1) as u64 * 8,
            ))
            .plus(GpuEstimate::buffer(
                vertices.saturating_mul(u64::from(params.shells) * 8),
            ))
            .plus(GpuEstimate::textures(texture::bytes_bound(
                params.texture_size,
                params.mipmaps != params::Mipmaps::None,
            )))
            .plus(GpuEstimate::buffer(
                std::mem::size_of::<ParamsUniform>() as u64
            )))
    }

    fn params(&self) -> &Params {
        &self.params
    }
}

impl Bakay {
    /// Whether the shells are drawn: only when the texture holds blades.
    fn drawn(&self) -> bool {
        self.texture_blades > 0
    }
}

/// The texture the scene's grass asks for.
pub fn texture_spec(params: &Params, scene: &grassbench::Scene) -> texture::TextureSpec {
    let g = &scene.config.grass;
    texture::TextureSpec {
        size: params.texture_size,
        tile_size: params.tile_size,
        density: g.density * params.density_scale,
        height: [g.height[0] / g.height[1], 1.0],
        height_skew: params.height_skew,
        width: g.width,
        aspect: params.blade_aspect,
        color_tip: g.color_tip,
        color_variation: g.color_variation,
        seed: scene.config.seed ^ 0xBA4A_7000,
    }
}

/// The shader's uniform for `params` on `scene` (`ground_side` = ground mesh vertices along x
/// and z).
pub fn uniform(
    params: &Params,
    scene: &grassbench::Scene,
    ground_side: (u32, u32),
) -> ParamsUniform {
    let g = &scene.config.grass;
    let ratio = |k: usize| g.color_root[k] / g.color_tip[k].max(1e-4);
    ParamsUniform {
        counts: [
            params.shells,
            ground_side.0 * ground_side.1,
            u32::from(params.wind == WindSource::PointSource),
            ground_side.0,
        ],
        shape: [
            g.height[1] / params.shells as f32,
            params.stiffness,
            params.max_intensity,
            params.reference_speed,
        ],
        source: [
            params.source_position[0],
            params.source_position[1],
            params.source_position[2],
            params.source_period,
        ],
        steps: [
            params.source_step_length,
            params.source_step_delay,
            params.source_bias,
            1.0 / params.tile_size,
        ],
        color_ratio: [ratio(0), ratio(1), ratio(2), params.translucency],
    }
}

/// Blades the tiled texture puts on grass-covered terrain under the density map.
fn count_blades(texture: &texture::GrassTexture, tile: f32, terrain: &Terrain) -> u64 {
    let (lo, hi) = (terrain.min_corner(), terrain.min_corner() + terrain.size());
    let (t0, t1) = ((lo / tile).floor(), (hi / tile).ceil());
    let mut n = 0u64;
    for tj in t0.y as i64..t1.y as i64 {
        for ti in t0.x as i64..t1.x as i64 {
            let origin = Vec2::new(ti as f32, tj as f32);
            for b in &texture.blades {
                let xz = (origin + b.uv) * tile;
                if terrain.contains(xz)
                    && terrain.covering_at(xz) == covering::GRASS
                    && b.threshold < terrain.density_at(xz)
                {
                    n += 1;
                }
            }
        }
    }
    n
}

impl GrassTechnique for Bakay {
    fn update(&mut self, inputs: &FrameInputs<'_>) -> Result<()> {
        // The chunks in view; wind vectors, intensities and offsets are computed on the GPU
        // from the time in the frame globals.
        self.chunks.plan_into(
            &inputs.camera,
            inputs.size.height,
            &self.lod,
            &mut self.plan,
        );
        Ok(())
    }

    fn prepare(&mut self, gpu: &GpuContext, _inputs: &FrameInputs<'_>) -> Result<()> {
        if self.drawn() {
            self.gpu.upload(gpu, &self.plan);
        }
        Ok(())
    }

    fn encode(&self, encoder: &mut FrameEncoder<'_>) {
        // A texture without blades (`grass.density = 0`) would only discard: no shells.
        if self.drawn() {
            self.gpu.encode(encoder, &self.lod, &self.plan);
        }
    }

    fn stats(&self) -> TechniqueStats {
        let lod = &self.lod;
        TechniqueStats {
            // Every blade is in the shells' texture, none is geometry.
            blades_drawn: 0,
            blades_represented: self.blades,
            triangles: if self.drawn() {
                self.plan
                    .draws
                    .iter()
                    .map(|d| {
                        u64::from(d.indices.end - d.indices.start) / 3
                            * u64::from(lod.shells_at(d.level))
                    })
                    .sum::<u64>()
            } else {
                0
            },
            gpu_bytes: self.gpu.bytes,
        }
    }
}

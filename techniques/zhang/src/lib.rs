//! # `zhang`: physically based prairie with billboards far away
//!
//! Zhang Xia, *Physically Based Animation and Fast Rendering of Large-Scale Prairie* (MSc
//! thesis, 2006). Wind comes from a Navier-Stokes (Stam "stable fluids") simulation; each
//! blade is a cubic Bezier curve over four control points moved by that wind with Verlet
//! integration and length constraints; flowers are petal quads on heavier points. The camera
//! grid and its eight neighbours draw these single plants; every other grass grid draws
//! billboards of six rectangles whose length doubles with the grid offset (Ch. 4, Sec. 5.2).
//! Grids are culled against the view frustum, single plants of the near grids too (Sec. 5.3);
//! everything is drawn far to near and blended (Sec. 5.4), and grids crossing between the two
//! representations fade (Sec. 6.1); the scene's moving object pushes blades aside (Sec. 6.2),
//! and the covering map's trees and stones are simple meshes (Sec. 5.5.2).
//!
//! ## Algorithm
//! - **Wind (Ch. 2, Sec. 3.2.2).** Whatever [`WindField`](grassbench::wind::WindField) the
//!   scene has; with `[wind] model = "fluid"` that is the core's
//!   [`FluidWind`](grassbench::wind::FluidWind): the thesis' 8³ Stam solver, one solution
//!   tiled over the grass grids with per-grid offsets (Sec. 5.1), sampled trilinearly. Each
//!   moving control point of a drawn blade reads the wind at its own position every frame
//!   (one batched `inputs.wind.velocities(points, time)` call per thread's share; the breeze
//!   computes its per-time constants once and reuses its noise cells, bit for bit equal to
//!   `velocity`); blades animated but not drawn read it once, at `P2` (see Animation).
//! - **Prairie (Sec. 3.1.2, 5.1).** `grids x grids` grass grids (16 x 16) fitted over the
//!   terrain (grid size = terrain size / grids), `n x n` blades per grid (32 x 32) on a
//!   jittered lattice with random facing, heights on the shared terrain, gaps where the
//!   covering map is not grass (ID 0, trees, stones). The density map thins blades with the
//!   shared threshold rule of `grassbench::grass` (a hashed per-blade threshold in [0, 1)
//!   below the map's value), so `zhang` keeps the same fraction of its candidates as
//!   `reference`; candidate densities differ: `(16·32)² = 262 144` candidates here against
//!   `grass.density · area` there (576 000 on the meadow; `blades_per_side = 47` matches it).
//!   Heights, widths, stiffness, lean and colour variation are drawn from the scene's
//!   `[grass]` ranges, like the reference's.
//! - **Blade (Sec. 3.1.1, Fig. 5).** Four control points `P0..P3`; `P0` is the root (inverse
//!   mass 0, Sec. 3.4). The vertex shader samples the backbone at `n` points with Eq. (5)
//!   (`t = i/(n−1)`) and extends each backbone point sideways into two segment points along
//!   the horizontal width axis; consecutive pairs form the quads of one triangle strip. A
//!   procedural blade texture with alpha (tapering outline, midrib, streaks) cuts the blade
//!   out of the quads (Fig. 5b), by alpha test (and alpha-to-coverage under MSAA).
//! - **Animation (Sec. 3.2.3-3.2.5), on the CPU in `update`.** Per moving control point,
//!   Verlet (Eq. 7): `x' = x + keep·(x − x'') + a·dt²` with
//!   `a = wind_response · height · w(x) / mass + spring · stiffness · (rest − x)`, the point
//!   reflected above the ground as the thesis' `abs(y)`; then the length constraints
//!   bottom-up (`P_i -= (P_i − P_{i−1})·(l' − l)/l'`, Sec. 3.2.4); then the rotation θ of
//!   Sec. 3.2.5 (segment points of backbone point `i` turn by `θ·i/(n−1)` around up).
//!   `prepare` uploads `P1..P3` and θ (48 bytes a blade) of the blades drawn. Blades the
//!   level of detail animates without drawing them this frame (culled grids, grids two away,
//!   anchors beyond the drawn step's) are *hidden*: kept in motion every other frame (half
//!   of them each frame) by one Verlet step of two frames' time with the wind at `P2` for
//!   all three points, and no instance data ([`animate::StepRanges::hidden`]); a blade
//!   coming into view is then within 2 % of its height of where full steps would have put
//!   it. Blades and anchors are stepped together, one equal share per core (scoped
//!   threads).
//! - **Culling (Sec. 5.3, [`culling`]).** Blades are planted grid by grid, so each grass grid
//!   is a contiguous instance range with a conservative box (widened for the billboards'
//!   anchor plants); `update` keeps the grids whose box meets the frustum. With sorting, the
//!   single plants of the near grids are culled one by one as well (bounding spheres), since
//!   they are visited one by one anyway; without, near grids are drawn whole as merged
//!   instance ranges. `culling = false` draws every grid.
//! - **Billboards (Sec. 4.1-4.2, [`billboard`], [`billboard_texture`]).** A grid `g` grids from
//!   the camera grid (`g = max(|Δx|, |Δz|)`) is cut into `n' x n'` blocks of
//!   `l' = 2·2^⌊log2 g⌋ + 1` plants per side (Eq. 8-9: 8 x 8 blocks of 5 at `g = 2, 3`, 4 x 4
//!   of 9 at `g = 4..7`, 2 x 2 of 17 beyond; the last block of a row shorter). Each block's
//!   billboard is six rectangles ("wings") joined at a vertical middle line on the block's
//!   centre plant, reaching to the middles of its four edges and two opposite corners. Every
//!   wing corner is a lattice plant ("anchor"), so a wing joins the root and top points of two
//!   plants as Sec. 4.2 says; anchors are animated like blades (only their top points are
//!   drawn), and the anchors of step `2s` are a prefix of those of `s`, so a grid animates
//!   just the prefix its step needs. Far billboards sway `1 + billboard_sway·(g − 2)` times
//!   their plants' displacement. The texture (Fig. 11) is composed at start-up from the blade
//!   and petal textures with the scene's blade sizes, one layer per step with `s/(2+√2)`
//!   blades per spacing (what a billboard standing for `s²` plants on `(2+√2)·s` spacings of
//!   wings must show); its texels carry luminance, a density threshold, colour variation or
//!   petal colour, and alpha, so wings are coloured like blades and thinned by the density
//!   map with the shared threshold rule. Gaps, trees and stones in the covering map drop the
//!   wings that touch them, splitting billboards (Sec. 5.5.2). Each wing is cut down at
//!   start-up to the texels it can show ([`wing_trim`]; see Deviations), and lit per vertex
//!   by the ambient and the sun, per pixel by the point light.
//! - **Level of detail (Sec. 5.2, [`lod`], [`frame`]).** `g ≤ 1`: single plants; otherwise
//!   billboards. Blades are animated in the grids up to two away and anchors at the step one
//!   grid closer, so a grid whose level changes at a border crossing is already in motion;
//!   the far blades are not animated at all (the bulk of part 1's CPU time). Of what is
//!   animated, only what the frame draws gets the full step; the rest is hidden (see
//!   Animation).
//! - **Far to near (Sec. 5.4, [`order`]).** `sorting = "sort"`: grids by squared grid offset
//!   (quicksort), billboards by the pre-computed orders of the nine sections of Fig. 17,
//!   the camera grid's plants quicksorted by distance, the surrounding grids' plants line by
//!   line (Table 1) with each line walked from its far end towards the eye. Blended with
//!   Eq. (10) (`C = S·S_a + D·(1 − S_a)`), depth written, alpha cut at 0.05; the sorted single
//!   plants are copied into their own instance buffers in draw order. Petals are alpha-tested
//!   and drawn first (they need no order). `sorting = "alpha_to_coverage"`: no sorting, alpha
//!   test with depth writes (and alpha to coverage under MSAA); the `sort_ms` counter gives
//!   the CPU cost of ordering to compare.
//! - **Fades (Sec. 6.1, [`fade`]).** Within `fade_radius` grid sizes of a grid border, the
//!   grids whose level differs across it are drawn both ways with complementary alphas (the
//!   other side's at `½·(1 − r1/r0)`), blended when sorting, dissolved (per-blade threshold)
//!   otherwise.
//! - **Sphere-plant interaction (Sec. 6.2, `BladeState::interact`).** The scene's moving
//!   object (`[object]`, shared with every technique) is the interaction sphere. After each
//!   frame's Verlet steps, a blade whose root lies under the sphere has its first backbone
//!   point inside it moved out to the surface along the ray from the centre, the length
//!   constraint applied, and the points above continued in that direction, tangent to the
//!   sphere. Where that would leave a point inside (a blade right under the centre) the rest
//!   of the blade points away from the centre. Pushed points lose their velocity; the spring
//!   brings the blade back after the sphere has passed. Only animated (near) blades react:
//!   billboards do not.
//! - **Flowers (Sec. 3.3-3.4).** A `flower_fraction` of blade positions also carry a flower:
//!   a petal point at `0.65 · height` (±10 %) on an invisible stalk, animated like a blade's
//!   top point with mass `flower_mass` (the wind push divided by it), drawn as a square petal
//!   perpendicular to the stalk (horizontal at rest) with one of six procedural petal
//!   textures.
//!
//! ## Deviations and interpretations
//! - The thesis' Verlet step has no restoring force and no damping: blades return only when
//!   the (random, zero-mean) fluid wind pushes them back, and a steady wind of any other
//!   model would lay them flat. We add a spring to the rest pose (`spring`, scaled by the
//!   blade's stiffness) and damping (`damping`, `keep = exp(−damping·dt)`); with both set to
//!   0 the step is exactly Eq. (7).
//! - Eq. (7) is driven by the wind *velocity* (the thesis' `SetForce(temp)` stores the
//!   interpolated velocity as the acceleration); `wind_response · height` converts m/s to
//!   m/s² so blades of all heights bend by similar angles.
//! - Sec. 3.2.5 computes `θ = acos(wind · blade)`, yet asks for the blade to end up
//!   perpendicular to the wind; we rotate by the signed angle to the nearer perpendicular and
//!   fade the rotation in for blades whose tip moved less than 10 % of their height (an
//!   upright blade's wind direction is undefined).
//! - The Bezier evaluation and the segment points are computed in the vertex shader from the
//!   control points (the thesis does it on the CPU): same geometry, 48 instead of `24·n`
//!   bytes of upload per blade. `blade::bezier` writes Eq. (5) on the CPU; nothing draws or
//!   animates with it, and only its own property test (the curve passes through `P0` and
//!   `P3`) calls it: no test compares it with the shader's `bezier`.
//! - The ground under a blade is the plane through its root; flowers attach to a blade
//!   position rather than being sprinkled independently.
//! - Sec. 4.2 raises the *velocity* of far billboards with distance; we scale their top
//!   points' displacement from rest instead (faster and wider sway: the anchors' Verlet state
//!   is shared by all steps, so their time cannot run faster per grid).
//! - Sec. 6.1's fade reaches alpha 1 at the border, so it needs the camera's direction of
//!   motion (Fig. 20) and pops when the camera stops or turns there; we spread the same ramp
//!   over both sides of the border (continuous for any motion, no state between frames).
//! - Table 1's fixed in-line arrows cannot be far to near for a camera standing beside a
//!   line; we walk each line from its far end towards the camera (tested exhaustively).
//! - Billboard textures and the single plants' colours come from the scene's grass colours,
//!   not from separate photographs.
//! - A wing is drawn as the part of its rectangle that holds the texels it can show (ends
//!   moved in to the first and last such column, top down to the highest such row;
//!   [`wing_trim`], `trim_wings = false` draws whole ones), not the whole rectangle as tall as
//!   the scene's tallest blade: the same texels where a wing is planar, a quarter less fill on
//!   the meadow's walk and half on the prairie's flight, 8 % off zhang's frame on the meadow
//!   on lavapipe (A/B, `results/zhang_lod/README.md`).
//! - Wings are shaded per vertex for the ambient and the sun (exact: over a wing only the
//!   ambient occlusion varies, affinely with the height, so the sum interpolates exactly)
//!   and for the fog (across a wing, at most 1.8 m deep for the coarsest diagonal ones,
//!   `1 − exp(−k·d)` departs from a line by at most `k²·1.8²/8`, 2·10⁻⁶ at the default
//!   `k` = 0.002/m), per pixel for the point light (a second pipeline, drawn only in frames
//!   that have one). The per-pixel `shade_leaf` made zhang's frame 17 % longer on the meadow
//!   on lavapipe (13 k wings, five screens of fill); the blades keep it.
//! - The thesis steps every animated blade every frame with the wind at each control point.
//!   Blades that are animated but not drawn this frame (about two thirds of them on the
//!   meadow: grids behind the camera, grids two away, the finer billboard step's extra
//!   anchors) take one step every other frame, of two frames' time (`ω·dt` ≤ 0.48 at the
//!   default spring, well inside Verlet's stability bound of 2), with one wind sample at
//!   `P2`: they only have to be moving plausibly when they come into view, and their tips
//!   stay within 2 % of the blade height of fully stepped ones (tested; what remains decays
//!   with the damping once they are drawn).
//!
//! ## Cost model
//! CPU per frame: animated are the blades of the (at most 5 x 5) grids up to two away, their
//! flowers, and the anchors of the far grids (289 per grid at `l' = 5`, 81 at 9, 25 at 17,
//! for `n = 32`). The drawn ones (`B_draw`: the visible near grids' blades and the anchors
//! the visible wings read) cost 3 wind samples + Verlet + 3 length constraints each (and one
//! `acos` for θ, blades only); the hidden ones (`B_hid`) half of one sample + Verlet each
//! frame. On the meadow walk (16 x 16 grids of `n = 32`): 21 320 blades and 31 117 anchors
//! animated, of which 6 256 blades and 11 183 anchors drawn, 15 064 and 19 934 hidden, so
//! about 70 k wind samples and 35 k Verlet steps a frame (part 2 took 157 k and 52 k). A
//! breeze sample (3 `sin`, 2 value noises, mostly from the cached cell) costs about as much
//! as a blade's Verlet step; both are spread over the cores, and so are the wings
//! (13 k on the meadow: one top point per anchor per grid, then 80 bytes each). Sorting: a
//! quicksort of the camera grid's `≤ n²` plants, line walks of the surrounding grids, a sort
//! of the visible grids (0.2-0.3 ms measured on the meadow). Measured `update` on the meadow
//! at 640x360 (2 shared vCPUs, lavapipe, another engineer's jobs running: load average
//! 1.5-1.9; 13 runs of 30 frames per binary, alternating): median of the runs' medians
//! 5.2 ms against 13.4 ms before hidden blades and batched breeze samples (at load 3.5-3.8:
//! 8.6 against 21.8 ms; the quiet-machine figure before was 10.0 ms,
//! `results/zhang_lod/README.md`). Upload `48·B_draw + 32·F_anim` bytes, 80 bytes per wing,
//! and with sorting 80 bytes per drawn single plant. GPU: `2(n−1)` triangles (8 at `n = 5`)
//! per visible near blade, 2 per petal and 2 per wing (at most `6·n'²` wings per far grid);
//! 3-5 draws. On a software rasteriser the wings' fill dominates: on the meadow's walk at
//! 640x360 they cover 5.4 screens whole and 4.0 cut (on the prairie's flight 1.1 and 0.6),
//! most of it in the nearest billboards (`l' = 5`). Memory: `80·B + 32·F` bytes of
//! instances, 80 per wing, 80 per sorted single plant (16 near grids' worth), 91 KB of
//! textures plus 128 KB per billboard layer (3 on the canonical scenes). Measured numbers:
//! `README.md`, `results/zhang_lod/`.
//!
//! ## Known artifacts
//! - Textures are sampled at mip level 0 (a cut-out's alpha would blur away with distance) and
//!   the billboard texture nearest (its channels are ids): far billboards alias and shimmer.
//! - Billboards are a little lighter and more uniform than the blades they replace; the step
//!   changes of Eq. 8 (5 → 9 → 17) are not faded (the thesis fades only billboards ↔ single
//!   plants) and show as faint seams along grid borders; petals in billboards are full-size
//!   specks that read as more flowers far away.
//! - Sorting is by roots and block centres: leaning blades and swaying wings can still overlap
//!   out of order; the near grids' fading billboards are drawn in the wing pass, before the
//!   blades of farther fading grids. Petals of a fading grid appear and vanish at once.
//! - Without sorting and MSAA the alpha test gives hard, aliased outlines.
//! - A swaying wing whose two tops move apart is not planar; its cut rectangle's diagonal is
//!   not the whole one's, so a nearest-texel lookup lands a texel off here and there
//!   (8.6 % of the pixels differ at the meadow's frame 30, FLIP 0.018 between the two; both
//!   are about as far from the finest image, FLIP 0.042).
//! - Hidden blades (animated, not drawn) are up to 2 % of their height off the pose full
//!   steps would give. With the default fades a grid's blades are drawn, and so stepped in
//!   full, from the start of the fade band, about a second before they are half opaque, and
//!   the difference has decayed by then; with `fade_radius = 0` the blades of a grid that
//!   switches to single plants show it for the first second (at the meadow's frame 30 the
//!   mean absolute difference from the finest image grows from 2.2 to 2.7 levels of 255;
//!   with fades it stays at 3.1) and a grid turning into view shows it either way.
//! - With the tiled fluid wind the same motion repeats every grass grid (offset per grid,
//!   Sec. 5.1); the thesis accepts this.

#![cfg_attr(test, allow(clippy::unwrap_used, clippy::expect_used, clippy::panic))]

pub mod animate;
pub mod billboard;
pub mod billboard_texture;
pub mod blade;
pub mod culling;
pub mod fade;
pub mod flower;
pub mod frame;
pub mod lod;
pub mod order;
pub mod params;
pub mod pipelines;
pub mod prairie;
pub mod props;
pub mod shader_data;
pub mod textures;
pub mod wing_trim;

use grassbench::glam::{IVec2, Vec3};
use grassbench::technique::{LodBlades, TechniqueEntry};
use grassbench::wgpu::util::DeviceExt as _;
use grassbench::{
    Error, FrameEncoder, FrameInputs, GpuContext, GrassTechnique, InitContext, Result,
    TechniqueInfo, TechniqueStats, bytemuck, wgpu,
};

pub use animate::Animation;
pub use params::Params;
pub use pipelines::{BILLBOARD_SHADER, PROPS_SHADER, SHADER};
pub use shader_data::{
    BladeDynamic, BladeStatic, FlowerInstance, ParamsUniform, PropVertex, WingInstance,
};

const INFO: TechniqueInfo = TechniqueInfo {
    id: "zhang",
    name: "Zhang 2006 (Navier-Stokes wind, Bezier blades, flowers)",
    paper: "Zhang Xia 2006, Physically Based Animation and Fast Rendering of Large-Scale Prairie",
    gpu_state: false,
    debug_views: &[],
};

/// The registry line for this technique.
pub const ENTRY: TechniqueEntry = TechniqueEntry {
    info: INFO,
    // Single plants everywhere (level of detail off, Sec. 5.2). No `no_transitions` variant:
    // `fade_radius = 0` switches without fading, but the comparison suite's popping check
    // (a 0.25 m/frame dolly) cannot see zhang's switch under the parallax of near blades and
    // sees more change with the fade band's two layers (peak 8.3 against 7.7 measured); the
    // switch itself is measured by `gpu_zhang`'s crossing test instead.
    variants: &[grassbench::technique::Variant {
        name: grassbench::technique::FINEST,
        params: "lod = false",
    }],
    default_params: || grassbench::params::to_table(&Params::default()),
    create: |ctx, overrides| Ok(Box::new(Zhang::new(ctx, overrides)?)),
    estimate: |scene, overrides| {
        use grassbench::gpu::GpuEstimate;
        let params: Params = grassbench::params::resolve(INFO.id, overrides)?;
        // At most one blade per lattice point; each carries a flower with probability
        // `flower_fraction`: the expected count plus four standard deviations (and the 64 bytes
        // an empty buffer keeps).
        let side = u64::from(params.grids) * u64::from(params.blades_per_side);
        let blades = side * side;
        let (n, f) = (blades as f64, f64::from(params.flower_fraction));
        let flowers = (n * f + 4.0 * (n * f * (1.0 - f)).sqrt()).ceil() as u64 + 2;
        let size = |n: u64, each: usize| GpuEstimate::buffer(n.saturating_mul(each as u64));
        // Billboard wings: at most six per billboard of the finest step in every grid.
        let (wings, layers) = if params.lod {
            let steps = billboard::steps(params.blades_per_side, params.grids);
            let per_side = u64::from(lod::billboards_per_side(params.blades_per_side, 5));
            let grids = u64::from(params.grids).pow(2);
            (6 * per_side * per_side * grids, steps.len() as u32)
        } else {
            (1, 0)
        };
        let sorted = if params.sorting == params::Sorting::Sort {
            sorted_capacity(&params, blades)
        } else {
            0
        };
        Ok(size(blades, std::mem::size_of::<BladeStatic>())
            .plus(size(blades, std::mem::size_of::<BladeDynamic>()))
            .plus(size(sorted.max(1), std::mem::size_of::<BladeStatic>()))
            .plus(size(sorted.max(1), std::mem::size_of::<BladeDynamic>()))
            .plus(size(flowers, std::mem::size_of::<FlowerInstance>()))
            .plus(size(wings, std::mem::size_of::<WingInstance>()))
            .plus(size(
                prop_vertices(&params, &scene.terrain),
                std::mem::size_of::<PropVertex>(),
            ))
            .plus(GpuEstimate::textures(pipelines::Pipelines::bytes(
                layers.max(1),
            ))))
    },
};

/// The technique.
pub struct Zhang {
    params: Params,
    layout: prairie::Layout,
    animation: Animation,
    pipelines: pipelines::Pipelines,
    statics: wgpu::Buffer,
    dynamics: wgpu::Buffer,
    flowers: wgpu::Buffer,
    wing_buffer: wgpu::Buffer,
    /// The trees and stones (Sec. 5.5.2) and their vertex count.
    props: wgpu::Buffer,
    prop_count: u32,
    gpu_bytes: u64,
    /// The grass grids' blade and flower ranges and bounds (Sec. 5.3).
    grids: culling::GridIndex,
    /// Every grid's billboards at every step and their anchor plants (Sec. 4.1-4.2).
    billboards: billboard::Billboards,
    /// The anchors' animation (only `P3` is drawn) and their top points at rest.
    anchors: Animation,
    anchor_rest: Vec<Vec3>,
    /// Height of the billboard texture (the tallest blade), m.
    billboard_height: f32,
    /// This frame's plan (`update` → `prepare`, `encode`).
    plan: frame::Plan,
    /// This frame's wings (`update` → `prepare`).
    wings: Vec<WingInstance>,
    /// Whether this frame has a point light (`update` → `encode`: the wings' pipeline).
    point_lit: bool,
    /// Scratch for [`frame::wings`].
    wing_scratch: frame::WingScratch,
    /// Sorting (Sec. 5.4): the pre-computed billboard orders of the nine sections, each
    /// blade's root and height, the blade at each lattice point (`grid·n² + cell`), the
    /// frame's single plants far to near and their instance data in that order.
    sorting: Option<Sorted>,
    /// CPU time of this frame's far-to-near ordering, ms (a statistic).
    sort_ms: f64,
}

/// What sorting (Sec. 5.4) keeps.
struct Sorted {
    orders: order::BlockOrders,
    statics: Vec<BladeStatic>,
    plants: Vec<[f32; 4]>,
    slots: Vec<u32>,
    order: Vec<u32>,
    scratch: Vec<u32>,
    statics_out: Vec<BladeStatic>,
    dynamics_out: Vec<BladeDynamic>,
    statics_buf: wgpu::Buffer,
    dynamics_buf: wgpu::Buffer,
}

fn buffer(
    device: &wgpu::Device,
    label: &str,
    bytes: &[u8],
    usage: wgpu::BufferUsages,
) -> wgpu::Buffer {
    // An empty buffer cannot be bound: keep 64 zero bytes (drawn with 0 instances).
    let zeros = [0u8; 64];
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: if bytes.is_empty() { &zeros } else { bytes },
        usage,
    })
}

impl Zhang {
    /// Plants the prairie, builds the animation state, textures and pipelines.
    pub fn new(ctx: &InitContext<'_>, overrides: &toml::Table) -> Result<Self> {
        let params: Params = grassbench::params::resolve(INFO.id, overrides)?;
        let sort = params.sorting == params::Sorting::Sort;
        let scene = ctx.scene;
        let grass = &scene.config.grass;
        let seed = scene.config.seed;
        let (layout, planted) = prairie::plant(&params, grass, &scene.terrain, seed);
        let animation = Animation::new(&planted, params.flower_mass);
        let statics: Vec<BladeStatic> = planted
            .iter()
            .map(|p| BladeStatic {
                root_facing: p.root.extend(p.facing).to_array(),
                shape: [p.height, p.width, p.variation, 0.0],
            })
            .collect();
        let device = &ctx.gpu.device;
        let per_frame = std::mem::size_of_val(animation.blade_out.as_slice()) as u64;
        let max = device.limits().max_buffer_size;
        if per_frame > max {
            return Err(Error::Technique {
                technique: INFO.id.into(),
                message: format!(
                    "{} blades need {per_frame} bytes of instance data but this adapter allows buffers of {max} bytes; lower zhang.blades_per_side or zhang.grids",
                    planted.len()
                ),
            });
        }
        // Billboards (Ch. 4): anchors, wings and the start-up texture of Fig. 11.
        let billboard_height = grass.height[1];
        let mut billboards = if params.lod {
            billboard::Billboards::new(&layout, &params, grass, &scene.terrain, seed)
        } else {
            billboard::Billboards::empty()
        };
        let mut anchors = Animation::new(&billboards.anchors, params.flower_mass);
        anchors.set_rotations(false);
        let anchor_rest = anchors
            .blade_out
            .iter()
            .map(|d| Vec3::from_slice(&d.p3[..3]))
            .collect();
        let look = billboard_texture::Look {
            grass,
            spacing: layout.spacing().min_element(),
            flower_fraction: params.flower_fraction,
            petal_size: params.petal_size,
        };
        let layers = billboards.steps.len().max(1) as u32;
        let mut billboard_texels =
            billboard_texture::billboard_texture(&look, &billboards.steps, seed);
        billboard_texels.resize(
            (billboard_texture::SIZE.0 * billboard_texture::SIZE.1 * layers) as usize,
            [0; 4],
        );
        let alpha_cutoff = if sort {
            params.alpha_cutoff.min(BLEND_CUTOFF)
        } else {
            params.alpha_cutoff
        };
        if params.trim_wings {
            let skyline = wing_trim::Skyline::new(
                &billboard_texels,
                billboard_texture::SIZE,
                layers,
                alpha_cutoff,
            );
            billboards.cut_wings(&skyline);
        }
        let usage = wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST;
        let statics_buf = buffer(
            device,
            "zhang blades (static)",
            bytemuck::cast_slice(&statics),
            usage,
        );
        let dynamics = buffer(
            device,
            "zhang blades (control points)",
            bytemuck::cast_slice(&animation.blade_out),
            usage,
        );
        let flowers = buffer(
            device,
            "zhang flowers",
            bytemuck::cast_slice(&animation.flower_out),
            usage,
        );
        let wing_buffer = buffer(
            device,
            "zhang billboard wings",
            bytemuck::cast_slice(&vec![WingInstance::default(); billboards.max_wings()]),
            usage,
        );
        let prop_vertices = if params.props {
            props::meshes(&scene.terrain, seed)
        } else {
            Vec::new()
        };
        let props_buf = buffer(
            device,
            "zhang trees and stones",
            bytemuck::cast_slice(&prop_vertices),
            wgpu::BufferUsages::VERTEX,
        );
        let uniform = ParamsUniform {
            color_root: Vec3::from(grass.color_root)
                .extend(grass.color_variation)
                .to_array(),
            color_tip: Vec3::from(grass.color_tip)
                .extend(params.translucency)
                .to_array(),
            shape: [
                params.backbone_points as f32,
                alpha_cutoff,
                params.petal_size,
                billboard_height,
            ],
            modes: [f32::from(u8::from(sort)), 0.0, 0.0, 0.0],
        };
        let pipelines =
            pipelines::Pipelines::new(ctx, &uniform, seed, (&billboard_texels, layers), sort);
        let sorting = sort.then(|| {
            let n = layout.per_side;
            let mut slots = vec![u32::MAX; (layout.grids * layout.grids * n * n) as usize];
            for (b, p) in planted.iter().enumerate() {
                slots[(p.grid * n * n + p.cell) as usize] = b as u32;
            }
            let capacity = sorted_capacity(&params, planted.len() as u64) as usize;
            Sorted {
                orders: order::BlockOrders::new(&billboards.per_side(n)),
                plants: planted
                    .iter()
                    .map(|p| p.root.extend(p.height).to_array())
                    .collect(),
                slots,
                order: Vec::new(),
                scratch: Vec::new(),
                statics_out: Vec::new(),
                dynamics_out: Vec::new(),
                statics_buf: buffer(
                    device,
                    "zhang blades far to near (static)",
                    bytemuck::cast_slice(&vec![BladeStatic::default(); capacity]),
                    usage,
                ),
                dynamics_buf: buffer(
                    device,
                    "zhang blades far to near (control points)",
                    bytemuck::cast_slice(&vec![BladeDynamic::default(); capacity]),
                    usage,
                ),
                statics: statics.clone(),
            }
        });
        let gpu_bytes = statics_buf.size()
            + dynamics.size()
            + flowers.size()
            + wing_buffer.size()
            + props_buf.size()
            + sorting
                .as_ref()
                .map_or(0, |s| s.statics_buf.size() + s.dynamics_buf.size())
            + pipelines.bytes;
        let mut grids = culling::GridIndex::new(&planted);
        grids.include(&billboards.anchors, billboard_height);
        let plan = frame::Plan::new(
            &layout,
            &grids,
            &billboards,
            &fade::Transition::none(IVec2::MIN),
            None,
            (false, false),
        );
        Ok(Self {
            plan,
            grids,
            layout,
            params,
            animation,
            pipelines,
            statics: statics_buf,
            dynamics,
            flowers,
            wing_buffer,
            props: props_buf,
            prop_count: prop_vertices.len() as u32,
            gpu_bytes,
            billboards,
            anchors,
            anchor_rest,
            billboard_height,
            wings: Vec::new(),
            point_lit: false,
            wing_scratch: frame::WingScratch::default(),
            sorting,
            sort_ms: 0.0,
        })
    }

    /// The animation state (for inspection).
    pub fn animation(&self) -> &Animation {
        &self.animation
    }
}

impl GrassTechnique for Zhang {
    fn info(&self) -> TechniqueInfo {
        INFO
    }

    fn params(&self) -> toml::Table {
        grassbench::params::to_table(&self.params)
    }

    fn update(&mut self, inputs: &FrameInputs<'_>) -> Result<()> {
        let p = &self.params;
        let frustum = inputs.camera.frustum();
        let frustum = p.culling.then_some(&frustum);
        let eye = inputs.camera.eye;
        let radius = if p.lod { p.fade_radius } else { 0.0 };
        let transition = fade::Transition::new(&self.layout, eye, radius);
        // Sorting time is a statistic (the `sort_ms` counter), not an input of the frame.
        let sort_start = std::time::Instant::now();
        self.plan = frame::Plan::new(
            &self.layout,
            &self.grids,
            &self.billboards,
            &transition,
            frustum,
            (p.lod, self.sorting.is_some()),
        );
        let mut sort_time = sort_start.elapsed();
        let k = (p.wind_response, p.spring, p.damping);
        let plan = &self.plan;
        self.point_lit = inputs.lights().at(inputs.time).point.is_some();
        // Sec. 6.2: the scene's moving object is the interaction sphere.
        self.animation.set_sphere(inputs.object());
        // Blades and anchors share one set of threads.
        let blades = animate::StepRanges {
            drawn: &plan.animate_blades,
            hidden: &plan.hidden_blades,
            flowers: &plan.animate_flowers,
        };
        let anchors = animate::StepRanges {
            drawn: &plan.animate_anchors,
            hidden: &plan.hidden_anchors,
            flowers: &[],
        };
        animate::step_together(
            inputs.wind,
            inputs.time,
            inputs.dt,
            k,
            &mut [(&mut self.animation, blades), (&mut self.anchors, anchors)],
        );
        frame::wings(
            plan,
            &self.billboards,
            self.sorting.as_ref().map(|s| &s.orders),
            &self.anchors.blade_out,
            &self.anchor_rest,
            (self.billboard_height, p.billboard_sway),
            &mut self.wing_scratch,
            &mut self.wings,
        );
        // Fading single plants (Sec. 6.1): `P2.w` carries how far each has faded out.
        for near in &plan.near {
            let out = &mut self.animation.blade_out;
            let r = self.grids.blades(near.k);
            for d in &mut out[r.start as usize..r.end as usize] {
                d.p2[3] = 1.0 - near.alpha;
            }
        }
        if let Some(s) = &mut self.sorting {
            let start = std::time::Instant::now();
            let look = frame::BladeLookup {
                layout: &self.layout,
                index: &self.grids,
                slots: &s.slots,
                plants: &s.plants,
            };
            frame::sorted_blades(plan, &look, eye, frustum, &mut s.scratch, &mut s.order);
            sort_time += start.elapsed();
            s.statics_out.clear();
            s.statics_out
                .extend(s.order.iter().map(|&b| s.statics[b as usize]));
            s.dynamics_out.clear();
            s.dynamics_out.extend(
                s.order
                    .iter()
                    .map(|&b| self.animation.blade_out[b as usize]),
            );
        }
        self.sort_ms = if self.sorting.is_some() {
            sort_time.as_secs_f64() * 1e3
        } else {
            0.0
        };
        Ok(())
    }

    /// Uploads what this frame animated: the blades and flowers of the grids up to two away
    /// (all of them without LOD) and the far grids' wings.
    fn prepare(&mut self, gpu: &GpuContext, _inputs: &FrameInputs<'_>) -> Result<()> {
        fn upload<T: bytemuck::Pod>(
            gpu: &GpuContext,
            buffer: &wgpu::Buffer,
            data: &[T],
            ranges: &[std::ops::Range<u32>],
        ) {
            let each = std::mem::size_of::<T>() as u64;
            for r in ranges {
                let r = (r.start as usize).min(data.len())..(r.end as usize).min(data.len());
                if !r.is_empty() {
                    let bytes = bytemuck::cast_slice(&data[r.clone()]);
                    gpu.queue.write_buffer(buffer, r.start as u64 * each, bytes);
                }
            }
        }
        let plan = &self.plan;
        upload(
            gpu,
            &self.dynamics,
            &self.animation.blade_out,
            &plan.animate_blades,
        );
        upload(
            gpu,
            &self.flowers,
            &self.animation.flower_out,
            &plan.animate_flowers,
        );
        let wings = 0..self.wings.len() as u32;
        upload(
            gpu,
            &self.wing_buffer,
            &self.wings,
            std::slice::from_ref(&wings),
        );
        if let Some(s) = &self.sorting {
            let all = 0..s.order.len() as u32;
            let all = std::slice::from_ref(&all);
            upload(gpu, &s.statics_buf, &s.statics_out, all);
            upload(gpu, &s.dynamics_buf, &s.dynamics_out, all);
        }
        Ok(())
    }

    /// Without sorting: wings, then the near grids' blade ranges, then petals (all
    /// alpha-tested). Sorting (Sec. 5.4): petals first (alpha-tested, they need no order),
    /// then the wings and the single plants far to near, blended (Eq. 10).
    fn encode(&self, encoder: &mut FrameEncoder<'_>) {
        let v = &self.plan;
        let blades = self.blade_count();
        if blades == 0 && v.flowers.is_empty() && self.wings.is_empty() && self.prop_count == 0 {
            return;
        }
        let mut pass = encoder.render_pass("plants");
        pass.set_bind_group(1, &self.pipelines.bind_group, &[]);
        // Trees and stones first: opaque, they need no order.
        if self.prop_count > 0 {
            pass.set_pipeline(&self.pipelines.props);
            pass.set_vertex_buffer(0, self.props.slice(..));
            pass.draw(0..self.prop_count, 0..1);
        }
        let flowers = |pass: &mut wgpu::RenderPass<'_>| {
            if !v.flowers.is_empty() {
                pass.set_pipeline(&self.pipelines.flowers);
                pass.set_vertex_buffer(0, self.flowers.slice(..));
                for r in &v.flowers {
                    pass.draw(0..4, r.clone());
                }
            }
        };
        if self.sorting.is_some() {
            flowers(&mut pass);
        }
        if !self.wings.is_empty() {
            pass.set_pipeline(if self.point_lit {
                &self.pipelines.wings_point_lit
            } else {
                &self.pipelines.wings
            });
            pass.set_vertex_buffer(0, self.wing_buffer.slice(..));
            pass.draw(0..4, 0..self.wings.len() as u32);
        }
        let strip = 0..2 * self.params.backbone_points;
        match &self.sorting {
            Some(s) if !s.order.is_empty() => {
                pass.set_pipeline(&self.pipelines.blades);
                pass.set_vertex_buffer(0, s.statics_buf.slice(..));
                pass.set_vertex_buffer(1, s.dynamics_buf.slice(..));
                pass.draw(strip, 0..s.order.len() as u32);
            }
            Some(_) => {}
            None => {
                if !v.blades.is_empty() {
                    pass.set_pipeline(&self.pipelines.blades);
                    pass.set_vertex_buffer(0, self.statics.slice(..));
                    pass.set_vertex_buffer(1, self.dynamics.slice(..));
                    for r in &v.blades {
                        pass.draw(strip.clone(), r.clone());
                    }
                }
                flowers(&mut pass);
            }
        }
        drop(pass);
        encoder.count_draws(self.draw_calls());
    }

    /// Grass grids drawn and culled (Sec. 5.3), single plants drawn, billboards drawn by
    /// length `l'` (Eq. 8).
    fn counters(&self) -> Vec<(&'static str, f64)> {
        let mut c = vec![
            ("grids_drawn", self.plan.grids as f64),
            ("grids_culled", self.plan.culled as f64),
            ("single_plants", self.blade_count() as f64),
        ];
        let mut by_level = vec![0u64; self.billboards.steps.len()];
        for f in &self.plan.far {
            by_level[f.level] +=
                u64::from(self.billboards.grids[f.grid as usize][f.level].billboards);
        }
        for (&step, n) in self.billboards.steps.iter().zip(by_level) {
            c.push((billboard_counter(step), n as f64));
        }
        c.push(("wings", self.wings.len() as f64));
        c.push(("fading_grids", self.plan.fading as f64));
        if self.sorting.is_some() {
            c.push(("sort_ms", self.sort_ms));
        }
        c
    }

    /// Blades represented: drawn as single plants or standing in the billboards drawn.
    fn stats(&self) -> TechniqueStats {
        let blades = self.blade_count();
        let flowers = self.plan.flower_count();
        TechniqueStats {
            blades: blades + self.plan.billboard_blades,
            triangles: blades * u64::from(2 * (self.params.backbone_points - 1))
                + 2 * flowers
                + 2 * self.wings.len() as u64
                + u64::from(self.prop_count / 3),
            draw_calls: self.draw_calls(),
            gpu_bytes: self.gpu_bytes,
        }
    }

    /// Single plants as geometry, billboards as vertical slices.
    fn lod_blades(&self) -> Option<LodBlades> {
        Some(LodBlades {
            geometry: self.blade_count(),
            vertical_slices: self.plan.billboard_blades,
            horizontal_slices: 0,
        })
    }
}

/// The counter name of billboards of step `step` (`billboards_l5` for `l' = 5`, ...).
fn billboard_counter(step: u32) -> &'static str {
    match step {
        4 => "billboards_l5",
        8 => "billboards_l9",
        16 => "billboards_l17",
        32 => "billboards_l33",
        64 => "billboards_l65",
        128 => "billboards_l129",
        256 => "billboards_l257",
        512 => "billboards_l513",
        _ => "billboards_other",
    }
}

impl Zhang {
    /// Single plants drawn (with sorting, after culling single plants, Sec. 5.3).
    fn blade_count(&self) -> u64 {
        self.sorting
            .as_ref()
            .map_or(self.plan.blade_count(), |s| s.order.len() as u64)
    }

    fn draw_calls(&self) -> u64 {
        let blades = match &self.sorting {
            Some(s) => usize::from(!s.order.is_empty()),
            None => self.plan.blades.len(),
        };
        (blades
            + self.plan.flowers.len()
            + usize::from(!self.wings.is_empty())
            + usize::from(self.prop_count > 0)) as u64
    }
}

/// Vertices of the trees and stones (Sec. 5.5.2; at least one: an empty buffer keeps 64 bytes).
fn prop_vertices(params: &Params, terrain: &grassbench::terrain::Terrain) -> u64 {
    let (trees, stones) = if params.props {
        props::count(terrain)
    } else {
        (0, 0)
    };
    ((trees * props::TREE_VERTICES + stones * props::STONE_VERTICES) as u64).max(2)
}

/// Alpha cut-off while blending (Sec. 5.4): only the clear part of the textures is discarded.
const BLEND_CUTOFF: f32 = 0.05;

/// Instances of the far-to-near blade buffers. With LOD, single plants are drawn in the grids
/// next to the camera grid or, fading near a border corner (Sec. 6.1), next to any of the
/// 2 x 2 camera grids around the corner: at most 4 x 4 grids. Without, every blade.
fn sorted_capacity(params: &Params, blades: u64) -> u64 {
    if params.lod {
        blades.min(16 * u64::from(params.blades_per_side).pow(2))
    } else {
        blades
    }
}

//! # `zhang`: physically based prairie, part 1 (near plants everywhere)
//!
//! Zhang Xia, *Physically Based Animation and Fast Rendering of Large-Scale Prairie* (MSc
//! thesis, 2006). Wind comes from a Navier-Stokes (Stam "stable fluids") simulation; each
//! blade is a cubic Bezier curve over four control points moved by that wind with Verlet
//! integration and length constraints; flowers are petal quads on heavier points. This part
//! draws every grass grid as individual blades, culled per grid against the view frustum
//! (Sec. 5.3); part 2 adds the billboards of far grids (Ch. 4), the level-of-detail choice
//! (Sec. 5.2), culling of single plants in near grids, sorting (5.4) and
//! interaction (Ch. 6).
//!
//! ## Algorithm
//! - **Wind (Ch. 2, Sec. 3.2.2).** Whatever [`WindField`](grassbench::wind::WindField) the
//!   scene has; with `[wind] model = "fluid"` that is the core's
//!   [`FluidWind`](grassbench::wind::FluidWind): the thesis' 8³ Stam solver, one solution
//!   tiled over the grass grids with per-grid offsets (Sec. 5.1), sampled trilinearly. Each
//!   control point reads `inputs.wind.velocity(p, time)` at its own position every frame.
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
//!   `prepare` uploads `P1..P3` and θ (48 bytes a blade).
//! - **Culling (Sec. 5.3, [`culling`]).** Blades are planted grid by grid, so each grass grid
//!   is a contiguous instance range with a conservative box; `update` keeps the grids whose
//!   box meets the frustum and `encode` draws their ranges, merged where they touch (26 draws
//!   and 57 % of the blades on the meadow's first view; the picture is identical). All grids
//!   are still animated, so a grid coming into view is already in motion; `culling = false`
//!   draws everything.
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
//!   bytes of upload per blade. `blade::bezier` is the CPU mirror used by the tests.
//! - The ground under a blade is the plane through its root; flowers attach to a blade
//!   position rather than being sprinkled independently.
//!
//! ## Cost model
//! CPU per frame: `B` blades x 3 moving control points (wind sample + Verlet + constraint)
//! plus one `atan2` for θ, and `F` flowers x 1 point; linear in `B`, spread over the cores. Upload
//! `48·B + 32·F` bytes. GPU: `B x 2(n−1)` triangles (8 at the default
//! `n = 5`) + `2F` for the visible grids' `B` and `F`, one draw per run of visible grids.
//! Memory: `80·B + 32·F` bytes of instances, 91 KB of
//! textures. Measured numbers: `README.md`.
//!
//! ## Known artifacts
//! - Textures are sampled at mip level 0 (a cut-out's alpha would blur away with distance):
//!   far blades alias like the reference's geometry; part 2's billboards replace them.
//! - Without MSAA the alpha test gives hard, aliased blade outlines; there is no blending, so
//!   no far-to-near sorting is needed yet (Sec. 5.4 comes with part 2's translucent
//!   billboards).
//! - With the tiled fluid wind the same motion repeats every grass grid (offset per grid,
//!   Sec. 5.1); the thesis accepts this.

#![cfg_attr(test, allow(clippy::unwrap_used, clippy::expect_used, clippy::panic))]

pub mod animate;
pub mod blade;
pub mod culling;
pub mod flower;
pub mod gpu;
pub mod params;
pub mod prairie;
pub mod textures;

use grassbench::glam::Vec3;
use grassbench::technique::TechniqueEntry;
use grassbench::wgpu::util::DeviceExt as _;
use grassbench::{
    Error, FrameEncoder, FrameInputs, GpuContext, GrassTechnique, InitContext, Result,
    TechniqueInfo, TechniqueStats, bytemuck, wgpu,
};

pub use animate::Animation;
pub use gpu::{BladeDynamic, BladeStatic, FlowerInstance, ParamsUniform};
pub use params::Params;

/// The blade and flower shader (without the prelude).
pub const SHADER: &str = include_str!("../shaders/blade.wgsl");

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
    // Part 1 draws every grid as single plants: the default is the finest representation.
    // (Part 2's billboards add a real `finest` and a `no_transitions` variant.)
    variants: &[grassbench::technique::Variant {
        name: grassbench::technique::FINEST,
        params: "",
    }],
    default_params: || grassbench::params::to_table(&Params::default()),
    create: |ctx, overrides| Ok(Box::new(Zhang::new(ctx, overrides)?)),
    estimate: |_, overrides| {
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
        Ok(size(blades, std::mem::size_of::<BladeStatic>())
            .plus(size(blades, std::mem::size_of::<gpu::BladeDynamic>()))
            .plus(size(flowers, std::mem::size_of::<gpu::FlowerInstance>()))
            .plus(GpuEstimate::textures(gpu::Pipelines::BYTES)))
    },
};

/// The technique.
pub struct Zhang {
    params: Params,
    animation: Animation,
    pipelines: gpu::Pipelines,
    statics: wgpu::Buffer,
    dynamics: wgpu::Buffer,
    flowers: wgpu::Buffer,
    gpu_bytes: u64,
    /// The grass grids' blade and flower ranges and bounds (Sec. 5.3).
    grids: culling::GridIndex,
    /// This frame's draws (`update` → `encode`).
    visible: culling::Visible,
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
        let scene = ctx.scene;
        let grass = &scene.config.grass;
        let (_, planted) = prairie::plant(&params, grass, &scene.terrain, scene.config.seed);
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
        let uniform = ParamsUniform {
            color_root: Vec3::from(grass.color_root)
                .extend(grass.color_variation)
                .to_array(),
            color_tip: Vec3::from(grass.color_tip)
                .extend(params.translucency)
                .to_array(),
            shape: [
                params.backbone_points as f32,
                params.alpha_cutoff,
                params.petal_size,
                0.0,
            ],
        };
        let pipelines = gpu::Pipelines::new(ctx, &uniform, scene.config.seed);
        let gpu_bytes = statics_buf.size() + dynamics.size() + flowers.size() + pipelines.bytes;
        let grids = culling::GridIndex::new(&planted);
        Ok(Self {
            visible: grids.all(),
            grids,
            params,
            animation,
            pipelines,
            statics: statics_buf,
            dynamics,
            flowers,
            gpu_bytes,
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
        self.animation.step(
            inputs.wind,
            inputs.time,
            inputs.dt,
            p.wind_response,
            p.spring,
            p.damping,
        );
        self.visible = if p.culling {
            self.grids.visible(&inputs.camera.frustum())
        } else {
            self.grids.all()
        };
        Ok(())
    }

    fn prepare(&mut self, gpu: &GpuContext, _inputs: &FrameInputs<'_>) -> Result<()> {
        if !self.animation.blade_out.is_empty() {
            gpu.queue.write_buffer(
                &self.dynamics,
                0,
                bytemuck::cast_slice(&self.animation.blade_out),
            );
        }
        if !self.animation.flower_out.is_empty() {
            gpu.queue.write_buffer(
                &self.flowers,
                0,
                bytemuck::cast_slice(&self.animation.flower_out),
            );
        }
        Ok(())
    }

    fn encode(&self, encoder: &mut FrameEncoder<'_>) {
        let v = &self.visible;
        if v.blades.is_empty() && v.flowers.is_empty() {
            return;
        }
        let mut pass = encoder.render_pass("plants");
        pass.set_bind_group(1, &self.pipelines.bind_group, &[]);
        if !v.blades.is_empty() {
            pass.set_pipeline(&self.pipelines.blades);
            pass.set_vertex_buffer(0, self.statics.slice(..));
            pass.set_vertex_buffer(1, self.dynamics.slice(..));
            for r in &v.blades {
                pass.draw(0..2 * self.params.backbone_points, r.clone());
            }
        }
        if !v.flowers.is_empty() {
            pass.set_pipeline(&self.pipelines.flowers);
            pass.set_vertex_buffer(0, self.flowers.slice(..));
            for r in &v.flowers {
                pass.draw(0..4, r.clone());
            }
        }
        drop(pass);
        encoder.count_draws((v.blades.len() + v.flowers.len()) as u64);
    }

    /// Grass grids drawn and culled this frame (Sec. 5.3).
    fn counters(&self) -> Vec<(&'static str, f64)> {
        vec![
            ("grids_drawn", self.visible.grids as f64),
            ("grids_culled", self.visible.culled as f64),
        ]
    }

    /// Blades and flowers of the grids drawn this frame (all of them with `culling = false`).
    fn stats(&self) -> TechniqueStats {
        let blades = self.visible.blade_count();
        let flowers = self.visible.flower_count();
        TechniqueStats {
            blades,
            triangles: blades * u64::from(2 * (self.params.backbone_points - 1)) + 2 * flowers,
            draw_calls: (self.visible.blades.len() + self.visible.flowers.len()) as u64,
            gpu_bytes: self.gpu_bytes,
        }
    }
}

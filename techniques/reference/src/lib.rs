//! # `reference`: every blade, as geometry
//!
//! The brute-force baseline of grassbench. It draws *every* blade of the scene's
//! [`BladeField`](grassbench::grass::BladeField) as its own curved strip, with no level of
//! detail, no impostors and no culling beyond the GPU's clipping. Its images are the ground
//! truth the four published techniques are compared with, and its frame time is the baseline
//! their speed-ups are measured against, so it must look right and must not be slow for
//! avoidable reasons.
//!
//! ## Algorithm
//! - **Start-up.** The blade field (stratified, jittered, seeded; density and covering maps
//!   applied as in Boulanger Sec. 3.4 and Zhang Sec. 5.5.2) is generated on the CPU once and
//!   uploaded as one instance buffer of 48 bytes a blade: root; height,
//!   width, stiffness and colour variation; the facing's unit side axis and the rest lean as
//!   vectors (their sines and cosines taken once here, not at each of the blade's vertices).
//! - **Bend pass** (compute, `cs_bend` in `shaders/blade.wgsl`), once a frame: each blade's
//!   bend `φ`, the length of the rest lean plus the wind push `wind_response · v / stiffness`
//!   read from the scene's [`WindField`](grassbench::wind::WindField) texture (with a small
//!   per-blade flutter), clamped to `max_bend`, and its direction, 16 bytes a blade. The blades
//!   are bound a chunk at a time ([`chunk_blades`], `src/bend.rs`), so the pass needs no storage binding
//!   larger than WebGPU's default however many blades there are.
//! - **Vertex shader**. One instanced triangle strip per blade with `2n + 1` vertices for `n`
//!   segments, reading its blade and its bend as instance attributes. The blade bends in the
//!   plane of the wind: its tilt from vertical at relative height `s` is `θ(s) = φ·s^p` (`p` =
//!   `bend_profile`, Bakay Sec. 3's stiffness: large `p` keeps the base upright). Vertices are
//!   placed by summing `n` segments of equal length `h/n` tilted by `θ` at their mid-points, so
//!   the blade keeps its length however far it bends (the length-preserving idea of Bakay
//!   Sec. 3 and of Zhang's length constraints, Sec. 3.2.3). The powers that depend only on a
//!   vertex's level (`s^p` at the levels and mid-points, the width's taper `(1 − s)^0.7`, the
//!   colour's `s^0.8`) come from a table in the uniform ([`levels`]), filled once. The walk
//!   runs all `n` steps for every vertex and adds those below the vertex's level (a `select`,
//!   not a loop bounded by the level). The density test is made once, when the field is
//!   generated (no harness edits a density map while it runs): the shader does not repeat it.
//! - **Shading.** Two-sided Lambert with light passing through from behind (the prelude's
//!   `shade_leaf`), ambient darkened towards the root (occlusion by neighbours), colour from
//!   root to tip with per-blade variation, the scene's fog. No alpha: blades are opaque
//!   geometry, so the image needs no sorting; MSAA is the only anti-aliasing.
//!
//! ## Cost model
//! `B` blades x `2n − 1` triangles, all submitted every frame in one draw call after one
//! dispatch of `B` bend invocations (rounded up to 64s) per chunk of at most 2.8 M blades
//! (WebGPU's default binding); a bend invocation does four texel loads of the wind and a
//! `sin`; vertex work `B·(2n + 1)·n` segment steps, each a `sin` and a `cos`, plus a `sin`
//! and a `cos` of the vertex's own tilt: `2n + 2` transcendentals a vertex, 12 at the default
//! 5 segments, which the cost model counts as `n + 1` (each cosine beside the sine of its
//! angle is priced as part of it: `src/shaders/ops.rs`); no CPU work per frame. GPU
//! memory: `64·B + 320` bytes and 16 a chunk. On a software rasteriser the cost is dominated by triangle setup, i.e. linear
//! in `B·n`; the vertex shader's transcendentals and arithmetic come next (lavapipe, at
//! revision `bf07165`: 1.5 ns a transcendental, 0.04 ns a scalar operation, 238 of them a
//! vertex, against 7-8 ns for the rest of a vertex). The segment count reaches the shader as
//! a pipeline constant (`SEGMENTS`), so no driver re-specialises the vertex shader's walk
//! when the uniform is bound ([`grassbench::shaders::uniform_bound_loops`]). Taking the per-level powers from the table and the facing
//! and lean as vectors brought them from 13 to 5 a vertex and the reference's frames down
//! 16-20 % on the three canonical scenes at both sizes (two sweeps of
//! `experiments/cost_model.toml` on the same quiet host, 20 minutes apart, revision `8a00d08`
//! and the next; the pictures moved by at most one level in 255).
//!
//! On a software rasteriser a vertex shader pays for control flow that differs between the
//! lanes of a SIMD batch (eight vertices on lavapipe's 256-bit vectors), not only for the
//! work its lanes do. The shader's density test used to return early for blades the map
//! culls: none are uploaded (the field was already thinned on the CPU), yet the branch cost
//! the reference 11-23 % of its frame, because everything after a possible `return` runs
//! masked. The walk's loop bounded by the vertex's level ran masked too; run for all `n`
//! segments and unrolled it is faster though it evaluates more `sin`s and `cos`s. With the
//! early return gone, the walk unrolled and the ambient occlusion carried in the world
//! position's spare component (one interpolated slot fewer: every triangle that touches a
//! pixel pays each slot's set-up), the reference's frames fell 24-29 % on the three
//! canonical scenes, every picture byte for byte the same (`results/reference_shader`).
//! The cost model does not see divergence: it prices the shader's operations, not its
//! masks. Moving the bend (the wind's four loads, the flutter) from each of a blade's 11
//! vertices to the bend pass, once a blade, took another 14-19 % off, the pictures again
//! byte for byte the same.
//!
//! ## Known artifacts
//! Thin far blades alias into shimmering sub-pixel lines without MSAA (that is what ground
//! truth looks like at one sample per pixel: compare techniques with MSAA on for far fields).
//! Blades do not collide with each other or with the ground when bent far.

#![cfg_attr(test, allow(clippy::unwrap_used, clippy::expect_used, clippy::panic))]

mod bend;

use bend::BendPass;
pub use bend::chunk_blades;
use grassbench::glam::Vec3;
use grassbench::gpu::GpuEstimate;
use grassbench::params::{TechniqueParams, check_ranges};
use grassbench::shaders::buffer_entry;
use grassbench::technique::{Technique, TechniqueEntry, Variants};
use grassbench::wgpu::util::DeviceExt as _;
use grassbench::{
    Error, FrameEncoder, FrameInputs, GpuContext, GrassTechnique, InitContext, Result, Scene,
    TechniqueInfo, TechniqueStats, bytemuck, shaders, wgpu,
};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The blade shader (without the prelude).
pub const SHADER: &str = include_str!("../shaders/blade.wgsl");

/// The registry line for this technique.
pub const ENTRY: TechniqueEntry = grassbench::technique::entry::<Reference>();

/// Parameters (`[techniques.reference]` in scene files, `--param` on the command line).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Params {
    /// Segments per blade (triangles = 2·segments − 1).
    #[schemars(range(min = 1, max = 15))]
    pub segments: u32,
    /// Bend per unit of wind speed for a blade of stiffness 1, radians per (m/s).
    #[schemars(range(min = 0.0, max = 2.0))]
    pub wind_response: f32,
    /// Exponent of the tilt profile along the blade: 1 = circular arc, larger = stiffer base.
    #[schemars(range(min = 0.25, max = 4.0))]
    pub bend_profile: f32,
    /// Largest bend at the tip, radians.
    #[schemars(range(min = 0.0, max = 1.57))]
    pub max_bend: f32,
    /// Fraction of back-side sunlight passing through a blade.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub translucency: f32,
    /// Per-blade flutter amplitude, relative to the wind push.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub flutter: f32,
}

impl Default for Params {
    fn default() -> Self {
        Self {
            segments: 5,
            wind_response: 0.12,
            bend_profile: 1.5,
            max_bend: 1.4,
            translucency: 0.35,
            flutter: 0.15,
        }
    }
}

impl TechniqueParams for Params {
    fn validate(&self) -> Result<()> {
        check_ranges("reference", self)
    }
}

/// One blade on the GPU (vertex buffer, instance step). Its facing and rest lean are stored as
/// vectors, not angles: the vertex shader would otherwise take their sines and cosines at each
/// of the blade's vertices.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct BladeInstance {
    /// Root xyz; w unused (the density test was made when the field was generated).
    pub root: [f32; 4],
    /// Height, width, stiffness, colour variation.
    pub shape: [f32; 4],
    /// Unit side axis (x, z: the facing's cosine and sine), rest lean (x, z).
    pub side_lean: [f32; 4],
}

impl BladeInstance {
    /// The instance of blade `b`.
    pub fn of(b: &grassbench::grass::Blade) -> Self {
        let (sin_facing, cos_facing) = b.facing.sin_cos();
        let (sin_lean, cos_lean) = b.lean.x.sin_cos();
        Self {
            root: b.root.extend(0.0).to_array(),
            shape: [b.height, b.width, b.stiffness, b.variation],
            side_lean: [
                cos_facing,
                sin_facing,
                b.lean.y * cos_lean,
                b.lean.y * sin_lean,
            ],
        }
    }
}

/// Levels of a strip the uniform's table holds: the most segments (`Params::segments`' range)
/// plus one.
pub const MAX_LEVELS: usize = 16;

/// The shader's per-level table (`Params::levels` in `blade.wgsl`): for each level `L` of a
/// strip of `segments` segments, at relative height `s = L / segments`, the powers the vertex
/// shader would otherwise take per vertex: `s^profile`, `((L + 0.5) / segments)^profile`,
/// `0.5 (1 − s)^0.7` and `s^0.8`. Levels past `segments` repeat the top one.
pub fn levels(segments: u32, profile: f32) -> [[f32; 4]; MAX_LEVELS] {
    let n = segments.max(1) as f32;
    std::array::from_fn(|l| {
        let s = (l as f32 / n).min(1.0);
        let mid = ((l as f32 + 0.5) / n).min(1.0);
        [
            s.powf(profile),
            mid.powf(profile),
            0.5 * (1.0 - s).powf(0.7),
            s.powf(0.8),
        ]
    })
}

impl BladeInstance {
    const LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<Self>() as u64,
        step_mode: wgpu::VertexStepMode::Instance,
        attributes: &wgpu::vertex_attr_array![0 => Float32x4, 1 => Float32x4, 2 => Float32x4],
    };
}

/// Mirror of the shader's `Params` uniform.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ParamsUniform {
    /// Root colour; w = colour variation.
    pub color_root: [f32; 4],
    /// Tip colour; w = translucency.
    pub color_tip: [f32; 4],
    /// Segments, wind response, bend profile, max bend.
    pub shape: [f32; 4],
    /// Flutter.
    pub motion: [f32; 4],
    /// Per-level powers ([`levels`]).
    pub levels: [[f32; 4]; MAX_LEVELS],
}

/// The reference technique.
pub struct Reference {
    params: Params,
    pipeline: grassbench::shaders::RenderPipeline,
    bind_group: wgpu::BindGroup,
    bend: BendPass,
    instances: wgpu::Buffer,
    blade_count: u32,
    gpu_bytes: u64,
}

impl Technique for Reference {
    type Params = Params;

    const INFO: TechniqueInfo = TechniqueInfo {
        id: "reference",
        name: "Reference (every blade as geometry)",
        paper: "brute force; blade model after Bakay et al. 2002 Sec. 3 and Zhang 2006 Ch. 3",
        gpu_state: false,
        debug_views: &["wind speed (blue calm → red strong)", "bend amount"],
    };

    // No levels of detail: the default is already the finest representation.
    const VARIANTS: Variants = Variants {
        finest: "",
        others: &[],
    };

    /// Generates every blade of the scene and builds the pipeline.
    fn new(ctx: &InitContext<'_>, params: Params) -> Result<Self> {
        let device = &ctx.gpu.device;
        let scene = ctx.scene;
        let blades = scene.blades.all_blades(&scene.terrain);
        let instances: Vec<BladeInstance> = blades.iter().map(BladeInstance::of).collect();
        let bytes = std::mem::size_of_val(instances.as_slice()) as u64;
        let max = device.limits().max_buffer_size;
        if bytes > max {
            return Err(Error::Technique {
                technique: Self::INFO.id.into(),
                message: format!(
                    "{} blades need {bytes} bytes of instance data but this adapter allows buffers of {max} bytes; lower grass.density",
                    blades.len()
                ),
            });
        }
        // An empty buffer cannot be bound: keep one zero blade (drawn with 0 instances).
        let contents: &[u8] = if instances.is_empty() {
            bytemuck::bytes_of(&BladeInstance {
                root: [0.0; 4],
                shape: [0.0; 4],
                side_lean: [0.0; 4],
            })
        } else {
            bytemuck::cast_slice(&instances)
        };
        let instance_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("reference blades"),
            contents,
            usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::STORAGE,
        });
        let g = &scene.config.grass;
        let uniform = ParamsUniform {
            color_root: Vec3::from(g.color_root)
                .extend(g.color_variation)
                .to_array(),
            color_tip: Vec3::from(g.color_tip)
                .extend(params.translucency)
                .to_array(),
            shape: [
                params.segments as f32,
                params.wind_response,
                params.bend_profile,
                params.max_bend,
            ],
            motion: [params.flutter, 0.0, 0.0, 0.0],
            levels: levels(params.segments, params.bend_profile),
        };
        let uniform_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("reference params"),
            contents: bytemuck::bytes_of(&uniform),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("reference (group 1)"),
            entries: &[buffer_entry(
                0,
                wgpu::ShaderStages::VERTEX_FRAGMENT,
                wgpu::BufferBindingType::Uniform,
            )],
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("reference (group 1)"),
            layout: &layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: uniform_buffer.as_entire_binding(),
            }],
        });
        let module = shaders::module(device, "reference blade", SHADER);
        let blade_count = instances.len() as u32;
        let bend = BendPass::new(ctx, &module, &uniform_buffer, &instance_buffer, blade_count);
        let pipeline_layout = ctx
            .scene_gpu
            .pipeline_layout(device, "reference", &[&layout]);
        let buffers = [Some(BladeInstance::LAYOUT), Some(bend::LAYOUT)];
        let constants = [("SEGMENTS", f64::from(params.segments))];
        let pipeline = shaders::render_pipeline(
            device,
            &shaders::PipelineSpec {
                constants: &constants,
                ..shaders::PipelineSpec::new(
                    "reference blades",
                    &pipeline_layout,
                    &module,
                    ("vs_main", "fs_main"),
                    &buffers,
                    ctx.sample_count,
                )
            },
        );
        Ok(Self {
            blade_count,
            gpu_bytes: bytes + bend.bytes() + std::mem::size_of::<ParamsUniform>() as u64,
            params,
            pipeline,
            bind_group,
            bend,
            instances: instance_buffer,
        })
    }

    fn estimate(scene: &Scene, _params: &Params) -> Result<GpuEstimate> {
        // At most one instance and one bend per candidate (fewer where the density map thins
        // them), and a chunk's uniform per chunk of the bend pass.
        let candidates = scene.blades.candidate_count(&scene.terrain);
        Ok(GpuEstimate::buffer(
            candidates.saturating_mul(std::mem::size_of::<BladeInstance>() as u64),
        )
        .plus(BendPass::estimate(candidates))
        .plus(GpuEstimate::buffer(
            std::mem::size_of::<ParamsUniform>() as u64
        )))
    }

    /// The bend pass binds the blades a chunk at a time ([`chunk_blades`]): it needs a storage
    /// binding as large as one workgroup's blades, not the field's (WebGPU's default is far
    /// more; a device that offers less than the default is served too).
    fn required_limits(_scene: &Scene, _params: &Params) -> wgpu::Limits {
        wgpu::Limits {
            max_storage_buffer_binding_size: u64::from(bend::WORKGROUP)
                * std::mem::size_of::<BladeInstance>() as u64,
            ..wgpu::Limits::default()
        }
    }

    fn params(&self) -> &Params {
        &self.params
    }
}

impl Reference {
    /// Vertices per blade strip.
    fn vertices_per_blade(&self) -> u32 {
        2 * self.params.segments + 1
    }
}

impl GrassTechnique for Reference {
    fn update(&mut self, _inputs: &FrameInputs<'_>) -> Result<()> {
        // Nothing to do on the CPU: blades are static, the wind is read on the GPU.
        Ok(())
    }

    fn prepare(&mut self, _gpu: &GpuContext, _inputs: &FrameInputs<'_>) -> Result<()> {
        Ok(())
    }

    fn encode(&self, encoder: &mut FrameEncoder<'_>) {
        if self.blade_count == 0 {
            return;
        }
        self.bend.encode(encoder);
        let mut pass = encoder.render_pass("blades");
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(1, &self.bind_group, &[]);
        pass.set_vertex_buffer(0, self.instances.slice(..));
        pass.set_vertex_buffer(1, self.bend.bends().slice(..));
        pass.draw(0..self.vertices_per_blade(), 0..self.blade_count);
    }

    fn stats(&self) -> TechniqueStats {
        TechniqueStats {
            // Every blade is geometry; none is an impostor.
            blades_drawn: u64::from(self.blade_count),
            blades_represented: 0,
            triangles: u64::from(self.blade_count) * u64::from(2 * self.params.segments - 1),
            gpu_bytes: self.gpu_bytes,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_mirror_matches_the_shader() {
        assert_eq!(
            shaders::struct_size(SHADER, "Params").unwrap() as usize,
            std::mem::size_of::<ParamsUniform>()
        );
    }
    /// Every key has a description, and `validate` accepts each end of the schema's ranges
    /// and refuses the values just past them (the schema is where the ranges are written).
    #[test]
    fn the_schema_describes_every_key_and_validate_keeps_its_ranges() {
        assert_eq!(
            grassbench::params::schema_problems::<Params>("reference", &[]),
            Vec::<String>::new()
        );
    }
}

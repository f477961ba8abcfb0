//! One description of a render pipeline for every technique: their pipelines differ only in
//! entry points, vertex buffers, primitive, depth, samples and targets. [`PipelineSpec::new`]
//! gives the common case (a triangle strip without culling, depth test `Less` with writes, the
//! harness's colour target and sample count); techniques change the fields that differ.

use super::{FragmentKind, ShaderOps};
use crate::target;

/// What differs between the technique's render pipelines.
pub struct PipelineSpec<'a> {
    /// Label.
    pub label: &'a str,
    /// Layout (group 0 first).
    pub layout: &'a wgpu::PipelineLayout,
    /// Shader module (composed with the prelude, by [`super::module`]).
    pub module: &'a super::Module,
    /// Vertex entry point.
    pub vertex: &'a str,
    /// Fragment entry point.
    pub fragment: &'a str,
    /// Vertex buffers.
    pub buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
    /// Topology and culling.
    pub primitive: wgpu::PrimitiveState,
    /// Depth test, if any.
    pub depth: Option<wgpu::DepthStencilState>,
    /// Samples and alpha to coverage.
    pub multisample: wgpu::MultisampleState,
    /// Colour targets.
    pub targets: &'a [Option<wgpu::ColorTargetState>],
    /// Values of the module's pipeline-overridable constants (WGSL `override`), by name: the
    /// counts fixed when the technique is created that its loops run to, so no driver
    /// re-specialises the shader when a uniform changes ([`super::uniform_bound_loops`]),
    /// and the op counter counts those loops' bodies once per trip (`shaders::trips`).
    pub constants: &'a [(&'a str, f64)],
}

/// What one invocation of each stage of a pipeline does beyond what the pipeline statistics
/// count: how its fragments reach the target, and the costly operations (texture fetches,
/// transcendentals: [`ShaderOps`]) of its vertex and fragment entry points (a render
/// pipeline) or of its compute entry point (a compute pipeline). Read off the pipeline and its shader, never declared by a technique; the work
/// counters ([`crate::technique::work`]) keep a pipeline's invocations apart from those of
/// pipelines that cost otherwise.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize)]
pub struct PipelineCost {
    /// How its fragments reach the target.
    pub fragments: FragmentKind,
    /// Costly operations of one vertex shader invocation.
    pub vertex_ops: ShaderOps,
    /// Costly operations of one fragment shader invocation.
    pub fragment_ops: ShaderOps,
    /// Costly operations of one compute shader invocation.
    pub compute_ops: ShaderOps,
    /// Input slots its fragment shader reads ([`super::fragment_inputs`]): set up for every
    /// triangle rasterised.
    pub fragment_inputs: u32,
}

impl PipelineCost {
    /// The cost of a pipeline whose fragments are of `fragments`' kind, with the operations
    /// of `module`'s entry points `vertex` and `fragment` under the pipeline's overridable
    /// `constants` ([`PipelineSpec::constants`]).
    pub fn of(
        fragments: FragmentKind,
        module: &super::Module,
        (vertex, fragment): (&str, &str),
        constants: &[(&str, f64)],
    ) -> Self {
        Self {
            fragments,
            vertex_ops: module.ops(vertex, constants),
            fragment_ops: module.ops(fragment, constants),
            compute_ops: ShaderOps::default(),
            fragment_inputs: module.fragment_inputs(fragment),
        }
    }

    /// The cost of a compute pipeline running `module`'s entry point `entry` under its
    /// overridable `constants`.
    pub fn compute(module: &super::Module, entry: &str, constants: &[(&str, f64)]) -> Self {
        Self {
            compute_ops: module.ops(entry, constants),
            ..Self::default()
        }
    }

    /// The fragment input slots set up for `work`'s primitives drawn with pipelines of this
    /// cost: each rasterised primitive times [`PipelineCost::fragment_inputs`].
    pub fn primitive_inputs(&self, work: &crate::technique::work::PassWork) -> u64 {
        work.clipper_primitives_out * u64::from(self.fragment_inputs)
    }

    /// The costly operations of `work` done with pipelines of this cost: each stage's
    /// invocations times what one invocation does.
    pub fn ops(&self, work: &crate::technique::work::PassWork) -> PassOps {
        PassOps {
            vertex: self.vertex_ops.times(work.vertex_invocations),
            fragment: self.fragment_ops.times(work.fragment_invocations),
            compute: self.compute_ops.times(work.compute_invocations),
        }
    }
}

/// The costly operations of some passes ([`PipelineCost::ops`]), by stage: the cost model
/// prices texture fetches alike in every stage ([`PassOps::all`]) and transcendentals by
/// stage (their costs differ by stage).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PassOps {
    /// Of the vertex shader invocations.
    pub vertex: ShaderOps,
    /// Of the fragment shader invocations.
    pub fragment: ShaderOps,
    /// Of the compute shader invocations.
    pub compute: ShaderOps,
}

impl PassOps {
    /// Every stage's together.
    pub fn all(&self) -> ShaderOps {
        self.vertex + self.fragment + self.compute
    }
}

impl std::ops::Add for PassOps {
    type Output = Self;

    fn add(self, o: Self) -> Self {
        Self {
            vertex: self.vertex + o.vertex,
            fragment: self.fragment + o.fragment,
            compute: self.compute + o.compute,
        }
    }
}

/// A compute pipeline and what its invocations cost (their costly operations), as the frame
/// encoder's compute passes take it, so the work of every dispatch is counted by
/// [`PipelineCost`] ([`crate::technique::work`]).
#[derive(Debug)]
pub struct ComputePipeline {
    raw: wgpu::ComputePipeline,
    cost: PipelineCost,
}

impl ComputePipeline {
    /// What its invocations cost.
    pub fn cost(&self) -> PipelineCost {
        self.cost
    }
}

impl std::ops::Deref for ComputePipeline {
    type Target = wgpu::ComputePipeline;

    /// The wgpu pipeline, for passes outside the frame.
    fn deref(&self) -> &wgpu::ComputePipeline {
        &self.raw
    }
}

/// A bind group layout entry for one buffer of kind `ty` at `binding`, seen by `visibility`:
/// not an array, no dynamic offset, its minimum size left to the shader's declaration (what
/// nearly every buffer of the harness's pipelines is).
pub fn buffer_entry(
    binding: u32,
    visibility: wgpu::ShaderStages,
    ty: wgpu::BufferBindingType,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// Creates the compute pipeline running `module`'s entry point `entry` with `layout` and the
/// pipeline-overridable `constants` (as [`PipelineSpec::constants`]), its cost read off the
/// shader.
pub fn compute_pipeline(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::PipelineLayout,
    module: &super::Module,
    entry: &str,
    constants: &[(&str, f64)],
) -> ComputePipeline {
    let raw = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(label),
        layout: Some(layout),
        module,
        entry_point: Some(entry),
        compilation_options: wgpu::PipelineCompilationOptions {
            constants,
            ..Default::default()
        },
        cache: None,
    });
    ComputePipeline {
        raw,
        cost: PipelineCost::compute(module, entry, constants),
    }
}

/// A render pipeline and what its invocations cost: what the frame encoder's passes take, so
/// the work of every draw is counted by [`PipelineCost`] ([`crate::technique::work`]).
#[derive(Debug)]
pub struct RenderPipeline {
    raw: wgpu::RenderPipeline,
    cost: PipelineCost,
}

impl RenderPipeline {
    /// A pipeline created elsewhere, with its cost (the core's background pipelines, whose
    /// descriptors are not [`PipelineSpec`]s).
    pub fn from_raw(raw: wgpu::RenderPipeline, cost: PipelineCost) -> Self {
        Self { raw, cost }
    }

    /// How its fragments reach the target.
    pub fn kind(&self) -> FragmentKind {
        self.cost.fragments
    }

    /// What its invocations cost.
    pub fn cost(&self) -> PipelineCost {
        self.cost
    }
}

impl std::ops::Deref for RenderPipeline {
    type Target = wgpu::RenderPipeline;

    /// The wgpu pipeline, for passes outside the frame (bakes into a technique's textures).
    fn deref(&self) -> &wgpu::RenderPipeline {
        &self.raw
    }
}

/// Creates the pipeline `spec` describes, classified by the kind of its fragments.
pub fn render_pipeline(device: &wgpu::Device, spec: &PipelineSpec<'_>) -> RenderPipeline {
    let kind = FragmentKind::of(
        spec.targets,
        &spec.multisample,
        spec.module.discards(spec.fragment),
    );
    let raw = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(spec.label),
        layout: Some(spec.layout),
        vertex: wgpu::VertexState {
            module: spec.module,
            entry_point: Some(spec.vertex),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants: spec.constants,
                ..Default::default()
            },
            buffers: spec.buffers,
        },
        primitive: spec.primitive,
        depth_stencil: spec.depth.clone(),
        multisample: spec.multisample,
        fragment: Some(wgpu::FragmentState {
            module: spec.module,
            entry_point: Some(spec.fragment),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants: spec.constants,
                ..Default::default()
            },
            targets: spec.targets,
        }),
        multiview_mask: None,
        cache: None,
    });
    RenderPipeline {
        raw,
        cost: PipelineCost::of(
            kind,
            spec.module,
            (spec.vertex, spec.fragment),
            spec.constants,
        ),
    }
}

/// A depth test with `compare` against `format`, writing depth when `write`.
pub fn depth_test(
    format: wgpu::TextureFormat,
    compare: wgpu::CompareFunction,
    write: bool,
) -> Option<wgpu::DepthStencilState> {
    Some(wgpu::DepthStencilState {
        format,
        depth_write_enabled: Some(write),
        depth_compare: Some(compare),
        stencil: Default::default(),
        bias: Default::default(),
    })
}

/// A depth test with `Less` against `format`, writing depth when `write`.
pub fn depth_less(format: wgpu::TextureFormat, write: bool) -> Option<wgpu::DepthStencilState> {
    depth_test(format, wgpu::CompareFunction::Less, write)
}

/// The harness's colour target, opaque.
pub const COLOR_TARGETS: &[Option<wgpu::ColorTargetState>] = &[Some(wgpu::ColorTargetState {
    format: target::COLOR_FORMAT,
    blend: None,
    write_mask: wgpu::ColorWrites::ALL,
})];

impl<'a> PipelineSpec<'a> {
    /// The common case for the harness's target with `sample_count` samples: a triangle strip
    /// without culling (blades are seen from both sides), depth test `Less` with writes, the
    /// opaque colour target.
    pub fn new(
        label: &'a str,
        layout: &'a wgpu::PipelineLayout,
        module: &'a super::Module,
        (vertex, fragment): (&'a str, &'a str),
        buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
        sample_count: u32,
    ) -> Self {
        Self {
            label,
            layout,
            module,
            vertex,
            fragment,
            buffers,
            primitive: wgpu::PrimitiveState {
                topology: wgpu::PrimitiveTopology::TriangleStrip,
                cull_mode: None,
                ..Default::default()
            },
            depth: depth_less(target::DEPTH_FORMAT, true),
            multisample: wgpu::MultisampleState {
                count: sample_count,
                ..Default::default()
            },
            targets: COLOR_TARGETS,
            constants: &[],
        }
    }
}

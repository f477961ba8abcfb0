//! One description of a render pipeline for every technique: their pipelines differ only in
//! entry points, vertex buffers, primitive, depth, samples and targets. [`PipelineSpec::new`]
//! gives the common case (a triangle strip without culling, depth test `Less` with writes, the
//! harness's colour target and sample count); techniques change the fields that differ.

use super::FragmentKind;
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
}

/// A render pipeline and the kind of its fragments: what the frame encoder's passes take, so
/// the fragments of every draw are counted by kind ([`crate::technique::work`]).
#[derive(Debug)]
pub struct RenderPipeline {
    raw: wgpu::RenderPipeline,
    kind: FragmentKind,
}

impl RenderPipeline {
    /// A pipeline created elsewhere, with the kind of its fragments (the core's background and
    /// calibration pipelines, whose descriptors are not [`PipelineSpec`]s).
    pub fn from_raw(raw: wgpu::RenderPipeline, kind: FragmentKind) -> Self {
        Self { raw, kind }
    }

    /// How its fragments reach the target.
    pub fn kind(&self) -> FragmentKind {
        self.kind
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
            compilation_options: Default::default(),
            buffers: spec.buffers,
        },
        primitive: spec.primitive,
        depth_stencil: spec.depth.clone(),
        multisample: spec.multisample,
        fragment: Some(wgpu::FragmentState {
            module: spec.module,
            entry_point: Some(spec.fragment),
            compilation_options: Default::default(),
            targets: spec.targets,
        }),
        multiview_mask: None,
        cache: None,
    });
    RenderPipeline { raw, kind }
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
        }
    }
}

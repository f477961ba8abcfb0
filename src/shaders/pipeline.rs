//! One description of a render pipeline for every technique: their pipelines differ only in
//! entry points, vertex buffers, primitive, depth, samples and targets. [`PipelineSpec::new`]
//! gives the common case (a triangle strip without culling, depth test `Less` with writes, the
//! harness's colour target and sample count); techniques change the fields that differ.

use crate::target;

/// What differs between the technique's render pipelines.
pub struct PipelineSpec<'a> {
    /// Label.
    pub label: &'a str,
    /// Layout (group 0 first).
    pub layout: &'a wgpu::PipelineLayout,
    /// Shader module (composed with the prelude).
    pub module: &'a wgpu::ShaderModule,
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

/// Creates the pipeline `spec` describes.
pub fn render_pipeline(device: &wgpu::Device, spec: &PipelineSpec<'_>) -> wgpu::RenderPipeline {
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
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
    })
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
        module: &'a wgpu::ShaderModule,
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

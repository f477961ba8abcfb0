//! One helper for the technique's four render pipelines (blades, slice, bake, mip chain): they
//! differ only in entry points, vertex buffers, primitive, depth, samples and targets.

use grassbench::wgpu;

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

/// A depth test with `Less` against `format`, writing depth when `write`.
pub fn depth_less(format: wgpu::TextureFormat, write: bool) -> Option<wgpu::DepthStencilState> {
    Some(wgpu::DepthStencilState {
        format,
        depth_write_enabled: Some(write),
        depth_compare: Some(wgpu::CompareFunction::Less),
        stencil: Default::default(),
        bias: Default::default(),
    })
}

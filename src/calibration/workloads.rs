//! The calibration's micro-workloads as GPU objects: built once, then recorded and timed as
//! often as the calibration needs (each a dozen times), apart from the timing loop that reads
//! them.

use std::time::Instant;

use wgpu::util::DeviceExt as _;

use super::{COPY_BYTES, LAYERS, STRIPS};
use crate::target::{COLOR_FORMAT, DEPTH_FORMAT, Size};
use crate::{GpuContext, RenderTarget, Result, shaders};

/// The pipelines, bindings and target of `shaders/calibration.wgsl`'s three workloads.
pub(super) struct Workloads<'g> {
    gpu: &'g GpuContext,
    target: RenderTarget,
    /// Blade-like strips of 9 tiny depth-tested triangles.
    tiny: wgpu::RenderPipeline,
    /// Full-screen blended triangles.
    fill: wgpu::RenderPipeline,
    /// A compute copy of one storage buffer into another.
    copy: wgpu::ComputePipeline,
    /// Group 0 (the prelude's slot, empty here).
    empty_group: wgpu::BindGroup,
    /// Group 1: the grid uniform and the copy's two buffers.
    group: wgpu::BindGroup,
}

impl<'g> Workloads<'g> {
    /// Builds the workloads for a target of `size`: [`STRIPS`] strips laid out in the target's
    /// aspect ratio, and two buffers of [`COPY_BYTES`] for the copy.
    pub(super) fn new(gpu: &'g GpuContext, size: Size) -> Result<Self> {
        let target = RenderTarget::new(gpu, size, false)?;
        let device = &gpu.device;
        gpu.scoped("building calibration workloads", || {
            let module = shaders::module(
                device,
                "calibration",
                include_str!("../shaders/calibration.wgsl"),
            );
            // Group 0 is the prelude's; the workloads bind nothing there, so an empty layout
            // stands in.
            let empty = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("empty"),
                entries: &[],
            });
            let buffer_entry = |binding, read_only| wgpu::BindGroupLayoutEntry {
                binding,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Storage { read_only },
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            };
            let layout1 = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("calibration"),
                entries: &[
                    wgpu::BindGroupLayoutEntry {
                        binding: 0,
                        visibility: wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::COMPUTE,
                        ty: wgpu::BindingType::Buffer {
                            ty: wgpu::BufferBindingType::Uniform,
                            has_dynamic_offset: false,
                            min_binding_size: None,
                        },
                        count: None,
                    },
                    buffer_entry(1, true),
                    buffer_entry(2, false),
                ],
            });
            let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("calibration"),
                bind_group_layouts: &[Some(&empty), Some(&layout1)],
                immediate_size: 0,
            });
            // Strips per row so the grid has the target's aspect ratio.
            let cols = (f64::from(STRIPS) * f64::from(size.width) / f64::from(size.height))
                .sqrt()
                .ceil() as f32;
            let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("calibration uniform"),
                contents: bytemuck::cast_slice(&[
                    1.0 / size.width as f32,
                    1.0 / size.height as f32,
                    cols,
                    (f64::from(STRIPS) / f64::from(cols)).ceil() as f32,
                ]),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let storage = |label| {
                device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(label),
                    size: COPY_BYTES,
                    usage: wgpu::BufferUsages::STORAGE,
                    mapped_at_creation: false,
                })
            };
            let (src, dst) = (storage("calibration src"), storage("calibration dst"));
            let empty_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("empty"),
                layout: &empty,
                entries: &[],
            });
            let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("calibration"),
                layout: &layout1,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: uniform.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: src.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 2,
                        resource: dst.as_entire_binding(),
                    },
                ],
            });
            let render = |label, vs, blend, depth: bool, topology| {
                device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                    label: Some(label),
                    layout: Some(&layout),
                    vertex: wgpu::VertexState {
                        module: &module,
                        entry_point: Some(vs),
                        compilation_options: Default::default(),
                        buffers: &[],
                    },
                    primitive: wgpu::PrimitiveState {
                        topology,
                        ..Default::default()
                    },
                    depth_stencil: Some(wgpu::DepthStencilState {
                        format: DEPTH_FORMAT,
                        depth_write_enabled: Some(depth),
                        depth_compare: Some(if depth {
                            wgpu::CompareFunction::Less
                        } else {
                            wgpu::CompareFunction::Always
                        }),
                        stencil: Default::default(),
                        bias: Default::default(),
                    }),
                    multisample: Default::default(),
                    fragment: Some(wgpu::FragmentState {
                        module: &module,
                        entry_point: Some("fs_color"),
                        compilation_options: Default::default(),
                        targets: &[Some(wgpu::ColorTargetState {
                            format: COLOR_FORMAT,
                            blend,
                            write_mask: wgpu::ColorWrites::ALL,
                        })],
                    }),
                    multiview_mask: None,
                    cache: None,
                })
            };
            let tiny = render(
                "calibration triangles",
                "vs_tiny",
                None,
                true,
                wgpu::PrimitiveTopology::TriangleStrip,
            );
            let fill = render(
                "calibration fill",
                "vs_full",
                Some(wgpu::BlendState::ALPHA_BLENDING),
                false,
                wgpu::PrimitiveTopology::TriangleList,
            );
            let copy = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("calibration copy"),
                layout: Some(&layout),
                module: &module,
                entry_point: Some("cs_copy"),
                compilation_options: Default::default(),
                cache: None,
            });
            Self {
                gpu,
                target,
                tiny,
                fill,
                copy,
                empty_group,
                group,
            }
        })
    }

    /// Records one submission with `record` and times it: submit to idle, wall time, seconds.
    pub(super) fn time(
        &self,
        label: &str,
        record: &dyn Fn(&mut wgpu::CommandEncoder),
    ) -> Result<f64> {
        let device = &self.gpu.device;
        let encoder = self.gpu.scoped(label, || {
            let mut encoder = device.create_command_encoder(&Default::default());
            record(&mut encoder);
            encoder.finish()
        })?;
        let t = Instant::now();
        self.gpu.queue.submit([encoder]);
        self.gpu.wait_idle(label)?;
        Ok(t.elapsed().as_secs_f64())
    }

    /// Records the triangle workload: every strip, 11 vertices each.
    pub(super) fn triangles(&self, encoder: &mut wgpu::CommandEncoder) {
        self.pass(encoder, &self.tiny, 11, STRIPS);
    }

    /// Records the fill workload: [`LAYERS`] full-screen blended triangles.
    pub(super) fn fill(&self, encoder: &mut wgpu::CommandEncoder) {
        self.pass(encoder, &self.fill, 3, LAYERS);
    }

    /// Records the bandwidth workload: one buffer copied into the other.
    pub(super) fn copy(&self, encoder: &mut wgpu::CommandEncoder) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("calibration copy"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.copy);
        pass.set_bind_group(0, &self.empty_group, &[]);
        pass.set_bind_group(1, &self.group, &[]);
        // 256 invocations a workgroup, 16 bytes an invocation.
        let groups = (COPY_BYTES / 16).div_ceil(256) as u32;
        pass.dispatch_workgroups(groups.min(65535), groups.div_ceil(65535), 1);
    }

    fn pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        pipeline: &wgpu::RenderPipeline,
        vertices: u32,
        instances: u32,
    ) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("calibration"),
            color_attachments: &[Some(self.target.color_attachment(Some(wgpu::Color::BLACK)))],
            depth_stencil_attachment: Some(self.target.depth_attachment(true)),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &self.empty_group, &[]);
        pass.set_bind_group(1, &self.group, &[]);
        pass.draw(0..vertices, 0..instances);
    }
}

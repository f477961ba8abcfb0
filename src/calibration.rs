//! Calibration: the adapter's raw limits, measured with micro-workloads, so every technique's
//! cost can be read against what the hardware (or software rasteriser) can do at best.
//!
//! - **triangles/s**: instanced blade-like strips of 9 tiny triangles (2 x 10 pixels),
//!   depth-tested like blades; their time per instance is the raw cost of a reference blade;
//! - **fill rate**: full-screen triangles alpha-blended over each other (pixels/s);
//! - **bandwidth**: a compute shader copying a 32 MiB buffer (bytes read + written per s).
//!
//! Every figure is submit-to-`poll(wait)` wall time, the lower of two rounds' medians of five
//! runs, after one warm-up (timestamps are not used: on lavapipe compute-pass timestamps are
//! wrong). Two rounds because a process's first large submissions may all run slow: lavapipe
//! in a fresh process drew the triangle workload at 5.9 M triangles/s in one process of three
//! and at 8.8-10.1 M in the others (one round each, 2026-12-05), and these are the first
//! submissions of every `run` and `sweep` ([`crate::cost`]'s unit costs follow them). A slow
//! round can only read slower, so the lower median is the adapter's. The raw blade cost is a
//! lower bound: real blades cover more pixels and are shaded.

use std::time::Instant;

use wgpu::util::DeviceExt as _;

use crate::target::{COLOR_FORMAT, DEPTH_FORMAT, Size};
use crate::{GpuContext, RenderTarget, Result, shaders};

/// Triangles of a reference blade at its default 5 segments (`2·5 − 1`).
pub const REFERENCE_BLADE_TRIANGLES: f64 = 9.0;

/// An adapter's measured limits.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Calibration {
    /// Target size used.
    pub size: String,
    /// Tiny depth-tested triangles per second, drawn as 9-triangle instanced strips.
    pub triangles_per_s: f64,
    /// Blended pixels per second.
    pub fill_pixels_per_s: f64,
    /// Bytes read plus written per second by a compute copy.
    pub compute_bytes_per_s: f64,
    /// `REFERENCE_BLADE_TRIANGLES / triangles_per_s`, ns.
    pub raw_blade_cost_ns: f64,
    /// Which clock: always submit-to-poll wall time.
    pub clock: String,
}

/// Instances (9-triangle strips) in the triangle workload.
const STRIPS: u32 = 100_000;
/// Layers in the fill workload.
const LAYERS: u32 = 24;
/// Bytes in each buffer of the bandwidth workload.
const COPY_BYTES: u64 = 32 << 20;
/// Timed rounds of each workload (the lower median is kept: the module's documentation).
const ROUNDS: usize = 2;
/// Timed submissions in a round.
const RUNS: usize = 5;

/// Runs the three workloads at `size`.
pub fn calibrate(gpu: &GpuContext, size: Size) -> Result<Calibration> {
    let target = RenderTarget::new(gpu, size, false)?;
    let device = &gpu.device;
    let (pipelines, bind_group) = gpu.scoped("building calibration workloads", || {
        let module = shaders::module(
            device,
            "calibration",
            include_str!("shaders/calibration.wgsl"),
        );
        // Group 0 is the prelude's; the workloads bind nothing there, so an empty layout stands in.
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
        ((tiny, fill, copy), (empty_group, group))
    })?;
    let (tiny, fill, copy) = pipelines;
    let (empty_group, group) = bind_group;

    let time = |label: &str, record: &dyn Fn(&mut wgpu::CommandEncoder)| -> Result<f64> {
        // One submission of the workload, its submit-to-idle wall time in seconds.
        let once = || -> Result<f64> {
            let encoder = gpu.scoped(label, || {
                let mut encoder = device.create_command_encoder(&Default::default());
                record(&mut encoder);
                encoder.finish()
            })?;
            let t = Instant::now();
            gpu.queue.submit([encoder]);
            gpu.wait_idle(label)?;
            Ok(t.elapsed().as_secs_f64())
        };
        once()?; // the warm-up
        let mut lowest = f64::NAN;
        for _ in 0..ROUNDS {
            let samples = (0..RUNS).map(|_| once()).collect::<Result<Vec<f64>>>()?;
            if let Some(p) = crate::runner::Percentiles::of(samples) {
                lowest = lowest.min(p.median);
            }
        }
        Ok(lowest)
    };
    let pass = |encoder: &mut wgpu::CommandEncoder,
                pipeline: &wgpu::RenderPipeline,
                vertices: u32,
                instances: u32| {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("calibration"),
            color_attachments: &[Some(target.color_attachment(Some(wgpu::Color::BLACK)))],
            depth_stencil_attachment: Some(target.depth_attachment(true)),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &empty_group, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.draw(0..vertices, 0..instances);
    };
    let tri_s = time("calibration: triangles", &|e| pass(e, &tiny, 11, STRIPS))?;
    let fill_s = time("calibration: fill", &|e| pass(e, &fill, 3, LAYERS))?;
    let texels = (COPY_BYTES / 16) as u32;
    let groups = texels.div_ceil(256);
    let copy_s = time("calibration: bandwidth", &|e| {
        let mut pass = e.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("calibration copy"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&copy);
        pass.set_bind_group(0, &empty_group, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.dispatch_workgroups(groups.min(65535), groups.div_ceil(65535), 1);
    })?;
    let triangles_per_s = REFERENCE_BLADE_TRIANGLES * f64::from(STRIPS) / tri_s;
    Ok(Calibration {
        size: size.to_string(),
        triangles_per_s,
        fill_pixels_per_s: f64::from(LAYERS) * f64::from(size.width) * f64::from(size.height)
            / fill_s,
        compute_bytes_per_s: 2.0 * COPY_BYTES as f64 / copy_s,
        raw_blade_cost_ns: REFERENCE_BLADE_TRIANGLES / triangles_per_s * 1e9,
        clock: format!(
            "wall time, submit to poll(wait), the lower of {ROUNDS} rounds' medians of {RUNS} after 1 warm-up"
        ),
    })
}

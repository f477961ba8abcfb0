//! The GPU side of the calibration's micro-workloads: their pipelines and buffers, and
//! recording, submitting and timing one submission of one or more workloads (see
//! `measure` for what is run when, `workloads` for what each one is).

use std::ops::Range;
use std::time::Instant;

use wgpu::util::DeviceExt as _;

use super::workloads::{self, Shape, Workload, dispatch_grid};
use super::{FragmentKind, Work};
use crate::frame::FrameGlobals;
use crate::shaders::{PipelineCost, buffer_entry};
use crate::target::{COLOR_FORMAT, DEPTH_FORMAT, Size};
use crate::technique::{PassKind, WorkCounter};
use crate::{Error, GpuContext, RenderTarget, Result, shaders};

/// Elements of the compute workload's buffer (16 bytes each: 16 MiB). A power of two: the
/// spring updates wrap their index with a mask, not a division (`wrap` in the shader).
const SPRING_COUNT: u64 = 1 << 20;
const _: () = assert!(SPRING_COUNT.is_power_of_two());
/// Bytes of the upload workload's destination buffer (its largest size).
const UPLOAD_CAPACITY: u64 = 64 << 20;
/// Elements of the `vertex_storage` strips' instance data (16 bytes each: 4 MiB, more than a
/// core's cache, as a meadow's blade arrays are).
const INSTANCE_DATA_COUNT: u64 = 1 << 18;
/// Side of the texture the `texture_*` workloads fetch from (mip-mapped down to 1 texel), the
/// size of a technique's slice or blade texture.
const FETCH_TEXTURE_SIDE: u32 = 512;

/// What the GPU's counters measured of one submission.
pub(super) struct Counted {
    /// Its work (draw calls and uploads as known: no counter sees them; instances as the
    /// harness counts them for a frame).
    pub work: Work,
    /// Samples that passed the depth test and were not discarded (occlusion queries around
    /// the render workloads).
    pub samples_passed: u64,
}

/// The GPU resources of the workloads.
pub(super) struct Rig<'g> {
    gpu: &'g GpuContext,
    target: RenderTarget,
    group0: wgpu::BindGroup,
    group1: wgpu::BindGroup,
    offscreen: crate::shaders::RenderPipeline,
    subpixel: crate::shaders::RenderPipeline,
    /// The sub-pixel strips with a fragment shader reading no interpolated slot.
    bare_subpixel: crate::shaders::RenderPipeline,
    layers: [crate::shaders::RenderPipeline; 3],
    /// The coverage checks' hidden layers, by fragment kind (as `layers`).
    hidden: [crate::shaders::RenderPipeline; 3],
    /// The coverage checks' blades on screen, by width ([`workloads::BladeWidth::ALL`]) and
    /// fragment kind (as `layers`).
    blades: [[crate::shaders::RenderPipeline; 3]; workloads::BladeWidth::ALL.len()],
    /// Opaque layers fetching texels, in [`workloads::Fetch::ALL`]'s order.
    fetch_layers: [crate::shaders::RenderPipeline; workloads::Fetch::ALL.len()],
    /// The `transcendentals_*` workloads': off-screen strips, opaque layers.
    math: [crate::shaders::RenderPipeline; 2],
    /// The `arithmetic_*` workloads': off-screen strips, opaque layers.
    arithmetic: [crate::shaders::RenderPipeline; 2],
    /// The `vertex_*texture_loads` workloads': off-screen strips loading texels, RGBA8 and
    /// floating-point.
    load_strips: [crate::shaders::RenderPipeline; 2],
    /// The `vertex_storage` workload's off-screen strips reading their instance's data.
    storage_strips: crate::shaders::RenderPipeline,
    /// The spring update, plain and with each chain, in [`workloads::Chain::ALL`]'s order.
    springs: [crate::shaders::ComputePipeline; workloads::Chain::ALL.len()],
    upload: wgpu::Buffer,
    upload_data: Vec<u8>,
}

impl<'g> Rig<'g> {
    /// Builds the target (4x multisampled where `msaa`), pipelines and buffers at `size`.
    pub(super) fn new(gpu: &'g GpuContext, size: Size, msaa: bool) -> Result<Self> {
        let target = RenderTarget::new(gpu, size, msaa)?;
        let device = &gpu.device;
        gpu.scoped("building the unit-cost workloads", || {
            let module = shaders::module_with_bindings(
                device,
                "unit costs",
                workloads::SHADER,
                &workloads::texture_formats(),
                &[workloads::SINGLE_LEVEL_SAMPLER],
            );
            let sampler_entry = |binding| wgpu::BindGroupLayoutEntry {
                binding,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                count: None,
            };
            let uniform_entry = |binding, visibility| {
                buffer_entry(binding, visibility, wgpu::BufferBindingType::Uniform)
            };
            let layout0 = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("unit costs globals"),
                entries: &[uniform_entry(
                    0,
                    wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT,
                )],
            });
            let layout1 = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("unit costs"),
                entries: &[
                    uniform_entry(
                        0,
                        wgpu::ShaderStages::VERTEX
                            | wgpu::ShaderStages::FRAGMENT
                            | wgpu::ShaderStages::COMPUTE,
                    ),
                    buffer_entry(
                        1,
                        wgpu::ShaderStages::COMPUTE,
                        wgpu::BufferBindingType::Storage { read_only: false },
                    ),
                    // The `vertex_storage` strips' instance data.
                    buffer_entry(
                        6,
                        wgpu::ShaderStages::VERTEX,
                        wgpu::BufferBindingType::Storage { read_only: true },
                    ),
                    // The trilinear sampler (3) and the one-level one (7).
                    sampler_entry(3),
                    sampler_entry(7),
                ]
                .into_iter()
                .chain(workloads::FETCH_TEXTURES.map(|t| {
                    wgpu::BindGroupLayoutEntry {
                        binding: t.binding,
                        // The vertex stage's for the `vertex_*texture_loads` strips.
                        visibility: wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT,
                        ty: wgpu::BindingType::Texture {
                            // Filterable or not, as the format is (`R32Float` is not).
                            sample_type: t
                                .format
                                .sample_type(None, Some(device.features()))
                                .unwrap_or(wgpu::TextureSampleType::Float { filterable: false }),
                            view_dimension: wgpu::TextureViewDimension::D2,
                            multisampled: false,
                        },
                        count: None,
                    }
                }))
                .collect::<Vec<_>>(),
            });
            let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("unit costs"),
                bind_group_layouts: &[Some(&layout0), Some(&layout1)],
                immediate_size: 0,
            });
            let globals = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("unit costs globals"),
                contents: bytemuck::bytes_of(&globals(size)),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("unit costs params"),
                contents: bytemuck::cast_slice(&[
                    size.width as f32,
                    size.height as f32,
                    1.0 / size.width as f32,
                    1.0 / size.height as f32,
                ]),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let springs_buffer = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("unit costs springs"),
                size: SPRING_COUNT * 16,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            });
            let mut rng = crate::rng::Rng::new(0x5eed);
            let instance_values: Vec<f32> = (0..INSTANCE_DATA_COUNT * 4)
                .map(|_| (rng.next_u64() % 1000) as f32 / 1000.0)
                .collect();
            let instance_data = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("unit costs instance data"),
                contents: bytemuck::cast_slice(&instance_values),
                usage: wgpu::BufferUsages::STORAGE,
            });
            let group0 = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("unit costs globals"),
                layout: &layout0,
                entries: &[wgpu::BindGroupEntry {
                    binding: 0,
                    resource: globals.as_entire_binding(),
                }],
            });
            let fetched = workloads::FETCH_TEXTURES.map(|t| {
                (
                    t.binding,
                    fetch_texture(gpu, t.format).create_view(&Default::default()),
                )
            });
            // Bilinear filtering within a level; between two levels (`trilinear`), or the
            // nearer level alone (`single_level`, the shader's `SINGLE_LEVEL_SAMPLER`).
            let sampler = |label, mipmap_filter| {
                device.create_sampler(&wgpu::SamplerDescriptor {
                    label: Some(label),
                    address_mode_u: wgpu::AddressMode::Repeat,
                    address_mode_v: wgpu::AddressMode::Repeat,
                    mag_filter: wgpu::FilterMode::Linear,
                    min_filter: wgpu::FilterMode::Linear,
                    mipmap_filter,
                    ..Default::default()
                })
            };
            let trilinear = sampler("unit costs trilinear", wgpu::MipmapFilterMode::Linear);
            let single_level = sampler("unit costs one level", wgpu::MipmapFilterMode::Nearest);
            let group1 = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("unit costs"),
                layout: &layout1,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: params.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: springs_buffer.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 6,
                        resource: instance_data.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 3,
                        resource: wgpu::BindingResource::Sampler(&trilinear),
                    },
                    wgpu::BindGroupEntry {
                        binding: 7,
                        resource: wgpu::BindingResource::Sampler(&single_level),
                    },
                ]
                .into_iter()
                .chain(fetched.iter().map(|(binding, view)| wgpu::BindGroupEntry {
                    binding: *binding,
                    resource: wgpu::BindingResource::TextureView(view),
                }))
                .collect::<Vec<_>>(),
            });
            let pipeline_with = |label, vs, fs, write: bool, blend, constants: &[(&str, f64)]| {
                shaders::render_pipeline(
                    device,
                    &shaders::PipelineSpec {
                        label,
                        layout: &layout,
                        module: &module,
                        vertex: vs,
                        fragment: fs,
                        buffers: &[],
                        primitive: wgpu::PrimitiveState {
                            topology: wgpu::PrimitiveTopology::TriangleStrip,
                            cull_mode: None,
                            ..Default::default()
                        },
                        depth: shaders::depth_test(
                            DEPTH_FORMAT,
                            wgpu::CompareFunction::LessEqual,
                            write,
                        ),
                        multisample: wgpu::MultisampleState {
                            count: target.sample_count,
                            ..Default::default()
                        },
                        targets: &[Some(wgpu::ColorTargetState {
                            format: COLOR_FORMAT,
                            blend,
                            write_mask: wgpu::ColorWrites::ALL,
                        })],
                        constants,
                    },
                )
            };
            let pipeline =
                |label, vs, fs, write, blend| pipeline_with(label, vs, fs, write, blend, &[]);
            // Drawn by `vs` with each kind's fragment shader (`FragmentKind::ALL`'s order): opaque
            // and alpha-tested ones write depth, blended ones blend and do not.
            let by_kind = |label, vs, constants: &[(&str, f64)]| {
                FragmentKind::ALL.map(|kind| {
                    let blended = kind == FragmentKind::Blended;
                    pipeline_with(
                        label,
                        vs,
                        workloads::layer_fragment_entry(kind),
                        !blended,
                        blended.then_some(wgpu::BlendState::ALPHA_BLENDING),
                        constants,
                    )
                })
            };
            Self {
                gpu,
                offscreen: pipeline(
                    "unit costs: vertices",
                    "vs_offscreen",
                    "fs_opaque",
                    true,
                    None,
                ),
                subpixel: pipeline(
                    "unit costs: primitive inputs",
                    "vs_subpixel",
                    workloads::subpixel_fragment_entry(true),
                    true,
                    None,
                ),
                bare_subpixel: pipeline(
                    "unit costs: primitives",
                    "vs_subpixel",
                    workloads::subpixel_fragment_entry(false),
                    true,
                    None,
                ),
                layers: by_kind("unit costs: layers", "vs_layer", &[]),
                hidden: by_kind("unit costs: hidden layers", "vs_hidden_layer", &[]),
                blades: workloads::BladeWidth::ALL.map(|width| {
                    by_kind(
                        "unit costs: blades on screen",
                        workloads::ONSCREEN_BLADE_VERTEX,
                        &width.constants(),
                    )
                }),
                fetch_layers: workloads::Fetch::ALL.map(|fetch| {
                    pipeline(
                        "unit costs: fetches",
                        "vs_layer",
                        fetch.fragment_entry(),
                        true,
                        None,
                    )
                }),
                math: [
                    pipeline(
                        "unit costs: vertex transcendentals",
                        "vs_math",
                        "fs_opaque",
                        true,
                        None,
                    ),
                    pipeline(
                        "unit costs: fragment transcendentals",
                        "vs_layer",
                        "fs_math",
                        true,
                        None,
                    ),
                ],
                arithmetic: [
                    pipeline(
                        "unit costs: vertex arithmetic",
                        "vs_arithmetic",
                        "fs_opaque",
                        true,
                        None,
                    ),
                    pipeline(
                        "unit costs: fragment arithmetic",
                        "vs_layer",
                        "fs_arithmetic",
                        true,
                        None,
                    ),
                ],
                load_strips: [false, true].map(|float| {
                    pipeline(
                        "unit costs: vertex loads",
                        workloads::load_strips_entry(float),
                        "fs_opaque",
                        true,
                        None,
                    )
                }),
                storage_strips: pipeline(
                    "unit costs: vertex storage",
                    "vs_storage",
                    "fs_opaque",
                    true,
                    None,
                ),
                springs: workloads::Chain::ALL.map(|chain| {
                    let entry = chain.compute_entry();
                    let label = format!("unit costs: {entry}");
                    shaders::compute_pipeline(device, &label, &layout, &module, entry, &[])
                }),
                upload: device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("unit costs upload"),
                    size: UPLOAD_CAPACITY,
                    usage: wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }),
                upload_data: (0..UPLOAD_CAPACITY).map(|i| (i % 251) as u8).collect(),
                target,
                group0,
                group1,
            }
        })
    }

    /// Records, submits and times one submission doing all of `mix`; with `counter`, also
    /// counts its work with the GPU's pipeline statistics (one query per workload, so the
    /// fragments split by kind and the fetches by shader; draw calls and uploads as known). Returns the
    /// submit-to-idle wall time in ms.
    pub(super) fn run(
        &self,
        mix: &[Workload],
        mut counter: Option<&mut WorkCounter>,
    ) -> Result<(f64, Option<Counted>)> {
        let gpu = self.gpu;
        let names: Vec<&str> = mix.iter().map(|w| w.name).collect();
        let label = format!("unit-cost workload `{}`", names.join(" + "));
        if let Some(c) = counter.as_deref_mut() {
            c.begin_frame();
        }
        let (commands, costs) = gpu.scoped(&label, || {
            let mut encoder = gpu.device.create_command_encoder(&Default::default());
            let costs = self.record(&mut encoder, mix, counter.as_deref_mut());
            if let Some(c) = counter.as_deref() {
                c.resolve(&mut encoder);
            }
            (encoder.finish(), costs)
        })?;
        for w in mix {
            if let Shape::Upload { bytes } = w.shape {
                // More than the buffer holds is written in buffer-sized pieces, over it again.
                let mut left = bytes;
                while left > 0 {
                    let n = left.min(UPLOAD_CAPACITY);
                    let len = usize::try_from(n).unwrap_or(self.upload_data.len());
                    gpu.queue
                        .write_buffer(&self.upload, 0, &self.upload_data[..len]);
                    left -= n;
                }
            }
        }
        let t = Instant::now();
        gpu.queue.submit([commands]);
        gpu.wait_idle(&label)?;
        let ms = t.elapsed().as_secs_f64() * 1e3;
        let Some(counter) = counter else {
            return Ok((ms, None));
        };
        let records = counter
            .read(gpu)
            .map_err(|e| Error::Validation {
                during: label.clone(),
                message: e.to_string(),
            })?
            .ok_or_else(|| Error::DeviceLost {
                during: label.clone(),
                message: "reading the pipeline statistics failed".into(),
            })?;
        let known = mix
            .iter()
            .fold(Work::default(), |a, w| a + w.work(self.target.size));
        let counted = records
            .iter()
            .zip(costs)
            .fold(Work::default(), |a, (r, cost)| {
                a + Work::from_counters(&r.work, cost)
            });
        Ok((
            ms,
            Some(Counted {
                work: Work {
                    draw_calls: known.draw_calls,
                    upload_bytes: known.upload_bytes,
                    ..counted
                },
                samples_passed: records.iter().map(|r| r.work.samples_passed).sum(),
            }),
        ))
    }

    /// One submission: a render pass clearing the target with the draws of the render
    /// workloads, then a compute pass with the dispatches of the compute ones. Layers of
    /// successive workloads continue each other's depth order (their instance indices run
    /// on), so every layer passes the depth test. Returns the pipeline cost of each
    /// statistics query begun, in order.
    fn record(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        mix: &[Workload],
        mut counter: Option<&mut WorkCounter>,
    ) -> Vec<PipelineCost> {
        let mut costs = Vec::new();
        {
            let occlusion = counter.as_deref().map(|c| c.occlusion_set().clone());
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("unit costs"),
                color_attachments: &[Some(self.target.color_attachment(Some(wgpu::Color::BLACK)))],
                depth_stencil_attachment: Some(self.target.depth_attachment(true)),
                timestamp_writes: None,
                occlusion_query_set: occlusion.as_ref(),
                multiview_mask: None,
            });
            pass.set_bind_group(0, &self.group0, &[]);
            pass.set_bind_group(1, &self.group1, &[]);
            let mut layer_base = 0u32;
            for w in mix {
                let Some(pipeline) = self.pipeline(w) else {
                    continue;
                };
                let query = counter.as_deref_mut().and_then(|c| {
                    c.next(w.name.to_owned(), PassKind::Render, Some(pipeline.cost()))
                });
                if let Some(q) = &query {
                    q.begin_render(&mut pass);
                    costs.push(pipeline.cost());
                }
                pass.set_pipeline(pipeline);
                // The draws, each a vertex range and an instance range.
                let draws: Vec<(Range<u32>, Range<u32>)> = match w.shape {
                    Shape::OffscreenStrips {
                        vertices,
                        instances,
                    } => vec![(0..vertices, 0..instances)],
                    Shape::SubpixelStrips { instances, .. }
                    | Shape::MathStrips { instances }
                    | Shape::ArithmeticStrips { instances }
                    | Shape::LoadStrips { instances, .. }
                    | Shape::StorageStrips { instances }
                    | Shape::OnscreenBlades { instances, .. } => {
                        vec![(0..workloads::STRIP_VERTICES, 0..instances)]
                    }
                    Shape::Layers { layers, .. }
                    | Shape::HiddenLayers { layers, .. }
                    | Shape::FetchLayers { layers, .. }
                    | Shape::MathLayers { layers }
                    | Shape::ArithmeticLayers { layers } => {
                        let end = layer_base.saturating_add(layers);
                        let range = layer_base..end;
                        layer_base = end;
                        vec![(0..workloads::LAYER_VERTICES, range)]
                    }
                    Shape::Draws { draws } => (0..draws)
                        .map(|i| (0..workloads::DRAW_VERTICES, i..i + 1))
                        .collect(),
                    Shape::Empty | Shape::Compute { .. } | Shape::Upload { .. } => Vec::new(),
                };
                for (vertices, instances) in draws {
                    // Instances are counted as the frame encoder counts them: by the
                    // harness, into the segment's record.
                    if let Some(c) = counter.as_deref_mut().filter(|_| query.is_some()) {
                        c.add_instances(u64::from(instances.end - instances.start));
                    }
                    pass.draw(vertices, instances);
                }
                if query.is_some() {
                    crate::technique::work::end_render(&mut pass);
                }
            }
        }
        let dispatches: Vec<(&Workload, u32, workloads::Chain)> = mix
            .iter()
            .filter_map(|w| match w.shape {
                Shape::Compute { groups, chain } => Some((w, groups, chain)),
                _ => None,
            })
            .collect();
        if !dispatches.is_empty() {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("unit costs: compute"),
                timestamp_writes: None,
            });
            pass.set_bind_group(0, &self.group0, &[]);
            pass.set_bind_group(1, &self.group1, &[]);
            for (w, groups, chain) in dispatches {
                // In bounds: one pipeline per variant (`Chain::ALL`).
                let pipeline = &self.springs[chain as usize];
                pass.set_pipeline(pipeline);
                let query = counter.as_deref_mut().and_then(|c| {
                    c.next(w.name.to_owned(), PassKind::Compute, Some(pipeline.cost()))
                });
                if let Some(q) = &query {
                    q.begin_compute(&mut pass);
                    costs.push(pipeline.cost());
                }
                let (x, y) = dispatch_grid(groups);
                pass.dispatch_workgroups(x, y, 1);
                if query.is_some() {
                    pass.end_pipeline_statistics_query();
                }
            }
        }
        costs
    }

    /// The render pipeline drawing render workload `w` (`None` for the others).
    fn pipeline(&self, w: &Workload) -> Option<&crate::shaders::RenderPipeline> {
        match w.shape {
            Shape::OffscreenStrips { .. } => Some(&self.offscreen),
            Shape::SubpixelStrips {
                interpolated: false,
                ..
            } => Some(&self.bare_subpixel),
            Shape::SubpixelStrips { .. } | Shape::Draws { .. } => Some(&self.subpixel),
            // In bounds: one pipeline per kind (`FragmentKind::ALL`) and width
            // (`BladeWidth::ALL`).
            Shape::Layers { kind, .. } => Some(&self.layers[kind as usize]),
            Shape::HiddenLayers { kind, .. } => Some(&self.hidden[kind as usize]),
            Shape::OnscreenBlades { kind, width, .. } => {
                Some(&self.blades[width as usize][kind as usize])
            }
            // In bounds: one pipeline per fetch (`Fetch::ALL`).
            Shape::FetchLayers { fetch, .. } => Some(&self.fetch_layers[fetch as usize]),
            Shape::MathStrips { .. } => Some(&self.math[0]),
            Shape::MathLayers { .. } => Some(&self.math[1]),
            Shape::ArithmeticStrips { .. } => Some(&self.arithmetic[0]),
            Shape::ArithmeticLayers { .. } => Some(&self.arithmetic[1]),
            Shape::LoadStrips { float, .. } => Some(&self.load_strips[usize::from(float)]),
            Shape::StorageStrips { .. } => Some(&self.storage_strips),
            Shape::Empty | Shape::Compute { .. } | Shape::Upload { .. } => None,
        }
    }
}

/// A `texture_*` workload's texture: [`FETCH_TEXTURE_SIDE`]² texels of `format` (8-bit
/// normalised channels, or 16- or 32-bit floating-point ones) with every mip level, hashed (no
/// level is uniform, so no fetch can be folded away; the same values, multiples of 1/255, in
/// every format).
fn fetch_texture(gpu: &GpuContext, format: wgpu::TextureFormat) -> wgpu::Texture {
    let levels = FETCH_TEXTURE_SIDE.ilog2() + 1;
    let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("unit costs fetches"),
        size: wgpu::Extent3d {
            width: FETCH_TEXTURE_SIDE,
            height: FETCH_TEXTURE_SIDE,
            depth_or_array_layers: 1,
        },
        mip_level_count: levels,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    // One channel's bytes from its hashed byte: the byte itself (8-bit normalised) or its value
    // over 255 as a half or a single float.
    let channels = u32::from(format.components());
    let texel_bytes = format.block_copy_size(None).unwrap_or(4);
    let float = shaders::is_float(format);
    let encode = |b: u8| -> Vec<u8> {
        let v = f32::from(b) / 255.0;
        match (float, texel_bytes / channels.max(1)) {
            (true, 2) => half::f16::from_f32(v).to_le_bytes().to_vec(),
            (true, _) => v.to_le_bytes().to_vec(),
            (false, _) => vec![b],
        }
    };
    let mut rng = crate::rng::Rng::new(0x7e7e);
    for level in 0..levels {
        let side = (FETCH_TEXTURE_SIDE >> level).max(1);
        let data: Vec<u8> = (0..side * side * channels)
            .flat_map(|_| encode(rng.next_u64() as u8))
            .collect();
        gpu.queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: level,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            &data,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(side * texel_bytes),
                rows_per_image: None,
            },
            wgpu::Extent3d {
                width: side,
                height: side,
                depth_or_array_layers: 1,
            },
        );
    }
    texture
}

/// The frame globals the lit fragments read: a camera 1.7 m above the field looking along
/// it, a sun 55° high, daylight ambient and a light haze, no point light (the lighting
/// branch most scenes take).
fn globals(size: Size) -> FrameGlobals {
    let eye = glam::Vec3::new(25.0, 1.7, -5.0);
    let view = glam::Mat4::look_at_rh(eye, glam::Vec3::new(25.0, 0.0, 20.0), glam::Vec3::Y);
    let proj = glam::Mat4::perspective_rh(60f32.to_radians(), size.aspect(), 0.1, 500.0);
    let view_proj = proj * view;
    let sun = glam::Vec3::new(0.4, 0.82, 0.4).normalize();
    let mut g: FrameGlobals = bytemuck::Zeroable::zeroed();
    g.view_proj = view_proj.to_cols_array_2d();
    g.inv_view_proj = view_proj.inverse().to_cols_array_2d();
    g.camera_pos = [eye.x, eye.y, eye.z, 1.0];
    g.camera_forward = [0.0, -0.07, 1.0, 1.0 / 60.0];
    g.sun_direction = [sun.x, sun.y, sun.z, 0.0];
    g.sun_color = [3.0, 2.9, 2.7, 0.0];
    g.ambient = [0.30, 0.35, 0.42, 0.0];
    g.sky_zenith = [0.25, 0.45, 0.85, 0.0];
    g.sky_horizon = [0.70, 0.80, 0.90, 0.0];
    g.ground_color = [0.30, 0.25, 0.15, 0.004];
    g.viewport = [
        size.width as f32,
        size.height as f32,
        1.0 / size.width as f32,
        1.0 / size.height as f32,
    ];
    g
}

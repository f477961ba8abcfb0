//! The horizontal slice (Boulanger Sec. 3.3, last paragraphs): rendered once at start-up from
//! the geometric patch, with wgpu, as an orthographic top view, and the patch orientation map
//! (Sec. 4.1) that lets macro-cells repeat it with each cell's mirror.
//!
//! The bake draws the patch and its eight neighbours (so blades leaning in from the neighbours
//! are not cut at the border, Sec. 3.3) with the same vertex shader as the geometric blades, in
//! baking mode: no terrain, wind, density or LOD test. Two `Rgba16Float` targets receive the
//! unlit colour (Fig. 7's ambient row) and (two-sided diffuse factor for the scene's sun, 0,
//! density threshold, occlusion) (Fig. 10's threshold image, plus what lighting needs). It is rendered with 4x
//! MSAA and resolved, so coverage becomes alpha with soft borders and every channel is
//! premultiplied by it; the mip chain is then built by 2x2 box filtering, which keeps
//! premultiplied channels consistent, for the trilinear filtering of far grass.

use grassbench::wgpu::util::DeviceExt as _;
use grassbench::{InitContext, Result, bytemuck, shaders, wgpu};

use crate::CellUniform;
use crate::patch::Orientation;
use crate::quadtree::CellGrid;
use grassbench::shaders::{PipelineSpec, render_pipeline};

/// The mip chain shader (without the prelude).
pub const MIP_SHADER: &str = include_str!("../shaders/mip.wgsl");

/// Format of both slice textures.
pub const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// The baked slice: colour and auxiliary textures with full mip chains.
pub struct SliceTextures {
    /// Albedo x coverage, coverage.
    pub color: wgpu::TextureView,
    /// (diffuse factor, 0, density threshold, occlusion) x coverage.
    pub aux: wgpu::TextureView,
    /// GPU memory, bytes.
    pub bytes: u64,
}

/// What the bake draws with: the blade pipeline in baking mode and its bind groups.
pub struct BakeInputs<'a> {
    /// Pipeline: `vs_blade` + `fs_bake`, two `FORMAT` targets, 4x MSAA, depth.
    pub pipeline: &'a wgpu::RenderPipeline,
    /// Group 1 (params, blade texture, samplers).
    pub group1: &'a wgpu::BindGroup,
    /// Layout of group 2 ([`crate::cells::layout`]).
    pub cell_layout: &'a wgpu::BindGroupLayout,
    /// The patch's blades (storage buffer) and how many.
    pub blades: &'a wgpu::Buffer,
    /// Blades in the patch.
    pub blade_count: u32,
    /// Vertices per blade strip.
    pub vertices: u32,
    /// Patch side, m.
    pub patch_size: f32,
    /// Texture side, texels.
    pub resolution: u32,
}

/// GPU memory of the two slice textures of side `resolution` with their mip chains.
pub fn texture_bytes(resolution: u32) -> u64 {
    let levels = 32 - resolution.leading_zeros();
    (0..levels)
        .map(|l| 2 * 8 * u64::from((resolution >> l).max(1)).pow(2))
        .sum()
}

/// Renders the slice textures and their mip chains.
pub fn bake(ctx: &InitContext<'_>, inputs: &BakeInputs<'_>) -> Result<SliceTextures> {
    let device = &ctx.gpu.device;
    let r = inputs.resolution;
    let levels = 32 - r.leading_zeros();
    let size = wgpu::Extent3d {
        width: r,
        height: r,
        depth_or_array_layers: 1,
    };
    let final_texture = |label| {
        device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size,
            mip_level_count: levels,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: FORMAT,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::RENDER_ATTACHMENT,
            view_formats: &[],
        })
    };
    let multisampled = |label, format| {
        device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size,
            mip_level_count: 1,
            sample_count: 4,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            view_formats: &[],
        })
    };
    let color = final_texture("boulanger slice colour");
    let aux = final_texture("boulanger slice aux");
    let color_ms = multisampled("boulanger slice colour (msaa)", FORMAT);
    let aux_ms = multisampled("boulanger slice aux (msaa)", FORMAT);
    let depth_ms = multisampled("boulanger slice depth", wgpu::TextureFormat::Depth32Float);
    let level_view = |t: &wgpu::Texture, level: u32| {
        t.create_view(&wgpu::TextureViewDescriptor {
            base_mip_level: level,
            mip_level_count: Some(1),
            ..Default::default()
        })
    };

    // The patch and its eight unmirrored neighbours: cells 0-8, drawn as one instanced draw.
    let cells: Vec<CellUniform> = (-1..=1)
        .flat_map(|dz| (-1..=1).map(move |dx| (dx, dz)))
        .map(|(dx, dz)| CellUniform {
            center_signs: [
                dx as f32 * inputs.patch_size,
                dz as f32 * inputs.patch_size,
                1.0,
                1.0,
            ],
            mode: [1.0, 0.0, 0.0, 0.0],
        })
        .collect();
    let cell_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("boulanger bake cells"),
        contents: bytemuck::cast_slice(&cells),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let cell_group = crate::cells::group(
        device,
        inputs.cell_layout,
        &cell_buffer,
        cells.len() as u64,
        inputs.blades,
    );

    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("boulanger slice bake"),
    });
    {
        let (cv, av, dv) = (
            color_ms.create_view(&Default::default()),
            aux_ms.create_view(&Default::default()),
            depth_ms.create_view(&Default::default()),
        );
        let (c0, a0) = (level_view(&color, 0), level_view(&aux, 0));
        let attachment = |view, resolve| {
            Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: Some(resolve),
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Discard,
                },
            })
        };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("boulanger slice bake"),
            color_attachments: &[attachment(&cv, &c0), attachment(&av, &a0)],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &dv,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(inputs.pipeline);
        pass.set_bind_group(0, &ctx.scene_gpu.bind_group, &[]);
        pass.set_bind_group(1, inputs.group1, &[]);
        pass.set_bind_group(2, &cell_group, &[0]);
        pass.draw(0..inputs.vertices, 0..9 * inputs.blade_count);
    }
    build_mips(ctx, &mut encoder, &color, &aux, levels);
    ctx.gpu.queue.submit([encoder.finish()]);

    let bytes = texture_bytes(r);
    Ok(SliceTextures {
        color: color.create_view(&Default::default()),
        aux: aux.create_view(&Default::default()),
        bytes,
    })
}

fn build_mips(
    ctx: &InitContext<'_>,
    encoder: &mut wgpu::CommandEncoder,
    color: &wgpu::Texture,
    aux: &wgpu::Texture,
    levels: u32,
) {
    let device = &ctx.gpu.device;
    let texture_entry = |binding| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: true },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    };
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("boulanger mip (group 1)"),
        entries: &[
            texture_entry(0),
            texture_entry(1),
            wgpu::BindGroupLayoutEntry {
                binding: 2,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                count: None,
            },
        ],
    });
    let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("boulanger mip"),
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        ..Default::default()
    });
    let module = shaders::module(device, "boulanger mip", MIP_SHADER);
    let pipeline_layout = ctx
        .scene_gpu
        .pipeline_layout(device, "boulanger mip", &[&layout]);
    let target = Some(wgpu::ColorTargetState::from(FORMAT));
    let targets = [target.clone(), target];
    let pipeline = render_pipeline(
        device,
        &PipelineSpec {
            label: "boulanger mip",
            layout: &pipeline_layout,
            module: &module,
            vertex: "vs_mip",
            fragment: "fs_mip",
            buffers: &[],
            primitive: Default::default(),
            depth: None,
            multisample: Default::default(),
            targets: &targets,
        },
    );
    let view = |t: &wgpu::Texture, level: u32| {
        t.create_view(&wgpu::TextureViewDescriptor {
            base_mip_level: level,
            mip_level_count: Some(1),
            ..Default::default()
        })
    };
    for level in 1..levels {
        let (sc, sa) = (view(color, level - 1), view(aux, level - 1));
        let (dc, da) = (view(color, level), view(aux, level));
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("boulanger mip"),
            layout: &layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&sc),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&sa),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::Sampler(&sampler),
                },
            ],
        });
        let attachment = |v| {
            Some(wgpu::RenderPassColorAttachment {
                view: v,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })
        };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("boulanger mip"),
            color_attachments: &[attachment(&dc), attachment(&da)],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &ctx.scene_gpu.bind_group, &[]);
        pass.set_bind_group(1, &group, &[]);
        pass.draw(0..3, 0..1);
    }
}

/// The patch orientation map (Sec. 4.1, Fig. 20a): one `R8Uint` texel per cell, bit 0 = mirror
/// x, bit 1 = mirror z; the same hash as the CPU's [`Orientation::of_cell`].
pub fn orientation_map(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    grid: &CellGrid,
    seed: u64,
) -> (wgpu::TextureView, u64) {
    let data: Vec<u8> = (0..grid.nz)
        .flat_map(|j| (0..grid.nx).map(move |i| Orientation::of_cell(seed, i, j).bits()))
        .collect();
    let texture = device.create_texture_with_data(
        queue,
        &wgpu::TextureDescriptor {
            label: Some("boulanger patch orientation map"),
            size: wgpu::Extent3d {
                width: grid.nx,
                height: grid.nz,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::R8Uint,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        &data,
    );
    (texture.create_view(&Default::default()), data.len() as u64)
}

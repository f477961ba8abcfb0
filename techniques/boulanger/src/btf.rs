//! The BTF pre-computation (Boulanger Sec. 3.3, Fig. 6, 7 and 10): slices of the geometric
//! patch rendered once at start-up, with wgpu, by orthographic cameras between two clip
//! planes.
//!
//! A *layer* is one slice seen from one side (the horizontal slice has one, each vertical slice
//! two: Sec. 3.3 keeps the two view directions a zero-thickness slice is visible from). For
//! each layer the patch and its eight neighbours (so blades leaning in from them are not cut,
//! Sec. 3.3) are drawn with the blades' own vertex shader in baking mode (no terrain, wind,
//! density or LOD) into three `Rgba16Float` targets at once:
//!
//! - **colour**: the blade colour without lighting, `K_d` (Fig. 7's ambient row), and coverage
//!   (Fig. 7's alpha channel);
//! - **diffuse**: the two-sided diffuse factor `K_d`-free `max(N·L_i, 0)` (+ translucency) for
//!   the light directions Y+, X+, Z+, X− (Fig. 7's light rows; the colour multiplies at run
//!   time);
//! - **extra**: the same for Z−, the density threshold (Fig. 10) and the ambient occlusion.
//!
//! The five light rows come from one pass: the light is a direction, so only the shading
//! changes between them. The paper renders the alpha channel separately with white blades on
//! black; here 4x MSAA resolve turns coverage into alpha with the same soft borders, and every
//! channel comes out premultiplied by it. A box-filtered mip chain follows for trilinear
//! filtering. The blades each layer draws are listed on the CPU (those whose horizontal extent
//! meets the layer's slab, [`crate::vertical`]), so a vertical slice does not pay for the nine
//! patches.

use std::ops::Range;

use grassbench::wgpu::util::DeviceExt as _;
use grassbench::{Error, InitContext, Result, bytemuck, shaders, wgpu};

use crate::shader::CellRecord;
use grassbench::shaders::{PipelineSpec, render_pipeline};

/// The mip chain shader (without the prelude).
pub const MIP_SHADER: &str = include_str!("../shaders/mip.wgsl");

/// Format of the three BTF textures.
pub const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// Textures per layer: colour, diffuse, extra.
pub const TEXTURES: u64 = 3;

/// Baked BTF layers: three 2D array textures with full mip chains.
pub struct BtfTextures {
    /// `(K_d, 1) x coverage`.
    pub color: wgpu::TextureView,
    /// Diffuse factors for Y+, X+, Z+, X−, x coverage.
    pub diffuse: wgpu::TextureView,
    /// (diffuse factor for Z−, density threshold, occlusion, 0) x coverage.
    pub extra: wgpu::TextureView,
    /// The textures themselves (for read-back).
    pub textures: [wgpu::Texture; 3],
    /// GPU memory, bytes.
    pub bytes: u64,
}

/// Mip levels of a `width x height` texture down to 1 x 1.
pub fn levels(width: u32, height: u32) -> u32 {
    32 - width.max(height).leading_zeros()
}

/// GPU memory of `layers` layers of `width x height` with their mip chains.
pub fn texture_bytes(width: u32, height: u32, layers: u32) -> u64 {
    let texel = 8 * TEXTURES;
    (0..levels(width, height))
        .map(|l| texel * u64::from((width >> l).max(1)) * u64::from((height >> l).max(1)))
        .sum::<u64>()
        * u64::from(layers)
}

/// What the bake draws with.
pub struct BakeInputs<'a> {
    /// Pipeline: `vs_bake` + `fs_bake`, three [`FORMAT`] targets, 4x MSAA, depth.
    pub pipeline: &'a grassbench::shaders::RenderPipeline,
    /// Group 1 (params, blade texture, samplers).
    pub group1: &'a wgpu::BindGroup,
    /// Layout of group 2 ([`crate::cells::layout`]).
    pub cell_layout: &'a wgpu::BindGroupLayout,
    /// Layout of group 3 ([`refs_layout`]).
    pub refs_layout: &'a wgpu::BindGroupLayout,
    /// The patch's blades (storage buffer).
    pub blades: &'a wgpu::Buffer,
    /// Vertices per blade strip.
    pub vertices: u32,
}

/// The layers to bake: the cells (each with its camera in `mode`), the blade list (values in
/// the blade pipeline's instance numbering) and, per layer, its range of the list.
pub struct Layers<'a> {
    /// Cells the blade list refers to.
    pub cells: &'a [CellRecord],
    /// Blades, as `cell x blade count + blade`.
    pub refs: &'a [u32],
    /// One range of `refs` per layer.
    pub ranges: &'a [Range<u32>],
}

/// Layout of the bake's group 3: the blade list (`bake_refs`).
pub fn refs_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("boulanger bake refs (group 3)"),
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only: true },
                has_dynamic_offset: false,
                min_binding_size: wgpu::BufferSize::new(4),
            },
            count: None,
        }],
    })
}

/// Renders the layers into `width x height` BTF textures with their mip chains.
pub fn bake(
    ctx: &InitContext<'_>,
    inputs: &BakeInputs<'_>,
    width: u32,
    height: u32,
    layers: &Layers<'_>,
) -> Result<BtfTextures> {
    let device = &ctx.gpu.device;
    let limits = device.limits();
    let count = layers.ranges.len() as u32;
    if width.max(height) > limits.max_texture_dimension_2d
        || count > limits.max_texture_array_layers
        || count == 0
    {
        return Err(Error::Technique {
            technique: "boulanger".to_owned(),
            message: format!(
                "{count} BTF layers of {width} x {height} exceed this device ({} layers of {} texels a side): lower boulanger.vertical_slices or the slice resolutions",
                limits.max_texture_array_layers, limits.max_texture_dimension_2d
            ),
        });
    }
    let levels = levels(width, height);
    let multisampled = |label, format| {
        device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 4,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            view_formats: &[],
        })
    };
    let textures = create_textures(device, width, height, count);
    // Each layer is resolved and mip-mapped in a single-layer texture, then copied into its
    // layer: resolving or rendering into a layer of an array texture is not reliable on every
    // driver (on lavapipe every layer's resolve landed in layer 0).
    let scratch = create(device, width, height, 1);
    let ms = [
        multisampled("boulanger BTF colour (msaa)", FORMAT),
        multisampled("boulanger BTF diffuse (msaa)", FORMAT),
        multisampled("boulanger BTF extra (msaa)", FORMAT),
    ];
    let depth_ms = multisampled("boulanger BTF depth", wgpu::TextureFormat::Depth32Float);

    let cell_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("boulanger bake cells"),
        contents: bytemuck::cast_slice(layers.cells),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let cell_group = crate::cells::group(
        device,
        inputs.cell_layout,
        &cell_buffer,
        layers.cells.len() as u64,
        inputs.blades,
    );
    // A zero never read keeps the buffer non-empty when no layer draws anything.
    let refs: &[u32] = if layers.refs.is_empty() {
        &[0]
    } else {
        layers.refs
    };
    let refs_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("boulanger bake refs"),
        contents: bytemuck::cast_slice(refs),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let refs_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("boulanger bake refs (group 3)"),
        layout: inputs.refs_layout,
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: refs_buffer.as_entire_binding(),
        }],
    });

    let mips = MipPipeline::new(ctx);
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("boulanger BTF bake"),
    });
    let ms_views = ms.each_ref().map(|t| t.create_view(&Default::default()));
    let depth_view = depth_ms.create_view(&Default::default());
    for (layer, range) in layers.ranges.iter().enumerate() {
        let resolve = scratch.each_ref().map(|t| layer_view(t, 0, 0));
        let attachments: Vec<_> = ms_views
            .iter()
            .zip(&resolve)
            .map(|(view, resolve)| {
                Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: Some(resolve),
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                        store: wgpu::StoreOp::Discard,
                    },
                })
            })
            .collect();
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("boulanger BTF layer"),
            color_attachments: &attachments,
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &depth_view,
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
        if !range.is_empty() {
            pass.set_pipeline(inputs.pipeline);
            pass.set_bind_group(0, &ctx.scene_gpu.bind_group, &[]);
            pass.set_bind_group(1, inputs.group1, &[]);
            pass.set_bind_group(2, &cell_group, &[0]);
            pass.set_bind_group(3, &refs_group, &[]);
            pass.draw(0..inputs.vertices, range.clone());
        }
        drop(pass);
        mips.build(ctx, &mut encoder, &scratch, levels);
        for (from, to) in scratch.iter().zip(&textures) {
            for level in 0..levels {
                encoder.copy_texture_to_texture(
                    wgpu::TexelCopyTextureInfo {
                        texture: from,
                        mip_level: level,
                        origin: wgpu::Origin3d::ZERO,
                        aspect: wgpu::TextureAspect::All,
                    },
                    wgpu::TexelCopyTextureInfo {
                        texture: to,
                        mip_level: level,
                        origin: wgpu::Origin3d {
                            x: 0,
                            y: 0,
                            z: layer as u32,
                        },
                        aspect: wgpu::TextureAspect::All,
                    },
                    wgpu::Extent3d {
                        width: (width >> level).max(1),
                        height: (height >> level).max(1),
                        depth_or_array_layers: 1,
                    },
                );
            }
        }
    }
    ctx.gpu.queue.submit([encoder.finish()]);

    Ok(wrap(textures, width, height, count))
}

/// Fewest layers an array texture is given. wgpu's GL backend picks a texture's GL target when
/// the texture is created, from its layer count alone: one layer makes a `TEXTURE_2D`, which a
/// `texture_2d_array` binding then samples as nothing (gfx-rs/wgpu#2161, #4081). On GL llvmpipe
/// the one-layer shadow mask and horizontal slice read as zero: blades lit as fully shadowed
/// (about 11 levels darker), the far band a dark grey (issue 24 §1). A second, unused layer
/// makes every array an array on every backend, for 1/N more memory where N is 1.
pub const MIN_ARRAY_LAYERS: u32 = 2;

/// Layers allocated for an array of `layers` layers (at least [`MIN_ARRAY_LAYERS`]).
pub fn array_layers(layers: u32) -> u32 {
    layers.max(MIN_ARRAY_LAYERS)
}

/// The three textures (colour, diffuse, extra) of an array of `layers` layers with full mip
/// chains (allocated with [`array_layers`], so a one-layer array is an array on GL too).
pub fn create_textures(
    device: &wgpu::Device,
    width: u32,
    height: u32,
    layers: u32,
) -> [wgpu::Texture; 3] {
    create(device, width, height, array_layers(layers))
}

/// The three textures with exactly `layers` layers (1 for a render scratch viewed as 2D).
fn create(device: &wgpu::Device, width: u32, height: u32, layers: u32) -> [wgpu::Texture; 3] {
    [
        "boulanger BTF colour",
        "boulanger BTF diffuse",
        "boulanger BTF extra",
    ]
    .map(|label| {
        device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: layers,
            },
            mip_level_count: levels(width, height),
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: FORMAT,
            usage: wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        })
    })
}

/// The array views of three textures made by [`create_textures`].
pub fn wrap(textures: [wgpu::Texture; 3], width: u32, height: u32, layers: u32) -> BtfTextures {
    let array_view = |t: &wgpu::Texture| {
        t.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        })
    };
    BtfTextures {
        color: array_view(&textures[0]),
        diffuse: array_view(&textures[1]),
        extra: array_view(&textures[2]),
        bytes: texture_bytes(width, height, array_layers(layers)),
        textures,
    }
}

/// A 2D view of one layer at one mip level.
fn layer_view(t: &wgpu::Texture, layer: u32, level: u32) -> wgpu::TextureView {
    t.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(wgpu::TextureViewDimension::D2),
        base_mip_level: level,
        mip_level_count: Some(1),
        base_array_layer: layer,
        array_layer_count: Some(1),
        ..Default::default()
    })
}

/// The mip chain's pipeline (`shaders/mip.wgsl`), made once per bake.
struct MipPipeline {
    layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
    pipeline: grassbench::shaders::RenderPipeline,
}

impl MipPipeline {
    fn new(ctx: &InitContext<'_>) -> Self {
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
                texture_entry(3),
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
        let targets = [target.clone(), target.clone(), target];
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
                constants: &[],
            },
        );
        Self {
            layout,
            sampler,
            pipeline,
        }
    }

    /// Each level the 2x2 box average of the one above, of single-layer textures.
    fn build(
        &self,
        ctx: &InitContext<'_>,
        encoder: &mut wgpu::CommandEncoder,
        textures: &[wgpu::Texture; 3],
        levels: u32,
    ) {
        let device = &ctx.gpu.device;
        let (layout, sampler, pipeline) = (&self.layout, &self.sampler, &self.pipeline);
        for level in 1..levels {
            let src = textures.each_ref().map(|t| layer_view(t, 0, level - 1));
            let dst = textures.each_ref().map(|t| layer_view(t, 0, level));
            let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("boulanger mip"),
                layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: wgpu::BindingResource::TextureView(&src[0]),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::TextureView(&src[1]),
                    },
                    wgpu::BindGroupEntry {
                        binding: 3,
                        resource: wgpu::BindingResource::TextureView(&src[2]),
                    },
                    wgpu::BindGroupEntry {
                        binding: 2,
                        resource: wgpu::BindingResource::Sampler(sampler),
                    },
                ],
            });
            let attachments: Vec<_> = dst
                .iter()
                .map(|view| {
                    Some(wgpu::RenderPassColorAttachment {
                        view,
                        depth_slice: None,
                        resolve_target: None,
                        ops: wgpu::Operations {
                            load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                            store: wgpu::StoreOp::Store,
                        },
                    })
                })
                .collect();
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("boulanger mip"),
                color_attachments: &attachments,
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, &ctx.scene_gpu.bind_group, &[]);
            pass.set_bind_group(1, &group, &[]);
            pass.draw(0..3, 0..1);
        }
    }
}

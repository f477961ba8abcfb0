//! What the technique keeps on the GPU: the pre-computed patches (blades, segment tilts,
//! painted coordinates), the posture table, the strip and 2D texture arrays, the three
//! pipelines, and the per-frame entries and receivers (grown when a frame needs more).

use grassbench::color::srgb_encode;
use grassbench::wgpu::util::DeviceExt as _;
use grassbench::{Error, FrameEncoder, GpuContext, InitContext, Result, bytemuck, shaders, wgpu};

use crate::frame::Entry;
use crate::paint::Image;

/// The shader (without the prelude).
pub const SHADER: &str = include_str!("../shaders/perbet.wgsl");

/// Cells per side of the 2D surface of a patch (it follows the terrain).
pub const FLAT_CELLS: u32 = 4;

/// One blade of a pre-computed patch on the GPU (the shader's `Blade`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct BladeGpu {
    /// Root x, z in the patch; facing; height.
    pub root_facing: [f32; 4],
    /// Width, colour variation, density threshold, unused.
    pub shape: [f32; 4],
    /// The strip painting the blade, per orientation; its kind; unused.
    pub strips: [u32; 4],
}

/// Mirror of the shader's `Params` uniform.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ParamsUniform {
    /// Patch size, strip height, strip margin, height of the 2D surface.
    pub sizes: [f32; 4],
    /// Blades per patch, segments, strips per orientation, polygons along a strip.
    pub counts: [u32; 4],
    /// Postures per kind, variants, 2D cells per side, the kind strip edges bend as.
    pub more: [u32; 4],
    /// Root colour; w: colour variation.
    pub color_root: [f32; 4],
    /// Tip colour; w: translucency.
    pub color_tip: [f32; 4],
    /// First strips entry, first 2D entry.
    pub bases: [u32; 4],
    /// Elevations of the 2D textures, radians (`paint::FLAT_ELEVATIONS`).
    pub flat_elevations: [f32; 4],
    /// Patches of the tiling along x and z; unused, unused.
    pub tiling: [u32; 4],
}

/// The static data the GPU needs, made on the CPU.
pub struct Statics<'a> {
    /// Blades of every variant, variant-major.
    pub blades: &'a [BladeGpu],
    /// Rest tilt of every segment of every blade.
    pub tilts: &'a [[f32; 2]],
    /// Painted coordinates of every point of every blade, per orientation.
    pub painted: &'a [[f32; 2]],
    /// The posture tables of every kind, kind after kind.
    pub postures: &'a [f32],
    /// Strip textures: one mip chain per layer.
    pub strip_layers: &'a [Vec<Image>],
    /// 2D textures: one mip chain per variant and elevation.
    pub flat_layers: &'a [Vec<Image>],
    /// The variant each patch of the tiling shows, row-major.
    pub variants: &'a [u32],
    /// Segments per blade (strip rows): the shader's `SEGMENTS`, which its loops run to.
    pub segments: u32,
}

/// A storage buffer that grows to what a frame needs.
struct Growing {
    label: &'static str,
    buffer: wgpu::Buffer,
}

impl Growing {
    /// A buffer of `bytes` (the expected need; at most what one binding may hold).
    fn new(device: &wgpu::Device, label: &'static str, bytes: u64) -> Self {
        let max = device.limits().max_storage_buffer_binding_size;
        Self {
            label,
            buffer: storage(device, label, bytes.clamp(16, max.max(16))),
        }
    }

    /// Makes room for `bytes` (twice as much, to grow rarely); true if the buffer was replaced.
    /// More than one storage binding may hold is an error naming the fix.
    fn reserve(&mut self, device: &wgpu::Device, bytes: u64) -> Result<bool> {
        if bytes <= self.buffer.size() {
            return Ok(false);
        }
        let max = device.limits().max_storage_buffer_binding_size;
        if bytes > max {
            return Err(Error::Technique {
                technique: "perbet".into(),
                message: format!(
                    "this frame's {} need {bytes} bytes but the device binds at most {max}; \
                     lower blades_per_patch (or the scene's grass density) or draw fewer patches \
                     in 3D (a smaller strip_range[0])",
                    self.label
                ),
            });
        }
        let size = bytes.saturating_mul(2).min(max);
        self.buffer = storage(device, self.label, size);
        Ok(true)
    }
}

fn storage(device: &wgpu::Device, label: &str, bytes: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: bytes.next_multiple_of(16),
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// GPU resources of the technique.
pub struct Gpu {
    blade_pipeline: grassbench::shaders::RenderPipeline,
    strip_pipeline: grassbench::shaders::RenderPipeline,
    flat_pipeline: grassbench::shaders::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    params: wgpu::Buffer,
    blades: wgpu::Buffer,
    tilts: wgpu::Buffer,
    painted: wgpu::Buffer,
    postures: wgpu::Buffer,
    variants: wgpu::Buffer,
    strip_color: wgpu::TextureView,
    strip_aux: wgpu::TextureView,
    flat_color: wgpu::TextureView,
    flat_aux: wgpu::TextureView,
    clamp_sampler: wgpu::Sampler,
    repeat_sampler: wgpu::Sampler,
    entries: Growing,
    blade_receivers: Growing,
    edge_receivers: Growing,
    bind_group: wgpu::BindGroup,
    /// Bytes of the static resources.
    static_bytes: u64,
}

/// Sizes of one frame's draws.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Draws {
    /// 3D entries.
    pub geometry: u32,
    /// Strip entries.
    pub strips: u32,
    /// 2D entries.
    pub flat: u32,
    /// Vertices of one blade, one strip, one 2D patch.
    pub vertices: [u32; 3],
    /// Blades per patch and strips per patch.
    pub per_entry: [u32; 2],
}

impl Gpu {
    /// Uploads `statics`, builds the pipelines and per-frame buffers for `capacity` entries,
    /// blade receivers and edge receivers.
    pub fn new(ctx: &InitContext<'_>, statics: &Statics<'_>, capacity: [u64; 3]) -> Self {
        let device = &ctx.gpu.device;
        let init = |label: &str, contents: &[u8]| {
            // Storage bindings cannot be empty.
            let padded;
            let contents = if contents.is_empty() {
                padded = [0u8; 16];
                &padded[..]
            } else {
                contents
            };
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage: wgpu::BufferUsages::STORAGE,
            })
        };
        let blades = init("perbet blades", bytemuck::cast_slice(statics.blades));
        let tilts = init("perbet tilts", bytemuck::cast_slice(statics.tilts));
        let painted = init("perbet painted", bytemuck::cast_slice(statics.painted));
        let postures = init("perbet postures", bytemuck::cast_slice(statics.postures));
        let variants = init("perbet variants", bytemuck::cast_slice(statics.variants));
        let (strip_color, a) = upload_array(ctx, "perbet strips", statics.strip_layers, true);
        let (strip_aux, b) = upload_array(ctx, "perbet strips aux", statics.strip_layers, false);
        let (flat_color, c) = upload_array(ctx, "perbet 2D", statics.flat_layers, true);
        let (flat_aux, d) = upload_array(ctx, "perbet 2D aux", statics.flat_layers, false);
        let params = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("perbet params"),
            size: std::mem::size_of::<ParamsUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let sampler = |label: &str, mode: wgpu::AddressMode| {
            device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some(label),
                address_mode_u: mode,
                address_mode_v: mode,
                mag_filter: wgpu::FilterMode::Linear,
                min_filter: wgpu::FilterMode::Linear,
                mipmap_filter: wgpu::MipmapFilterMode::Linear,
                ..Default::default()
            })
        };
        let clamp_sampler = sampler("perbet clamp", wgpu::AddressMode::ClampToEdge);
        let repeat_sampler = sampler("perbet repeat", wgpu::AddressMode::Repeat);
        let layout = bind_group_layout(device);
        let entries = Growing::new(device, "perbet entries", capacity[0] * 32);
        let blade_receivers = Growing::new(device, "perbet blade receivers", capacity[1] * 16);
        let edge_receivers = Growing::new(device, "perbet edge receivers", capacity[2] * 16);

        let module = shaders::module(device, "perbet", SHADER);
        let pipeline_layout = ctx.scene_gpu.pipeline_layout(device, "perbet", &[&layout]);
        let blend = [Some(wgpu::ColorTargetState {
            format: grassbench::target::COLOR_FORMAT,
            blend: Some(wgpu::BlendState::ALPHA_BLENDING),
            write_mask: wgpu::ColorWrites::ALL,
        })];
        let constants = [("SEGMENTS", f64::from(statics.segments))];
        let pipeline = |label: &str, entry: (&str, &str), topology| {
            let mut spec = shaders::PipelineSpec::new(
                label,
                &pipeline_layout,
                &module,
                entry,
                &[],
                ctx.sample_count,
            );
            spec.primitive.topology = topology;
            spec.targets = &blend;
            spec.constants = &constants;
            shaders::render_pipeline(device, &spec)
        };
        let blade_pipeline = pipeline(
            "perbet 3D blades",
            ("vs_blade", "fs_blade"),
            wgpu::PrimitiveTopology::TriangleStrip,
        );
        let strip_pipeline = pipeline(
            "perbet 2.5D strips",
            ("vs_strip", "fs_strip"),
            wgpu::PrimitiveTopology::TriangleList,
        );
        let flat_pipeline = pipeline(
            "perbet 2D",
            ("vs_flat", "fs_flat"),
            wgpu::PrimitiveTopology::TriangleList,
        );
        let static_bytes = [&blades, &tilts, &painted, &postures, &variants, &params]
            .iter()
            .map(|b| b.size())
            .sum::<u64>()
            + a
            + b
            + c
            + d;
        let bind_group = bind_group(
            device,
            &layout,
            [
                &params,
                &entries.buffer,
                &blades,
                &tilts,
                &painted,
                &postures,
                &blade_receivers.buffer,
                &edge_receivers.buffer,
            ],
            [&strip_color, &strip_aux, &flat_color, &flat_aux],
            [&clamp_sampler, &repeat_sampler],
            &variants,
        );
        Self {
            bind_group,
            blade_pipeline,
            strip_pipeline,
            flat_pipeline,
            layout,
            params,
            blades,
            tilts,
            painted,
            postures,
            variants,
            strip_color,
            strip_aux,
            flat_color,
            flat_aux,
            clamp_sampler,
            repeat_sampler,
            entries,
            blade_receivers,
            edge_receivers,
            static_bytes,
        }
    }

    fn rebind(&mut self, device: &wgpu::Device) {
        self.bind_group = bind_group(
            device,
            &self.layout,
            [
                &self.params,
                &self.entries.buffer,
                &self.blades,
                &self.tilts,
                &self.painted,
                &self.postures,
                &self.blade_receivers.buffer,
                &self.edge_receivers.buffer,
            ],
            [
                &self.strip_color,
                &self.strip_aux,
                &self.flat_color,
                &self.flat_aux,
            ],
            [&self.clamp_sampler, &self.repeat_sampler],
            &self.variants,
        );
    }

    /// Uploads one frame: the uniform, the entries and the receivers (growing their buffers
    /// if needed; an error if they would exceed what the adapter can bind).
    pub fn upload(
        &mut self,
        gpu: &GpuContext,
        params: &ParamsUniform,
        entries: &[Entry],
        blade_receivers: &[[f32; 4]],
        edge_receivers: &[[f32; 4]],
    ) -> Result<()> {
        let device = &gpu.device;
        let entry_bytes = std::mem::size_of_val(entries) as u64;
        let blade_bytes = std::mem::size_of_val(blade_receivers) as u64;
        let edge_bytes = std::mem::size_of_val(edge_receivers) as u64;
        let grew = self.entries.reserve(device, entry_bytes)?
            | self.blade_receivers.reserve(device, blade_bytes)?
            | self.edge_receivers.reserve(device, edge_bytes)?;
        if grew {
            self.rebind(device);
        }
        gpu.write_buffer(&self.params, 0, bytemuck::bytes_of(params));
        gpu.write_buffer(&self.entries.buffer, 0, bytemuck::cast_slice(entries));
        gpu.write_buffer(
            &self.blade_receivers.buffer,
            0,
            bytemuck::cast_slice(blade_receivers),
        );
        gpu.write_buffer(
            &self.edge_receivers.buffer,
            0,
            bytemuck::cast_slice(edge_receivers),
        );
        Ok(())
    }

    /// Bytes held: static resources and the per-frame buffers as they are now.
    pub fn bytes(&self) -> u64 {
        self.static_bytes
            + self.entries.buffer.size()
            + self.blade_receivers.buffer.size()
            + self.edge_receivers.buffer.size()
    }

    /// Records the frame: 2D, then strips, then 3D blades (far to near, Sec. 2.2); nothing when
    /// there is nothing to draw.
    pub fn encode(&self, encoder: &mut FrameEncoder<'_>, draws: &Draws) {
        if draws.geometry == 0 && draws.strips == 0 && draws.flat == 0 {
            // Nothing in view grows (e.g. `grass.density = 0`): no pass at all.
            return;
        }
        let mut pass = encoder.render_pass("prairie");
        pass.set_bind_group(1, &self.bind_group, &[]);
        let [blade_vertices, strip_vertices, flat_vertices] = draws.vertices;
        let [blades, strips] = draws.per_entry;
        if draws.flat > 0 {
            pass.set_pipeline(&self.flat_pipeline);
            pass.draw(0..flat_vertices, 0..draws.flat);
        }
        if draws.strips > 0 {
            pass.set_pipeline(&self.strip_pipeline);
            pass.draw(0..strip_vertices, 0..draws.strips * strips);
        }
        if draws.geometry > 0 {
            pass.set_pipeline(&self.blade_pipeline);
            pass.draw(0..blade_vertices, 0..draws.geometry * blades);
        }
    }
}

/// Group 1: buffers at bindings 0-7, texture arrays at 8-11, samplers at 12-13, the patches'
/// variants (read by 2D fragments) at 14 (the shader's order).
fn bind_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    buffers: [&wgpu::Buffer; 8],
    views: [&wgpu::TextureView; 4],
    samplers: [&wgpu::Sampler; 2],
    variants: &wgpu::Buffer,
) -> wgpu::BindGroup {
    let mut entries: Vec<wgpu::BindGroupEntry<'_>> = Vec::with_capacity(15);
    for (i, b) in buffers.into_iter().enumerate() {
        entries.push(wgpu::BindGroupEntry {
            binding: i as u32,
            resource: b.as_entire_binding(),
        });
    }
    for (i, v) in views.into_iter().enumerate() {
        entries.push(wgpu::BindGroupEntry {
            binding: 8 + i as u32,
            resource: wgpu::BindingResource::TextureView(v),
        });
    }
    for (i, s) in samplers.into_iter().enumerate() {
        entries.push(wgpu::BindGroupEntry {
            binding: 12 + i as u32,
            resource: wgpu::BindingResource::Sampler(s),
        });
    }
    entries.push(wgpu::BindGroupEntry {
        binding: 14,
        resource: variants.as_entire_binding(),
    });
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("perbet (group 1)"),
        layout,
        entries: &entries,
    })
}

fn bind_group_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let vf = wgpu::ShaderStages::VERTEX_FRAGMENT;
    let storage = |binding| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::VERTEX,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only: true },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    };
    let texture = |binding| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: true },
            view_dimension: wgpu::TextureViewDimension::D2Array,
            multisampled: false,
        },
        count: None,
    };
    let sampler = |binding| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
        count: None,
    };
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("perbet (group 1)"),
        entries: &[
            wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: vf,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            },
            storage(1),
            storage(2),
            storage(3),
            storage(4),
            storage(5),
            storage(6),
            storage(7),
            texture(8),
            texture(9),
            texture(10),
            texture(11),
            sampler(12),
            sampler(13),
            wgpu::BindGroupLayoutEntry {
                binding: 14,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ..storage(14)
            },
        ],
    })
}

fn unorm8(v: f32) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// Bytes per texel of the colour (sRGB + alpha) and auxiliary (threshold, height, face) arrays.
pub const fn texel_bytes(_color: bool) -> u64 {
    4
}

/// Uploads a texture array of `layers` (each a full mip chain, all alike): their colour
/// (`Rgba8UnormSrgb`) or their auxiliary triple (`Rgba8Unorm`). Returns the view and its bytes.
fn upload_array(
    ctx: &InitContext<'_>,
    label: &str,
    layers: &[Vec<Image>],
    color: bool,
) -> (wgpu::TextureView, u64) {
    let (width, height) = layers
        .first()
        .and_then(|l| l.first())
        .map_or((1, 1), |i| (i.width, i.height));
    let mips = layers.first().map_or(1, |l| l.len().max(1)) as u32;
    let format = if color {
        wgpu::TextureFormat::Rgba8UnormSrgb
    } else {
        wgpu::TextureFormat::Rgba8Unorm
    };
    let texture = ctx.gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: layers.len().max(1) as u32,
        },
        mip_level_count: mips,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    let mut bytes = 0;
    for (layer, chain) in layers.iter().enumerate() {
        for (mip, image) in chain.iter().enumerate() {
            let data: Vec<u8> = if color {
                image
                    .color
                    .iter()
                    .flat_map(|c| {
                        [
                            srgb_encode(c[0]),
                            srgb_encode(c[1]),
                            srgb_encode(c[2]),
                            unorm8(c[3]),
                        ]
                    })
                    .collect()
            } else {
                image
                    .aux
                    .iter()
                    .flat_map(|a| [unorm8(a[0]), unorm8(a[1]), unorm8(a[2]), 255])
                    .collect()
            };
            bytes += data.len() as u64;
            ctx.gpu.write_texture(
                wgpu::TexelCopyTextureInfo {
                    texture: &texture,
                    mip_level: mip as u32,
                    origin: wgpu::Origin3d {
                        x: 0,
                        y: 0,
                        z: layer as u32,
                    },
                    aspect: wgpu::TextureAspect::All,
                },
                &data,
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(image.width * texel_bytes(color) as u32),
                    rows_per_image: Some(image.height),
                },
                wgpu::Extent3d {
                    width: image.width,
                    height: image.height,
                    depth_or_array_layers: 1,
                },
            );
        }
    }
    let view = texture.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(wgpu::TextureViewDimension::D2Array),
        ..Default::default()
    });
    (view, bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gpu_structs_mirror_the_shader() {
        for (name, size) in [
            ("Params", std::mem::size_of::<ParamsUniform>()),
            ("Entry", std::mem::size_of::<crate::frame::Entry>()),
            ("Blade", std::mem::size_of::<BladeGpu>()),
        ] {
            assert_eq!(
                grassbench::shaders::struct_size(SHADER, name).unwrap() as usize,
                size,
                "perbet {name}"
            );
        }
    }
}

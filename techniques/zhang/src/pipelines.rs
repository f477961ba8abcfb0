//! The shaders, the vertex layouts of the instance data ([`shader_data`](crate::shader_data)),
//! the procedural textures, and the blade, flower and billboard pipelines
//! (group 1 = uniform + blade texture + petal texture array + sampler + billboard texture
//! array).

use grassbench::wgpu::util::DeviceExt as _;
use grassbench::{InitContext, bytemuck, shaders, wgpu};

use crate::billboard_texture;
use crate::params::WingLighting;
use crate::prairie::PETAL_TEXTURES;
use crate::shader_data::{BladeDynamic, BladeStatic, FlowerInstance, ParamsUniform, WingInstance};
use crate::textures::{BLADE_SIZE, PETAL_SIZE, blade_texture, petal_textures};

/// The blade and flower shader (without the prelude).
pub const SHADER: &str = include_str!("../shaders/blade.wgsl");
/// The billboard shader (without the prelude).
pub const BILLBOARD_SHADER: &str = include_str!("../shaders/billboard.wgsl");

const BLADE_LAYOUTS: [wgpu::VertexBufferLayout<'static>; 2] = [
    wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<BladeStatic>() as u64,
        step_mode: wgpu::VertexStepMode::Instance,
        attributes: &wgpu::vertex_attr_array![0 => Float32x4, 1 => Float32x4],
    },
    wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<BladeDynamic>() as u64,
        step_mode: wgpu::VertexStepMode::Instance,
        attributes: &wgpu::vertex_attr_array![2 => Float32x4, 3 => Float32x4, 4 => Float32x4],
    },
];

const FLOWER_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: std::mem::size_of::<FlowerInstance>() as u64,
    step_mode: wgpu::VertexStepMode::Instance,
    attributes: &wgpu::vertex_attr_array![0 => Float32x4, 1 => Float32x4],
};

const WING_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: std::mem::size_of::<WingInstance>() as u64,
    step_mode: wgpu::VertexStepMode::Instance,
    attributes: &wgpu::vertex_attr_array![
        0 => Float32x4, 1 => Float32x4, 2 => Float32x4, 3 => Float32x4, 4 => Float32x4
    ],
};

/// Blending of Eq. (10): `C = S·S_a + D·(1 − S_a)` for colour and alpha alike.
const EQ10: wgpu::BlendComponent = wgpu::BlendComponent {
    src_factor: wgpu::BlendFactor::SrcAlpha,
    dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
    operation: wgpu::BlendOperation::Add,
};

/// The harness's colour target blended with Eq. (10) (Sec. 5.4).
const BLENDED_TARGETS: &[Option<wgpu::ColorTargetState>] = &[Some(wgpu::ColorTargetState {
    format: grassbench::target::COLOR_FORMAT,
    blend: Some(wgpu::BlendState {
        color: EQ10,
        alpha: EQ10,
    }),
    write_mask: wgpu::ColorWrites::ALL,
})];

/// The technique's pipelines and group-1 resources.
pub struct Pipelines {
    /// Blade strips.
    pub blades: grassbench::shaders::RenderPipeline,
    /// Petal quads.
    pub flowers: grassbench::shaders::RenderPipeline,
    /// Billboard wings, lit by the ambient and the sun (per vertex).
    pub wings: grassbench::shaders::RenderPipeline,
    /// Billboard wings with the point light added per pixel, for frames that have one.
    pub wings_point_lit: grassbench::shaders::RenderPipeline,
    /// Group 1.
    pub bind_group: wgpu::BindGroup,
    /// Bytes of textures and uniform.
    pub bytes: u64,
}

fn texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    (width, height, layers): (u32, u32, u32),
    texels: &[[u8; 4]],
) -> wgpu::Texture {
    device.create_texture_with_data(
        queue,
        &wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: layers,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba8Unorm,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        bytemuck::cast_slice(texels),
    )
}

impl Pipelines {
    /// GPU memory of the textures and the uniform, with `layers` billboard texture layers.
    pub const fn bytes(layers: u32) -> u64 {
        (BLADE_SIZE.0 * BLADE_SIZE.1 * 4) as u64
            + (PETAL_SIZE * PETAL_SIZE * 4 * PETAL_TEXTURES) as u64
            + (billboard_texture::SIZE.0 * billboard_texture::SIZE.1 * 4) as u64 * layers as u64
            + std::mem::size_of::<ParamsUniform>() as u64
    }

    /// Creates textures, uniform, bind group and the pipelines; `billboard` holds `layers`
    /// layers of the billboard texture ([`billboard_texture::billboard_texture`]). With
    /// `blend`, blades and wings are blended with Eq. (10) (drawn far to near, Sec. 5.4);
    /// without, they are alpha-tested (alpha to coverage under MSAA). Petals are always
    /// alpha-tested (drawn first, they need no order).
    pub fn new(
        ctx: &InitContext<'_>,
        uniform: &ParamsUniform,
        seed: u64,
        (billboard, layers): (&[[u8; 4]], u32),
        blend: bool,
        wing_lighting: WingLighting,
    ) -> Self {
        let device = &ctx.gpu.device;
        let queue = &ctx.gpu.queue;
        let blade_tex = texture(
            device,
            queue,
            "zhang blade texture",
            (BLADE_SIZE.0, BLADE_SIZE.1, 1),
            &blade_texture(seed),
        );
        let petal_tex = texture(
            device,
            queue,
            "zhang petal textures",
            (PETAL_SIZE, PETAL_SIZE, PETAL_TEXTURES),
            &petal_textures(),
        );
        let billboard_tex = texture(
            device,
            queue,
            "zhang billboard texture",
            (billboard_texture::SIZE.0, billboard_texture::SIZE.1, layers),
            billboard,
        );
        let uniform_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("zhang params"),
            contents: bytemuck::bytes_of(uniform),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("zhang textures"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let tex_entry = |binding, dim| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: true },
                view_dimension: dim,
                multisampled: false,
            },
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("zhang (group 1)"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
                tex_entry(1, wgpu::TextureViewDimension::D2),
                tex_entry(2, wgpu::TextureViewDimension::D2Array),
                wgpu::BindGroupLayoutEntry {
                    binding: 3,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    count: None,
                },
                tex_entry(4, wgpu::TextureViewDimension::D2Array),
            ],
        });
        let blade_view = blade_tex.create_view(&Default::default());
        let petal_view = petal_tex.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        let billboard_view = billboard_tex.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("zhang (group 1)"),
            layout: &layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: uniform_buffer.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&blade_view),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(&petal_view),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: wgpu::BindingResource::Sampler(&sampler),
                },
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: wgpu::BindingResource::TextureView(&billboard_view),
                },
            ],
        });
        let module = shaders::module(device, "zhang", SHADER);
        let billboard_module = shaders::module(device, "zhang billboards", BILLBOARD_SHADER);
        let pipeline_layout = ctx.scene_gpu.pipeline_layout(device, "zhang", &[&layout]);
        let pipeline = |label,
                        module: &grassbench::shaders::Module,
                        (vs, fs),
                        blended: bool,
                        buffers: &[Option<wgpu::VertexBufferLayout<'_>>]| {
            let spec = shaders::PipelineSpec::new(
                label,
                &pipeline_layout,
                module,
                (vs, fs),
                buffers,
                ctx.sample_count,
            );
            shaders::render_pipeline(
                device,
                &shaders::PipelineSpec {
                    multisample: wgpu::MultisampleState {
                        // With MSAA the texture's alpha also drives coverage (smoother
                        // cut-outs); the alpha test still discards the clear part.
                        alpha_to_coverage_enabled: ctx.sample_count > 1 && !blended,
                        ..spec.multisample
                    },
                    targets: if blended {
                        BLENDED_TARGETS
                    } else {
                        spec.targets
                    },
                    ..spec
                },
            )
        };
        let blades = pipeline(
            "zhang blades",
            &module,
            ("vs_blade", "fs_blade"),
            blend,
            &[
                Some(BLADE_LAYOUTS[0].clone()),
                Some(BLADE_LAYOUTS[1].clone()),
            ],
        );
        let flowers = pipeline(
            "zhang flowers",
            &module,
            ("vs_flower", "fs_flower"),
            false,
            &[Some(FLOWER_LAYOUT.clone())],
        );
        // Per pixel, one fragment shader serves frames with and without a point light.
        let (plain, point_lit) = match wing_lighting {
            WingLighting::Vertex => ("fs_wing", "fs_wing_point_lit"),
            WingLighting::Pixel => ("fs_wing_pixel_lit", "fs_wing_pixel_lit"),
        };
        let wings = pipeline(
            "zhang billboard wings",
            &billboard_module,
            ("vs_wing", plain),
            blend,
            &[Some(WING_LAYOUT.clone())],
        );
        let wings_point_lit = pipeline(
            "zhang billboard wings (point light)",
            &billboard_module,
            ("vs_wing", point_lit),
            blend,
            &[Some(WING_LAYOUT.clone())],
        );
        Self {
            blades,
            flowers,
            wings,
            wings_point_lit,
            bind_group,
            bytes: Self::bytes(layers),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shader_data::ParamsUniform;

    #[test]
    fn the_parameter_uniform_mirrors_both_shaders() {
        for source in [SHADER, BILLBOARD_SHADER] {
            assert_eq!(
                grassbench::shaders::struct_size(source, "Params").unwrap() as usize,
                std::mem::size_of::<ParamsUniform>()
            );
        }
    }
}

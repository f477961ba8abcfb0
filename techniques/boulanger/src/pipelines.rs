//! The technique's bind group layouts and render pipelines, all from one shader module
//! ([`SHADER`]): the geometric blades (Sec. 3.2), the horizontal and vertical slices (Sec. 3.3),
//! the ground shadows (Sec. 3.5, [`crate::ground_shadow`]) and the BTF bake (Sec. 3.3, 4x MSAA
//! into three targets, [`crate::btf`]).
//!
//! Bind groups: 0 is the core's frame globals; 1 ([`Layouts::shared`]) the technique's
//! parameters, blade texture, samplers, shadow mask and ambient occlusion map, read by every
//! pipeline; 2 the geometry cells and the patch's blades ([`Layouts::cells`], blade and bake
//! pipelines) or the BTFs and the orientation map ([`Layouts::slices`], slice pipelines); 3 the
//! bake's blade list ([`Layouts::bake_refs`]).

use grassbench::shaders::{self, PipelineSpec, depth_less, render_pipeline};
use grassbench::{InitContext, target, wgpu};

use crate::btf;
use crate::cells;
use crate::ground_shadow::GroundShadows;
use crate::params::{Params, Transparency};
use crate::shader::{CellRecord, SHADER, SliceQuad};
use crate::texture;

/// The grass shader's textures and the formats bound to them, for the cost model (a fetch of
/// floating-point texels costs more: `grassbench::shaders::module_with_formats`): the blade
/// texture, the ambient occlusion and orientation maps, and the BTF bakes (slices and the
/// ground's shadow mask, `Rgba16Float`).
const TEXTURE_FORMATS: [(&str, wgpu::TextureFormat); 10] = [
    ("blade_texture", texture::FORMAT),
    ("ao_map", crate::gpu::AO_FORMAT),
    ("orientation_map", crate::slice::ORIENTATION_FORMAT),
    ("shadow_mask", btf::FORMAT),
    ("slice_color", btf::FORMAT),
    ("slice_diffuse", btf::FORMAT),
    ("slice_extra", btf::FORMAT),
    ("vslice_color", btf::FORMAT),
    ("vslice_diffuse", btf::FORMAT),
    ("vslice_extra", btf::FORMAT),
];

/// The bind group layouts of groups 1 to 3.
pub struct Layouts {
    /// Group 1 of every pipeline: params (0), blade texture (1), clamping and repeating
    /// samplers (2, 3), shadow mask (4), ambient occlusion map (5).
    pub shared: wgpu::BindGroupLayout,
    /// Group 2 of the blade and bake pipelines ([`cells::layout`]).
    pub cells: wgpu::BindGroupLayout,
    /// Group 2 of the slice pipelines: the three textures of each BTF (1, 2, 5 horizontal;
    /// 6, 7, 8 vertical) and the orientation map (3).
    pub slices: wgpu::BindGroupLayout,
    /// Group 3 of the bake ([`btf::refs_layout`]).
    pub bake_refs: wgpu::BindGroupLayout,
}

impl Layouts {
    /// Creates the four layouts.
    pub fn new(device: &wgpu::Device) -> Self {
        let vf = wgpu::ShaderStages::VERTEX_FRAGMENT;
        // A filterable float texture of `view_dimension` at `binding`.
        let texture_entry = |binding, view_dimension| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: vf,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: true },
                view_dimension,
                multisampled: false,
            },
            count: None,
        };
        let float_texture = |binding| texture_entry(binding, wgpu::TextureViewDimension::D2);
        let array_texture = |binding| texture_entry(binding, wgpu::TextureViewDimension::D2Array);
        let sampler_entry = |binding| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: vf,
            ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
            count: None,
        };
        let shared = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("boulanger (group 1)"),
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
                float_texture(1),
                sampler_entry(2),
                sampler_entry(3),
                array_texture(4),
                float_texture(5),
            ],
        });
        let cells = cells::layout(device);
        let slices = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("boulanger slices (group 2)"),
            entries: &[
                array_texture(1),
                array_texture(2),
                array_texture(5),
                array_texture(6),
                array_texture(7),
                array_texture(8),
                wgpu::BindGroupLayoutEntry {
                    binding: 3,
                    visibility: vf,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Uint,
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
            ],
        });
        Self {
            shared,
            cells,
            slices,
            bake_refs: btf::refs_layout(device),
        }
    }
}

/// The render pipelines.
pub struct Pipelines {
    /// The geometric blades (`vs_blade`, `fs_blade`; blade layout).
    pub blades: grassbench::shaders::RenderPipeline,
    /// The horizontal slice quads (`vs_slice`, `fs_slice`; slice layout).
    pub horizontal_slices: grassbench::shaders::RenderPipeline,
    /// The vertical slices (`vs_vslice`, `fs_vslice`; slice layout).
    pub vertical_slices: grassbench::shaders::RenderPipeline,
    /// Sec. 3.5's shadows on the ground, when `ground_shadows` is on.
    pub ground_shadows: Option<GroundShadows>,
    /// The BTF bake (`vs_bake`, `fs_bake`): three [`btf::FORMAT`] targets, 4x MSAA.
    pub bake: grassbench::shaders::RenderPipeline,
}

impl Pipelines {
    /// Builds every pipeline for the frame's target (`ctx.sample_count`) and the bake's.
    pub fn new(ctx: &InitContext<'_>, layouts: &Layouts, params: &Params) -> Self {
        let device = &ctx.gpu.device;
        let a2c = params.transparency == Transparency::AlphaToCoverage;
        let module =
            shaders::module_with_formats(device, "boulanger grass", SHADER, &TEXTURE_FORMATS);
        let blade_layout = ctx.scene_gpu.pipeline_layout(
            device,
            "boulanger blades",
            &[&layouts.shared, &layouts.cells],
        );
        let slice_layout = ctx.scene_gpu.pipeline_layout(
            device,
            "boulanger slice",
            &[&layouts.shared, &layouts.slices],
        );
        let blend = (!a2c).then_some(wgpu::BlendState::ALPHA_BLENDING);
        let color_target = [Some(wgpu::ColorTargetState {
            format: target::COLOR_FORMAT,
            blend,
            write_mask: wgpu::ColorWrites::ALL,
        })];
        let multisample = wgpu::MultisampleState {
            count: ctx.sample_count,
            alpha_to_coverage_enabled: a2c,
            ..Default::default()
        };
        let strip = wgpu::PrimitiveState {
            topology: wgpu::PrimitiveTopology::TriangleStrip,
            cull_mode: None,
            ..Default::default()
        };
        let spec = |label, layout, vertex, fragment, buffers| PipelineSpec {
            label,
            layout,
            module: &module,
            vertex,
            fragment,
            buffers,
            primitive: strip,
            depth: depth_less(target::DEPTH_FORMAT, true),
            multisample,
            targets: &color_target,
            constants: &[],
        };
        let blades = render_pipeline(
            device,
            &spec(
                "boulanger blades",
                &blade_layout,
                "vs_blade",
                "fs_blade",
                &[],
            ),
        );
        let quad_buffers = [Some(SliceQuad::LAYOUT)];
        let horizontal_slices = render_pipeline(
            device,
            &PipelineSpec {
                primitive: wgpu::PrimitiveState {
                    cull_mode: None,
                    ..Default::default()
                },
                ..spec(
                    "boulanger horizontal slice",
                    &slice_layout,
                    "vs_slice",
                    "fs_slice",
                    &quad_buffers,
                )
            },
        );
        let vertical_slices = render_pipeline(
            device,
            &PipelineSpec {
                primitive: wgpu::PrimitiveState {
                    cull_mode: None,
                    ..Default::default()
                },
                ..spec(
                    "boulanger vertical slices",
                    &slice_layout,
                    "vs_vslice",
                    "fs_vslice",
                    &[Some(CellRecord::LAYOUT)],
                )
            },
        );
        let ground_shadows = params.ground_shadows.then(|| {
            GroundShadows::new(
                device,
                &module,
                [
                    &blade_layout,
                    &slice_layout,
                    &ctx.scene_gpu
                        .pipeline_layout(device, "boulanger shadow cover", &[]),
                ],
                ctx.sample_count,
            )
        });
        // The BTF bake (Sec. 3.3): the blade shader in baking mode, three targets, 4x MSAA.
        let bake_layout = ctx.scene_gpu.pipeline_layout(
            device,
            "boulanger BTF bake",
            &[&layouts.shared, &layouts.cells, &layouts.bake_refs],
        );
        let bake_target = Some(wgpu::ColorTargetState::from(btf::FORMAT));
        let bake_targets = [bake_target.clone(), bake_target.clone(), bake_target];
        let bake = render_pipeline(
            device,
            &PipelineSpec {
                depth: depth_less(wgpu::TextureFormat::Depth32Float, true),
                multisample: wgpu::MultisampleState {
                    count: 4,
                    ..Default::default()
                },
                targets: &bake_targets,
                ..spec(
                    "boulanger BTF bake",
                    &bake_layout,
                    "vs_bake",
                    "fs_bake",
                    &[],
                )
            },
        );
        Self {
            blades,
            horizontal_slices,
            vertical_slices,
            ground_shadows,
            bake,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_texture_is_named_with_its_format() {
        // The cost model prices fetches of floating-point texels apart (the slices'
        // `Rgba16Float`): a texture missing from the list would be priced as RGBA8, a
        // misspelt one never. The prelude's are the core's.
        let composed = shaders::compose(SHADER);
        let module = naga::front::wgsl::parse_str(&composed)
            .map_err(|e| e.emit_to_string(&composed))
            .unwrap_or_else(|e| panic!("{e}"));
        let mut named: Vec<&str> = TEXTURE_FORMATS
            .iter()
            .chain(&shaders::PRELUDE_TEXTURES)
            .map(|(n, _)| *n)
            .collect();
        named.sort_unstable();
        assert_eq!(shaders::texture_globals(&module), named);
        // The slices' samples are the floating-point ones; both also sample the ambient
        // occlusion map (one byte a texel).
        let float = shaders::float_textures(&TEXTURE_FORMATS);
        let bound = shaders::Bound {
            float: &float,
            single_level: &[],
        };
        let ops = shaders::entry_ops(&module, bound, &[]);
        let of = |entry: &str| {
            ops.iter()
                .find(|(e, _)| e == entry)
                .map(|(_, o)| (o.samples, o.float_samples))
        };
        assert_eq!(of("fs_slice"), Some((1, 3)));
        assert_eq!(of("fs_vslice"), Some((1, 3)));
        assert_eq!(
            of("fs_blade").map(|(normalised, _)| normalised > 0),
            Some(true)
        );
    }
}

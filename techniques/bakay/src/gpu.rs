//! What the shells keep on the GPU: the grass texture (two planes, full mip chain), the
//! per-vertex wind and per-shell offsets written by the bend pass, the chunks it bends this
//! frame, and the two pipelines.

use grassbench::terrain::GroundVertex;
use grassbench::wgpu::util::DeviceExt as _;
use grassbench::{Error, InitContext, Result, bytemuck, shaders, target, wgpu};

use crate::chunks::{CHUNK, Chunks, Plan};
use crate::lod::{LEVEL_INSTANCES, ShellLod};
use crate::params::{Lod, Mipmaps, Params};
use crate::texture::{GrassTexture, Level};

/// The shader (without the prelude): the bend pass and the shells.
pub const SHADER: &str = include_str!("../shaders/bakay.wgsl");

/// The shader's sampler of the shell texture (`grass_sampler`): where its mipmap filter is
/// `Nearest` the module is created saying so ([`shaders::module_with_bindings`]).
const SAMPLER: &str = "grass_sampler";

/// Mirror of the shader's `Params` uniform.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ParamsUniform {
    /// Shells, ground vertices, wind mode (0 = scene, 1 = point source), ground vertices along
    /// x (a row of the mesh, for the bend pass's chunks).
    pub counts: [u32; 4],
    /// Inter-shell distance (m), stiffness exponent, largest |I|, reference speed (m/s).
    pub shape: [f32; 4],
    /// Point source position; w = period (s).
    pub source: [f32; 4],
    /// Step length (m), step delay (s), bias, 1 / tile size (1/m).
    pub steps: [f32; 4],
    /// Root albedo over tip albedo; w = translucency.
    pub color_ratio: [f32; 4],
}

/// Pipelines, bind groups and the buffers and textures they hold.
pub struct ShellGpu {
    bend: shaders::ComputePipeline,
    bend_group: wgpu::BindGroup,
    shells: grassbench::shaders::RenderPipeline,
    shell_group: wgpu::BindGroup,
    /// The ground mesh's triangles chunk by chunk ([`crate::chunks`]).
    indices: wgpu::Buffer,
    /// The first cell of each chunk the bend pass moves this frame ([`Plan::bent`]).
    bent: wgpu::Buffer,
    /// GPU memory held, bytes.
    pub bytes: u64,
}

/// The shells' fragment entry point for level-of-detail mode `lod`: one entry point each, with
/// no branch on the mode (a SIMD rasteriser runs both sides of a branch, even on a uniform:
/// lavapipe paid a second lookup a texture for it).
pub fn fragment_entry(lod: Lod) -> &'static str {
    match lod {
        Lod::MinorAxis => "fs_shell_minor_axis",
        Lod::Hardware => "fs_shell_hardware",
    }
}

/// Workgroup size of `cs_bend`.
const WORKGROUP: u32 = 64;

/// Workgroups of `cs_bend` a chunk: its `(CHUNK + 1)²` vertices, 64 a workgroup (the shader
/// finds its chunk and its vertex from the workgroup's index the same way).
pub const BEND_WORKGROUPS_PER_CHUNK: u32 = ((CHUNK + 1) * (CHUNK + 1)).div_ceil(WORKGROUP);

impl ShellGpu {
    /// Uploads the texture, allocates the per-vertex buffers and builds both pipelines (the
    /// sampler and the fragment entry point from `params`' mip levels, level of detail and
    /// anisotropy).
    pub fn new(
        ctx: &InitContext<'_>,
        chunks: &Chunks,
        uniform: &ParamsUniform,
        texture: &GrassTexture,
        params: &Params,
    ) -> Result<Self> {
        let Params {
            mipmaps,
            anisotropy,
            lod,
            ..
        } = *params;
        let device = &ctx.gpu.device;
        let terrain = &ctx.scene_gpu.terrain;
        let (nx, nz) = terrain.ground_side;
        let vertex_count = nx * nz;
        let shells = uniform.counts[0];
        let wind_bytes = u64::from(vertex_count) * 16;
        let offset_bytes = u64::from(vertex_count) * u64::from(shells) * 8;
        let max = device.limits().max_storage_buffer_binding_size;
        if offset_bytes > max {
            return Err(Error::Technique {
                technique: "bakay".into(),
                message: format!(
                    "{shells} shells over {vertex_count} ground vertices need {offset_bytes} bytes of offsets, more than this adapter's {max}-byte storage bindings; lower bakay.shells"
                ),
            });
        }
        let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("bakay params"),
            contents: bytemuck::bytes_of(uniform),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let storage = |label, size| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            })
        };
        let vertex_wind = storage("bakay vertex wind", wind_bytes);
        let offsets = storage("bakay shell offsets", offset_bytes);
        let bent_bytes = chunks.len().max(1) as u64 * 8;
        let bent = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("bakay bent chunks"),
            size: bent_bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let color_height = upload(ctx, "bakay colour+height", &texture.levels, true);
        let blade = upload(ctx, "bakay blade attributes", &texture.levels, false);
        let mipmap_filter = if mipmaps == Mipmaps::Box {
            wgpu::MipmapFilterMode::Linear
        } else {
            wgpu::MipmapFilterMode::Nearest
        };
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("bakay grass"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            // Blending two representative levels would average two different blades: the felt
            // custom mips avoid. Box levels are averages anyway.
            mipmap_filter,
            anisotropy_clamp: anisotropy,
            ..Default::default()
        });

        let entry = |binding, stage, ty| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: stage,
            ty,
            count: None,
        };
        let buffer = |ty| wgpu::BindingType::Buffer {
            ty,
            has_dynamic_offset: false,
            min_binding_size: None,
        };
        let read = wgpu::BufferBindingType::Storage { read_only: true };
        let write = wgpu::BufferBindingType::Storage { read_only: false };
        let uniform_ty = buffer(wgpu::BufferBindingType::Uniform);
        let compute = wgpu::ShaderStages::COMPUTE;
        let both = wgpu::ShaderStages::VERTEX_FRAGMENT;
        let texture_ty = wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: true },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        };
        let bend_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("bakay bend (group 1)"),
            entries: &[
                entry(0, compute, uniform_ty),
                entry(1, compute, buffer(read)),
                entry(2, compute, buffer(write)),
                entry(3, compute, buffer(write)),
                entry(9, compute, buffer(read)),
            ],
        });
        let shell_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("bakay shells (group 1)"),
            entries: &[
                entry(0, both, uniform_ty),
                entry(4, wgpu::ShaderStages::VERTEX, buffer(read)),
                entry(5, wgpu::ShaderStages::VERTEX, buffer(read)),
                entry(6, wgpu::ShaderStages::FRAGMENT, texture_ty),
                entry(7, wgpu::ShaderStages::FRAGMENT, texture_ty),
                entry(
                    8,
                    wgpu::ShaderStages::FRAGMENT,
                    wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                ),
            ],
        });
        let bind = |binding, resource| wgpu::BindGroupEntry { binding, resource };
        let bend_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("bakay bend (group 1)"),
            layout: &bend_layout,
            entries: &[
                bind(0, params.as_entire_binding()),
                bind(1, terrain.ground_vertices.as_entire_binding()),
                bind(2, vertex_wind.as_entire_binding()),
                bind(3, offsets.as_entire_binding()),
                bind(9, bent.as_entire_binding()),
            ],
        });
        let shell_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("bakay shells (group 1)"),
            layout: &shell_layout,
            entries: &[
                bind(0, params.as_entire_binding()),
                bind(4, vertex_wind.as_entire_binding()),
                bind(5, offsets.as_entire_binding()),
                bind(6, wgpu::BindingResource::TextureView(&color_height)),
                bind(7, wgpu::BindingResource::TextureView(&blade)),
                bind(8, wgpu::BindingResource::Sampler(&sampler)),
            ],
        });

        // Through a `Nearest` mipmap filter every lookup filters one level: the op counter
        // must not count it as blending two (`shaders::ShaderOps::mip_blends`).
        let single_level: &[&str] = if mipmap_filter == wgpu::MipmapFilterMode::Nearest {
            &[SAMPLER]
        } else {
            &[]
        };
        let module = shaders::module_with_bindings(device, "bakay", SHADER, &[], single_level);
        let constants = [("SHELLS", f64::from(shells)), ("CHUNK", f64::from(CHUNK))];
        let bend = shaders::compute_pipeline(
            device,
            "bakay bend",
            &ctx.scene_gpu
                .pipeline_layout(device, "bakay bend", &[&bend_layout]),
            &module,
            "cs_bend",
            &constants,
        );
        let shell_pipeline_layout =
            ctx.scene_gpu
                .pipeline_layout(device, "bakay shells", &[&shell_layout]);
        let buffers = [Some(GroundVertex::LAYOUT)];
        let shells_pipeline = shaders::render_pipeline(
            device,
            &shaders::PipelineSpec {
                primitive: wgpu::PrimitiveState {
                    topology: wgpu::PrimitiveTopology::TriangleList,
                    // A camera down in the grass sees shells from below.
                    cull_mode: None,
                    ..Default::default()
                },
                // Shell 0 lies exactly on the core's ground (same vertices, same transform).
                depth: shaders::depth_test(
                    target::DEPTH_FORMAT,
                    wgpu::CompareFunction::LessEqual,
                    true,
                ),
                constants: &constants,
                ..shaders::PipelineSpec::new(
                    "bakay shells",
                    &shell_pipeline_layout,
                    &module,
                    ("vs_shell", fragment_entry(lod)),
                    &buffers,
                    ctx.sample_count,
                )
            },
        );
        let indices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("bakay chunked ground indices"),
            contents: bytemuck::cast_slice(&chunks.indices),
            usage: wgpu::BufferUsages::INDEX,
        });
        Ok(Self {
            bend,
            bend_group,
            shells: shells_pipeline,
            shell_group,
            indices,
            bent,
            bytes: std::mem::size_of_val(chunks.indices.as_slice()) as u64
                + bent_bytes
                + texture.bytes()
                + wind_bytes
                + offset_bytes
                + std::mem::size_of::<ParamsUniform>() as u64,
        })
    }

    /// Uploads the first cells of the chunks `plan` bends.
    pub fn upload(&self, gpu: &grassbench::GpuContext, plan: &Plan) {
        if !plan.bent.is_empty() {
            gpu.write_buffer(&self.bent, 0, bytemuck::cast_slice(&plan.bent));
        }
    }

    /// Records the bend pass (per-vertex wind, running sums) over the vertices of the chunks
    /// `plan` draws, uploaded by [`Self::upload`], and the shells of its draws (each a run of
    /// chunks at one level of detail), each draw's shells bottom to top.
    pub fn encode(&self, encoder: &mut grassbench::FrameEncoder<'_>, lod: &ShellLod, plan: &Plan) {
        if plan.draws.is_empty() {
            return;
        }
        {
            let mut pass = encoder.compute_pass("bend");
            pass.set_pipeline(&self.bend);
            pass.set_bind_group(1, &self.bend_group, &[]);
            // At most 225 chunks (a ground mesh is at most `MAX_GROUND_SIDE` = 241 vertices a
            // side, 15 chunks): 1 125 workgroups, far under the 65 535 a dimension every
            // adapter offers.
            pass.dispatch_workgroups(plan.bent.len() as u32 * BEND_WORKGROUPS_PER_CHUNK, 1, 1);
        }
        let vertices = encoder.scene.terrain.ground_vertices.slice(..);
        let mut pass = encoder.render_pass("shells");
        pass.set_pipeline(&self.shells);
        pass.set_bind_group(1, &self.shell_group, &[]);
        pass.set_vertex_buffer(0, vertices);
        pass.set_index_buffer(self.indices.slice(..), wgpu::IndexFormat::Uint32);
        // Instance `level · LEVEL_INSTANCES + i` is the level's `i`-th shell from the bottom:
        // instances are drawn in order, so shells go bottom to top.
        for draw in &plan.draws {
            let first = draw.level * LEVEL_INSTANCES;
            pass.draw_indexed(
                draw.indices.clone(),
                0,
                first..first + lod.shells_at(draw.level),
            );
        }
    }
}

/// One plane of the texture with every level of the chain.
fn upload(ctx: &InitContext<'_>, label: &str, levels: &[Level], color: bool) -> wgpu::TextureView {
    let size = levels.first().map_or(1, |l| l.size);
    let (format, texel) = if color {
        (wgpu::TextureFormat::Rgba8UnormSrgb, 4)
    } else {
        (wgpu::TextureFormat::Rg8Unorm, 2)
    };
    let texture = ctx.gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: size,
            height: size,
            depth_or_array_layers: 1,
        },
        mip_level_count: levels.len().max(1) as u32,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    for (mip, level) in levels.iter().enumerate() {
        let data: &[u8] = if color {
            bytemuck::cast_slice(&level.color_height)
        } else {
            bytemuck::cast_slice(&level.blade)
        };
        ctx.gpu.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: mip as u32,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            data,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(level.size * texel),
                rows_per_image: Some(level.size),
            },
            wgpu::Extent3d {
                width: level.size,
                height: level.size,
                depth_or_array_layers: 1,
            },
        );
    }
    texture.create_view(&Default::default())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_mirror_matches_the_shader() {
        assert_eq!(
            shaders::struct_size(SHADER, "Params").unwrap() as usize,
            std::mem::size_of::<ParamsUniform>()
        );
    }

    #[test]
    fn each_level_of_detail_mode_looks_each_texture_up_once() {
        // The op counter counts both sides of a branch, as a SIMD rasteriser runs them: an
        // entry point that chose its lookup by a branch on the mode would count 4.
        let module = naga::front::wgsl::parse_str(&shaders::compose(SHADER)).unwrap();
        let ops = |single_level: &[&str]| {
            let bound = shaders::Bound {
                float: &[],
                single_level,
            };
            shaders::entry_ops(&module, bound, &[])
        };
        // The sampler named as reading one level is the shader's.
        assert!(
            module
                .global_variables
                .iter()
                .any(|(_, g)| g.name.as_deref() == Some(SAMPLER))
        );
        for (single_level, blends) in [(&[][..], 2), (&[SAMPLER][..], 0)] {
            for lod in [Lod::MinorAxis, Lod::Hardware] {
                let entry = fragment_entry(lod);
                let samples = ops(single_level)
                    .into_iter()
                    .find(|(e, _)| e == entry)
                    .map(|(_, o)| (o.samples, o.mip_blends));
                // The colour and height, then (for the texels kept) the blade's attributes;
                // each blending two levels unless the sampler reads one.
                assert_eq!(samples, Some((2, blends)), "{entry}");
            }
        }
    }
}

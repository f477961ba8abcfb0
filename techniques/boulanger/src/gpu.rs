//! What the technique keeps on the GPU: the patch's blades, the shared resources of group 1
//! (parameters, blade texture, samplers, shadow mask, ambient occlusion map), the baked BTFs
//! and the orientation map of the slices, the per-frame buffers of geometry cells, slice quads
//! and vertical-slice cells (grown by powers of two), and the pipelines
//! ([`crate::pipelines`]). [`BoulangerGpu::new`] builds them and runs the start-up bakes
//! ([`crate::bakes`]); each frame [`BoulangerGpu::upload`] writes the [`FramePlan`] and
//! [`BoulangerGpu::encode`] draws it.

use glam::Vec3;
use grassbench::bytemuck::Zeroable as _;
use grassbench::technique::RenderPass;
use grassbench::wgpu::util::DeviceExt as _;
use grassbench::{Error, FrameEncoder, GpuContext, InitContext, Result, bytemuck, wgpu};

use crate::bakes::{self, BakeReport};
use crate::btf::{self, BakeInputs};
use crate::cells;
use crate::ground_shadow::{self, GroundShadows};
use crate::occlusion;
use crate::params::{Params, Transparency};
use crate::pipelines::{Layouts, Pipelines};
use crate::plan::FramePlan;
use crate::shader::{CellRecord, ParamsUniform, SliceQuad};
use crate::slice;
use crate::texture;
use crate::tiling::Tiling;

/// Slice quads (and cells with vertical slices) the buffers hold at first (they grow by powers
/// of two).
pub const INITIAL_QUADS: usize = 256;

/// Format of the ambient occlusion map (one byte a texel).
pub const AO_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R8Unorm;

/// The shaders' uniform block.
pub fn params_uniform(params: &Params, grass: &grassbench::grass::GrassConfig) -> ParamsUniform {
    let a2c = params.transparency == Transparency::AlphaToCoverage;
    let tallest = grass.height[1];
    ParamsUniform {
        color_root: Vec3::from(grass.color_root)
            .extend(grass.color_variation)
            .to_array(),
        color_tip: Vec3::from(grass.color_tip)
            .extend(params.translucency)
            .to_array(),
        blade: [
            params.segments as f32,
            params.gravity,
            if params.animate {
                params.wind_response
            } else {
                0.0
            },
            params.ao_root,
        ],
        lod: [
            params.min_geom,
            params.max_geom,
            params.omega,
            if a2c {
                1.0 / 255.0
            } else {
                params.alpha_threshold
            },
        ],
        tile: [
            params.patch_size,
            params.slice_height * tallest,
            params.slice_resolution as f32,
            1.3 * tallest + 0.05,
        ],
        btf: [
            params.vertical_slices as f32,
            params.min_btf,
            params.max_btf,
            f32::from(u8::from(params.shadow_mask)),
        ],
    }
}

/// Pipelines, bind groups and the buffers and textures they hold.
pub struct BoulangerGpu {
    /// The geometric blades.
    blade_pipeline: grassbench::shaders::RenderPipeline,
    /// The horizontal slice quads.
    horizontal_slice_pipeline: grassbench::shaders::RenderPipeline,
    /// The vertical slices.
    vertical_slice_pipeline: grassbench::shaders::RenderPipeline,
    /// Sec. 3.5's shadows on the ground, when `ground_shadows` is on.
    pub ground_shadows: Option<GroundShadows>,
    /// Group 1 of every pipeline, with the baked shadow mask.
    shared_group: wgpu::BindGroup,
    /// Layout of the geometry cells' group, for a grown buffer.
    cell_layout: wgpu::BindGroupLayout,
    /// The geometry cells' group (a page at a dynamic offset, the patch's blades).
    cell_group: wgpu::BindGroup,
    /// This frame's geometry cells.
    cell_buffer: wgpu::Buffer,
    /// Cells `cell_buffer` holds.
    cell_capacity: usize,
    /// How geometry cells are paged into draws.
    pub paging: cells::Paging,
    /// Group 2 of the slice pipelines: the BTFs and the orientation map.
    slice_group: wgpu::BindGroup,
    /// The patch's blades (storage buffer).
    blades: wgpu::Buffer,
    /// This frame's horizontal slice quads (instances).
    quad_buffer: wgpu::Buffer,
    /// Quads `quad_buffer` holds.
    quad_capacity: usize,
    /// This frame's cells with vertical slices (instances).
    vslice_buffer: wgpu::Buffer,
    /// Cells `vslice_buffer` holds.
    vslice_capacity: usize,
    /// Bytes of everything that does not grow.
    fixed_bytes: u64,
}

impl BoulangerGpu {
    /// Uploads the patch and the maps, builds the pipelines and bakes the shadow mask and the
    /// BTFs (or loads them from the cache); returns how the BTFs were obtained.
    pub fn new(
        ctx: &InitContext<'_>,
        params: &Params,
        uniform: &ParamsUniform,
        tiling: &Tiling,
    ) -> Result<(Self, BakeReport)> {
        let device = &ctx.gpu.device;
        let patch = &tiling.patch;
        // An empty patch (no grass) still binds one record, which nothing draws.
        let padding = [crate::patch::PatchBlade::zeroed()];
        let records = if patch.blades.is_empty() {
            &padding[..]
        } else {
            &patch.blades[..]
        };
        let blades = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("boulanger patch blades"),
            contents: bytemuck::cast_slice(records),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let uniform_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("boulanger params"),
            contents: bytemuck::bytes_of(uniform),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let (blade_texture, blade_texture_bytes) = texture::upload(device, &ctx.gpu.queue);
        let sampler = |label, address| {
            device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some(label),
                address_mode_u: address,
                address_mode_v: address,
                mag_filter: wgpu::FilterMode::Linear,
                min_filter: wgpu::FilterMode::Linear,
                mipmap_filter: wgpu::MipmapFilterMode::Linear,
                ..Default::default()
            })
        };
        let clamp_sampler = sampler("boulanger blade", wgpu::AddressMode::ClampToEdge);
        let repeat_sampler = sampler("boulanger slice", wgpu::AddressMode::Repeat);
        let layouts = Layouts::new(device);
        // Sec. 3.5's ambient occlusion map (one white texel when it is off).
        let (ao_view, ao_bytes) = ao_texture(
            device,
            &ctx.gpu.queue,
            params.external_ao.then(|| {
                occlusion::visibility_map(
                    &ctx.scene.terrain,
                    params.tree_height,
                    params.stone_height,
                )
            }),
        );
        // Group 1 with a shadow mask: the mask's own bake sees a transparent one (no shadow).
        let shared_group_with = |mask: &wgpu::TextureView| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("boulanger (group 1)"),
                layout: &layouts.shared,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 4,
                        resource: wgpu::BindingResource::TextureView(mask),
                    },
                    wgpu::BindGroupEntry {
                        binding: 5,
                        resource: wgpu::BindingResource::TextureView(&ao_view),
                    },
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: uniform_buffer.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::TextureView(&blade_texture),
                    },
                    wgpu::BindGroupEntry {
                        binding: 2,
                        resource: wgpu::BindingResource::Sampler(&clamp_sampler),
                    },
                    wgpu::BindGroupEntry {
                        binding: 3,
                        resource: wgpu::BindingResource::Sampler(&repeat_sampler),
                    },
                ],
            })
        };
        let no_mask = btf::create_textures(device, 1, 1, 1);
        let no_mask_group = shared_group_with(&btf::wrap(no_mask, 1, 1, 1).color);
        let pipelines = Pipelines::new(ctx, &layouts, params);
        // The shadow mask first (Sec. 3.5): the blades and the BTF bake are lit through it.
        let unshadowed = BakeInputs {
            pipeline: &pipelines.bake,
            group1: &no_mask_group,
            cell_layout: &layouts.cells,
            refs_layout: &layouts.bake_refs,
            blades: &blades,
            vertices: 2 * params.segments + 2,
        };
        let mask = bakes::shadow_mask(ctx, &unshadowed, params, patch)?;
        let shared_group = shared_group_with(&mask.color);
        let shadowed = BakeInputs {
            group1: &shared_group,
            ..unshadowed
        };
        let btfs = bakes::slice_btfs(ctx, &shadowed, params, uniform, patch)?;
        let grid = tiling.tree.grid();
        let (orientation, orientation_bytes) =
            slice::orientation_map(device, &ctx.gpu.queue, grid, tiling.seed);
        let view = |binding, view| wgpu::BindGroupEntry {
            binding,
            resource: wgpu::BindingResource::TextureView(view),
        };
        let slice_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("boulanger slice (group 2)"),
            layout: &layouts.slices,
            entries: &[
                view(1, &btfs.horizontal.color),
                view(2, &btfs.horizontal.diffuse),
                view(5, &btfs.horizontal.extra),
                view(6, &btfs.verticals.color),
                view(7, &btfs.verticals.diffuse),
                view(8, &btfs.verticals.extra),
                view(3, &orientation),
            ],
        });
        let blade_bytes = std::mem::size_of_val(records) as u64;
        let paging = cells::Paging::new(patch.blades.len() as u32, &device.limits());
        let cell_capacity = paging.capacity(0);
        let (cell_buffer, cell_group) = cells::buffer(
            device,
            &layouts.cells,
            &blades,
            cell_capacity,
            paging.binding_cells(cell_capacity),
        );
        let gpu = Self {
            blade_pipeline: pipelines.blades,
            horizontal_slice_pipeline: pipelines.horizontal_slices,
            vertical_slice_pipeline: pipelines.vertical_slices,
            ground_shadows: pipelines.ground_shadows,
            shared_group,
            cell_layout: layouts.cells,
            cell_group,
            cell_buffer,
            cell_capacity,
            paging,
            slice_group,
            blades,
            quad_buffer: quad_buffer(device, INITIAL_QUADS),
            quad_capacity: INITIAL_QUADS,
            vslice_buffer: vslice_buffer(device, INITIAL_QUADS),
            vslice_capacity: INITIAL_QUADS,
            fixed_bytes: blade_bytes
                + mask.bytes
                + ao_bytes
                + btfs.horizontal.bytes
                + btfs.verticals.bytes
                + orientation_bytes
                + blade_texture_bytes
                + std::mem::size_of::<ParamsUniform>() as u64,
        };
        Ok((gpu, btfs.report))
    }

    /// GPU memory held, bytes.
    pub fn bytes(&self) -> u64 {
        self.fixed_bytes
            + self.cell_capacity as u64 * cells::CELL_BYTES
            + (self.quad_capacity * std::mem::size_of::<SliceQuad>()) as u64
            + (self.vslice_capacity * std::mem::size_of::<CellRecord>()) as u64
    }

    /// Grows the per-frame buffers to fit `plan` and writes it.
    pub fn upload(&mut self, gpu: &GpuContext, plan: &FramePlan) -> Result<()> {
        let device = &gpu.device;
        if plan.geometry.len() > self.cell_capacity {
            let capacity = self.paging.capacity(plan.geometry.len());
            if capacity as u64 * cells::CELL_BYTES > u64::from(u32::MAX) {
                return Err(Error::Technique {
                    technique: "boulanger".to_owned(),
                    message: format!(
                        "{} geometry cells in one frame do not fit one buffer: lower max_geom or raise patch_size",
                        plan.geometry.len()
                    ),
                });
            }
            self.cell_capacity = capacity;
            (self.cell_buffer, self.cell_group) = cells::buffer(
                device,
                &self.cell_layout,
                &self.blades,
                capacity,
                self.paging.binding_cells(capacity),
            );
        }
        if plan.slice_quads.len() > self.quad_capacity {
            self.quad_capacity = plan.slice_quads.len().next_power_of_two();
            self.quad_buffer = quad_buffer(device, self.quad_capacity);
        }
        if plan.vslice_records.len() > self.vslice_capacity {
            self.vslice_capacity = plan.vslice_records.len().next_power_of_two();
            self.vslice_buffer = vslice_buffer(device, self.vslice_capacity);
        }
        if !plan.vslice_records.is_empty() {
            gpu.write_buffer(
                &self.vslice_buffer,
                0,
                bytemuck::cast_slice(&plan.vslice_records),
            );
        }
        if !plan.geometry.is_empty() {
            let records: Vec<CellRecord> = plan.geometry.iter().map(|c| c.record).collect();
            gpu.write_buffer(&self.cell_buffer, 0, bytemuck::cast_slice(&records));
        }
        if !plan.slice_quads.is_empty() {
            gpu.write_buffer(
                &self.quad_buffer,
                0,
                bytemuck::cast_slice(&plan.slice_quads),
            );
        }
        Ok(())
    }

    /// Records `plan`'s passes: the ground shadows, the horizontal slices, the vertical slices,
    /// then the geometric blades.
    pub fn encode(&self, encoder: &mut FrameEncoder<'_>, plan: &FramePlan, params: &Params) {
        let vertices = 2 * params.segments + 2;
        if let Some(shadows) = &self.ground_shadows
            && !(plan.geometry.is_empty() && plan.slice_quads.is_empty())
        {
            // Sec. 3.5, before the grass: blades into the stencil, the cover, then the slices.
            let mut pass = encoder.render_pass("ground_shadows");
            pass.set_stencil_reference(ground_shadow::STENCIL_MARK);
            pass.set_bind_group(1, &self.shared_group, &[]);
            if !plan.geometry.is_empty() {
                pass.set_pipeline(&shadows.blades);
                self.draw_geometry(&mut pass, plan, vertices);
                pass.set_pipeline(&shadows.cover);
                pass.draw(0..3, 0..1);
            }
            if !plan.slice_quads.is_empty() {
                pass.set_pipeline(&shadows.slices);
                pass.set_bind_group(2, &self.slice_group, &[]);
                self.draw_quads(&mut pass, plan);
            }
        }
        if !plan.slice_quads.is_empty() {
            let mut pass = encoder.render_pass("horizontal_slice");
            pass.set_pipeline(&self.horizontal_slice_pipeline);
            pass.set_bind_group(1, &self.shared_group, &[]);
            pass.set_bind_group(2, &self.slice_group, &[]);
            self.draw_quads(&mut pass, plan);
        }
        if !plan.vslice_records.is_empty() {
            let mut pass = encoder.render_pass("vertical_slices");
            pass.set_pipeline(&self.vertical_slice_pipeline);
            pass.set_bind_group(1, &self.shared_group, &[]);
            pass.set_bind_group(2, &self.slice_group, &[]);
            pass.set_vertex_buffer(0, self.vslice_buffer.slice(..));
            pass.draw(
                0..12 * params.vertical_slices,
                0..plan.vslice_records.len() as u32,
            );
        }
        if !plan.geometry.is_empty() {
            let mut pass = encoder.render_pass("geometry");
            pass.set_pipeline(&self.blade_pipeline);
            pass.set_bind_group(1, &self.shared_group, &[]);
            self.draw_geometry(&mut pass, plan, vertices);
        }
    }

    /// Records `plan`'s geometric blades (`vertices` a strip) with the pass's pipeline (blade
    /// layout: the cells in group 2, one dynamic offset per page).
    fn draw_geometry(&self, pass: &mut RenderPass<'_>, plan: &FramePlan, vertices: u32) {
        for page in &plan.pages {
            // In range: `upload` refuses a buffer over 4 GiB.
            let offset = (u64::from(page.first_cell) * cells::CELL_BYTES) as u32;
            pass.set_bind_group(2, &self.cell_group, &[offset]);
            for r in &page.draws {
                pass.draw(0..vertices, r.clone());
            }
        }
    }

    /// Records `plan`'s horizontal slice quads with the pass's pipeline (slice layout), one
    /// draw per tessellation.
    fn draw_quads(&self, pass: &mut RenderPass<'_>, plan: &FramePlan) {
        pass.set_vertex_buffer(0, self.quad_buffer.slice(..));
        for (tess, range) in &plan.quad_groups {
            pass.draw(0..tess * tess * 6, range.clone());
        }
    }
}

fn quad_buffer(device: &wgpu::Device, capacity: usize) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("boulanger slice quads"),
        size: (capacity * std::mem::size_of::<SliceQuad>()) as u64,
        usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

fn vslice_buffer(device: &wgpu::Device, capacity: usize) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("boulanger vertical slice cells"),
        size: (capacity * std::mem::size_of::<CellRecord>()) as u64,
        usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// The ambient visibility map as an `R8Unorm` texture (a white texel without one) and its
/// bytes.
fn ao_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    map: Option<grassbench::terrain::Grid<f32>>,
) -> (wgpu::TextureView, u64) {
    let (w, h, data) = match map {
        Some(m) => (
            m.width() as u32,
            m.height() as u32,
            m.data()
                .iter()
                .map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
                .collect(),
        ),
        None => (1, 1, vec![255u8]),
    };
    let texture = device.create_texture_with_data(
        queue,
        &wgpu::TextureDescriptor {
            label: Some("boulanger ambient occlusion map"),
            size: wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: AO_FORMAT,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        &data,
    );
    (texture.create_view(&Default::default()), data.len() as u64)
}

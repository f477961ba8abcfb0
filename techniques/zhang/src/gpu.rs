//! What the technique keeps on the GPU and how a frame uses it: the blades' static and
//! per-frame instance buffers, the flowers', the wings', the far-to-near copies of the single
//! plants (with sorting, Sec. 5.4), and the [`Pipelines`] with their textures and uniform.
//! (The covering map's trees and stones of Sec. 5.5.2 are the core's: it draws them for every
//! technique, `grassbench::scene::props`.) Set up once; `prepare` uploads what the
//! frame animated ([`PrairieGpu::upload`]), `encode` draws it ([`PrairieGpu::encode`]).

use std::ops::Range;

use grassbench::glam::Vec3;
use grassbench::gpu::GpuEstimate;
use grassbench::technique::RenderPass;
use grassbench::wgpu::util::DeviceExt as _;
use grassbench::{FrameEncoder, GpuContext, InitContext, Scene, bytemuck, wgpu};

use crate::animate::Animation;
use crate::frame_plan::FramePlan;
use crate::params::{Params, Sorting};
use crate::pipelines::Pipelines;
use crate::plants::{BillboardTexels, Plants, blade_static};
use crate::prairie::{Layout, Planted};
use crate::shader_data::{BladeDynamic, BladeStatic, FlowerInstance, ParamsUniform, WingInstance};
use crate::{billboard, lod};

/// Pipelines, textures, uniform and every buffer the technique draws from.
pub struct PrairieGpu {
    pipelines: Pipelines,
    /// Every blade's static instance data.
    statics: wgpu::Buffer,
    /// Every blade's control points (the drawn ones rewritten each frame).
    dynamics: wgpu::Buffer,
    /// Every flower's petal (the animated ones rewritten each frame).
    flowers: wgpu::Buffer,
    /// The frame's wings (room for the most a frame can draw).
    wings: wgpu::Buffer,
    /// With sorting: the frame's single plants far to near (static data, control points).
    sorted: Option<(wgpu::Buffer, wgpu::Buffer)>,
    /// GPU memory held, bytes.
    pub bytes: u64,
}

/// A vertex buffer holding `bytes`.
fn buffer(
    device: &wgpu::Device,
    label: &str,
    bytes: &[u8],
    usage: wgpu::BufferUsages,
) -> wgpu::Buffer {
    // An empty buffer cannot be bound: keep 64 zero bytes (drawn with 0 instances).
    let zeros = [0u8; 64];
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: if bytes.is_empty() { &zeros } else { bytes },
        usage,
    })
}

/// Writes the `ranges` of `data` to the same places of `buffer`.
fn upload<T: bytemuck::Pod>(
    gpu: &GpuContext,
    buffer: &wgpu::Buffer,
    data: &[T],
    ranges: &[Range<u32>],
) {
    let each = std::mem::size_of::<T>() as u64;
    for r in ranges {
        let r = (r.start as usize).min(data.len())..(r.end as usize).min(data.len());
        if !r.is_empty() {
            let bytes = bytemuck::cast_slice(&data[r.clone()]);
            gpu.write_buffer(buffer, r.start as u64 * each, bytes);
        }
    }
}

/// The shaders' uniform for `params` on `scene`.
fn uniform(params: &Params, scene: &grassbench::Scene, billboard_height: f32) -> ParamsUniform {
    let grass = &scene.config.grass;
    ParamsUniform {
        color_root: Vec3::from(grass.color_root)
            .extend(grass.color_variation)
            .to_array(),
        color_tip: Vec3::from(grass.color_tip)
            .extend(params.translucency)
            .to_array(),
        shape: [
            params.backbone_points as f32,
            params.effective_alpha_cutoff(),
            params.petal_size,
            billboard_height,
        ],
        modes: [
            f32::from(u8::from(params.sorting == Sorting::Sort)),
            0.0,
            0.0,
            0.0,
        ],
    }
}

impl PrairieGpu {
    /// Uploads the blades `planted` and `plants`' animation at rest, allocates the per-frame
    /// buffers, builds the pipelines with the billboard `texture`.
    pub fn new(
        ctx: &InitContext<'_>,
        params: &Params,
        plants: &Plants,
        planted: &[Planted],
        texture: &BillboardTexels,
    ) -> Self {
        let scene = ctx.scene;
        let device = &ctx.gpu.device;
        let sort = params.sorting == Sorting::Sort;
        let usage = wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST;
        let statics: Vec<BladeStatic> = planted.iter().map(blade_static).collect();
        let statics = buffer(
            device,
            "zhang blades (static)",
            bytemuck::cast_slice(&statics),
            usage,
        );
        let blades: &Animation = &plants.blades;
        let dynamics = buffer(
            device,
            "zhang blades (control points)",
            bytemuck::cast_slice(&blades.blade_out),
            usage,
        );
        let flowers = buffer(
            device,
            "zhang flowers",
            bytemuck::cast_slice(&blades.flower_out),
            usage,
        );
        let wing_count = plants.billboards.max_wings();
        let wings = buffer(
            device,
            "zhang billboard wings",
            bytemuck::cast_slice(&vec![WingInstance::default(); wing_count]),
            usage,
        );
        let uniform = uniform(params, scene, plants.billboard_height);
        let pipelines = Pipelines::new(
            ctx,
            &uniform,
            scene.config.seed,
            (&texture.texels, texture.layers),
            sort,
            params.wing_lighting,
        );
        let sorted = sort.then(|| {
            let capacity = sorted_capacity(params, &plants.layout, planted.len() as u64) as usize;
            (
                buffer(
                    device,
                    "zhang blades far to near (static)",
                    bytemuck::cast_slice(&vec![BladeStatic::default(); capacity]),
                    usage,
                ),
                buffer(
                    device,
                    "zhang blades far to near (control points)",
                    bytemuck::cast_slice(&vec![BladeDynamic::default(); capacity]),
                    usage,
                ),
            )
        });
        let bytes = statics.size()
            + dynamics.size()
            + flowers.size()
            + wings.size()
            + sorted.as_ref().map_or(0, |(s, d)| s.size() + d.size())
            + pipelines.bytes;
        Self {
            pipelines,
            statics,
            dynamics,
            flowers,
            wings,
            sorted,
            bytes,
        }
    }

    /// Uploads what `frame` animated: the blades and flowers of the grids up to two away (all
    /// of them without LOD) from `blades`, the far grids' wings and, with sorting, the single
    /// plants in draw order.
    pub fn upload(&self, gpu: &GpuContext, frame: &FramePlan, blades: &Animation) {
        let plan = &frame.plan;
        upload(gpu, &self.dynamics, &blades.blade_out, &plan.animate_blades);
        upload(
            gpu,
            &self.flowers,
            &blades.flower_out,
            &plan.animate_flowers,
        );
        let wings = 0..frame.wings.len() as u32;
        upload(gpu, &self.wings, &frame.wings, std::slice::from_ref(&wings));
        if let (Some(s), Some((statics, dynamics))) = (&frame.sorted, &self.sorted) {
            let all = 0..s.order.len() as u32;
            let all = std::slice::from_ref(&all);
            upload(gpu, statics, &s.statics, all);
            upload(gpu, dynamics, &s.dynamics, all);
        }
    }

    /// Draws `frame` with blades of `backbone_points` backbone points. Without sorting: wings, then the near grids' blade ranges, then petals
    /// (all alpha-tested). Sorting (Sec. 5.4): petals first (alpha-tested, they need no
    /// order), then the wings and the single plants far to near, blended (Eq. 10).
    pub fn encode(&self, encoder: &mut FrameEncoder<'_>, frame: &FramePlan, backbone_points: u32) {
        let v = &frame.plan;
        let blades = frame.blade_count();
        if blades == 0 && v.flowers.is_empty() && frame.wings.is_empty() {
            return;
        }
        let mut pass = encoder.render_pass("plants");
        pass.set_bind_group(1, &self.pipelines.bind_group, &[]);
        let flowers = |pass: &mut RenderPass<'_>| {
            if !v.flowers.is_empty() {
                pass.set_pipeline(&self.pipelines.flowers);
                pass.set_vertex_buffer(0, self.flowers.slice(..));
                for r in &v.flowers {
                    pass.draw(0..4, r.clone());
                }
            }
        };
        if frame.sorted.is_some() {
            flowers(&mut pass);
        }
        if !frame.wings.is_empty() {
            pass.set_pipeline(if frame.point_lit {
                &self.pipelines.wings_point_lit
            } else {
                &self.pipelines.wings
            });
            pass.set_vertex_buffer(0, self.wings.slice(..));
            pass.draw(0..4, 0..frame.wings.len() as u32);
        }
        let strip = 0..2 * backbone_points;
        match (&frame.sorted, &self.sorted) {
            (Some(s), Some((statics, dynamics))) if !s.order.is_empty() => {
                pass.set_pipeline(&self.pipelines.blades);
                pass.set_vertex_buffer(0, statics.slice(..));
                pass.set_vertex_buffer(1, dynamics.slice(..));
                pass.draw(strip, 0..s.order.len() as u32);
            }
            (Some(_), _) => {}
            (None, _) => {
                if !v.blades.is_empty() {
                    pass.set_pipeline(&self.pipelines.blades);
                    pass.set_vertex_buffer(0, self.statics.slice(..));
                    pass.set_vertex_buffer(1, self.dynamics.slice(..));
                    for r in &v.blades {
                        pass.draw(strip.clone(), r.clone());
                    }
                }
                flowers(&mut pass);
            }
        }
    }
}

/// An upper bound on the GPU memory of `params` on `scene` (the registry's estimate), from
/// the grids' layout alone (nothing planted).
pub fn estimate(params: &Params, scene: &Scene) -> GpuEstimate {
    let layout = Layout::new(params, &scene.blades, &scene.terrain);
    // At most one blade per candidate (and the 64 bytes an empty buffer keeps); each carries
    // a flower with probability `flower_fraction`: the expected count plus four standard
    // deviations.
    let blades = layout.candidates();
    let (n, f) = (blades as f64, f64::from(params.flower_fraction));
    let flowers = (n * f + 4.0 * (n * f * (1.0 - f)).sqrt()).ceil() as u64 + 2;
    let blades = blades.max(2);
    let size = |n: u64, each: usize| GpuEstimate::buffer(n.saturating_mul(each as u64));
    // Billboard wings: at most six per billboard of the finest step in every grid.
    let (wings, layers) = if params.lod && layout.grid_count() > 0 {
        let most = layout.grids.max_element();
        let steps = billboard::steps(layout.per_side, most);
        let groups = billboard::group_levels(params.far_groups, most);
        let per_side = u64::from(lod::billboards_per_side(layout.per_side, 5));
        let grids = u64::from(layout.grid_count());
        // A group has one billboard, of at most six wings.
        let group_wings: u64 = (1..=groups)
            .map(|k| 6 * u64::from(billboard::group_layout(&layout, k).grid_count()))
            .sum();
        (
            6 * per_side * per_side * grids + group_wings,
            steps.len() as u32 + groups,
        )
    } else {
        (1, 0)
    };
    let sorted = if params.sorting == Sorting::Sort {
        sorted_capacity(params, &layout, blades)
    } else {
        0
    };
    size(blades, std::mem::size_of::<BladeStatic>())
        .plus(size(blades, std::mem::size_of::<BladeDynamic>()))
        .plus(size(sorted.max(1), std::mem::size_of::<BladeStatic>()))
        .plus(size(sorted.max(1), std::mem::size_of::<BladeDynamic>()))
        .plus(size(flowers, std::mem::size_of::<FlowerInstance>()))
        .plus(size(wings.max(1), std::mem::size_of::<WingInstance>()))
        .plus(GpuEstimate::textures(Pipelines::bytes(layers.max(1))))
}

/// Instances of the far-to-near blade buffers. With LOD, single plants are drawn in the grids
/// next to the camera grid or, fading near a border corner (Sec. 6.1), next to any of the
/// 2 x 2 camera grids around the corner: at most 4 x 4 grids of `layout`. Without, every
/// blade.
fn sorted_capacity(params: &Params, layout: &Layout, blades: u64) -> u64 {
    if params.lod {
        blades.min(16 * u64::from(layout.per_side).pow(2))
    } else {
        blades
    }
}

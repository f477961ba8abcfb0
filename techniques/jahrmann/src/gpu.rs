//! What the technique keeps on the GPU: the blade arrays, two copies of the simulated tips
//! (read one frame, written the next), the draw list (each visible blade's root, looks and
//! curve, appended by the compute pass), the counters that are also the two indirect draws, the
//! uniform; the compute pipeline and the two draw pipelines; and the frame's commands.

use grassbench::camera::Camera;
use grassbench::glam::Vec3;
use grassbench::grass::GrassConfig;
use grassbench::wgpu::util::DeviceExt as _;
use grassbench::{Error, FrameEncoder, GpuContext, InitContext, Result, bytemuck, shaders, wgpu};

use crate::Params;
use crate::blades::BladeArrays;
use crate::counts::GpuCounts;
use crate::sim::FRONT_GRAVITY;

/// The shader (without the prelude): `cs_simulate`, `vs_near`, `vs_far`, `fs_blade`.
pub const SHADER: &str = include_str!("../shaders/jahrmann.wgsl");

/// Invocations per workgroup of `cs_simulate`.
pub const WORKGROUP: u32 = 64;

/// Bytes of one blade's entry in each per-blade array (`vec4<f32>`).
const ENTRY: u64 = 16;
/// Per-blade arrays of `ENTRY` bytes: v0, rest, looks, and two copies of v2.
const ARRAYS: u64 = 5;
/// Bytes of one slot of each of the draw list's two halves (the shader's `DrawHalf`: root and
/// looks, or guide and tip).
const DRAW_HALF: u64 = 32;
/// The draw list's halves: one slot a blade in each.
const DRAW_HALVES: u64 = 2;

/// Bit switches of `ParamsUniform::flags[0]` (the shader's `FLAG_*`).
pub mod flags {
    /// Orientation test.
    pub const ORIENTATION: u32 = 1;
    /// Frustum test.
    pub const FRUSTUM: u32 = 2;
    /// Distance test.
    pub const DISTANCE: u32 = 4;
    /// Two levels.
    pub const LOD: u32 = 8;
    /// Blended hand-overs.
    pub const TRANSITIONS: u32 = 16;
}

/// Mirror of the shader's `Params` uniform.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ParamsUniform {
    /// Frustum planes `(n, d)`, inside where `n·p + d ≥ 0`, normalised.
    pub planes: [[f32; 4]; 6],
    /// The eye; w: tile size (m).
    pub eye: [f32; 4],
    /// Root albedo; w: colour variation.
    pub color_root: [f32; 4],
    /// Tip albedo; w: translucency.
    pub color_tip: [f32; 4],
    /// Recovery, gravity, wind response, front gravity share.
    pub forces: [f32; 4],
    /// Orientation threshold, frustum tolerance, cull distance, distance fade.
    pub cull: [f32; 4],
    /// LOD distance, band, far widening, orientation fade.
    pub lod: [f32; 4],
    /// Thinning distance (0: off), unused, unused, unused.
    pub thin: [f32; 4],
    /// Switches ([`flags`]), distance buckets, far keep, unused.
    pub flags: [u32; 4],
    /// Blades, workgroups along x, unused (the dispatched ranges are counted in the storage
    /// block: [`GpuCounts::ranges`]), 1 when the pass runs over the ranges (`tiles.rs`) and 0
    /// when over every blade.
    pub counts: [u32; 4],
}

/// The uniform for `params` on a scene with grass `grass`, seen by `camera`, over `blades`
/// blades dispatched with `groups_x` workgroups along x.
pub fn uniform(
    params: &Params,
    grass: &GrassConfig,
    camera: &Camera,
    blades: u32,
    groups_x: u32,
) -> ParamsUniform {
    let switches = [
        (params.orientation_culling, flags::ORIENTATION),
        (params.frustum_culling, flags::FRUSTUM),
        (params.distance_culling, flags::DISTANCE),
        (params.lod, flags::LOD),
        (params.transitions, flags::TRANSITIONS),
    ]
    .iter()
    .filter(|(on, _)| *on)
    .fold(0, |acc, (_, bit)| acc | bit);
    ParamsUniform {
        planes: camera.frustum().planes.map(|p| p.to_array()),
        eye: camera.eye.extend(params.tile_size).to_array(),
        color_root: Vec3::from(grass.color_root)
            .extend(grass.color_variation)
            .to_array(),
        color_tip: Vec3::from(grass.color_tip)
            .extend(params.translucency)
            .to_array(),
        forces: [
            params.stiffness,
            params.gravity,
            params.wind_response,
            FRONT_GRAVITY,
        ],
        cull: [
            params.orientation_threshold,
            params.frustum_tolerance,
            params.cull_distance,
            params.distance_fade,
        ],
        lod: [
            params.lod_distance,
            params.band,
            params.far_widen,
            params.orientation_fade,
        ],
        thin: [params.thin_distance, 0.0, 0.0, 0.0],
        flags: [switches, params.buckets, params.far_keep, 0],
        counts: [blades, groups_x, 0, 0],
    }
}

/// Workgroups of `cs_simulate` for `blades` blades: `(x, y)` with `x` within the adapter's
/// per-dimension limit.
pub fn workgroups(blades: u32, max_per_dimension: u32) -> (u32, u32) {
    let groups = blades.div_ceil(WORKGROUP);
    let x = groups.clamp(1, max_per_dimension.max(1));
    (x, groups.div_ceil(x))
}

/// GPU memory for `blades` blades, bytes: the per-blade arrays and draw list, and the
/// per-frame blocks (uniform, counters and their starting values, read-back ring; the
/// table of ranges is [`ranges_bytes`]).
pub fn bytes(blades: u64) -> u64 {
    blades.max(1) * (ENTRY * ARRAYS + DRAW_HALF * DRAW_HALVES)
        + std::mem::size_of::<ParamsUniform>() as u64
        + RANGES_OFFSET
        + GpuCounts::SIZE
        + crate::counts::Readback::bytes()
}

/// GPU memory of the table of `ranges` dispatched ranges, bytes.
pub fn ranges_bytes(ranges: usize) -> u64 {
    ranges.max(1) as u64 * RANGE_ENTRY
}

/// The largest single buffer for `blades` blades, bytes: a half of the draw list, bound
/// whole.
pub fn largest_buffer(blades: u64) -> u64 {
    blades.max(1) * DRAW_HALF
}

/// Halvings of the compute pass's binary search over at most `max_ranges` ranges (the
/// shader's `SEARCH_STEPS`): ⌈log₂ max_ranges⌉, enough to narrow any count up to it to one.
pub fn search_steps(max_ranges: usize) -> u32 {
    max_ranges.max(1).next_power_of_two().trailing_zeros()
}

/// Bytes of one entry of the table of dispatched ranges.
const RANGE_ENTRY: u64 = 16;
/// Byte offset of the table of dispatched ranges in the counters' buffer (the shader's
/// `CountBlock`: the counts, then the table at the next 16-byte boundary).
pub const RANGES_OFFSET: u64 = GpuCounts::SIZE.next_multiple_of(RANGE_ENTRY);

/// Buffers, pipelines and bind groups.
pub struct BladeGpu {
    blades: u32,
    groups: (u32, u32),
    max_per_dimension: u32,
    uniform: wgpu::Buffer,
    rest: wgpu::Buffer,
    v2: [wgpu::Buffer; 2],
    /// The counts (also the indirect draws), then the frame's dispatched ranges
    /// (`tiles.rs`) from [`RANGES_OFFSET`].
    counters: wgpu::Buffer,
    /// Ranges the counters' buffer has room for.
    max_ranges: usize,
    /// What the counters start each frame from (the CPU's verdicts on the blades it skips).
    counters_start: wgpu::Buffer,
    simulate: shaders::ComputePipeline,
    near: grassbench::shaders::RenderPipeline,
    far: grassbench::shaders::RenderPipeline,
    /// Per parity `p`: reads tips `p`, writes tips `1 − p` and the draw list.
    simulate_groups: [wgpu::BindGroup; 2],
    /// Reads the draw list.
    draw_group: wgpu::BindGroup,
}

impl BladeGpu {
    /// Uploads `arrays` and builds the pipelines, with room for `max_ranges` dispatched
    /// ranges a frame.
    pub fn new(ctx: &InitContext<'_>, arrays: &BladeArrays, max_ranges: usize) -> Result<Self> {
        let device = &ctx.gpu.device;
        let limits = device.limits();
        let blades = u32::try_from(arrays.len()).map_err(|_| too_many(arrays.len(), u64::MAX))?;
        let binding_limit = limits
            .max_storage_buffer_binding_size
            .min(limits.max_buffer_size);
        if largest_buffer(u64::from(blades)) > binding_limit {
            return Err(too_many(arrays.len(), binding_limit / DRAW_HALF));
        }
        let groups = workgroups(blades, limits.max_compute_workgroups_per_dimension);

        let init = |label: &str, data: &[[f32; 4]], usage| {
            let zero = [[0.0f32; 4]];
            let data = if data.is_empty() { &zero[..] } else { data };
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: bytemuck::cast_slice(data),
                usage,
            })
        };
        let storage = wgpu::BufferUsages::STORAGE;
        let v0 = init("jahrmann v0", &arrays.v0, storage);
        let rest = init(
            "jahrmann rest",
            &arrays.rest,
            storage | wgpu::BufferUsages::COPY_SRC,
        );
        let looks = init("jahrmann looks", &arrays.looks, storage);
        // Both copies of the tips start at rest (the paper's initial pose); the guides are
        // written by the first step before anything draws them.
        let tips = |k| {
            init(
                &format!("jahrmann v2 {k}"),
                &arrays.rest,
                storage | wgpu::BufferUsages::COPY_DST,
            )
        };
        let v2 = [tips(0), tips(1)];
        let empty = |label: &str, size: u64, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage,
                mapped_at_creation: false,
            })
        };
        let visible_roots = empty(
            "jahrmann visible roots",
            largest_buffer(u64::from(blades)),
            storage,
        );
        let visible_curves = empty(
            "jahrmann visible curves",
            largest_buffer(u64::from(blades)),
            storage,
        );
        let counters = empty(
            "jahrmann counters and dispatched ranges",
            RANGES_OFFSET + ranges_bytes(max_ranges),
            storage
                | wgpu::BufferUsages::INDIRECT
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST,
        );
        let counters_start = empty(
            "jahrmann counters start",
            GpuCounts::SIZE,
            wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
        );
        let uniform = empty(
            "jahrmann params",
            std::mem::size_of::<ParamsUniform>() as u64,
            wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        );

        let entry = |binding, visibility, ty| wgpu::BindGroupLayoutEntry {
            binding,
            visibility,
            ty,
            count: None,
        };
        let buffer = |ty| wgpu::BindingType::Buffer {
            ty,
            has_dynamic_offset: false,
            min_binding_size: None,
        };
        let read = buffer(wgpu::BufferBindingType::Storage { read_only: true });
        let write = buffer(wgpu::BufferBindingType::Storage { read_only: false });
        let uniform_ty = buffer(wgpu::BufferBindingType::Uniform);
        let compute = wgpu::ShaderStages::COMPUTE;
        let vertex = wgpu::ShaderStages::VERTEX;
        let simulate_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("jahrmann simulate (group 1)"),
            entries: &[
                entry(0, compute, uniform_ty),
                entry(1, compute, read),
                entry(2, compute, read),
                entry(3, compute, read),
                entry(4, compute, read),
                entry(5, compute, write),
                entry(6, compute, write),
                entry(7, compute, write),
                entry(8, compute, write),
            ],
        });
        let draw_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("jahrmann draw (group 1)"),
            entries: &[
                entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT, uniform_ty),
                entry(11, vertex, read),
                entry(12, vertex, read),
            ],
        });
        fn bind(binding: u32, buffer: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
            wgpu::BindGroupEntry {
                binding,
                resource: buffer.as_entire_binding(),
            }
        }
        let simulate_group = |p: usize| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("jahrmann simulate (group 1)"),
                layout: &simulate_layout,
                entries: &[
                    bind(0, &uniform),
                    bind(1, &v0),
                    bind(2, &rest),
                    bind(3, &looks),
                    bind(4, &v2[p]),
                    bind(5, &visible_curves),
                    bind(6, &v2[1 - p]),
                    bind(7, &visible_roots),
                    bind(8, &counters),
                ],
            })
        };
        let draw_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("jahrmann draw (group 1)"),
            layout: &draw_layout,
            entries: &[
                bind(0, &uniform),
                bind(11, &visible_roots),
                bind(12, &visible_curves),
            ],
        });

        let module = shaders::module(device, "jahrmann", SHADER);
        let simulate = shaders::compute_pipeline(
            device,
            "jahrmann simulate",
            &ctx.scene_gpu
                .pipeline_layout(device, "jahrmann simulate", &[&simulate_layout]),
            &module,
            "cs_simulate",
            &[("SEARCH_STEPS", f64::from(search_steps(max_ranges)))],
        );
        let draw_pipeline_layout =
            ctx.scene_gpu
                .pipeline_layout(device, "jahrmann draw", &[&draw_layout]);
        let pipeline = |label, vs| {
            shaders::render_pipeline(
                device,
                &shaders::PipelineSpec::new(
                    label,
                    &draw_pipeline_layout,
                    &module,
                    (vs, "fs_blade"),
                    &[],
                    ctx.sample_count,
                ),
            )
        };
        Ok(Self {
            blades,
            groups,
            max_per_dimension: limits.max_compute_workgroups_per_dimension,
            counters_start,
            near: pipeline("jahrmann near", "vs_near"),
            far: pipeline("jahrmann far", "vs_far"),
            simulate,
            simulate_groups: [simulate_group(0), simulate_group(1)],
            draw_group,
            max_ranges: max_ranges.max(1),
            uniform,
            rest,
            v2,
            counters,
        })
    }

    /// Workgroups along x and y of the compute pass over every blade.
    pub fn groups(&self) -> (u32, u32) {
        self.groups
    }

    /// Workgroups along x and y for `groups` workgroups, within the adapter's limit.
    pub fn split(&self, groups: u32) -> (u32, u32) {
        let x = groups.clamp(1, self.max_per_dimension.max(1));
        (x, groups.div_ceil(x))
    }

    /// Uploads this frame's uniform, the counters' starting values and the dispatched ranges
    /// (none when the pass runs over every blade).
    pub fn upload(
        &self,
        gpu: &GpuContext,
        uniform: &ParamsUniform,
        start: &GpuCounts,
        ranges: &[[u32; 4]],
    ) {
        gpu.write_buffer(&self.uniform, 0, bytemuck::bytes_of(uniform));
        gpu.write_buffer(&self.counters_start, 0, bytemuck::bytes_of(start));
        if !ranges.is_empty() {
            let ranges = &ranges[..ranges.len().min(self.max_ranges)];
            gpu.write_buffer(&self.counters, RANGES_OFFSET, bytemuck::cast_slice(ranges));
        }
    }

    /// Records the frame's compute work: (after a reset, the rest pose into the tips read)
    /// the counters' start, the compute pass reading copy `parity` over `groups` workgroups,
    /// then the counts' copy into `readback`.
    pub fn encode_compute(
        &self,
        encoder: &mut FrameEncoder<'_>,
        parity: usize,
        reset: bool,
        groups: (u32, u32),
        readback: &wgpu::Buffer,
    ) {
        if self.blades == 0 {
            return;
        }
        let p = parity & 1;
        {
            let commands = encoder.command_encoder();
            if reset {
                commands.copy_buffer_to_buffer(
                    &self.rest,
                    0,
                    &self.v2[p],
                    0,
                    u64::from(self.blades) * ENTRY,
                );
            }
            commands.copy_buffer_to_buffer(
                &self.counters_start,
                0,
                &self.counters,
                0,
                GpuCounts::SIZE,
            );
        }
        {
            let mut pass = encoder.compute_pass("simulate");
            pass.set_pipeline(&self.simulate);
            pass.set_bind_group(1, &self.simulate_groups[p], &[]);
            pass.dispatch_workgroups(groups.0, groups.1, 1);
        }
        encoder.command_encoder().copy_buffer_to_buffer(
            &self.counters,
            0,
            readback,
            0,
            GpuCounts::SIZE,
        );
    }

    /// Records the draws of the list the compute pass wrote: the near level, and the far one
    /// with `far`, both with the GPU's counts as instance counts.
    pub fn encode_draw(&self, encoder: &mut FrameEncoder<'_>, far: bool) {
        if self.blades == 0 {
            return;
        }
        let mut pass = encoder.render_pass("blades");
        pass.set_bind_group(1, &self.draw_group, &[]);
        pass.set_pipeline(&self.near);
        pass.draw_indirect(&self.counters, GpuCounts::NEAR_ARGS);
        if far {
            pass.set_pipeline(&self.far);
            pass.draw_indirect(&self.counters, GpuCounts::FAR_ARGS);
        }
    }
}

fn too_many(blades: usize, most: u64) -> Error {
    Error::Technique {
        technique: "jahrmann".into(),
        message: format!(
            "{blades} blades need a draw list larger than this adapter's storage bindings allow (at most {most} blades); lower grass.density"
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_and_counters_mirror_the_shader() {
        assert_eq!(
            shaders::struct_size(SHADER, "Params").unwrap() as usize,
            std::mem::size_of::<ParamsUniform>()
        );
        assert_eq!(
            u64::from(shaders::struct_size(SHADER, "Counters").unwrap()),
            GpuCounts::SIZE
        );
        // WGSL puts `CountBlock.ranges` (16-byte aligned) at the first multiple of 16 after
        // the 72-byte counts.
        assert_eq!(RANGES_OFFSET, 80);
    }

    #[test]
    fn the_search_narrows_any_count_of_ranges_to_one() {
        assert_eq!(search_steps(0), 0);
        assert_eq!(search_steps(1), 0);
        assert_eq!(search_steps(2), 1);
        assert_eq!(search_steps(3), 2);
        assert_eq!(search_steps(4096), 12);
        assert_eq!(search_steps(4097), 13);
        // The shader's halvings (`len -= len / 2`) leave one range of any count up to the
        // most, and no fewer steps would for the most.
        for max in 1..=2_000usize {
            let steps = search_steps(max);
            let narrowed = |mut len: usize, steps: u32| {
                for _ in 0..steps {
                    len -= len / 2;
                }
                len
            };
            for count in 1..=max {
                assert_eq!(narrowed(count, steps), 1, "{count} of {max}");
            }
            if max > 1 {
                assert!(narrowed(max, steps - 1) > 1, "{max}");
            }
        }
    }

    #[test]
    fn workgroups_cover_every_blade_within_the_limit() {
        assert_eq!(workgroups(0, 65_535), (1, 0));
        assert_eq!(workgroups(64, 65_535), (1, 1));
        assert_eq!(workgroups(65, 65_535), (2, 1));
        // 8 M blades: 125 000 workgroups, more than one dimension holds.
        let (x, y) = workgroups(8_000_000, 65_535);
        assert!(x <= 65_535 && u64::from(x) * u64::from(y) * 64 >= 8_000_000);
    }

    #[test]
    fn switches_follow_the_parameters() {
        let camera = Camera::look_at(Vec3::ZERO, Vec3::Z, 1.0, 0.1, 100.0, 1.0);
        let grass = GrassConfig::default();
        let all = uniform(&Params::default(), &grass, &camera, 10, 1);
        assert_eq!(all.flags[0], 31);
        let finest: Params = grassbench::params::resolve(
            "jahrmann",
            &crate::VARIANTS.finest.parse::<toml::Table>().unwrap(),
        )
        .unwrap();
        assert_eq!(
            uniform(&finest, &grass, &camera, 10, 1).flags[0],
            flags::TRANSITIONS
        );
    }
}

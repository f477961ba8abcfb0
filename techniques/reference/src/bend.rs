//! The bend pass: each blade's bend (`blade_bend` in `blade.wgsl`: the wind's push, the
//! flutter, the rest lean) computed once a frame in a compute pass, not at each of the blade's
//! vertices; the strips read it as their fourth instance attribute. The blades are bound a
//! chunk at a time ([`chunk_blades`]), so no storage binding grows with the field.

use grassbench::gpu::GpuEstimate;
use grassbench::shaders::{self, buffer_entry};
use grassbench::wgpu::util::DeviceExt as _;
use grassbench::{FrameEncoder, InitContext, bytemuck, wgpu};

use crate::BladeInstance;

/// Bytes of one blade's bend (direction, angle, wind speed).
const BYTES: u64 = 16;

/// Bytes of a chunk's uniform (its first blade, padded to a `vec4<u32>`).
const CHUNK_UNIFORM_BYTES: u64 = 16;

/// Invocations in a workgroup of the bend pass (`BEND_WORKGROUP` in `blade.wgsl`).
pub const WORKGROUP: u32 = 64;

/// The bends as the vertex shader reads them: one per blade, the strip's fourth attribute.
pub const LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: BYTES,
    step_mode: wgpu::VertexStepMode::Instance,
    attributes: &wgpu::vertex_attr_array![3 => Float32x4],
};

/// Blades in a chunk of the bend pass, bound as one range of the blade and bend buffers: a
/// whole number of workgroups (so every chunk starts at a multiple of 64 blades: 3 072 bytes
/// of blades and 1 024 of bends, multiples of the 256 bytes WebGPU allows as the largest
/// storage offset alignment), whose blades fit the device's storage binding size and whose
/// workgroups fit one dimension of a dispatch (and the count a `u32`).
pub fn chunk_blades(limits: &wgpu::Limits) -> u32 {
    let blade = std::mem::size_of::<BladeInstance>() as u64;
    let groups = (limits.max_storage_buffer_binding_size / blade / u64::from(WORKGROUP))
        .min(u64::from(limits.max_compute_workgroups_per_dimension))
        .clamp(1, u64::from(u32::MAX / WORKGROUP));
    u32::try_from(groups).unwrap_or(1) * WORKGROUP
}

/// One chunk of the bend pass: its bind group (the chunk's ranges and first blade) and its
/// workgroups.
struct Chunk {
    bind_group: wgpu::BindGroup,
    workgroups: u32,
}

/// The bend pass's GPU objects.
pub struct BendPass {
    pipeline: shaders::ComputePipeline,
    chunks: Vec<Chunk>,
    /// This frame's bend of every blade, written by the pass, read by the strips.
    bends: wgpu::Buffer,
}

impl BendPass {
    /// The pass over `blade_count` blades of `instances`, with the technique's `params`
    /// uniform, running `module`'s `cs_bend`.
    pub fn new(
        ctx: &InitContext<'_>,
        module: &shaders::Module,
        params: &wgpu::Buffer,
        instances: &wgpu::Buffer,
        blade_count: u32,
    ) -> Self {
        let device = &ctx.gpu.device;
        let bends = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("reference bends"),
            size: u64::from(blade_count.max(1)) * BYTES,
            usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        let compute = wgpu::ShaderStages::COMPUTE;
        let uniform = wgpu::BufferBindingType::Uniform;
        let storage = |read_only| wgpu::BufferBindingType::Storage { read_only };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("reference bend (group 1)"),
            entries: &[
                buffer_entry(0, compute, uniform),
                buffer_entry(1, compute, storage(true)),
                buffer_entry(2, compute, storage(false)),
                buffer_entry(3, compute, uniform),
            ],
        });
        let blade_bytes = std::mem::size_of::<BladeInstance>() as u64;
        let range = |buffer, first: u32, count: u32, bytes: u64| {
            wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                buffer,
                offset: u64::from(first) * bytes,
                size: std::num::NonZeroU64::new(u64::from(count) * bytes),
            })
        };
        let per_chunk = chunk_blades(&device.limits());
        let chunks = (0..blade_count)
            .step_by(per_chunk as usize)
            .map(|first| {
                let count = per_chunk.min(blade_count - first);
                let first_blade = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("reference bend chunk"),
                    contents: bytemuck::bytes_of(&[first, 0, 0, 0]),
                    usage: wgpu::BufferUsages::UNIFORM,
                });
                let entry = |binding, resource| wgpu::BindGroupEntry { binding, resource };
                let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("reference bend (group 1)"),
                    layout: &layout,
                    entries: &[
                        entry(0, params.as_entire_binding()),
                        entry(1, range(instances, first, count, blade_bytes)),
                        entry(2, range(&bends, first, count, BYTES)),
                        entry(3, first_blade.as_entire_binding()),
                    ],
                });
                Chunk {
                    bind_group,
                    workgroups: count.div_ceil(WORKGROUP),
                }
            })
            .collect();
        let pipeline = shaders::compute_pipeline(
            device,
            "reference bend",
            &ctx.scene_gpu
                .pipeline_layout(device, "reference bend", &[&layout]),
            module,
            "cs_bend",
            &[],
        );
        Self {
            pipeline,
            chunks,
            bends,
        }
    }

    /// GPU memory of the pass over `candidates` blades at most, on a device with WebGPU's
    /// default limits.
    pub fn estimate(candidates: u64) -> GpuEstimate {
        let chunks = candidates.div_ceil(u64::from(chunk_blades(&wgpu::Limits::default())));
        GpuEstimate::buffer(candidates.saturating_mul(BYTES))
            .plus(GpuEstimate::buffer(CHUNK_UNIFORM_BYTES * chunks))
    }

    /// GPU memory it holds: the bends and the chunks' uniforms.
    pub fn bytes(&self) -> u64 {
        self.bends.size() + CHUNK_UNIFORM_BYTES * self.chunks.len() as u64
    }

    /// The bends the pass writes.
    pub fn bends(&self) -> &wgpu::Buffer {
        &self.bends
    }

    /// Records the pass: one dispatch a chunk.
    pub fn encode(&self, encoder: &mut FrameEncoder<'_>) {
        let mut pass = encoder.compute_pass("bend");
        pass.set_pipeline(&self.pipeline);
        for chunk in &self.chunks {
            pass.set_bind_group(1, &chunk.bind_group, &[]);
            pass.dispatch_workgroups(chunk.workgroups, 1, 1);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shader's bend pass runs workgroups as wide as the dispatches count them.
    #[test]
    fn the_shader_s_workgroup_is_the_one_dispatched() {
        let module = naga::front::wgsl::parse_str(&shaders::compose(crate::SHADER)).unwrap();
        let entry = module
            .entry_points
            .iter()
            .find(|e| e.name == "cs_bend")
            .unwrap();
        assert_eq!(entry.workgroup_size, [WORKGROUP, 1, 1]);
    }

    /// Chunks are whole workgroups that fit the storage binding and one dispatch dimension.
    #[test]
    fn chunks_fit_the_binding_and_the_dispatch() {
        let blade = std::mem::size_of::<BladeInstance>() as u64;
        let defaults = wgpu::Limits::default();
        let per_chunk = chunk_blades(&defaults);
        assert_eq!(per_chunk % WORKGROUP, 0);
        assert!(u64::from(per_chunk) * blade <= defaults.max_storage_buffer_binding_size);
        // One more workgroup would not fit: the chunk is as large as the binding allows.
        assert!(
            u64::from(per_chunk + WORKGROUP) * blade > defaults.max_storage_buffer_binding_size
        );
        // A device with a binding as large as memory: the dispatch dimension bounds the chunk.
        let wide = wgpu::Limits {
            max_storage_buffer_binding_size: u64::MAX,
            ..defaults.clone()
        };
        assert_eq!(
            chunk_blades(&wide),
            defaults.max_compute_workgroups_per_dimension * WORKGROUP
        );
        // And with no dispatch limit to speak of, the count still fits a `u32` in whole
        // workgroups.
        let unbounded = wgpu::Limits {
            max_compute_workgroups_per_dimension: u32::MAX,
            ..wide
        };
        assert_eq!(chunk_blades(&unbounded), u32::MAX / WORKGROUP * WORKGROUP);
        // Every chunk starts at a multiple of 256 bytes in both buffers (WebGPU's largest
        // storage offset alignment).
        assert_eq!((u64::from(per_chunk) * blade) % 256, 0);
        assert_eq!((u64::from(per_chunk) * BYTES) % 256, 0);
    }
}

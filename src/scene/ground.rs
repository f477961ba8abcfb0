//! The ground on the GPU, drawn in chunks ([`crate::terrain::chunks`]): one instanced draw
//! per level for the chunks' surfaces and one per level for the skirts where levels meet.
//! The vertex shader (`background.wgsl`, `vs_ground`) places each pattern vertex on the mesh
//! vertex it stands for, its height and normal read from the scene's height map as the mesh's
//! were computed on the CPU, so every level draws the mesh's own vertices and no storage
//! buffer is bound to the vertex stage.

use std::ops::Range;

use wgpu::util::DeviceExt as _;

use crate::GpuContext;
use crate::camera::Camera;
use crate::terrain::TerrainGpu;
use crate::terrain::chunks::{ChunkInstance, EDGES, GroundLod, LEVELS, Pattern};

/// A level's pattern on the GPU.
struct PatternGpu {
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    index_count: u32,
}

impl PatternGpu {
    fn new(device: &wgpu::Device, label: &str, pattern: &Pattern) -> Self {
        let vertices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytemuck::cast_slice(&pattern.vertices),
            usage: wgpu::BufferUsages::VERTEX,
        });
        let indices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytemuck::cast_slice(&pattern.indices),
            usage: wgpu::BufferUsages::INDEX,
        });
        Self {
            vertices,
            indices,
            index_count: pattern.indices.len() as u32,
        }
    }

    fn bytes(&self) -> u64 {
        self.vertices.size() + self.indices.size()
    }
}

/// Which instances a frame draws at each level ([`GroundGpu::upload`]'s answer).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GroundDraws {
    /// Instance range of each level's surfaces.
    pub surfaces: [Range<u32>; LEVELS],
    /// Instance range of each level's skirts.
    pub skirts: [Range<u32>; LEVELS],
}

/// The ground's level patterns and the per-frame instance buffer.
pub struct GroundGpu {
    surfaces: Vec<PatternGpu>,
    skirts: Vec<PatternGpu>,
    instances: wgpu::Buffer,
}

impl GroundGpu {
    /// The patterns of every level and room for every chunk's surface and four skirts.
    pub fn new(device: &wgpu::Device, terrain: &TerrainGpu) -> Self {
        let (cx, cz) = terrain.chunks.count();
        let capacity =
            u64::from(cx * cz * (1 + EDGES)) * std::mem::size_of::<ChunkInstance>() as u64;
        let instances = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("ground chunks"),
            size: capacity,
            usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let levels = 0..LEVELS as u32;
        Self {
            surfaces: levels
                .clone()
                .map(|l| PatternGpu::new(device, "ground surface", &Pattern::surface(l)))
                .collect(),
            skirts: levels
                .map(|l| PatternGpu::new(device, "ground skirt", &Pattern::skirt(l)))
                .collect(),
            instances,
        }
    }

    /// Chooses this frame's chunks and levels for `camera` on a target `height` pixels tall
    /// and uploads their instances.
    pub fn upload(
        &self,
        gpu: &GpuContext,
        terrain: &TerrainGpu,
        camera: &Camera,
        height: u32,
        lod: GroundLod,
    ) -> GroundDraws {
        let plan = terrain.chunks.plan(camera, height, lod);
        if !plan.instances.is_empty() {
            gpu.write_buffer(&self.instances, 0, bytemuck::cast_slice(&plan.instances));
        }
        GroundDraws {
            surfaces: plan.surfaces,
            skirts: plan.skirts,
        }
    }

    /// Draws `draws` with the ground pipeline set; bind group 0 must be set.
    pub fn draw(&self, pass: &mut crate::technique::RenderPass<'_>, draws: &GroundDraws) {
        pass.set_vertex_buffer(1, self.instances.slice(..));
        let all = self.surfaces.iter().zip(&draws.surfaces);
        for (pattern, instances) in all.chain(self.skirts.iter().zip(&draws.skirts)) {
            if instances.is_empty() {
                continue;
            }
            pass.set_vertex_buffer(0, pattern.vertices.slice(..));
            pass.set_index_buffer(pattern.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..pattern.index_count, 0, instances.clone());
        }
    }

    /// GPU memory held, bytes.
    pub fn bytes(&self) -> u64 {
        let patterns: u64 = self
            .surfaces
            .iter()
            .chain(&self.skirts)
            .map(PatternGpu::bytes)
            .sum();
        patterns + self.instances.size()
    }
}

//! The terrain on the GPU: its three maps as textures and the ground mesh every technique
//! shares (Bakay's shells are copies of it; the core draws it in chunks, [`super::chunks`]).

use glam::Vec2;
use wgpu::util::DeviceExt as _;

use super::chunks::GroundChunks;
use super::{Grid, Terrain};

/// A vertex of the ground mesh.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GroundVertex {
    /// World position on the ground.
    pub position: [f32; 3],
    /// Unit surface normal.
    pub normal: [f32; 3],
}

impl GroundVertex {
    /// Vertex layout: location 0 = position, location 1 = normal.
    pub const LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<Self>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3],
    };
}

/// Format of the height map (metres).
pub const HEIGHT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;
/// Format of the density map (`[0, 1]`).
pub const DENSITY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;
/// Format of the covering map (IDs).
pub const COVERING_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R8Uint;

/// Most vertices along one side of the ground mesh: about one a metre up to a 240 m terrain.
///
/// Not 257 (256 m): lavapipe's vertex stage (Mesa's draw module) dedupes an indexed draw's
/// vertices through a 256-entry cache keyed by `index % 256`, and on a mesh 257 vertices wide a
/// cell's vertices `(i, j + 1)` and `(i + 1, j)` are 256 apart and evict each other: bakay's
/// shells shaded 2.0 vertices a triangle on it against 0.6 on every narrower mesh
/// (`results/scaling/README.md`). A GPU does not care either way.
pub const MAX_GROUND_SIDE: u32 = 241;

/// Height, density and covering textures plus the ground mesh.
pub struct TerrainGpu {
    /// Heights in metres (`R32Float`).
    pub heights: wgpu::TextureView,
    /// Density in `[0, 1]` (`R32Float`).
    pub density: wgpu::TextureView,
    /// Covering IDs (`R8Uint`).
    pub covering: wgpu::TextureView,
    /// Ground mesh vertices ([`GroundVertex`]), row by row (cells wound by
    /// [`Self::cell_indices`]).
    pub ground_vertices: wgpu::Buffer,
    /// Vertices along x and z.
    pub ground_side: (u32, u32),
    /// The mesh's chunks, their boxes and their errors per level of detail.
    pub chunks: GroundChunks,
    bytes: u64,
}

impl TerrainGpu {
    /// Vertices per side of the ground mesh over `terrain`: about one a metre (computed
    /// without a GPU, for memory estimates).
    pub fn ground_side_for(terrain: &Terrain) -> (u32, u32) {
        let side = |s: f32| (s.ceil() as u32 + 1).clamp(2, MAX_GROUND_SIDE);
        (side(terrain.size().x), side(terrain.size().y))
    }

    /// Where vertex `(i, j)` of a ground mesh of `side` vertices stands on `terrain` (x, z):
    /// the mesh spans the terrain evenly, row `j` after row `j − 1`.
    pub fn ground_xz(terrain: &Terrain, side: (u32, u32), i: u32, j: u32) -> Vec2 {
        let uv = Vec2::new(
            i as f32 / (side.0 - 1) as f32,
            j as f32 / (side.1 - 1) as f32,
        );
        terrain.min_corner() + uv * terrain.size()
    }

    /// The two triangles of cell `(i, j)` of a ground mesh `nx` vertices wide, counter-clockwise
    /// seen from above (+y).
    pub fn cell_indices(nx: u32, i: u32, j: u32) -> [u32; 6] {
        let a = j * nx + i;
        let (b, c, d) = (a + 1, a + nx, a + nx + 1);
        [a, c, b, b, c, d]
    }

    /// The ground mesh's vertices over `terrain`, row by row, and its side in vertices.
    pub fn ground_mesh(terrain: &Terrain) -> ((u32, u32), Vec<GroundVertex>) {
        let (nx, nz) = Self::ground_side_for(terrain);
        let vertices = (0..nz)
            .flat_map(|j| (0..nx).map(move |i| (i, j)))
            .map(|(i, j)| {
                let xz = Self::ground_xz(terrain, (nx, nz), i, j);
                GroundVertex {
                    position: terrain.point_at(xz).to_array(),
                    normal: terrain.normal_at(xz).to_array(),
                }
            })
            .collect();
        ((nx, nz), vertices)
    }

    /// Uploads `terrain`. The ground mesh has about one vertex per metre (at most
    /// `MAX_GROUND_SIDE` a side) so per-vertex effects (Bakay's wind vectors) have detail
    /// even on a flat terrain whose heightmap has 2x2 samples.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, terrain: &Terrain) -> Self {
        let (heights, hb) = upload(
            device,
            queue,
            "terrain heights",
            HEIGHT_FORMAT,
            terrain.heights(),
            4,
        );
        let (density, db) = upload(
            device,
            queue,
            "terrain density",
            DENSITY_FORMAT,
            terrain.density(),
            4,
        );
        let (covering, cb) = upload(
            device,
            queue,
            "terrain covering",
            COVERING_FORMAT,
            terrain.covering(),
            1,
        );
        let ((nx, nz), vertices) = Self::ground_mesh(terrain);
        let ground_vertices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("ground vertices"),
            contents: bytemuck::cast_slice(&vertices),
            usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::STORAGE,
        });
        let bytes = hb + db + cb + (vertices.len() * std::mem::size_of::<GroundVertex>()) as u64;
        Self {
            heights,
            density,
            covering,
            ground_vertices,
            ground_side: (nx, nz),
            chunks: GroundChunks::new((nx, nz), &vertices),
            bytes,
        }
    }

    /// GPU memory held, bytes.
    pub fn bytes(&self) -> u64 {
        self.bytes
    }
}

fn upload<T: bytemuck::Pod>(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    format: wgpu::TextureFormat,
    grid: &Grid<T>,
    texel_bytes: u32,
) -> (wgpu::TextureView, u64) {
    let size = wgpu::Extent3d {
        width: grid.width() as u32,
        height: grid.height() as u32,
        depth_or_array_layers: 1,
    };
    let texture = device.create_texture_with_data(
        queue,
        &wgpu::TextureDescriptor {
            label: Some(label),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        bytemuck::cast_slice(grid.data()),
    );
    let bytes = u64::from(size.width * size.height * texel_bytes);
    (texture.create_view(&Default::default()), bytes)
}

//! The scene's props: the trees and stones of the covering map (Zhang 2006, Sec. 5.5.2,
//! Table 2). Where the covering map holds ID 253 a simple tree stands, where it holds 254 a
//! stone lies, "rendered with a random offset for orientation, size, and rotation": stones
//! turn about all three axes, trees about Y only. The thesis loads 3D models; these are built
//! once per scene from a few primitives (a hexagonal trunk under a cone crown, a jittered
//! icosahedron) and baked into one static vertex buffer ([`PropsGpu`]).
//!
//! Zhang's thesis is the paper that has props, and `zhang` drew them alone until issue 19:
//! its images then held trees that no other technique's did, which biased every comparison.
//! The props are part of the scene, like the sky, the ground and the moving object, so the
//! core draws them for every technique (the `none` technique included) in the background pass
//! ([`super::Background::draw`]: opaque, depth-tested, after the ground), and a technique
//! draws grass only (leaving it out where the covering map is not grass).

use glam::{EulerRot, Quat, Vec2, Vec3};
use wgpu::util::DeviceExt as _;

use crate::rng::hash_f32;
use crate::terrain::{Terrain, covering};

/// One vertex of the trees and stones (a triangle list, flat-shaded: each triangle's three
/// vertices carry its face normal).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct PropVertex {
    /// Position xyz; w = 1.
    pub position: [f32; 4],
    /// Face normal xyz; w unused.
    pub normal: [f32; 4],
    /// Albedo rgb; w unused.
    pub color: [f32; 4],
}

impl PropVertex {
    /// Vertex layout: location 0 = position, 1 = normal, 2 = albedo.
    pub const LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<Self>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &wgpu::vertex_attr_array![0 => Float32x4, 1 => Float32x4, 2 => Float32x4],
    };
}

/// The props of a scene on the GPU: one static triangle list.
pub struct PropsGpu {
    /// The vertices ([`PropVertex`]); `None` when the scene has no props.
    pub vertices: Option<wgpu::Buffer>,
    /// Number of vertices.
    pub count: u32,
}

impl PropsGpu {
    /// Builds and uploads the props of `terrain`'s covering map, placed with `seed`.
    pub fn new(device: &wgpu::Device, terrain: &Terrain, seed: u64) -> Self {
        let mesh = meshes(terrain, seed);
        let vertices = (!mesh.is_empty()).then(|| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("trees and stones"),
                contents: bytemuck::cast_slice(&mesh),
                usage: wgpu::BufferUsages::VERTEX,
            })
        });
        Self {
            vertices,
            count: mesh.len() as u32,
        }
    }

    /// GPU memory held, bytes.
    pub fn bytes(&self) -> u64 {
        self.vertices.as_ref().map_or(0, wgpu::Buffer::size)
    }

    /// Triangles drawn.
    pub fn triangles(&self) -> u64 {
        u64::from(self.count / 3)
    }
}

/// Sides of a trunk and of a crown.
const TRUNK_SIDES: usize = 6;
const CROWN_SIDES: usize = 8;
/// Vertices of one tree: trunk side quads, crown side and base triangles.
pub const TREE_VERTICES: usize = TRUNK_SIDES * 6 + CROWN_SIDES * 6;
/// Vertices of one stone: the 20 faces of an icosahedron.
pub const STONE_VERTICES: usize = 20 * 3;

/// Covering samples holding a tree and a stone.
pub fn count(terrain: &Terrain) -> (usize, usize) {
    let data = terrain.covering().data();
    let n = |id| data.iter().filter(|&&v| v == id).count();
    (n(covering::TREE), n(covering::STONE))
}

/// Vertices of every tree and stone of `terrain`'s covering map.
pub fn meshes(terrain: &Terrain, seed: u64) -> Vec<PropVertex> {
    let map = terrain.covering();
    let (w, h) = (map.width(), map.height());
    let mut out = Vec::new();
    for j in 0..h {
        for i in 0..w {
            let id = map.get(i as isize, j as isize);
            if id != covering::TREE && id != covering::STONE {
                continue;
            }
            let uv = Vec2::new(
                i as f32 / (w.max(2) - 1) as f32,
                j as f32 / (h.max(2) - 1) as f32,
            );
            let xz = terrain.min_corner() + uv * terrain.size();
            let r = |k: i64| hash_f32(seed ^ 0x7072_6f70, &[i as i64, j as i64, k]);
            let base = terrain.point_at(xz);
            if id == covering::TREE {
                tree(
                    base,
                    r(0) * std::f32::consts::TAU,
                    0.7 + 0.6 * r(1),
                    r(2),
                    &mut out,
                );
            } else {
                let spin = Quat::from_euler(
                    EulerRot::YXZ,
                    r(0) * std::f32::consts::TAU,
                    (r(1) - 0.5) * 1.2,
                    (r(2) - 0.5) * 1.2,
                );
                stone(
                    base,
                    spin,
                    0.5 + 0.5 * r(3),
                    r(4),
                    seed ^ (i * w + j) as u64,
                    &mut out,
                );
            }
        }
    }
    out
}

fn push_triangle(out: &mut Vec<PropVertex>, [a, b, c]: [Vec3; 3], color: Vec3) {
    let n = (b - a).cross(c - a).normalize_or(Vec3::Y);
    for p in [a, b, c] {
        out.push(PropVertex {
            position: p.extend(1.0).to_array(),
            normal: n.extend(0.0).to_array(),
            color: color.extend(1.0).to_array(),
        });
    }
}

/// A tree of `size` (1 = 2 m trunk, 4 m crown) at `base`, turned by `yaw`.
fn tree(base: Vec3, yaw: f32, size: f32, tint: f32, out: &mut Vec<PropVertex>) {
    let ring = |k: usize, sides: usize, radius: f32, y: f32| {
        let a = yaw + k as f32 / sides as f32 * std::f32::consts::TAU;
        base + Vec3::new(a.cos() * radius, y, a.sin() * radius) * size
    };
    let bark = Vec3::new(0.25, 0.16, 0.08);
    for k in 0..TRUNK_SIDES {
        let (a0, a1) = (
            ring(k, TRUNK_SIDES, 0.15, -0.3),
            ring(k + 1, TRUNK_SIDES, 0.15, -0.3),
        );
        let (b0, b1) = (
            ring(k, TRUNK_SIDES, 0.12, 2.2),
            ring(k + 1, TRUNK_SIDES, 0.12, 2.2),
        );
        push_triangle(out, [a0, b0, a1], bark);
        push_triangle(out, [a1, b0, b1], bark);
    }
    let leaves = Vec3::new(0.07, 0.19, 0.05) * (0.8 + 0.4 * tint);
    let top = base + Vec3::Y * 6.0 * size;
    let centre = base + Vec3::Y * 1.8 * size;
    for k in 0..CROWN_SIDES {
        let (c0, c1) = (
            ring(k, CROWN_SIDES, 1.5, 1.8),
            ring(k + 1, CROWN_SIDES, 1.5, 1.8),
        );
        push_triangle(out, [c0, top, c1], leaves);
        push_triangle(out, [c1, centre, c0], leaves * 0.6);
    }
}

/// A stone of radius `size` m at `base`, turned by `spin`, half sunk, its corners jittered.
fn stone(base: Vec3, spin: Quat, size: f32, tint: f32, seed: u64, out: &mut Vec<PropVertex>) {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let corners = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ];
    const FACES: [[usize; 3]; 20] = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let scale = Vec3::new(1.0, 0.6, 0.8) * size;
    let points: Vec<Vec3> = corners
        .iter()
        .enumerate()
        .map(|(k, &(x, y, z))| {
            let jitter = 0.8 + 0.4 * hash_f32(seed, &[k as i64]);
            let local = Vec3::new(x, y, z).normalize() * jitter * scale;
            base + spin * local - Vec3::Y * 0.3 * size
        })
        .collect();
    let rock = Vec3::splat(0.38 + 0.12 * tint) * Vec3::new(1.0, 0.97, 0.92);
    for f in FACES {
        push_triangle(out, [points[f[0]], points[f[1]], points[f[2]]], rock);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_mesh_per_tree_and_stone_standing_on_the_ground() {
        let terrain = Terrain::flat(Vec2::new(10.0, 10.0));
        assert_eq!(count(&terrain), (0, 0));
        assert!(meshes(&terrain, 1).is_empty());
        let mut out = Vec::new();
        tree(Vec3::ZERO, 0.3, 1.0, 0.5, &mut out);
        assert_eq!(out.len(), TREE_VERTICES);
        let top = out.iter().map(|v| v.position[1]).fold(f32::MIN, f32::max);
        assert!((top - 6.0).abs() < 1e-5);
        let n = out.len();
        stone(
            Vec3::ZERO,
            Quat::from_rotation_x(0.4),
            0.5,
            0.5,
            9,
            &mut out,
        );
        assert_eq!(out.len() - n, STONE_VERTICES);
        // Outward normals: each face's normal points away from the stone's centre.
        for tri in out[n..].chunks(3) {
            let c = tri
                .iter()
                .map(|v| Vec3::from_slice(&v.position[..3]))
                .sum::<Vec3>()
                / 3.0;
            let normal = Vec3::from_slice(&tri[0].normal[..3]);
            assert!(normal.dot(c + Vec3::Y * 0.15) > 0.0, "inward face");
        }
    }
}

//! The ground mesh drawn in chunks, culled to the view, coarser far away (issue 20 §7).
//!
//! The core's ground mesh has about a vertex a metre, at most [`MAX_GROUND_SIDE`] a side, so
//! drawn whole it costs the same primitives wherever the camera looks: 115 k triangles on a
//! 400 m terrain (131 k on the 257-wide mesh it had then), most of them outside the view or
//! far smaller than a pixel (on lavapipe that pass grew 6.9 → 18.8 ms from an 80 m to a 400 m
//! meadow, for every technique). Here the mesh is cut into square chunks of [`CHUNK_CELLS`]
//! cells. Each frame the chunks whose box meets the view frustum are drawn, each at a level `L`
//! (every `2^L`-th vertex of the mesh, the same vertices, so a coarse chunk's corners are mesh
//! vertices), the coarsest whose height error and cell size both stay small on screen at the
//! chunk's nearest depth `z` (focal length `f` in pixels):
//! - the error: the largest vertical distance between a mesh vertex of the chunk and the
//!   coarse surface above or below it, `e_L`, must stay `e_L · f / z ≤ error_pixels`;
//! - the cell: the coarse cell's side `s · 2^L` must stay `s · 2^L · f / z ≤ cell_pixels`,
//!   which keeps the interpolated normals' shading close to the mesh's where the ground is
//!   curved but its error is small.
//!
//! So on a flat terrain the picture is the same at every level, and triangles drawn stay about
//! the screen's area over `cell_pixels²` plus a few per chunk, whatever the terrain's size.
//!
//! **Cracks.** Where two chunks at different levels meet, the finer one's edge has vertices
//! the coarser one's lacks, and the two edges part by up to the sum of their edge errors.
//! Each of the two chunks then draws a *skirt* along that edge: a vertical strip hanging from
//! its own edge down by that sum (plus a margin for rounding at the T-junctions), both faces,
//! which fills the gap from whichever side is higher (the gap lies in the plane of the edge,
//! between two curves that are linear between the finer edge's vertices, so its largest
//! height is at one of those vertices, where each curve's distance to the mesh is at most its
//! edge error). Skirts are drawn only at level changes between two chunks both in view.
//!
//! A mesh whose cells are not a multiple of [`CHUNK_CELLS`] has shorter chunks at its far
//! edges: their vertices are clamped to the last row or column (the shader does the same), so
//! cells past the edge collapse to nothing.

use glam::Vec3;

use super::gpu::{GroundVertex, MAX_GROUND_SIDE};
use crate::camera::{Aabb, Camera};

/// Cells along a chunk's side at level 0.
pub const CHUNK_CELLS: u32 = 8;
/// Levels of detail: level `L` keeps every `2^L`-th vertex, so the coarsest draws a chunk as
/// one cell.
pub const LEVELS: usize = CHUNK_CELLS.trailing_zeros() as usize + 1;
/// Skirts hang this fraction of the mesh spacing below the edge error's bound (T-junctions
/// crack by a rounding error even on a flat terrain).
const SKIRT_MARGIN: f32 = 0.05;
/// Chunk edges: `i = 0` (west), `i = CHUNK_CELLS` (east), `j = 0` (south), `j = CHUNK_CELLS`
/// (north); the shader's `edge` numbers. [`SURFACE`] marks a chunk's surface instead.
pub const EDGES: u32 = 4;
/// The `edge` of a surface instance.
pub const SURFACE: u32 = EDGES;

/// How coarse the ground may be drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GroundLod {
    /// Largest height error of a coarser level on screen, pixels.
    pub error_pixels: f32,
    /// Largest side of a coarse cell on screen, pixels.
    pub cell_pixels: f32,
}

impl GroundLod {
    /// Half a pixel of height error, cells of at most 16 pixels.
    pub const DEFAULT: Self = Self {
        error_pixels: 0.5,
        cell_pixels: 16.0,
    };
    /// Every chunk in view at level 0: the mesh's own triangles, culled to the view.
    pub const FINEST: Self = Self {
        error_pixels: 0.0,
        cell_pixels: 0.0,
    };
}

impl Default for GroundLod {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// One drawn chunk surface or skirt: what the shader's instance attributes read
/// (`background.wgsl`, `vs_ground`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ChunkInstance {
    /// Mesh vertex (column, row) of the chunk's first corner.
    pub origin: [u32; 2],
    /// Mesh vertices along x and z (indices are clamped to them).
    pub side: [u32; 2],
    /// [`SURFACE`], or the edge (`0..EDGES`) a skirt hangs from.
    pub edge: u32,
    /// How far a skirt hangs below its edge, m (0 for a surface).
    pub depth: f32,
}

impl ChunkInstance {
    /// The mesh vertex (column, row) that the pattern's local vertex `(i, j)` stands on for
    /// this instance: turned onto the skirt's edge (skirt patterns are built along the west
    /// edge, `i = 0`), then clamped to the mesh. The Rust twin of the shader's
    /// `ground_vertex`.
    pub fn vertex(&self, i: u32, j: u32) -> (u32, u32) {
        let (i, j) = match self.edge {
            0 => (0, j),
            1 => (CHUNK_CELLS, j),
            2 => (j, 0),
            3 => (j, CHUNK_CELLS),
            _ => (i, j),
        };
        (
            (self.origin[0] + i).min(self.side[0] - 1),
            (self.origin[1] + j).min(self.side[1] - 1),
        )
    }

    /// Instance-rate layout: locations 1 (origin and side), 2 (edge), 3 (depth).
    pub const LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<Self>() as u64,
        step_mode: wgpu::VertexStepMode::Instance,
        attributes: &wgpu::vertex_attr_array![1 => Uint32x4, 2 => Uint32, 3 => Float32],
    };
}

/// A level's triangles in a chunk's own vertex coordinates: `(i, j, lowered)` with `i, j` in
/// `0..=CHUNK_CELLS` mesh cells from the chunk's corner (`lowered` = 1 for a skirt's bottom).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Pattern {
    /// Local vertices `(i, j, lowered)`.
    pub vertices: Vec<[u32; 3]>,
    /// Triangle list into `vertices`.
    pub indices: Vec<u32>,
}

impl Pattern {
    /// Per-vertex layout: location 0 (`i`, `j`, `lowered`).
    pub const LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
        array_stride: 12,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &wgpu::vertex_attr_array![0 => Uint32x3],
    };

    /// The surface of a chunk at `level`: the cells of `2^level` mesh cells, two triangles
    /// each, wound like the mesh's (`TerrainGpu::cell_indices`).
    pub fn surface(level: u32) -> Self {
        let step = 1u32 << level;
        let n = CHUNK_CELLS / step + 1;
        let vertices = (0..n)
            .flat_map(|j| (0..n).map(move |i| [i * step, j * step, 0]))
            .collect();
        let mut indices = Vec::new();
        for j in 0..n - 1 {
            for i in 0..n - 1 {
                indices.extend_from_slice(&super::TerrainGpu::cell_indices(n, i, j));
            }
        }
        Self { vertices, indices }
    }

    /// The skirt of the west edge (`i = 0`) at `level`, both faces; the shader turns it onto
    /// the edge an instance names.
    pub fn skirt(level: u32) -> Self {
        let step = 1u32 << level;
        let n = CHUNK_CELLS / step + 1;
        // Vertex 2k: the edge's k-th vertex; 2k + 1: the same lowered.
        let vertices = (0..n)
            .flat_map(|k| [[0, k * step, 0], [0, k * step, 1]])
            .collect();
        let mut indices = Vec::new();
        for k in 0..n - 1 {
            let (top0, bottom0, top1, bottom1) = (2 * k, 2 * k + 1, 2 * k + 2, 2 * k + 3);
            indices.extend_from_slice(&[top0, bottom0, top1, top1, bottom0, bottom1]);
            indices.extend_from_slice(&[top0, top1, bottom0, top1, bottom1, bottom0]);
        }
        Self { vertices, indices }
    }
}

/// One chunk at one level, as [`GroundChunks::levels`] chose it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ChunkLevel {
    /// Chunk index (`cz · chunks.x + cx`).
    pub chunk: u32,
    /// Its level.
    pub level: u32,
}

/// What a frame draws of the ground: surfaces and skirts by level.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GroundPlan {
    /// Instances, surfaces by level then skirts by level.
    pub instances: Vec<ChunkInstance>,
    /// Instance range of each level's surfaces.
    pub surfaces: [std::ops::Range<u32>; LEVELS],
    /// Instance range of each level's skirts.
    pub skirts: [std::ops::Range<u32>; LEVELS],
}

impl GroundPlan {
    /// Triangles the plan draws.
    pub fn triangles(&self) -> u64 {
        (0..LEVELS as u32)
            .map(|l| {
                let s = Pattern::surface(l).indices.len() as u64 / 3;
                let k = Pattern::skirt(l).indices.len() as u64 / 3;
                s * self.surfaces[l as usize].len() as u64
                    + k * self.skirts[l as usize].len() as u64
            })
            .sum()
    }
}

/// The ground mesh's chunks: boxes and errors per level.
#[derive(Clone, Debug)]
pub struct GroundChunks {
    /// Mesh vertices along x and z.
    side: (u32, u32),
    /// Chunks along x and z.
    count: (u32, u32),
    /// Each chunk's box, skirts included.
    bounds: Vec<Aabb>,
    /// Each chunk's error per level: the largest vertical distance from a mesh vertex to
    /// the level's surface, m.
    errors: Vec<[f32; LEVELS]>,
    /// Each chunk's edge errors per level and edge, m.
    edge_errors: Vec<[[f32; EDGES as usize]; LEVELS]>,
    /// Largest vertex spacing of the mesh, m.
    spacing: f32,
}

impl GroundChunks {
    /// The chunks of a mesh `side` vertices wide, its vertices row by row.
    pub fn new(side: (u32, u32), vertices: &[GroundVertex]) -> Self {
        let (nx, nz) = side;
        debug_assert_eq!(vertices.len(), (nx * nz) as usize);
        debug_assert!(nx <= MAX_GROUND_SIDE && nz <= MAX_GROUND_SIDE);
        let count = (
            (nx - 1).div_ceil(CHUNK_CELLS).max(1),
            (nz - 1).div_ceil(CHUNK_CELLS).max(1),
        );
        let height =
            |i: u32, j: u32| vertices[(j.min(nz - 1) * nx + i.min(nx - 1)) as usize].position[1];
        let position = |i: u32, j: u32| Vec3::from(vertices[(j * nx + i) as usize].position);
        let spacing = if nx > 1 && nz > 1 {
            let dx = position(1, 0) - position(0, 0);
            let dz = position(0, 1) - position(0, 0);
            dx.x.abs().max(dz.z.abs())
        } else {
            0.0
        };
        let mut errors = Vec::new();
        let mut edge_errors = Vec::new();
        let mut corners = Vec::new();
        for cz in 0..count.1 {
            for cx in 0..count.0 {
                let origin = (cx * CHUNK_CELLS, cz * CHUNK_CELLS);
                let last = (
                    (origin.0 + CHUNK_CELLS).min(nx - 1),
                    (origin.1 + CHUNK_CELLS).min(nz - 1),
                );
                let mut err = [0.0f32; LEVELS];
                let mut edge = [[0.0f32; EDGES as usize]; LEVELS];
                for (level, (e, ee)) in err.iter_mut().zip(&mut edge).enumerate() {
                    for j in origin.1..=last.1 {
                        for i in origin.0..=last.0 {
                            let coarse = coarse_height(&height, side, origin, level as u32, (i, j));
                            let d = (height(i, j) - coarse).abs();
                            *e = e.max(d);
                            let on = [i == origin.0, i == last.0, j == origin.1, j == last.1];
                            for (k, on) in on.into_iter().enumerate() {
                                if on {
                                    ee[k] = ee[k].max(d);
                                }
                            }
                        }
                    }
                }
                let points = (origin.1..=last.1)
                    .flat_map(|j| (origin.0..=last.0).map(move |i| (i, j)))
                    .map(|(i, j)| position(i, j));
                // A chunk holds at least one vertex.
                let corner = Aabb {
                    min: position(origin.0, origin.1),
                    max: position(origin.0, origin.1),
                };
                errors.push(err);
                edge_errors.push(edge);
                corners.push(Aabb::around(points).unwrap_or(corner));
            }
        }
        // A skirt hangs at most two edge errors and the margin below its chunk's lowest point.
        let worst = edge_errors
            .iter()
            .flatten()
            .flatten()
            .fold(0.0f32, |a, &b| a.max(b));
        let bounds = corners
            .into_iter()
            .map(|b: Aabb| Aabb {
                min: b.min - Vec3::Y * (2.0 * worst + SKIRT_MARGIN * spacing),
                max: b.max,
            })
            .collect();
        Self {
            side,
            count,
            bounds,
            errors,
            edge_errors,
            spacing,
        }
    }

    /// Chunks along x and z.
    pub fn count(&self) -> (u32, u32) {
        self.count
    }

    /// Chunk `c`'s box (skirts included).
    pub fn bounds(&self, c: u32) -> &Aabb {
        &self.bounds[c as usize]
    }

    /// Chunk `c`'s height error at `level`, m.
    pub fn error(&self, c: u32, level: u32) -> f32 {
        self.errors[c as usize][level as usize]
    }

    /// Chunk `c`'s height error along `edge` at `level`, m.
    pub fn edge_error(&self, c: u32, level: u32, edge: u32) -> f32 {
        self.edge_errors[c as usize][level as usize][edge as usize]
    }

    /// The level each chunk in view gets: the chunks whose box meets the frustum of `camera`,
    /// each at the coarsest level `lod` allows at its nearest depth on a target `height`
    /// pixels tall (level 0 where the eye is inside or near the box).
    pub fn levels(&self, camera: &Camera, height: u32, lod: GroundLod) -> Vec<ChunkLevel> {
        let frustum = camera.frustum();
        let focal = camera.focal_pixels(height);
        let mut out = Vec::new();
        for (c, b) in self.bounds.iter().enumerate() {
            if !frustum.intersects_aabb(b) {
                continue;
            }
            let depth = camera.nearest_visible_depth(b);
            let mut level = 0;
            if depth > 0.0 {
                let pixels_per_metre = focal / depth;
                for l in 1..LEVELS {
                    if self.spacing * (1u32 << l) as f32 * pixels_per_metre > lod.cell_pixels {
                        break;
                    }
                    if self.errors[c][l] * pixels_per_metre <= lod.error_pixels {
                        level = l as u32;
                    }
                }
            }
            out.push(ChunkLevel {
                chunk: c as u32,
                level,
            });
        }
        out
    }

    /// The frame's draws: [`Self::levels`] grouped by level, with a skirt on every edge where
    /// two chunks in view meet at different levels.
    pub fn plan(&self, camera: &Camera, height: u32, lod: GroundLod) -> GroundPlan {
        let chosen = self.levels(camera, height, lod);
        let mut level_of = vec![None; self.bounds.len()];
        for c in &chosen {
            level_of[c.chunk as usize] = Some(c.level);
        }
        let mut plan = GroundPlan::default();
        for l in 0..LEVELS as u32 {
            let start = plan.instances.len() as u32;
            for c in chosen.iter().filter(|c| c.level == l) {
                plan.instances.push(self.instance(c.chunk, SURFACE, 0.0));
            }
            plan.surfaces[l as usize] = start..plan.instances.len() as u32;
        }
        let (cx_count, cz_count) = (self.count.0 as i64, self.count.1 as i64);
        for l in 0..LEVELS as u32 {
            let start = plan.instances.len() as u32;
            for c in chosen.iter().filter(|c| c.level == l) {
                let (cx, cz) = (i64::from(c.chunk) % cx_count, i64::from(c.chunk) / cx_count);
                // West, east, south, north neighbours and the edge they share with us.
                let neighbours = [
                    (cx - 1, cz, 1),
                    (cx + 1, cz, 0),
                    (cx, cz - 1, 3),
                    (cx, cz + 1, 2),
                ];
                for (edge, (nx, nz, their_edge)) in neighbours.into_iter().enumerate() {
                    if !(0..cx_count).contains(&nx) || !(0..cz_count).contains(&nz) {
                        continue;
                    }
                    let n = (nz * cx_count + nx) as u32;
                    let Some(theirs) = level_of[n as usize] else {
                        continue;
                    };
                    if theirs == l {
                        continue;
                    }
                    let depth =
                        self.skirt_depth((c.chunk, l, edge as u32), (n, theirs, their_edge));
                    plan.instances
                        .push(self.instance(c.chunk, edge as u32, depth));
                }
            }
            plan.skirts[l as usize] = start..plan.instances.len() as u32;
        }
        plan
    }

    /// How far the skirt of `ours` = (chunk, level, edge) must hang to close the gap to
    /// `theirs`, the neighbour's (chunk, level, edge) on the same line: both edges' errors
    /// and the margin.
    pub fn skirt_depth(&self, ours: (u32, u32, u32), theirs: (u32, u32, u32)) -> f32 {
        self.edge_error(ours.0, ours.1, ours.2)
            + self.edge_error(theirs.0, theirs.1, theirs.2)
            + SKIRT_MARGIN * self.spacing
    }

    fn instance(&self, chunk: u32, edge: u32, depth: f32) -> ChunkInstance {
        ChunkInstance {
            origin: [
                chunk % self.count.0 * CHUNK_CELLS,
                chunk / self.count.0 * CHUNK_CELLS,
            ],
            side: [self.side.0, self.side.1],
            edge,
            depth,
        }
    }
}

/// Height of the surface a chunk at `origin` draws at `level`, at mesh vertex `(i, j)` of that
/// chunk: the coarse cell's two triangles (diagonal from its `(i1, j0)` to its `(i0, j1)`
/// corner, as `TerrainGpu::cell_indices` winds them), corners clamped to the mesh.
fn coarse_height(
    height: &dyn Fn(u32, u32) -> f32,
    side: (u32, u32),
    origin: (u32, u32),
    level: u32,
    (i, j): (u32, u32),
) -> f32 {
    let step = 1u32 << level;
    let cell = |o: u32, v: u32, n: u32| {
        let local = ((v - o) / step * step).min(CHUNK_CELLS - step);
        let v0 = (o + local).min(n - 1);
        let v1 = (o + local + step).min(n - 1);
        let t = if v1 > v0 {
            (v - v0) as f32 / (v1 - v0) as f32
        } else {
            0.0
        };
        (v0, v1, t)
    };
    let (i0, i1, u) = cell(origin.0, i, side.0);
    let (j0, j1, v) = cell(origin.1, j, side.1);
    let (a, b, c, d) = (
        height(i0, j0),
        height(i1, j0),
        height(i0, j1),
        height(i1, j1),
    );
    if u + v <= 1.0 {
        a + u * (b - a) + v * (c - a)
    } else {
        d + (1.0 - u) * (c - d) + (1.0 - v) * (b - d)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;
    use std::collections::BTreeMap;

    /// A mesh of `side` vertices `spacing` m apart with heights from `h`, centred on the origin.
    fn mesh(side: (u32, u32), spacing: f32, h: impl Fn(f32, f32) -> f32) -> Vec<GroundVertex> {
        let mut out = Vec::new();
        for j in 0..side.1 {
            for i in 0..side.0 {
                let x = (i as f32 - (side.0 - 1) as f32 * 0.5) * spacing;
                let z = (j as f32 - (side.1 - 1) as f32 * 0.5) * spacing;
                out.push(GroundVertex {
                    position: [x, h(x, z), z],
                    normal: [0.0, 1.0, 0.0],
                });
            }
        }
        out
    }

    /// Rolling hills with some roughness: errors at every level.
    fn hills(x: f32, z: f32) -> f32 {
        3.0 * (x * 0.05).sin() * (z * 0.07).cos() + 0.4 * (x * 0.9 + z * 1.3).sin()
    }

    /// The non-degenerate triangles an instance draws with `pattern`, as mesh vertices
    /// (column, row), rotated so the smallest comes first (orientation kept).
    fn triangles(inst: &ChunkInstance, pattern: &Pattern) -> Vec<[(u32, u32, u32); 3]> {
        pattern
            .indices
            .chunks(3)
            .filter_map(|t| {
                let v: Vec<_> = t
                    .iter()
                    .map(|&k| {
                        let [i, j, low] = pattern.vertices[k as usize];
                        let (c, r) = inst.vertex(i, j);
                        (c, r, low)
                    })
                    .collect();
                let degenerate = v[0] == v[1] || v[1] == v[2] || v[0] == v[2];
                let skirt_flat = v.iter().all(|p| (p.0, p.1) == (v[0].0, v[0].1));
                (!degenerate && !skirt_flat).then(|| {
                    let k = (0..3).min_by_key(|&k| v[k]).unwrap_or(0);
                    [v[k], v[(k + 1) % 3], v[(k + 2) % 3]]
                })
            })
            .collect()
    }

    fn surface(chunks: &GroundChunks, c: u32) -> ChunkInstance {
        chunks.instance(c, SURFACE, 0.0)
    }

    #[test]
    fn level_zero_draws_the_mesh_own_triangles() {
        for side in [(2, 2), (17, 17), (37, 50), (81, 81), (100, 33)] {
            let chunks = GroundChunks::new(side, &mesh(side, 1.0, hills));
            let mut drawn = BTreeMap::new();
            for c in 0..chunks.count().0 * chunks.count().1 {
                for t in triangles(&surface(&chunks, c), &Pattern::surface(0)) {
                    *drawn.entry(t).or_insert(0) += 1;
                }
            }
            let mut mesh_triangles = BTreeMap::new();
            for j in 0..side.1 - 1 {
                for i in 0..side.0 - 1 {
                    let idx = super::super::TerrainGpu::cell_indices(side.0, i, j);
                    for t in idx.chunks(3) {
                        let v: Vec<_> = t.iter().map(|&k| (k % side.0, k / side.0, 0)).collect();
                        let k = (0..3).min_by_key(|&k| v[k]).unwrap_or(0);
                        *mesh_triangles
                            .entry([v[k], v[(k + 1) % 3], v[(k + 2) % 3]])
                            .or_insert(0) += 1;
                    }
                }
            }
            assert_eq!(drawn, mesh_triangles, "side {side:?}");
        }
    }

    #[test]
    fn every_level_covers_its_chunk_once_with_the_mesh_winding() {
        let side = (37, 50);
        let vertices = mesh(side, 1.0, hills);
        let chunks = GroundChunks::new(side, &vertices);
        let xz = |(c, r, _): (u32, u32, u32)| {
            let p = vertices[(r * side.0 + c) as usize].position;
            (p[0], p[2])
        };
        for level in 0..LEVELS as u32 {
            let mut area = 0.0;
            for c in 0..chunks.count().0 * chunks.count().1 {
                for t in triangles(&surface(&chunks, c), &Pattern::surface(level)) {
                    let (a, b, d) = (xz(t[0]), xz(t[1]), xz(t[2]));
                    let signed = (b.0 - a.0) * (d.1 - a.1) - (b.1 - a.1) * (d.0 - a.0);
                    // The mesh's cells (`cell_indices`) have negative signed area in (x, z).
                    assert!(signed < 0.0, "level {level}: triangle {t:?} turned over");
                    area -= 0.5 * signed;
                }
            }
            let whole = ((side.0 - 1) * (side.1 - 1)) as f32;
            assert!(
                (area - whole).abs() < 1e-3 * whole,
                "level {level}: {area} of {whole}"
            );
        }
    }

    /// Height of what `inst` draws with `pattern` above (x, z), by finding the triangle that
    /// holds the point: independent of `coarse_height`.
    fn drawn_height(
        vertices: &[GroundVertex],
        side: (u32, u32),
        inst: &ChunkInstance,
        pattern: &Pattern,
        x: f32,
        z: f32,
    ) -> Option<f32> {
        let p =
            |(c, r, _): (u32, u32, u32)| Vec3::from(vertices[(r * side.0 + c) as usize].position);
        for t in triangles(inst, pattern) {
            let (a, b, c) = (p(t[0]), p(t[1]), p(t[2]));
            let det = (b.x - a.x) * (c.z - a.z) - (c.x - a.x) * (b.z - a.z);
            let u = ((x - a.x) * (c.z - a.z) - (c.x - a.x) * (z - a.z)) / det;
            let v = ((b.x - a.x) * (z - a.z) - (x - a.x) * (b.z - a.z)) / det;
            if u >= -1e-4 && v >= -1e-4 && u + v <= 1.0 + 1e-4 {
                return Some(a.y + u * (b.y - a.y) + v * (c.y - a.y));
            }
        }
        None
    }

    #[test]
    fn skirts_close_every_gap_between_two_levels() {
        let side = (70, 57);
        let vertices = mesh(side, 1.0, hills);
        let chunks = GroundChunks::new(side, &vertices);
        let (cx, cz) = chunks.count();
        let mut widest = 0.0f32;
        // Every pair of neighbours (east and north) at every pair of levels.
        for c in 0..cx * cz {
            let (x, z) = (c % cx, c / cx);
            for (n, ours, theirs) in [
                (x + 1 < cx).then(|| (c + 1, 1, 0)),
                (z + 1 < cz).then(|| (c + cx, 3, 2)),
            ]
            .into_iter()
            .flatten()
            {
                let (a, b) = (surface(&chunks, c), surface(&chunks, n));
                // The fine vertices along the shared edge.
                let line: Vec<(u32, u32)> = (0..=CHUNK_CELLS)
                    .map(|k| {
                        if ours == 1 {
                            b.vertex(0, k)
                        } else {
                            b.vertex(k, 0)
                        }
                    })
                    .collect();
                for la in 0..LEVELS as u32 {
                    for lb in 0..LEVELS as u32 {
                        if la == lb {
                            continue;
                        }
                        let depth_a = chunks.skirt_depth((c, la, ours), (n, lb, theirs));
                        let depth_b = chunks.skirt_depth((n, lb, theirs), (c, la, ours));
                        for &(col, row) in &line {
                            let q = vertices[(row * side.0 + col) as usize].position;
                            let ya = drawn_height(
                                &vertices,
                                side,
                                &a,
                                &Pattern::surface(la),
                                q[0],
                                q[2],
                            );
                            let yb = drawn_height(
                                &vertices,
                                side,
                                &b,
                                &Pattern::surface(lb),
                                q[0],
                                q[2],
                            );
                            let (Some(ya), Some(yb)) = (ya, yb) else {
                                panic!("edge vertex {col},{row} not drawn by chunks {c} and {n}");
                            };
                            // The higher side's skirt must reach the lower side's edge.
                            let gap = (ya - yb).abs();
                            widest = widest.max(gap);
                            let depth = if ya > yb { depth_a } else { depth_b };
                            assert!(
                                gap <= depth,
                                "gap {gap} > skirt {depth} between {c}@{la} and {n}@{lb}"
                            );
                        }
                    }
                }
            }
        }
        // The hills do open gaps (the test would pass on a flat mesh whatever the skirts).
        assert!(widest > 0.1, "widest gap {widest}");
    }

    fn walker(eye: Vec3, towards: Vec3) -> Camera {
        Camera::look_at(eye, towards, 50f32.to_radians(), 0.1, 1000.0, 16.0 / 9.0)
    }

    #[test]
    fn chunks_in_view_are_drawn_within_the_error_budget_and_coarser_far() {
        let side = (257, 257);
        let spacing = 400.0 / 256.0;
        let vertices = mesh(side, spacing, hills);
        let chunks = GroundChunks::new(side, &vertices);
        let mut rng = Rng::new(5);
        let height = 270;
        for _ in 0..200 {
            let eye = Vec3::new(
                rng.range(-200.0, 200.0),
                rng.range(2.0, 30.0),
                rng.range(-200.0, 200.0),
            );
            let look = Vec3::new(
                rng.range(-1.0, 1.0),
                rng.range(-0.5, 0.1),
                rng.range(-1.0, 1.0),
            );
            let cam = walker(eye, eye + look);
            let frustum = cam.frustum();
            let focal = cam.focal_pixels(height);
            let chosen = chunks.levels(&cam, height, GroundLod::DEFAULT);
            let finest = chunks.levels(&cam, height, GroundLod::FINEST);
            assert!(finest.iter().all(|c| c.level == 0));
            assert_eq!(chosen.len(), finest.len());
            for c in 0..chunks.count().0 * chunks.count().1 {
                let drawn = chosen.iter().find(|d| d.chunk == c);
                assert_eq!(drawn.is_some(), frustum.intersects_aabb(chunks.bounds(c)));
                if let Some(d) = drawn.filter(|d| d.level > 0) {
                    let depth = cam.nearest_visible_depth(chunks.bounds(c));
                    let err = chunks.error(c, d.level) * focal / depth;
                    let cell = spacing * (1u32 << d.level) as f32 * focal / depth;
                    assert!(
                        err <= 0.5 && cell <= 16.0,
                        "chunk {c} level {}: {err} px, {cell} px",
                        d.level
                    );
                }
            }
        }
    }

    #[test]
    fn triangles_drawn_do_not_grow_with_the_terrain() {
        // The scaling sweep's meadow walker: 2 m up, looking across the terrain.
        let count = |size: f32, h: &dyn Fn(f32, f32) -> f32| {
            let n = ((size.ceil() as u32) + 1).min(MAX_GROUND_SIDE);
            let vertices = mesh((n, n), size / (n - 1) as f32, h);
            let chunks = GroundChunks::new((n, n), &vertices);
            let eye = Vec3::new(-0.1 * size, 2.0 + h(-0.1 * size, 0.05 * size), 0.05 * size);
            let cam = walker(eye, eye + Vec3::new(1.0, -0.05, 0.3));
            let lod = chunks.plan(&cam, 270, GroundLod::DEFAULT).triangles();
            let finest = chunks.plan(&cam, 270, GroundLod::FINEST).triangles();
            eprintln!(
                "{size} m: {lod} triangles, {finest} at level 0 in view, {} in the mesh",
                (n - 1) * (n - 1) * 2
            );
            (lod, finest)
        };
        let bumpy = |x: f32, z: f32| 0.3 * (x * 0.2).sin() * (z * 0.15).cos();
        let (small, _) = count(80.0, &bumpy);
        let (large, large_finest) = count(400.0, &bumpy);
        // Measured 4 272 → 8 648 triangles (35 456 at level 0 in view, 115 200 in the mesh):
        // what still grows is the far chunks at the coarsest level, two triangles each, and
        // the mesh has at most 30 x 30 of them (`MAX_GROUND_SIDE`), however large the terrain.
        assert!(large_finest > 35_000, "{large_finest}");
        assert!((large as f64) < 2.5 * small as f64, "{small} → {large}");
        assert!(3 * large < large_finest, "{large} of {large_finest}");
    }
}

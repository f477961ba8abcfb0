//! The ground mesh in square chunks, so the shells are drawn only where the camera can see
//! them (issue 20 §7: drawn over the whole terrain, bakay's geometry grew with its area, 0.2 M
//! triangles at 80 m a side to 2.1 M at 400 m with a view already full).
//!
//! The paper draws the shells over one patch of ground; the harness's terrains are larger than
//! any view. The core's ground mesh (about one vertex a metre) is re-indexed chunk by chunk
//! (`CHUNK` x `CHUNK` cells, each chunk's triangles contiguous, in the core's order within
//! it), each chunk with a box around its vertices grown by the tallest blade in every
//! direction (a shell moves at most one blade height along the normal and the wind: the bend
//! keeps every segment's length, [`crate::bend`]), and every frame the chunks whose box meets
//! the view frustum are drawn, neighbours merged into one draw. A chunk outside the frustum
//! puts no fragment on screen, so the picture is the one the whole mesh gives (tested: the
//! snapshots did not move). Each chunk in view then gets its level of detail from its nearest
//! depth ([`crate::lod`]): fewer shells far away, none where the whole stack is a pixel tall,
//! and neighbours at one level are merged into one draw. The bend pass moves the vertices of
//! the chunks drawn and no others ([`Plan::bent`]): run over every vertex of the terrain, its
//! work grew with the terrain's area (6.6 k invocations a frame at 80 m a side, 66 k at 400 m,
//! on the meadow's walker at 480x270) where the shells' did not.

use std::ops::Range;

use grassbench::camera::{Aabb, Camera, Frustum};
use grassbench::glam::Vec3;
use grassbench::terrain::{Terrain, TerrainGpu};

use crate::lod::ShellLod;

/// Cells a side of a chunk.
pub const CHUNK: u32 = 16;

/// One draw of the shells: neighbouring chunks in view at one level of detail.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Draw {
    /// Index range in [`Chunks::indices`].
    pub indices: Range<u32>,
    /// Level of detail ([`ShellLod::level`]): every `2^level`-th shell is drawn.
    pub level: u32,
}

/// One frame's work: the draws, and the chunks whose vertices the bend pass moves.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Plan {
    /// The shells' draws: neighbouring chunks in view at one level of detail.
    pub draws: Vec<Draw>,
    /// The first cell `(i, j)` of every chunk drawn, in the order drawn: the bend pass moves
    /// their `(CHUNK + 1)²` vertices (fewer at the mesh's far edges), every vertex a draw
    /// uses.
    pub bent: Vec<[u32; 2]>,
}

/// The ground mesh's triangles chunk by chunk, with each chunk's bounds.
pub struct Chunks {
    /// Indices into the core's ground vertices, chunk after chunk.
    pub indices: Vec<u32>,
    /// Each chunk's index range in [`Self::indices`].
    ranges: Vec<Range<u32>>,
    /// Each chunk's box, grown by the reach of its shells.
    bounds: Vec<Aabb>,
    /// Each chunk's first cell `(i, j)`.
    origins: Vec<[u32; 2]>,
}

impl Chunks {
    /// Chunks of the ground mesh of `side` vertices on `terrain`, boxes grown by `reach`
    /// metres (the tallest blade).
    pub fn new(terrain: &Terrain, side: (u32, u32), reach: f32) -> Self {
        let (nx, nz) = side;
        let (cells_x, cells_z) = (nx.saturating_sub(1), nz.saturating_sub(1));
        let mut chunks = Self {
            indices: Vec::with_capacity((cells_x * cells_z * 6) as usize),
            ranges: Vec::new(),
            bounds: Vec::new(),
            origins: Vec::new(),
        };
        for cz in (0..cells_z).step_by(CHUNK as usize) {
            for cx in (0..cells_x).step_by(CHUNK as usize) {
                let start = chunks.indices.len() as u32;
                let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
                for j in cz..(cz + CHUNK).min(cells_z) {
                    for i in cx..(cx + CHUNK).min(cells_x) {
                        chunks
                            .indices
                            .extend_from_slice(&TerrainGpu::cell_indices(nx, i, j));
                    }
                }
                for j in cz..=(cz + CHUNK).min(cells_z) {
                    for i in cx..=(cx + CHUNK).min(cells_x) {
                        let p = terrain.point_at(TerrainGpu::ground_xz(terrain, side, i, j));
                        (lo, hi) = (lo.min(p), hi.max(p));
                    }
                }
                chunks.ranges.push(start..chunks.indices.len() as u32);
                chunks.origins.push([cx, cz]);
                chunks.bounds.push(Aabb {
                    min: lo - Vec3::splat(reach),
                    max: hi + Vec3::splat(reach),
                });
            }
        }
        chunks
    }

    /// Index ranges of the chunks whose box meets `frustum`, neighbours merged.
    pub fn visible(&self, frustum: &Frustum) -> Vec<Range<u32>> {
        let mut out = Vec::new();
        self.visible_into(frustum, &mut out);
        out
    }

    /// [`Self::visible`] into `out` (cleared first), so a frame reuses last frame's storage.
    pub fn visible_into(&self, frustum: &Frustum, out: &mut Vec<Range<u32>>) {
        out.clear();
        for (range, b) in self.ranges.iter().zip(&self.bounds) {
            if !frustum.intersects_aabb(b) {
                continue;
            }
            match out.last_mut() {
                Some(last) if last.end == range.start => last.end = range.end,
                _ => out.push(range.clone()),
            }
        }
    }

    /// The work of one frame into `out` (cleared first): the chunks whose box meets the
    /// frustum of `camera`, each at the level `lod` gives its nearest depth on a target
    /// `height` pixels tall, chunks without shells left out, neighbours at one level merged
    /// into one draw; and the chunks drawn, for the bend pass.
    pub fn plan_into(&self, camera: &Camera, height: u32, lod: &ShellLod, out: &mut Plan) {
        out.draws.clear();
        out.bent.clear();
        let frustum = camera.frustum();
        let focal = camera.focal_pixels(height);
        for ((range, b), origin) in self.ranges.iter().zip(&self.bounds).zip(&self.origins) {
            if !frustum.intersects_aabb(b) {
                continue;
            }
            let Some(level) = lod.level(camera.nearest_depth(b), focal) else {
                continue;
            };
            out.bent.push(*origin);
            match out.draws.last_mut() {
                Some(last) if last.indices.end == range.start && last.level == level => {
                    last.indices.end = range.end;
                }
                _ => out.draws.push(Draw {
                    indices: range.clone(),
                    level,
                }),
            }
        }
    }

    /// Chunks [`Self::new`] cuts a ground mesh of `side` vertices into (shorter ones at its
    /// far edges counted), without building them.
    pub fn count_for(side: (u32, u32)) -> usize {
        let chunks = |n: u32| n.saturating_sub(1).div_ceil(CHUNK) as usize;
        chunks(side.0) * chunks(side.1)
    }

    /// Chunks in the mesh.
    pub fn len(&self) -> usize {
        self.ranges.len()
    }

    /// Whether the mesh has no chunk (a terrain without cells).
    pub fn is_empty(&self) -> bool {
        self.ranges.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use grassbench::camera::Camera;
    use grassbench::glam::Vec4;
    use grassbench::terrain::{CoveringSource, MapSource, TerrainConfig};

    /// A hilly terrain `size` metres a side.
    fn terrain(size: f32) -> Terrain {
        let config = TerrainConfig {
            size: [size, size],
            max_height: 3.0,
            samples_per_metre: 1.0,
            height: MapSource::default(),
            density: MapSource::one(),
            covering: CoveringSource::Grass,
        };
        Terrain::build(&config, 7, std::path::Path::new(".")).unwrap()
    }

    #[test]
    fn every_triangle_once_in_the_cores_winding() {
        let t = terrain(40.0);
        let side = TerrainGpu::ground_side_for(&t);
        let chunks = Chunks::new(&t, side, 1.0);
        let mut core: Vec<[u32; 3]> = Vec::new();
        for j in 0..side.1 - 1 {
            for i in 0..side.0 - 1 {
                let c = TerrainGpu::cell_indices(side.0, i, j);
                core.extend([[c[0], c[1], c[2]], [c[3], c[4], c[5]]]);
            }
        }
        let mut ours: Vec<[u32; 3]> = chunks
            .indices
            .chunks(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect();
        assert_eq!(ours.len(), core.len());
        core.sort_unstable();
        ours.sort_unstable();
        assert_eq!(ours, core);
        // 40 cells a side: 3 x 3 chunks of up to 16.
        assert_eq!(chunks.len(), 9);
        for size in [12.0, 16.0, 17.0, 40.0, 100.0] {
            let t = terrain(size);
            let side = TerrainGpu::ground_side_for(&t);
            assert_eq!(
                Chunks::count_for(side),
                Chunks::new(&t, side, 1.0).len(),
                "{size} m"
            );
        }
    }

    #[test]
    fn boxes_hold_their_vertices_and_the_reach() {
        let t = terrain(40.0);
        let side = TerrainGpu::ground_side_for(&t);
        let reach = 0.8;
        let chunks = Chunks::new(&t, side, reach);
        for (range, b) in chunks.ranges.iter().zip(&chunks.bounds) {
            for &v in &chunks.indices[range.start as usize..range.end as usize] {
                let p = t.point_at(TerrainGpu::ground_xz(&t, side, v % side.0, v / side.0));
                for q in [
                    p,
                    p + Vec3::Y * reach,
                    p - Vec3::X * reach,
                    p + Vec3::Z * reach,
                ] {
                    assert!(
                        q.cmpge(b.min).all() && q.cmple(b.max).all(),
                        "{q} outside {b:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn a_view_draws_what_it_sees_and_merges_neighbours() {
        let t = terrain(160.0);
        let side = TerrainGpu::ground_side_for(&t);
        let chunks = Chunks::new(&t, side, 1.0);
        let total = chunks.indices.len() as u32;
        // Everything inside: one draw of the whole mesh.
        let all = Frustum {
            planes: [Vec4::new(0.0, 0.0, 0.0, 1.0); 6],
        };
        assert_eq!(chunks.visible(&all), vec![0..total]);
        // Nothing inside.
        let none = Frustum {
            planes: [Vec4::new(0.0, 0.0, 0.0, -1.0); 6],
        };
        assert!(chunks.visible(&none).is_empty());
        // A walker looking along +x from the terrain's west edge sees part of it, and every
        // chunk holding a point in front of it within the far plane is drawn.
        let cam = Camera::look_at(
            Vec3::new(-75.0, 2.0, 0.0),
            Vec3::new(0.0, 0.0, 0.0),
            1.2,
            0.1,
            60.0,
            16.0 / 9.0,
        );
        let f = cam.frustum();
        let seen = chunks.visible(&f);
        let drawn: u32 = seen.iter().map(|r| r.end - r.start).sum();
        assert!(drawn > 0 && drawn < total / 2, "{drawn} of {total}");
        let ahead = t.point_at(grassbench::glam::Vec2::new(-60.0, 0.0));
        let hit = chunks
            .ranges
            .iter()
            .zip(&chunks.bounds)
            .find(|(_, b)| ahead.cmpge(b.min).all() && ahead.cmple(b.max).all())
            .map(|(r, _)| r.clone())
            .unwrap();
        assert!(
            seen.iter()
                .any(|r| r.start <= hit.start && hit.end <= r.end)
        );
    }

    /// The meadow's walker at 480x270 on terrains of growing size: the shells drawn per frame
    /// (triangles x shells) as a function of the terrain's side, with the level of detail on
    /// (`pixels = 1`) or off.
    fn walker_shell_triangles(size: f32, pixels: f32) -> (u64, Vec<Draw>, Chunks, Camera) {
        let t = terrain(size);
        let side = TerrainGpu::ground_side_for(&t);
        let chunks = Chunks::new(&t, side, 0.7);
        let eye = t.point_at(grassbench::glam::Vec2::new(-25.0, 10.0)) + Vec3::Y * 1.6;
        let ahead = eye + Vec3::new(25.0, -6.5, -15.0);
        let cam = Camera::look_at(eye, ahead, 55f32.to_radians(), 0.05, 400.0, 16.0 / 9.0);
        let lod = ShellLod {
            shells: 16,
            height: 0.7,
            pixels,
        };
        let mut plan = Plan::default();
        chunks.plan_into(&cam, 270, &lod, &mut plan);
        let draws = plan.draws;
        let shells: u64 = draws
            .iter()
            .map(|d| {
                u64::from(d.indices.end - d.indices.start) / 3 * u64::from(lod.shells_at(d.level))
            })
            .sum();
        (shells, draws, chunks, cam)
    }

    #[test]
    fn far_chunks_get_fewer_shells_and_the_work_stays_bounded() {
        let (near, ..) = walker_shell_triangles(80.0, 1.0);
        let (far, draws, chunks, cam) = walker_shell_triangles(400.0, 1.0);
        let (all, ..) = walker_shell_triangles(400.0, 0.0);
        // Measured: 111 k shell triangles at 80 m, 137 k at 400 m, 614 k at 400 m without the
        // level of detail (the growth this guards against: every chunk in view with all 16).
        assert!(all > 3 * near, "{all} vs {near}");
        assert!(far * 10 < all * 3, "{far} of {all}");
        assert!(far * 2 < near * 3, "{far} at 400 m vs {near} at 80 m");
        // Levels rise with the chunks' depth, every drawn chunk is in the frustum, and chunks
        // far enough away draw nothing.
        let frustum = cam.frustum();
        let mut by_depth: Vec<(f32, u32)> = Vec::new();
        for d in &draws {
            for (range, b) in chunks.ranges.iter().zip(&chunks.bounds) {
                if d.indices.start <= range.start && range.end <= d.indices.end {
                    assert!(frustum.intersects_aabb(b));
                    by_depth.push((cam.nearest_depth(b), d.level));
                }
            }
        }
        by_depth.sort_by(|a, b| a.0.total_cmp(&b.0));
        assert!(by_depth.windows(2).all(|w| w[0].1 <= w[1].1));
        assert_eq!(by_depth.first().map(|d| d.1), Some(0));
        assert!(by_depth.last().is_some_and(|d| d.1 >= 3), "{by_depth:?}");
        let deepest = by_depth.last().map_or(0.0, |d| d.0);
        assert!(deepest < 200.0, "a chunk {deepest} m away still has shells");
        let in_view = chunks
            .bounds
            .iter()
            .filter(|b| frustum.intersects_aabb(b))
            .count();
        assert!(by_depth.len() < in_view, "{} of {in_view}", by_depth.len());
        // Neighbours at one level are one draw.
        assert!(
            draws
                .windows(2)
                .all(|w| w[0].indices.end != w[1].indices.start || w[0].level != w[1].level)
        );
    }

    /// The vertices the bend pass moves for a chunk at `origin` on a mesh of `side` vertices
    /// (the shader's `cs_bend` walks them the same way: `(CHUNK + 1)²` a chunk, row by row,
    /// cut at the mesh's edges).
    fn bent_vertices(origin: [u32; 2], side: (u32, u32)) -> impl Iterator<Item = u32> {
        let n = CHUNK + 1;
        (0..n * n).filter_map(move |local| {
            let (i, j) = (origin[0] + local % n, origin[1] + local / n);
            (i < side.0 && j < side.1).then_some(j * side.0 + i)
        })
    }

    #[test]
    fn the_bend_pass_moves_every_vertex_drawn_and_only_the_drawn_chunks() {
        for size in [40.0, 80.0, 400.0] {
            let t = terrain(size);
            let side = TerrainGpu::ground_side_for(&t);
            let chunks = Chunks::new(&t, side, 0.7);
            let eye = t.point_at(grassbench::glam::Vec2::new(-0.3 * size, 0.1 * size));
            let lod = ShellLod {
                shells: 16,
                height: 0.7,
                pixels: 1.0,
            };
            for (yaw, pitch) in [(0.0f32, -0.25f32), (1.3, -0.1), (2.9, -0.6), (4.4, -1.2)] {
                let ahead = eye
                    + Vec3::Y * 1.6
                    + Vec3::new(
                        yaw.cos() * pitch.cos(),
                        pitch.sin(),
                        yaw.sin() * pitch.cos(),
                    );
                let cam = Camera::look_at(
                    eye + Vec3::Y * 1.6,
                    ahead,
                    55f32.to_radians(),
                    0.05,
                    400.0,
                    16.0 / 9.0,
                );
                let mut plan = Plan::default();
                chunks.plan_into(&cam, 270, &lod, &mut plan);
                let mut bent = vec![false; (side.0 * side.1) as usize];
                for &origin in &plan.bent {
                    for v in bent_vertices(origin, side) {
                        bent[v as usize] = true;
                    }
                }
                let mut used = vec![false; bent.len()];
                for d in &plan.draws {
                    for &v in &chunks.indices[d.indices.start as usize..d.indices.end as usize] {
                        assert!(
                            bent[v as usize],
                            "{size} m, yaw {yaw}: vertex {v} drawn, not bent"
                        );
                        used[v as usize] = true;
                    }
                }
                // Nothing bent outside the drawn chunks' vertices: every bent vertex is a
                // vertex of a drawn triangle.
                assert_eq!(bent, used, "{size} m, yaw {yaw}");
                // One bent chunk a drawn chunk.
                let drawn_chunks = chunks
                    .ranges
                    .iter()
                    .filter(|r| {
                        plan.draws
                            .iter()
                            .any(|d| d.indices.start <= r.start && r.end <= d.indices.end)
                    })
                    .count();
                assert_eq!(plan.bent.len(), drawn_chunks, "{size} m, yaw {yaw}");
            }
        }
    }
}

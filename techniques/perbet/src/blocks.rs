//! The far 2D level drawn by blocks: patches settled at the 2D level are merged into squares of
//! `s x s` patches, a quadtree over the tiling whose squares grow with their discrete distance to
//! the camera (a square of side `s` is drawn whole once it is at least `distance · s` patches
//! away, `s` at most [`MAX_SIDE`]). Each square is one 2D surface of
//! [`FLAT_CELLS`](crate::gpu::FLAT_CELLS)² cells, whose fragments find their patch's variant in
//! the variant map, so the picture is the per-patch texture while the triangles no longer grow
//! with the patches in view.

/// Largest block side, patches. Its cells (`MAX_SIDE · patch_size / FLAT_CELLS`: 5 m with
/// 2.5 m patches) keep the block's surface within its offset above the ground: on the 400 m
/// meadow, a terrain-following grid of 5 m cells lies at most 0.21 m below the ground it
/// follows (0.54 m with 10 m cells), against a surface offset of half the strips' height.
pub const MAX_SIDE: u32 = 8;

/// What one patch needs from the 2D surface this frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cover {
    /// Nothing: out of view, or no blade of it grows. A block may span it.
    Empty,
    /// In view and settled at the 2D level: drawn by exactly one block.
    Flat,
    /// In view at another level or in a transition: drawn patch by patch, never by a block.
    Other,
}

/// One block: a rectangle of patches (a quadtree square clipped to the tiling).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Block {
    /// Column and row of its first patch.
    pub first: (u32, u32),
    /// Patches along x and z.
    pub extent: (u32, u32),
}

/// Per-node flags of one quadtree level.
#[derive(Clone, Copy, Debug, Default)]
struct Node {
    flat: bool,
    other: bool,
}

/// The quadtree over a tiling of `cols x rows` patches (its memory is kept between frames).
#[derive(Clone, Debug)]
pub struct Blocks {
    cols: u32,
    rows: u32,
    /// Level `l` holds the nodes of side `2^l`, row-major, `ceil(cols / 2^l)` a row.
    levels: Vec<Vec<Node>>,
}

impl Blocks {
    /// A quadtree over `cols x rows` patches, up to nodes of [`MAX_SIDE`].
    pub fn new(cols: u32, rows: u32) -> Self {
        let mut levels = Vec::new();
        let mut side = 1;
        while side <= MAX_SIDE {
            let n = cols.div_ceil(side) as usize * rows.div_ceil(side) as usize;
            levels.push(vec![Node::default(); n]);
            side *= 2;
        }
        Self { cols, rows, levels }
    }

    /// The blocks of one frame, appended to `out`: `cover[i]` (row-major) says what patch `i`
    /// needs; `camera` is the camera's patch; a node of side `s` is one block when none of its
    /// patches is [`Cover::Other`] and its discrete distance is at least `distance · s`
    /// (`distance = 0`: every block is one patch). Every [`Cover::Flat`] patch lies in exactly
    /// one block, no [`Cover::Other`] patch in any, and every block holds a [`Cover::Flat`]
    /// patch (so it meets the view).
    pub fn plan(
        &mut self,
        cover: &[Cover],
        camera: (i64, i64),
        distance: u32,
        out: &mut Vec<Block>,
    ) {
        let Some(leaves) = self.levels.first_mut() else {
            return;
        };
        for (i, node) in leaves.iter_mut().enumerate() {
            let c = cover.get(i).copied().unwrap_or(Cover::Empty);
            *node = Node {
                flat: c == Cover::Flat,
                other: c == Cover::Other,
            };
        }
        for l in 1..self.levels.len() {
            let (below, above) = self.levels.split_at_mut(l);
            let (Some(children), Some(parents)) = (below.last(), above.first_mut()) else {
                continue;
            };
            let child_cols = self.cols.div_ceil(1 << (l - 1)) as usize;
            let child_rows = self.rows.div_ceil(1 << (l - 1)) as usize;
            let cols = self.cols.div_ceil(1 << l) as usize;
            for (k, parent) in parents.iter_mut().enumerate() {
                let (x, z) = (k % cols * 2, k / cols * 2);
                *parent = Node::default();
                for (cx, cz) in [(x, z), (x + 1, z), (x, z + 1), (x + 1, z + 1)] {
                    if cx < child_cols && cz < child_rows {
                        let c = children[cz * child_cols + cx];
                        parent.flat |= c.flat;
                        parent.other |= c.other;
                    }
                }
            }
        }
        let top = self.levels.len() - 1;
        let cols = self.cols.div_ceil(1 << top);
        let rows = self.rows.div_ceil(1 << top);
        for z in 0..rows {
            for x in 0..cols {
                self.visit(top, x, z, camera, distance, out);
            }
        }
    }

    fn visit(
        &self,
        level: usize,
        x: u32,
        z: u32,
        camera: (i64, i64),
        distance: u32,
        out: &mut Vec<Block>,
    ) {
        let side = 1u32 << level;
        let cols = self.cols.div_ceil(side);
        let Some(node) = self
            .levels
            .get(level)
            .and_then(|nodes| nodes.get((z * cols + x) as usize))
        else {
            return;
        };
        if !node.flat {
            return;
        }
        let first = (x * side, z * side);
        let extent = (side.min(self.cols - first.0), side.min(self.rows - first.1));
        let near = |c: i64, lo: u32, n: u32| {
            let (lo, hi) = (i64::from(lo), i64::from(lo + n) - 1);
            (lo - c).max(c - hi).max(0)
        };
        let d = near(camera.0, first.0, extent.0).max(near(camera.1, first.1, extent.1));
        let far_enough = distance > 0 && d >= i64::from(distance) * i64::from(side);
        if !node.other && (level == 0 || far_enough) {
            out.push(Block { first, extent });
        } else if level > 0 {
            for (cx, cz) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                let (cx, cz) = (2 * x + cx, 2 * z + cz);
                if cx * (side / 2) < self.cols && cz * (side / 2) < self.rows {
                    self.visit(level - 1, cx, cz, camera, distance, out);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lod::{LodGrid, Ranges};
    use crate::tiling::Tiling;
    use glam::{Vec2, Vec3};
    use grassbench::camera::Camera;
    use grassbench::terrain::Terrain;

    /// A walker 1.6 m above a flat terrain of `side` m, looking along +z from near its middle
    /// (far plane 400 m, the meadow's), and the cover of its 2.5 m patches with the medium
    /// preset's levels.
    fn view(side: f32) -> (Tiling, Vec<Cover>, (i64, i64)) {
        let terrain = Terrain::flat(Vec2::splat(side));
        let tiling = Tiling::new(&terrain, 2.5, 4, 7, 0.3, 0.7);
        let eye = Vec3::new(-3.0, 1.6, -6.0);
        let camera = Camera::look_at(
            eye,
            eye + Vec3::new(0.3, -0.25, 1.0),
            55f32.to_radians(),
            0.05,
            400.0,
            16.0 / 9.0,
        );
        let frustum = camera.frustum();
        let at = tiling.patch_of(Vec2::new(eye.x, eye.z));
        let mut lod = LodGrid::new(
            tiling.cols,
            tiling.rows,
            Ranges {
                strips_from: 2,
                strips_to: 12,
                hysteresis: 1,
            },
            20,
        );
        let visible: Vec<bool> = tiling
            .bounds
            .iter()
            .map(|b| frustum.intersects_aabb(b))
            .collect();
        lod.update(at, |i| visible[i]);
        lod.update(at, |i| visible[i]);
        let cover = (0..tiling.len())
            .map(|i| {
                let s = lod.state(i);
                if !visible[i] {
                    Cover::Empty
                } else if s.level == crate::lod::Level::Flat && s.transition.is_none() {
                    Cover::Flat
                } else {
                    Cover::Other
                }
            })
            .collect();
        (tiling, cover, at)
    }

    /// How many blocks cover each patch.
    fn coverage(tiling: &Tiling, blocks: &[Block]) -> Vec<u32> {
        let mut n = vec![0; tiling.len()];
        for b in blocks {
            for z in b.first.1..b.first.1 + b.extent.1 {
                for x in b.first.0..b.first.0 + b.extent.0 {
                    n[(z * tiling.cols + x) as usize] += 1;
                }
            }
        }
        n
    }

    #[test]
    fn every_flat_patch_is_in_one_block_and_no_other_patch_in_any() {
        for side in [80.0, 400.0] {
            let (tiling, cover, at) = view(side);
            let mut blocks = Vec::new();
            Blocks::new(tiling.cols, tiling.rows).plan(&cover, at, 4, &mut blocks);
            let n = coverage(&tiling, &blocks);
            for (i, c) in cover.iter().enumerate() {
                match c {
                    Cover::Flat => assert_eq!(n[i], 1, "patch {i} at {side} m"),
                    Cover::Other => assert_eq!(n[i], 0, "patch {i} at {side} m"),
                    Cover::Empty => assert!(n[i] <= 1),
                }
            }
            // Nothing out of view is drawn: every block holds a patch in view at the 2D level.
            for b in &blocks {
                assert!(b.extent.0 <= MAX_SIDE && b.extent.1 <= MAX_SIDE);
                let flat = (b.first.1..b.first.1 + b.extent.1).any(|z| {
                    (b.first.0..b.first.0 + b.extent.0)
                        .any(|x| cover[(z * tiling.cols + x) as usize] == Cover::Flat)
                });
                assert!(flat, "{b:?} at {side} m");
            }
        }
    }

    #[test]
    fn far_patches_are_not_drawn_one_by_one() {
        let plan = |side: f32, distance: u32| {
            let (tiling, cover, at) = view(side);
            let mut blocks = Vec::new();
            Blocks::new(tiling.cols, tiling.rows).plan(&cover, at, distance, &mut blocks);
            let flat = cover.iter().filter(|c| **c == Cover::Flat).count();
            (flat, blocks.len())
        };
        let (flat_80, blocks_80) = plan(80.0, 4);
        let (flat_400, blocks_400) = plan(400.0, 4);
        // Patch by patch (distance 0), one block a patch: the old cost, growing with the view.
        assert_eq!(plan(400.0, 0).1, flat_400);
        assert!(flat_400 > 10 * flat_80, "{flat_80} -> {flat_400}");
        // Merged: 25x the terrain costs at most 4x the draws of 80 m, and at most one draw per
        // 16 patches at 400 m.
        assert!(blocks_400 <= 4 * blocks_80, "{blocks_80} -> {blocks_400}");
        assert!(
            16 * blocks_400 <= flat_400,
            "{blocks_400} blocks for {flat_400} patches"
        );
    }
}

//! The terrain tiled into square patches of grass (Sec. 2.2, Fig. 5): which pre-computed patch
//! each one shows, and the box each one occupies (for culling against the view).

use glam::{Vec2, Vec3};
use grassbench::camera::Aabb;
use grassbench::terrain::Terrain;

/// The patches over a terrain, row-major from its smallest corner.
#[derive(Clone, Debug)]
pub struct Tiling {
    /// Patches along x.
    pub cols: u32,
    /// Patches along z.
    pub rows: u32,
    /// World xz of patch (0, 0)'s corner.
    pub origin: Vec2,
    /// Side of a patch, m.
    pub size: f32,
    /// The pre-computed patch each patch shows.
    pub variants: Vec<u32>,
    /// The box each patch's grass can occupy, for any wind and level.
    pub bounds: Vec<Aabb>,
}

impl Tiling {
    /// Patch count along each axis for a terrain of `extent` (m) and patches of `size`.
    pub fn counts(extent: Vec2, size: f32) -> (u32, u32) {
        let n = |e: f32| ((e / size).ceil().max(1.0) as u32).max(1);
        (n(extent.x), n(extent.y))
    }

    /// Tiles `terrain` with patches of `size`, choosing among `variants` pre-computed patches by
    /// a hash of `seed` and the patch; `reach` is how far grass reaches out of its patch and
    /// `height` how high it stands (m).
    pub fn new(
        terrain: &Terrain,
        size: f32,
        variants: u32,
        seed: u64,
        reach: f32,
        height: f32,
    ) -> Self {
        let (cols, rows) = Self::counts(terrain.size(), size);
        let origin = terrain.min_corner();
        let mut kinds = Vec::with_capacity((cols * rows) as usize);
        let mut bounds = Vec::with_capacity((cols * rows) as usize);
        // Heights sampled at about the terrain's own spacing (at least 3 x 3 a patch).
        let spacing = terrain.sample_spacing().min_element().max(1e-3);
        let samples = ((size + 2.0 * reach) / spacing).ceil().clamp(2.0, 64.0) as u32;
        for j in 0..rows {
            for i in 0..cols {
                let corner = origin + Vec2::new(i as f32, j as f32) * size;
                kinds.push(
                    (grassbench::rng::hash(seed ^ 0x7061_7463, &[i64::from(i), i64::from(j)])
                        % u64::from(variants.max(1))) as u32,
                );
                let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
                for b in 0..=samples {
                    for a in 0..=samples {
                        let f = Vec2::new(a as f32, b as f32) / samples as f32;
                        let p = corner - Vec2::splat(reach) + f * (size + 2.0 * reach);
                        let h = terrain.height_at(p);
                        lo = lo.min(h);
                        hi = hi.max(h);
                    }
                }
                bounds.push(Aabb {
                    min: Vec3::new(corner.x - reach, lo - 0.05, corner.y - reach),
                    max: Vec3::new(
                        corner.x + size + reach,
                        hi + height + 0.05,
                        corner.y + size + reach,
                    ),
                });
            }
        }
        Self {
            cols,
            rows,
            origin,
            size,
            variants: kinds,
            bounds,
        }
    }

    /// Number of patches.
    pub fn len(&self) -> usize {
        self.variants.len()
    }

    /// Whether there are no patches.
    pub fn is_empty(&self) -> bool {
        self.variants.is_empty()
    }

    /// Column and row of patch `i`.
    pub fn coords(&self, i: usize) -> (i64, i64) {
        let c = self.cols.max(1) as usize;
        ((i % c) as i64, (i / c) as i64)
    }

    /// World xz of patch `i`'s corner.
    pub fn corner(&self, i: usize) -> Vec2 {
        let (x, z) = self.coords(i);
        self.origin + Vec2::new(x as f32, z as f32) * self.size
    }

    /// World xz of patch `i`'s centre.
    pub fn centre(&self, i: usize) -> Vec2 {
        self.corner(i) + Vec2::splat(0.5 * self.size)
    }

    /// The patch (column, row) containing `xz`, which may lie outside the terrain.
    pub fn patch_of(&self, xz: Vec2) -> (i64, i64) {
        let f = (xz - self.origin) / self.size;
        (f.x.floor() as i64, f.y.floor() as i64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn patches_cover_the_terrain_and_locate_points() {
        let terrain = Terrain::flat(Vec2::new(80.0, 30.0));
        let t = Tiling::new(&terrain, 2.5, 4, 7, 0.3, 0.7);
        assert_eq!((t.cols, t.rows), (32, 12));
        assert_eq!(t.len(), 384);
        assert!(t.variants.iter().all(|v| *v < 4));
        assert!(t.variants.iter().any(|v| *v != t.variants[0]));
        for i in [0, 5, 100, 383] {
            assert_eq!(t.patch_of(t.centre(i)), t.coords(i));
            let b = &t.bounds[i];
            let c = t.centre(i);
            assert!(b.min.x < c.x && c.x < b.max.x && b.min.z < c.y && c.y < b.max.z);
            assert!(b.max.y - b.min.y >= 0.7);
        }
        assert_eq!(t.patch_of(t.origin - Vec2::splat(0.1)), (-1, -1));
    }
}

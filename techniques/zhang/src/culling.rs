//! View-frustum culling of grass grids (Sec. 5.3): "only render the visible grass grids".
//!
//! [`prairie::plant`](crate::prairie::plant) lays the blades out grid by grid, so each grass
//! grid owns a contiguous range of blades (and of flowers, which follow their blades' order).
//! Each grid gets a conservative box: its roots' extent widened by the tallest blade (a blade
//! bent flat by the wind reaches at most its height sideways) and raised by it. Every frame the
//! grids whose box meets the view frustum are kept and their ranges merged where they touch,
//! so a row of visible grids is one draw ([`frame::Plan::new`](crate::frame::Plan::new)). The
//! thesis then culls single plants inside the near grids as well. Here that depends on the
//! sorting: with `sorting = "sort"` every single plant of the near grids is visited anyway to
//! be ordered far to near, and those whose bounding sphere (centred half-way up the blade,
//! radius its height) misses the frustum are left out
//! ([`frame::sorted_blades`](crate::frame::sorted_blades)); with `"alpha_to_coverage"` the
//! near grids are drawn whole, as the merged instance ranges above. `culling = false` draws
//! every grid and every plant.

use std::ops::Range;

use grassbench::camera::{Aabb, Frustum};
use grassbench::glam::Vec3;
use grassbench::technique::ranges::push_merged;

use crate::prairie::Planted;

/// The grids' ranges and bounds.
#[derive(Clone, Debug, Default)]
pub struct GridIndex {
    /// Blade range of each non-empty grid.
    blades: Vec<Range<u32>>,
    /// Flower range of each non-empty grid (same order).
    flowers: Vec<Range<u32>>,
    /// Conservative box of each non-empty grid (same order).
    bounds: Vec<Aabb>,
    /// Grid index (`gz·grids + gx`) of each non-empty grid (same order, ascending).
    ids: Vec<u32>,
}

/// What a frame draws.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Visible {
    /// Blade instance ranges, merged.
    pub blades: Vec<Range<u32>>,
    /// Flower instance ranges, merged.
    pub flowers: Vec<Range<u32>>,
    /// Grids kept.
    pub grids: usize,
    /// Grids culled.
    pub culled: usize,
}

impl Visible {
    /// Blades drawn.
    pub fn blade_count(&self) -> u64 {
        self.blades.iter().map(|r| u64::from(r.end - r.start)).sum()
    }

    /// Flowers drawn.
    pub fn flower_count(&self) -> u64 {
        self.flowers
            .iter()
            .map(|r| u64::from(r.end - r.start))
            .sum()
    }
}

/// A box holding `plants` standing up to `reach` high and leaning up to `reach` sideways (a
/// blade bent flat by the wind reaches at most its height from its root); `None` for none.
pub fn plants_box(plants: &[Planted], reach: f32) -> Option<Aabb> {
    let roots = Aabb::around(plants.iter().map(|p| p.root))?;
    let r = Vec3::new(reach, 0.0, reach);
    Some(Aabb {
        min: roots.min - r,
        max: roots.max + r + Vec3::Y * reach,
    })
}

impl GridIndex {
    /// Index of `planted`, which must be grid by grid (as `plant` returns it).
    pub fn new(planted: &[Planted]) -> Self {
        let mut index = Self::default();
        let mut flower = 0u32;
        let mut start = 0usize;
        while start < planted.len() {
            let grid = planted[start].grid;
            let len = planted[start..]
                .iter()
                .take_while(|p| p.grid == grid)
                .count();
            let blades = &planted[start..start + len];
            let flowers = blades.iter().filter(|p| p.flower.is_some()).count() as u32;
            let tallest = blades.iter().map(|p| p.height).fold(0.0f32, f32::max);
            // `len ≥ 1`: a grid's first plant starts it, so the box always exists.
            let root = planted[start].root;
            let at_root = Aabb {
                min: root,
                max: root,
            };
            index
                .bounds
                .push(plants_box(blades, tallest).unwrap_or(at_root));
            index.ids.push(grid);
            index.blades.push(start as u32..(start + len) as u32);
            index.flowers.push(flower..flower + flowers);
            flower += flowers;
            start += len;
        }
        index
    }

    /// Widens the boxes to hold `plants` standing up to `reach` high and leaning up to `reach`
    /// sideways (the billboards' anchor plants, which need not grow: [`crate::billboard`]);
    /// plants of grids without blades are ignored.
    pub fn include(&mut self, plants: &[Planted], reach: f32) {
        let r = Vec3::new(reach, 0.0, reach);
        for p in plants {
            if let Ok(k) = self.ids.binary_search(&p.grid) {
                let b = &mut self.bounds[k];
                b.min = b.min.min(p.root - r);
                b.max = b.max.max(p.root + r + Vec3::Y * reach);
            }
        }
    }

    /// The number `k` of grid index `grid` among the non-empty grids, if it has blades.
    pub fn slot(&self, grid: u32) -> Option<usize> {
        self.ids.binary_search(&grid).ok()
    }

    /// Grid index (`gz·grids + gx`) of non-empty grid `k`.
    pub fn id(&self, k: usize) -> u32 {
        self.ids[k]
    }

    /// Blade range of non-empty grid `k`.
    pub fn blades(&self, k: usize) -> std::ops::Range<u32> {
        self.blades[k].clone()
    }

    /// Flower range of non-empty grid `k`.
    pub fn flowers(&self, k: usize) -> std::ops::Range<u32> {
        self.flowers[k].clone()
    }

    /// Conservative box of non-empty grid `k`.
    pub fn bounds(&self, k: usize) -> &Aabb {
        &self.bounds[k]
    }

    /// Non-empty grids.
    pub fn len(&self) -> usize {
        self.bounds.len()
    }

    /// Whether no grid holds a blade.
    pub fn is_empty(&self) -> bool {
        self.bounds.is_empty()
    }

    /// Every grid, culled or not (culling off).
    pub fn all(&self) -> Visible {
        self.select(|_| true)
    }

    /// The grids whose box meets `frustum`.
    pub fn visible(&self, frustum: &Frustum) -> Visible {
        self.select(|b| frustum.intersects_aabb(b))
    }

    fn select(&self, keep: impl Fn(&Aabb) -> bool) -> Visible {
        let mut v = Visible::default();
        for (k, b) in self.bounds.iter().enumerate() {
            if keep(b) {
                push_merged(&mut v.blades, self.blades[k].clone());
                push_merged(&mut v.flowers, self.flowers[k].clone());
                v.grids += 1;
            } else {
                v.culled += 1;
            }
        }
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::Params;
    use crate::prairie::plant;
    use grassbench::camera::Camera;
    use grassbench::glam::Vec2;
    use grassbench::grass::GrassConfig;
    use grassbench::terrain::Terrain;
    use proptest::prelude::*;

    fn field() -> Vec<Planted> {
        let terrain = Terrain::flat(Vec2::new(64.0, 64.0));
        let params = Params {
            grids: 8,
            blades_per_side: 6,
            flower_fraction: 0.2,
            ..Params::default()
        };
        let field = grassbench::grass::BladeField::new(GrassConfig::default(), 3);
        plant(&params, &field, &terrain, 3).1
    }

    #[test]
    fn grids_are_contiguous_and_cover_every_blade_once() {
        let planted = field();
        let index = GridIndex::new(&planted);
        assert_eq!(index.len(), 64);
        let all = index.all();
        assert_eq!(all.blades, vec![0..planted.len() as u32]);
        let flowers = planted.iter().filter(|p| p.flower.is_some()).count() as u32;
        assert_eq!(all.flowers, vec![0..flowers]);
        for (k, r) in index.blades.iter().enumerate() {
            let grid = planted[r.start as usize].grid;
            assert!(
                planted[r.start as usize..r.end as usize]
                    .iter()
                    .all(|p| p.grid == grid)
            );
            assert!(k == 0 || index.blades[k - 1].end == r.start);
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        /// Culling never drops a grid with a blade in view: every blade whose root or standing
        /// tip is inside the frustum lies in a kept range.
        #[test]
        fn culling_never_drops_a_visible_blade(
            x in -10.0f32..74.0, z in -10.0f32..74.0, y in 0.5f32..30.0,
            yaw in 0.0f32..std::f32::consts::TAU, pitch in -1.2f32..0.3,
        ) {
            let planted = field();
            let index = GridIndex::new(&planted);
            let eye = Vec3::new(x, y, z);
            let forward = Vec3::new(yaw.cos() * pitch.cos(), pitch.sin(), yaw.sin() * pitch.cos());
            let camera = Camera::look_at(eye, eye + forward, 1.0, 0.1, 500.0, 16.0 / 9.0);
            let frustum = camera.frustum();
            let visible = index.visible(&frustum);
            prop_assert_eq!(visible.grids + visible.culled, index.len());
            for (k, p) in planted.iter().enumerate() {
                let tip = p.root + Vec3::Y * p.height;
                if frustum.contains_point(p.root) || frustum.contains_point(tip) {
                    let k = k as u32;
                    prop_assert!(visible.blades.iter().any(|r| r.contains(&k)),
                        "blade {} of grid {} is in view but culled", k, p.grid);
                }
            }
        }
    }
}

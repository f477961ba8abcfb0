//! The blades grouped by ground tile, and each frame's choice of what the compute pass runs
//! over: only the tiles whose box meets the view frustum, and in each only the blades that
//! the distance test and the far level can still draw there.
//!
//! At start-up the scene's blades are put in tile order (a permutation: the blades, their
//! positions and the hashes that pick their buckets and survivors stay the scene's, each
//! blade carrying its scene index). Within a tile, with levels on, the far level's survivors
//! ([`crate::cull::survivor`]) come first, then the others; each group is sorted by the
//! blade's *reach*, the ground distance up to which the distance test keeps it
//! ([`crate::cull::distance_cutoff`]; unbounded without that test), farthest first.
//!
//! Each frame, for each tile (the per-blade tests' order):
//! - **frustum**: a tile whose box (its roots' bounds grown by [`curve_margin`] for the
//!   curve's midpoint and tip) lies wholly outside one frustum plane, by more than the
//!   tolerance, holds no blade whose root, midpoint or tip the frustum test keeps: skipped,
//!   its blades counted as culled by the frustum;
//! - **distance**: with `d` the horizontal distance from the eye to the tile's roots'
//!   rectangle, a blade whose reach is below `d` is dropped by the distance test wherever it
//!   stands in the tile: only each group's prefix of reach `≥ d` is dispatched, the rest
//!   counted as culled by distance;
//! - **level**: when every root of the tile is beyond the far level's start by its tile
//!   centre's distance (`d` less half an LOD tile's diagonal), the non-survivors can only be
//!   stood for (or culled): not dispatched, counted as represented (`represented_untested`
//!   says how many: the per-blade orientation and frustum tests never saw them).
//!
//! The dispatched ranges go to the GPU as a table of `(first workgroup, first blade, end)`,
//! each range starting a fresh workgroup of [`WORKGROUP`] blades; the shader finds its range
//! by a binary search on its first invocation's index, of [`crate::gpu::search_steps`] halvings. Every test here is conservative (a skipped
//! blade is one the per-blade tests would not draw), which `tests` checks over random cameras.

use grassbench::glam::{Vec2, Vec3, Vec4};
use grassbench::grass::Blade;

use crate::cull::{self, CullSettings, Verdict};
use crate::gpu::WORKGROUP;

/// Rounding slack on the distances compared, m.
const SLACK: f32 = 0.01;

/// How far a blade's midpoint or tip can stand from its root, for a blade of height `h`: the
/// validation keeps the chord within `h` and the guide within `3h` of the root (the length
/// estimate `(2·L0 + L1)/3 = h` with `L1 ≥ L0`), so the midpoint `¼v0 + ½v1 + ¼v2` lies
/// within `1.75·h`; the ground clamp may lift the tip a little further. `2·h + 0.25` m.
pub fn curve_margin(h: f32) -> f32 {
    2.0 * h + 0.25
}

/// One ground tile's blades, `start..end` in tile order (survivors `start..split`).
#[derive(Clone, Debug, PartialEq)]
pub struct Tile {
    /// First blade.
    pub start: u32,
    /// First blade that is not a survivor of the far level (`end` without levels).
    pub split: u32,
    /// One past the last blade.
    pub end: u32,
    /// Lower corner of the roots' bounds.
    pub roots_min: Vec3,
    /// Upper corner of the roots' bounds.
    pub roots_max: Vec3,
    /// The tallest blade, m.
    pub max_height: f32,
}

/// The blades in tile order and the tiles.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TileGrid {
    /// Scene index of each blade, in tile order.
    pub order: Vec<u32>,
    /// Each blade's reach (see the module docs), in tile order.
    pub reach: Vec<f32>,
    /// The tiles holding blades.
    pub tiles: Vec<Tile>,
}

/// What one frame dispatches, and what it skips.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Selection {
    /// `(first invocation, first blade, end, 0)` per dispatched range: the ranges follow
    /// each other in invocation order without gaps, so a far tile's few blades do not take a
    /// workgroup of their own.
    pub ranges: Vec<[u32; 4]>,
    /// Workgroups in all (the dispatched blades rounded up to whole workgroups once).
    pub groups: u32,
    /// Blades dispatched.
    pub dispatched: u64,
    /// Blades skipped in tiles outside the frustum.
    pub frustum: u64,
    /// Blades skipped beyond their reach.
    pub distance: u64,
    /// Non-survivors skipped in tiles wholly beyond the far level's start.
    pub represented: u64,
}

impl TileGrid {
    /// Groups `blades` (the scene's, in its order) into square tiles of `tile` metres, with
    /// the order within tiles `s` asks for.
    pub fn new(blades: &[Blade], tile: f32, s: &CullSettings) -> Self {
        let tile = tile.max(1e-3);
        let key = |b: &Blade| {
            let c = (Vec2::new(b.root.x, b.root.z) / tile).floor();
            (c.y as i64, c.x as i64)
        };
        let reach_of = |id: u32| {
            if s.distance {
                cull::distance_cutoff(id, s)
            } else {
                f32::INFINITY
            }
        };
        let survives = |id: u32| !s.lod || cull::survivor(id, s.far_keep);
        let mut order: Vec<u32> = (0..blades.len() as u32).collect();
        order.sort_by(|&a, &b| {
            let (ba, bb) = (&blades[a as usize], &blades[b as usize]);
            key(ba)
                .cmp(&key(bb))
                .then(survives(b).cmp(&survives(a)))
                .then(reach_of(b).total_cmp(&reach_of(a)))
                .then(a.cmp(&b))
        });
        let reach = order.iter().map(|&id| reach_of(id)).collect();
        let mut tiles = Vec::new();
        let mut k = 0;
        while k < order.len() {
            let first = &blades[order[k] as usize];
            let here = key(first);
            let mut t = Tile {
                start: k as u32,
                split: k as u32,
                end: k as u32,
                roots_min: first.root,
                roots_max: first.root,
                max_height: 0.0,
            };
            while k < order.len() && key(&blades[order[k] as usize]) == here {
                let id = order[k];
                let b = &blades[id as usize];
                t.roots_min = t.roots_min.min(b.root);
                t.roots_max = t.roots_max.max(b.root);
                t.max_height = t.max_height.max(b.height);
                k += 1;
                if survives(id) {
                    t.split = k as u32;
                }
            }
            t.end = k as u32;
            tiles.push(t);
        }
        Self {
            order,
            reach,
            tiles,
        }
    }

    /// Blades held.
    pub fn len(&self) -> usize {
        self.order.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.order.is_empty()
    }

    /// Blades of `start..end` (one group of a tile) whose reach is at least `d`.
    fn within_reach(&self, start: u32, end: u32, d: f32) -> u32 {
        let group = &self.reach[start as usize..end as usize];
        group.partition_point(|&r| r >= d - SLACK) as u32
    }

    /// What the frame seen from `eye` through `planes` does with tile `t` under `s`.
    fn plan(&self, t: &Tile, eye: Vec3, planes: &[Vec4; 6], s: &CullSettings) -> Plan {
        if s.frustum && !self.box_in_frustum(t, planes, s.frustum_tolerance) {
            return Plan::Outside;
        }
        let d = if s.distance || s.lod {
            rect_distance(t, eye)
        } else {
            0.0
        };
        let half_diag = if s.tile_size > 0.0 {
            s.tile_size * std::f32::consts::FRAC_1_SQRT_2
        } else {
            0.0
        };
        Plan::Within {
            survivors: self.within_reach(t.start, t.split, d),
            others: self.within_reach(t.split, t.end, d),
            far: s.lod && d - half_diag - SLACK >= s.far_start(),
        }
    }

    /// The ranges the frame seen from `eye` through `planes` dispatches under `s`.
    pub fn select(&self, eye: Vec3, planes: &[Vec4; 6], s: &CullSettings) -> Selection {
        let mut out = Selection::default();
        let push = |out: &mut Selection, start: u32, count: u32| {
            if count == 0 {
                return;
            }
            // Invocations stay below 2^32: the blades are at most `u32::MAX`.
            out.ranges
                .push([out.dispatched as u32, start, start + count, 0]);
            out.dispatched += u64::from(count);
            out.groups = (out.dispatched as u32).div_ceil(WORKGROUP);
        };
        for t in &self.tiles {
            let total = u64::from(t.end - t.start);
            match self.plan(t, eye, planes, s) {
                Plan::Outside => out.frustum += total,
                Plan::Within {
                    survivors,
                    others,
                    far,
                } => {
                    push(&mut out, t.start, survivors);
                    if far {
                        out.represented += u64::from(others);
                    } else {
                        push(&mut out, t.split, others);
                    }
                    out.distance += total - u64::from(survivors) - u64::from(others);
                }
            }
        }
        out
    }

    /// The verdict [`select`](Self::select) gives each blade it skips, by scene index
    /// (`None`: dispatched, judged by the GPU): for CPU mirrors of the counts.
    pub fn skipped_verdicts(
        &self,
        eye: Vec3,
        planes: &[Vec4; 6],
        s: &CullSettings,
    ) -> Vec<Option<Verdict>> {
        let mut out = vec![None; self.order.len()];
        for t in &self.tiles {
            let mut set = |range: std::ops::Range<u32>, v: Verdict| {
                for k in range {
                    out[self.order[k as usize] as usize] = Some(v);
                }
            };
            match self.plan(t, eye, planes, s) {
                Plan::Outside => set(t.start..t.end, Verdict::Frustum),
                Plan::Within {
                    survivors,
                    others,
                    far,
                } => {
                    set(t.start + survivors..t.split, Verdict::Distance);
                    set(t.split + others..t.end, Verdict::Distance);
                    if far {
                        set(t.split..t.split + others, Verdict::Represented);
                    }
                }
            }
        }
        out
    }

    /// Whether tile `t`'s box meets every plane of `planes`, give or take `tolerance`.
    fn box_in_frustum(&self, t: &Tile, planes: &[Vec4; 6], tolerance: f32) -> bool {
        let m = Vec3::splat(curve_margin(t.max_height));
        let (lo, hi) = (t.roots_min - m, t.roots_max + m);
        planes.iter().all(|pl| {
            let n = pl.truncate();
            // The corner farthest along the plane's normal.
            let p = Vec3::select(n.cmpge(Vec3::ZERO), hi, lo);
            n.dot(p) + pl.w >= -tolerance
        })
    }
}

/// What a frame does with one tile.
enum Plan {
    /// Outside the frustum: nothing dispatched.
    Outside,
    /// The first `survivors` survivors and `others` others are within reach; the others are
    /// dispatched unless the tile is wholly `far`.
    Within {
        survivors: u32,
        others: u32,
        far: bool,
    },
}

/// Horizontal distance from `eye` to the rectangle of tile `t`'s roots (0 inside).
fn rect_distance(t: &Tile, eye: Vec3) -> f32 {
    let p = Vec2::new(eye.x, eye.z);
    let lo = Vec2::new(t.roots_min.x, t.roots_min.z);
    let hi = Vec2::new(t.roots_max.x, t.roots_max.z);
    (p.clamp(lo, hi) - p).length()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Params;
    use grassbench::camera::Camera;
    use grassbench::rng::Rng;

    fn blades(rng: &mut Rng, n: usize, side: f32) -> Vec<Blade> {
        (0..n)
            .map(|_| Blade {
                root: Vec3::new(
                    rng.range(-side, side),
                    rng.range(0.0, 4.0),
                    rng.range(-side, side),
                ),
                facing: rng.range(0.0, std::f32::consts::TAU),
                height: rng.range(0.2, 0.8),
                width: 0.02,
                stiffness: 1.0,
                lean: Vec2::new(rng.range(0.0, 6.3), rng.range(0.0, 0.6)),
                variation: 0.0,
                threshold: 0.0,
            })
            .collect()
    }

    /// Over many random cameras and settings, no blade the per-blade tests would draw (near
    /// or far, with its tip anywhere the validation allows) is skipped, and the skipped
    /// blades are counted once each under the verdict the selection gives them.
    #[test]
    fn the_selection_skips_no_blade_the_per_blade_tests_draw() {
        let mut rng = Rng::new(20);
        let mut skipped_total = 0u64;
        for case in 0..60 {
            let side = rng.range(20.0, 150.0);
            let scene = blades(&mut rng, 6000, side);
            let switches = [
                Params::default().orientation_culling,
                rng.next_f32() < 0.8,
                rng.next_f32() < 0.8,
                rng.next_f32() < 0.8,
                rng.next_f32() < 0.5,
            ];
            let params = Params::random_culling(&mut rng, switches);
            let s = CullSettings::of(&params);
            let grid = TileGrid::new(&scene, rng.range(2.0, 16.0), &s);
            let eye = Vec3::new(
                rng.range(-side, side),
                rng.range(0.5, 30.0),
                rng.range(-side, side),
            );
            let forward = Vec3::new(
                rng.range(-1.0, 1.0),
                rng.range(-0.8, 0.3),
                rng.range(-1.0, 1.0),
            );
            let camera = Camera::look_at(eye, eye + forward, 1.0, 0.1, 400.0, 1.6);
            let planes = camera.frustum().planes;
            let sel = grid.select(eye, &planes, &s);
            let mut dispatched = vec![false; scene.len()];
            for r in &sel.ranges {
                for k in r[1]..r[2] {
                    dispatched[grid.order[k as usize] as usize] = true;
                }
            }
            let mut skipped = 0u64;
            for (id, b) in scene.iter().enumerate() {
                if dispatched[id] {
                    continue;
                }
                skipped += 1;
                // Tips anywhere within the chord's bound, above the root, and the guide
                // anywhere the validation can put it.
                for _ in 0..4 {
                    let dir = Vec3::new(
                        rng.range(-1.0, 1.0),
                        rng.range(0.0, 1.0),
                        rng.range(-1.0, 1.0),
                    )
                    .normalize_or(Vec3::Y);
                    let v2 = b.root + dir * b.height * rng.range(0.0, 1.0);
                    let v1 = b.root + Vec3::Y * b.height * rng.range(0.0, 1.5);
                    let v = cull::verdict(id as u32, (b.root, v1, v2), b.facing, eye, &planes, &s);
                    assert!(
                        !matches!(v, Verdict::Near | Verdict::Far),
                        "case {case}: blade {id} skipped but drawn {v:?} ({s:?})"
                    );
                }
            }
            assert_eq!(skipped, sel.frustum + sel.distance + sel.represented);
            let verdicts = grid.skipped_verdicts(eye, &planes, &s);
            let tally = |v: Verdict| verdicts.iter().filter(|&&x| x == Some(v)).count() as u64;
            assert_eq!(
                (
                    tally(Verdict::Frustum),
                    tally(Verdict::Distance),
                    tally(Verdict::Represented)
                ),
                (sel.frustum, sel.distance, sel.represented)
            );
            for (id, v) in verdicts.iter().enumerate() {
                assert_eq!(v.is_none(), dispatched[id]);
            }
            assert_eq!(sel.dispatched + skipped, scene.len() as u64);
            skipped_total += skipped;
        }
        // The selection skips something (else the test shows nothing).
        eprintln!("measured: {skipped_total} of 360 000 blades skipped");
        assert!(skipped_total > 50_000, "{skipped_total}");
    }

    #[test]
    fn tiles_keep_every_blade_once_and_order_survivors_by_reach() {
        let mut rng = Rng::new(3);
        let scene = blades(&mut rng, 3000, 30.0);
        let s = CullSettings::of(&Params::default());
        let grid = TileGrid::new(&scene, 8.0, &s);
        let mut seen = grid.order.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..3000).collect::<Vec<u32>>());
        for t in &grid.tiles {
            for k in t.start..t.end {
                let id = grid.order[k as usize];
                assert_eq!(cull::survivor(id, s.far_keep), k < t.split);
                if k + 1 < t.end && k + 1 != t.split {
                    assert!(grid.reach[k as usize] >= grid.reach[k as usize + 1]);
                }
            }
        }
        // Workgroups start afresh per range.
        let camera = Camera::look_at(
            Vec3::new(0.0, 2.0, 0.0),
            Vec3::new(0.0, 0.0, 10.0),
            1.0,
            0.1,
            400.0,
            1.6,
        );
        let sel = grid.select(camera.eye, &camera.frustum().planes, &s);
        // The ranges follow each other in invocation order without gaps, and the workgroups
        // cover the dispatched blades once rounded up.
        let mut next = 0u32;
        for r in &sel.ranges {
            assert_eq!(r[0], next, "{:?}", sel.ranges);
            next += r[2] - r[1];
        }
        assert_eq!(u64::from(next), sel.dispatched);
        assert_eq!(sel.groups, next.div_ceil(WORKGROUP));
        assert!(sel.frustum > 0 && sel.dispatched > 0);
    }
}

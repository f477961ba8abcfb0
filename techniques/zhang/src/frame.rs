//! One frame's plan: for every grass grid its level of detail (Sec. 5.2), whether it is seen
//! (Sec. 5.3), what must be animated, and what is drawn: the single plants' instance ranges
//! and the billboards' wings (Sec. 4.1-4.2).
//!
//! Animation follows the level a grid will have one grid closer to the camera, so a grid that
//! turns from billboards into single plants (or into finer billboards) when the camera crosses
//! a grid border is already in motion: blades are animated in the grids up to two away, the
//! anchors of a grid one or more away at the finer of its own and its next-closer step.
//! Near a border a grid may be drawn both ways, fading (Sec. 6.1, [`crate::fade`]).
//!
//! With far groups ([`crate::billboard::GroupLevel`]), only the grids nearer than the groups
//! are planned one by one; the groups are found top-down ([`Plan::new`]) and animate their
//! anchors only while drawn.

use std::ops::Range;

use grassbench::camera::Frustum;
use grassbench::glam::{IVec2, Vec2, Vec3};
use grassbench::technique::ranges::push_merged;

use crate::billboard::Billboards;
use crate::culling::GridIndex;
use crate::fade::Transition;
use crate::lod::{Level, grid_coords, grid_offset};
use crate::order::{self, BlockOrders, line_order, section};
use crate::prairie::Layout;
use crate::shader_data::{BladeDynamic, WingInstance};

/// A grid drawn as single plants this frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NearGrid {
    /// Non-empty grid number in the [`GridIndex`].
    pub k: usize,
    /// Grid index (`gz·grids.x + gx`).
    pub grid: u32,
    /// Offset from the camera grid, in grids.
    pub delta: IVec2,
    /// Alpha (1 unless fading, Sec. 6.1).
    pub alpha: f32,
}

/// A far grid (or far group of grids) drawn as billboards this frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FarGrid {
    /// 0: a grid; `k ≥ 1`: a group of `2^k x 2^k` grids ([`crate::billboard::GroupLevel`]).
    pub group: u8,
    /// Grid index (`gz·grids.x + gx`), or the group's index in its level.
    pub grid: u32,
    /// Offset from the camera grid, in grids (of a group: from the camera grid to its
    /// middle, rounded towards the camera grid).
    pub delta: IVec2,
    /// Billboard level (index into [`Billboards::steps`]: the texture layer).
    pub level: usize,
    /// Grid offset `g` from the camera grid (of a group: to its nearest grid).
    pub offset: u32,
    /// Twice the offset of its middle from the camera grid's middle, in grids (the far to
    /// near order of grids and groups alike).
    pub centre2: IVec2,
    /// Alpha (1 unless fading, Sec. 6.1).
    pub alpha: f32,
}

/// What a frame animates and draws.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Plan {
    /// Blade ranges to animate and draw (sorted): the near grids drawn as single plants.
    pub animate_blades: Vec<Range<u32>>,
    /// Blade ranges animated but not drawn this frame (sorted; see
    /// [`crate::animate::StepRanges::hidden`]): culled grids, grids two away.
    pub hidden_blades: Vec<Range<u32>>,
    /// Flower ranges to animate (sorted).
    pub animate_flowers: Vec<Range<u32>>,
    /// Anchor ranges to animate whose top points the drawn wings read (sorted).
    pub animate_anchors: Vec<Range<u32>>,
    /// Anchor ranges animated but not read this frame (sorted): culled grids, and the
    /// anchors of the finer step one grid closer beyond those of the grid's own step.
    pub hidden_anchors: Vec<Range<u32>>,
    /// Blade instance ranges drawn as single plants.
    pub blades: Vec<Range<u32>>,
    /// Flower instance ranges drawn.
    pub flowers: Vec<Range<u32>>,
    /// Grids drawn as single plants (far to near when sorting, else in grid order).
    pub near: Vec<NearGrid>,
    /// Grids drawn as billboards (far to near when sorting, else in grid order).
    pub far: Vec<FarGrid>,
    /// Grids drawn (single plants or billboards).
    pub grids: usize,
    /// Grids culled.
    pub culled: usize,
    /// Blades the billboards drawn stand for: those growing in the blocks of the far grids
    /// drawn ([`crate::billboard::GridLevel::represented`]); a grid fading (drawn both ways,
    /// Sec. 6.1) counts its blades once, as single plants.
    pub billboard_blades: u64,
    /// Grids drawn both ways, fading between billboards and single plants (Sec. 6.1).
    pub fading: usize,
    /// Far groups drawn ([`crate::billboard::GroupLevel`]).
    pub groups: usize,
    /// Far groups culled.
    pub groups_culled: usize,
}

impl Plan {
    /// Blades drawn as single plants.
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

    /// The plan of a frame seen through `frustum` (`None`: no culling) with the camera grids
    /// and fade of `transition` (Sec. 6.1); `lod = false` draws single plants everywhere;
    /// `sort` orders the grids far to near by squared grid offset (Sec. 5.4.2).
    pub fn new(
        layout: &Layout,
        index: &GridIndex,
        billboards: &Billboards,
        transition: &Transition,
        frustum: Option<&Frustum>,
        (lod, sort): (bool, bool),
    ) -> Self {
        let mut plan = Self::default();
        let camera = transition.camera();
        // With far groups, the grids nearer than the groups one by one (the groups found
        // from the coarsest level down, so far grids are never visited); without, every grid.
        let (ks, group_anchors) = if lod && !billboards.groups.is_empty() {
            let mut ks = Vec::new();
            let anchors = plan.far_groups(layout, index, billboards, camera, frustum, &mut ks);
            ks.sort_unstable();
            (ks, anchors)
        } else {
            ((0..index.len()).collect(), Vec::new())
        };
        for k in ks {
            let grid = index.id(k);
            let g = grid_offset(layout, grid, camera);
            let delta = grid_coords(layout, grid) - camera;
            // Single plants where the camera grids of the fade (Sec. 6.1) say so; billboards
            // where they do not, at least at the finest step (a grid fading out of single
            // plants is one away).
            let single = transition.single_alpha(layout, grid, lod);
            let step = match Level::at(g.max(2), lod) {
                Level::Billboard { step } => Some(billboards.level(step)),
                Level::Single => None,
            };
            let visible = frustum.is_none_or(|f| f.intersects_aabb(index.bounds(k)));
            // Animated: blades up to two grids away (every grid without LOD), anchors at the
            // finer of the grid's step and the step one grid closer (the level a border
            // crossing can give it). What this frame draws is animated in full, the rest is
            // kept moving (hidden).
            if g <= 2 || !lod {
                let blades = if visible && single > 0.0 {
                    &mut plan.animate_blades
                } else {
                    &mut plan.hidden_blades
                };
                push_merged(blades, index.blades(k));
                push_merged(&mut plan.animate_flowers, index.flowers(k));
            }
            if let (true, Level::Billboard { step: finer }) =
                (g >= 1, Level::at(g.saturating_sub(1).max(2), lod))
            {
                let levels = &billboards.grids[grid as usize];
                let all = levels[billboards.level(finer)].anchors.clone();
                // The drawn step's anchors are a prefix of the finer step's.
                let read = match step {
                    Some(level) if visible && single < 1.0 => levels[level].anchors.end,
                    _ => all.start,
                }
                .clamp(all.start, all.end);
                push_merged(&mut plan.animate_anchors, all.start..read);
                push_merged(&mut plan.hidden_anchors, read..all.end);
            }
            if !visible {
                plan.culled += 1;
                continue;
            }
            plan.grids += 1;
            if single > 0.0 {
                push_merged(&mut plan.blades, index.blades(k));
                push_merged(&mut plan.flowers, index.flowers(k));
                plan.near.push(NearGrid {
                    k,
                    grid,
                    delta,
                    alpha: single,
                });
            }
            if let (Some(level), true) = (step, single < 1.0) {
                if single == 0.0 {
                    plan.billboard_blades += billboards.grids[grid as usize][level].represented;
                }
                plan.far.push(FarGrid {
                    group: 0,
                    grid,
                    delta,
                    level,
                    offset: g,
                    centre2: 2 * delta,
                    alpha: 1.0 - single,
                });
            }
            plan.fading += usize::from(single > 0.0 && single < 1.0);
        }
        // The groups' anchors follow every grid's.
        for r in group_anchors {
            push_merged(&mut plan.animate_anchors, r);
        }
        if sort {
            order::sort_grids(&mut plan.far, |f| f.centre2);
            order::sort_grids(&mut plan.near, |n| n.delta);
        }
        plan
    }

    /// Finds the far groups of this frame (Sec. 5.2's far level continued over groups of
    /// grids, [`crate::billboard::GroupLevel`]): from the coarsest level down, a group whose
    /// nearest grid is at least its level's threshold away from `camera` is drawn whole
    /// (when its box meets `frustum`; culled otherwise), any other is split into its four
    /// children; the non-empty grids reached below the finest groups are pushed to `ks`
    /// (their numbers in `index`). A group's children are never nearer than it, and the
    /// thresholds grow with the level, so every grid is drawn by exactly one grid or group.
    /// Returns the anchor ranges of the groups drawn (sorted), which are animated; the grids
    /// inside drawn groups are not animated.
    fn far_groups(
        &mut self,
        layout: &Layout,
        index: &GridIndex,
        billboards: &Billboards,
        camera: IVec2,
        frustum: Option<&Frustum>,
        ks: &mut Vec<usize>,
    ) -> Vec<Range<u32>> {
        let levels = &billboards.groups;
        let Some(top) = levels.last() else {
            return Vec::new();
        };
        let mut stack: Vec<(usize, IVec2)> = Vec::new();
        for az in 0..top.count.y as i32 {
            for ax in 0..top.count.x as i32 {
                stack.push((levels.len(), IVec2::new(ax, az)));
            }
        }
        let grids = layout.grids.as_ivec2();
        let mut drawn = Vec::new();
        while let Some((k, a)) = stack.pop() {
            if k == 0 {
                if a.cmplt(grids).all()
                    && let Some(slot) = index.slot((a.y * grids.x + a.x) as u32)
                {
                    ks.push(slot);
                }
                continue;
            }
            let level = &levels[k - 1];
            let size = level.size as i32;
            let (lo, hi) = (a * size, ((a + 1) * size).min(grids) - 1);
            if lo.cmpge(grids).any() {
                continue;
            }
            // Offset from the camera grid to the group's nearest grid.
            let near = (lo - camera)
                .max(camera - hi)
                .max(IVec2::ZERO)
                .max_element() as u32;
            if near < level.threshold {
                for d in [IVec2::ZERO, IVec2::X, IVec2::Y, IVec2::ONE] {
                    stack.push((k - 1, 2 * a + d));
                }
                continue;
            }
            let id = (a.y * level.count.x as i32 + a.x) as u32;
            let Some(bounds) = &level.bounds[id as usize] else {
                continue;
            };
            if !frustum.is_none_or(|f| f.intersects_aabb(bounds)) {
                self.groups_culled += 1;
                continue;
            }
            let cell = &level.cells[id as usize];
            if cell.billboards == 0 {
                continue;
            }
            self.groups += 1;
            self.billboard_blades += cell.represented;
            drawn.push((k, id, cell.anchors.clone()));
            let centre2 = (2 * a + IVec2::ONE) * size - (2 * camera + IVec2::ONE);
            self.far.push(FarGrid {
                group: k as u8,
                grid: id,
                delta: centre2 / 2,
                level: level.layer,
                offset: near,
                centre2,
                alpha: 1.0,
            });
        }
        // The groups' anchors in order (level by level, group by group).
        drawn.sort_unstable_by_key(|(k, id, _)| (*k, *id));
        let mut out = Vec::new();
        for (.., anchors) in drawn {
            push_merged(&mut out, anchors);
        }
        out
    }
}

/// Builds the wings of the far grids of `plan` into `out` (cleared first): bottom vertices at
/// the anchors' roots, top vertices at their animated top points (Sec. 4.2), scaled to the
/// billboard texture's `height` and swayed `1 + sway·(g − 2)` times as far from rest for a
/// grid `g` away (the horizontal offset is kept within `height`, so the culling boxes hold).
/// `rest` is each anchor's top point at rest; a fading grid's alpha (Sec. 6.1) goes with
/// each wing. With
/// `orders`, each grid's billboards follow the pre-computed far-to-near order of its section
/// (Sec. 5.4.2); the grids come in the plan's order. Each grid's top points are computed
/// once per anchor (an anchor serves up to six wings of its block and those of its
/// neighbours) into `scratch`'s buffers; from `PARALLEL_WINGS` wings on, the second half
/// of the grids is built on a second (scoped) thread and appended: the same wings in the
/// same order.
#[allow(clippy::too_many_arguments)]
pub fn wings(
    plan: &Plan,
    billboards: &Billboards,
    orders: Option<&BlockOrders>,
    anchors: &[BladeDynamic],
    rest: &[Vec3],
    (height, sway): (f32, f32),
    scratch: &mut WingScratch,
    out: &mut Vec<WingInstance>,
) {
    out.clear();
    let builder = WingBuilder {
        billboards,
        orders,
        anchors,
        rest,
        height,
        sway,
    };
    // Two halves of about equal wing counts on two threads, if worth it.
    let count = |f: &FarGrid| billboards.level_of(f.group, f.grid, f.level).wings.len();
    let total: usize = plan.far.iter().map(count).sum();
    let mut split = plan.far.len();
    if total >= PARALLEL_WINGS {
        let mut before = 0;
        for (i, f) in plan.far.iter().enumerate() {
            if 2 * before >= total {
                split = i;
                break;
            }
            before += count(f);
        }
    }
    let (head, tail) = plan.far.split_at(split);
    let WingScratch {
        tops: [head_tops, tail_tops],
        tail: tail_out,
    } = scratch;
    if tail.is_empty() {
        builder.build(head, head_tops, out);
        return;
    }
    tail_out.clear();
    std::thread::scope(|scope| {
        let builder = &builder;
        let tail_out = &mut *tail_out;
        scope.spawn(move || builder.build(tail, tail_tops, tail_out));
        builder.build(head, head_tops, out);
    });
    out.extend_from_slice(tail_out);
}

/// Fewest wings a frame builds on two threads.
const PARALLEL_WINGS: usize = 4096;

/// The buffers [`wings`] reuses from frame to frame.
#[derive(Clone, Debug, Default)]
pub struct WingScratch {
    /// One far grid's anchor top points, per thread.
    tops: [Vec<Vec3>; 2],
    /// The second thread's wings.
    tail: Vec<WingInstance>,
}

/// What building wings reads.
struct WingBuilder<'a> {
    billboards: &'a Billboards,
    orders: Option<&'a BlockOrders>,
    anchors: &'a [BladeDynamic],
    rest: &'a [Vec3],
    height: f32,
    sway: f32,
}

impl WingBuilder<'_> {
    /// Appends the wings of the grids `far` to `out`.
    fn build(&self, far: &[FarGrid], tops: &mut Vec<Vec3>, out: &mut Vec<WingInstance>) {
        let Self {
            billboards,
            orders,
            anchors,
            rest,
            height,
            sway,
        } = *self;
        for far in far {
            let gain = 1.0 + sway * far.offset.saturating_sub(2) as f32;
            let alpha = far.alpha;
            let top = |a: u32| {
                let a = a as usize;
                let p = &billboards.anchors[a];
                let tip = Vec3::from_slice(&anchors[a].p3[..3]);
                let (d0, d) = ((rest[a] - p.root) / p.height, (tip - p.root) / p.height);
                let mut v = (d0 + gain * (d - d0)) * height;
                let side = v.x.hypot(v.z);
                if side > height {
                    v.x *= height / side;
                    v.z *= height / side;
                }
                v.y = v.y.clamp(0.1 * height, height);
                p.root + v
            };
            let level = billboards.level_of(far.group, far.grid, far.level);
            // Every wing corner is one of the level's anchors (a prefix of the grid's).
            let first = level.anchors.start;
            tops.clear();
            tops.extend(level.anchors.clone().map(top));
            let tops = &*tops;
            let mut push = |w: &crate::billboard::Wing| {
                let Some(cut) = w.cut else { return };
                let (c, o) = (
                    &billboards.anchors[w.centre as usize],
                    &billboards.anchors[w.outer as usize],
                );
                let top = |a: u32| tops[(a - first) as usize];
                let (top_c, top_o) = (top(w.centre), top(w.outer));
                // The cut's corners and texture `u`: the wing's, interpolated along it.
                let at = |t: f32| {
                    (
                        c.root.lerp(o.root, t),
                        top_c.lerp(top_o, t),
                        w.u[0] + (w.u[1] - w.u[0]) * t,
                    )
                };
                let ((root0, top0, u0), (root1, top1, u1)) = (at(cut.along[0]), at(cut.along[1]));
                out.push(WingInstance {
                    centre_root: root0.extend(u0).to_array(),
                    outer_root: root1.extend(u1).to_array(),
                    centre_top: top0.extend(far.level as f32).to_array(),
                    outer_top: top1.extend(w.density).to_array(),
                    fade: [alpha, cut.top, 0.0, 0.0],
                });
            };
            match orders {
                Some(orders) => {
                    for &b in orders.get(far.level, section(far.delta, IVec2::ZERO)) {
                        let r = level.blocks[b as usize].clone();
                        level.wings[r.start as usize..r.end as usize]
                            .iter()
                            .for_each(&mut push);
                    }
                }
                None => level.wings.iter().for_each(push),
            }
        }
    }
}

/// What [`sorted_blades`] reads.
#[derive(Clone, Copy)]
pub struct BladeLookup<'a> {
    /// Where the grids lie.
    pub layout: &'a Layout,
    /// The grids' ranges.
    pub index: &'a GridIndex,
    /// Blade instance at each lattice point, `grid·n² + cell` (`u32::MAX` where none grows).
    pub slots: &'a [u32],
    /// Each blade's root xyz and height.
    pub plants: &'a [[f32; 4]],
}

/// The single plants of `plan`'s near grids far to near (Sec. 5.4.1), written to `out`
/// (instance indices; cleared first): grid by grid in the plan's (sorted) order, the camera
/// grid's plants quicksorted by squared distance to `eye`, the other grids' plants in the line
/// order of their section (Table 1) walked towards the eye ([`line_order`]). Plants whose
/// bounding sphere is outside `frustum` are left out (the second culling level of Sec. 5.3).
pub fn sorted_blades(
    plan: &Plan,
    look: &BladeLookup<'_>,
    eye: Vec3,
    frustum: Option<&Frustum>,
    scratch: &mut Vec<u32>,
    out: &mut Vec<u32>,
) {
    out.clear();
    let n = look.layout.per_side;
    let visible = |b: u32| {
        let [x, y, z, h] = look.plants[b as usize];
        frustum.is_none_or(|f| f.intersects_sphere(Vec3::new(x, y + 0.5 * h, z), h))
    };
    let distance = |b: u32| {
        let [x, y, z, _] = look.plants[b as usize];
        (Vec3::new(x, y, z) - eye).length_squared()
    };
    for near in &plan.near {
        if near.delta == IVec2::ZERO {
            let start = out.len();
            out.extend(look.index.blades(near.k).filter(|&b| visible(b)));
            out[start..].sort_unstable_by(|&a, &b| distance(b).total_cmp(&distance(a)));
        } else {
            let origin = look.layout.origin
                + grid_coords(look.layout, near.grid).as_vec2() * look.layout.grid_size;
            let local = (Vec2::new(eye.x, eye.z) - origin) / look.layout.spacing();
            line_order(n, near.delta.signum(), local, scratch);
            let base = near.grid as usize * (n * n) as usize;
            out.extend(
                scratch
                    .iter()
                    .map(|&cell| look.slots[base + cell as usize])
                    .filter(|&b| b != u32::MAX && visible(b)),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::Params;
    use crate::prairie::plant;
    use grassbench::camera::Camera;
    use grassbench::grass::{BladeField, GrassConfig};
    use grassbench::terrain::Terrain;

    proptest::proptest! {
        /// With far groups, every non-empty grid is drawn once, by itself (single plants or
        /// billboards) or inside one group, and nothing else is drawn: the population drawn
        /// is the planted one whatever the eye (no culling, no fades, flat full grass, so
        /// every block has a billboard).
        #[test]
        fn grids_and_far_groups_tile_the_prairie(x in -70.0f32..70.0, z in -70.0f32..70.0) {
            let (layout, index, billboards, planted) = &*GROUPED;
            let eye = Vec3::new(x, 1.6, z);
            let plan = Plan::new(
                layout,
                index,
                billboards,
                &Transition::new(layout, eye, 0.0),
                None,
                (true, true),
            );
            let mut drawn = vec![0u32; layout.grid_count() as usize];
            for n in &plan.near {
                drawn[n.grid as usize] += 1;
            }
            for f in &plan.far {
                if f.group == 0 {
                    drawn[f.grid as usize] += 1;
                    continue;
                }
                let g = &billboards.groups[usize::from(f.group) - 1];
                let (ax, az) = (f.grid % g.count.x, f.grid / g.count.x);
                for grid in 0..layout.grid_count() {
                    let (gx, gz) = (grid % layout.grids.x, grid / layout.grids.x);
                    if gx / g.size == ax && gz / g.size == az {
                        drawn[grid as usize] += 1;
                    }
                }
            }
            for k in 0..index.len() {
                proptest::prop_assert_eq!(drawn[index.id(k) as usize], 1, "grid {}", index.id(k));
            }
            proptest::prop_assert_eq!(
                plan.blade_count() + plan.billboard_blades,
                planted.len() as u64
            );
            proptest::prop_assert!(plan.groups > 0);
            // Far to near: grids and groups by their middles' offsets.
            let far_to_near = plan
                .far
                .windows(2)
                .all(|w| w[0].centre2.length_squared() >= w[1].centre2.length_squared());
            proptest::prop_assert!(far_to_near);
            // The anchors animated are sorted and hold every drawn group's.
            let sorted = plan.animate_anchors.windows(2).all(|w| w[0].end < w[1].start);
            proptest::prop_assert!(sorted);
        }
    }

    /// A flat 150 m prairie of full grass in 2.5 m grids, far groups from offset 6.
    static GROUPED: std::sync::LazyLock<(
        Layout,
        GridIndex,
        Billboards,
        Vec<crate::prairie::Planted>,
    )> = std::sync::LazyLock::new(|| {
        let terrain = Terrain::flat(Vec2::new(150.0, 150.0));
        let params = Params {
            grid_size: 2.5,
            far_groups: 6,
            ..Params::default()
        };
        let field = BladeField::new(
            GrassConfig {
                density: 3.0,
                ..GrassConfig::default()
            },
            4,
        );
        let (layout, planted) = plant(&params, &field, &terrain, 4);
        let index = GridIndex::new(&planted);
        let billboards = Billboards::new(&layout, &params, &field, &terrain, 4, &planted);
        (layout, index, billboards, planted)
    });

    #[test]
    fn wings_on_two_threads_are_the_wings_of_one() {
        let terrain = Terrain::flat(Vec2::new(80.0, 80.0));
        let params = Params {
            blades_per_side: 32,
            ..Params::default()
        };
        let field = BladeField::new(GrassConfig::default(), 3);
        let (layout, planted) = plant(&params, &field, &terrain, 3);
        let index = GridIndex::new(&planted);
        let billboards = Billboards::new(&layout, &params, &field, &terrain, 3, &planted);
        let mut anchors = crate::animate::Animation::new(&billboards.anchors, params.flower_mass);
        let rest: Vec<Vec3> = anchors
            .blade_out
            .iter()
            .map(|d| Vec3::from_slice(&d.p3[..3]))
            .collect();
        let wind = grassbench::wind::Breeze::new(Default::default(), 3);
        for f in 0..10 {
            anchors.step(&wind, f as f32 / 30.0, 1.0 / 30.0, 2.5, 40.0, 4.0);
        }
        let orders = BlockOrders::new(&billboards.per_side(layout.per_side));
        let eye = Vec3::new(-30.0, 1.6, -25.0);
        let plan = Plan::new(
            &layout,
            &index,
            &billboards,
            &Transition::new(&layout, eye, 0.25),
            None,
            (true, true),
        );
        let builder = WingBuilder {
            billboards: &billboards,
            orders: Some(&orders),
            anchors: &anchors.blade_out,
            rest: &rest,
            height: 0.7,
            sway: 0.05,
        };
        let mut one = Vec::new();
        builder.build(&plan.far, &mut Vec::new(), &mut one);
        assert!(
            one.len() > PARALLEL_WINGS,
            "{} wings: one thread only",
            one.len()
        );
        let (mut scratch, mut two) = (WingScratch::default(), Vec::new());
        for _ in 0..2 {
            let k = (0.7, 0.05);
            wings(
                &plan,
                &billboards,
                Some(&orders),
                &anchors.blade_out,
                &rest,
                k,
                &mut scratch,
                &mut two,
            );
            assert_eq!(one, two);
        }
    }

    #[test]
    fn sorted_blades_are_the_visible_near_plants_once_camera_grid_last_and_far_to_near() {
        let terrain = Terrain::flat(Vec2::new(80.0, 80.0));
        let params = Params {
            grids: 8,
            blades_per_side: 12,
            ..Params::default()
        };
        let field = BladeField::new(GrassConfig::default(), 3);
        let (layout, planted) = plant(&params, &field, &terrain, 3);
        let index = GridIndex::new(&planted);
        let billboards = Billboards::new(&layout, &params, &field, &terrain, 3, &planted);
        let n = layout.per_side;
        let mut slots = vec![u32::MAX; (64 * n * n) as usize];
        for (b, p) in planted.iter().enumerate() {
            slots[(p.grid * n * n + p.cell) as usize] = b as u32;
        }
        let plants: Vec<[f32; 4]> = planted
            .iter()
            .map(|p| p.root.extend(p.height).to_array())
            .collect();
        let look = BladeLookup {
            layout: &layout,
            index: &index,
            slots: &slots,
            plants: &plants,
        };
        for (eye, target) in [
            (Vec3::new(3.0, 1.6, 2.0), Vec3::new(20.0, 0.0, 9.0)),
            (Vec3::new(-12.0, 1.6, 7.0), Vec3::new(-30.0, 0.0, -2.0)),
        ] {
            let camera = Camera::look_at(eye, target, 1.0, 0.1, 300.0, 16.0 / 9.0);
            let frustum = camera.frustum();
            let transition = Transition::new(&layout, eye, 0.0);
            let plan = Plan::new(
                &layout,
                &index,
                &billboards,
                &transition,
                Some(&frustum),
                (true, true),
            );
            let (mut scratch, mut out) = (Vec::new(), Vec::new());
            sorted_blades(&plan, &look, eye, Some(&frustum), &mut scratch, &mut out);
            let mut seen = out.clone();
            seen.sort_unstable();
            seen.dedup();
            assert_eq!(seen.len(), out.len(), "a plant drawn twice");
            // Exactly the near grids' plants whose sphere is in view.
            let expected: Vec<u32> = plan
                .near
                .iter()
                .flat_map(|g| index.blades(g.k))
                .filter(|&b| {
                    let [x, y, z, h] = plants[b as usize];
                    frustum.intersects_sphere(Vec3::new(x, y + 0.5 * h, z), h)
                })
                .collect();
            let mut expected_sorted = expected.clone();
            expected_sorted.sort_unstable();
            assert_eq!(seen, expected_sorted);
            assert!(out.len() > 100 && out.len() < planted.len());
            // The camera grid comes last, its plants farthest first.
            let camera_grid = plan.near.last().expect("near grids").grid;
            assert_eq!(plan.near.last().map(|g| g.delta), Some(IVec2::ZERO));
            let tail: Vec<f32> = out
                .iter()
                .filter(|&&b| planted[b as usize].grid == camera_grid)
                .map(|&b| (planted[b as usize].root - eye).length())
                .collect();
            assert!(!tail.is_empty());
            assert!(tail.windows(2).all(|w| w[0] >= w[1]));
            let first_camera = out
                .iter()
                .position(|&b| planted[b as usize].grid == camera_grid)
                .expect("camera grid");
            assert!(
                out[first_camera..]
                    .iter()
                    .all(|&b| planted[b as usize].grid == camera_grid)
            );
        }
    }
}

//! One frame's plan: for every grass grid its level of detail (Sec. 5.2), whether it is seen
//! (Sec. 5.3), what must be animated, and what is drawn: the single plants' instance ranges
//! and the billboards' wings (Sec. 4.1-4.2).
//!
//! Animation follows the level a grid will have one grid closer to the camera, so a grid that
//! turns from billboards into single plants (or into finer billboards) when the camera crosses
//! a grid border is already in motion: blades are animated in the grids up to two away, the
//! anchors of a billboard grid at the finer of its own and its next-closer step.

use std::ops::Range;

use grassbench::camera::Frustum;
use grassbench::glam::{IVec2, Vec3};
use grassbench::technique::ranges::push_merged;

use crate::billboard::Billboards;
use crate::culling::GridIndex;
use crate::gpu::{BladeDynamic, WingInstance};
use crate::lod::{Level, grid_offset};
use crate::prairie::Layout;

/// A far grid drawn as billboards this frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FarGrid {
    /// Grid index (`gz·grids + gx`).
    pub grid: u32,
    /// Billboard level (index into [`Billboards::steps`]).
    pub level: usize,
    /// Grid offset `g` from the camera grid.
    pub offset: u32,
}

/// What a frame animates and draws.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Plan {
    /// Blade ranges to animate (sorted).
    pub animate_blades: Vec<Range<u32>>,
    /// Flower ranges to animate (sorted).
    pub animate_flowers: Vec<Range<u32>>,
    /// Anchor ranges to animate (sorted).
    pub animate_anchors: Vec<Range<u32>>,
    /// Blade instance ranges drawn as single plants.
    pub blades: Vec<Range<u32>>,
    /// Flower instance ranges drawn.
    pub flowers: Vec<Range<u32>>,
    /// Grids drawn as billboards, in grid order.
    pub far: Vec<FarGrid>,
    /// Grids drawn (single plants or billboards).
    pub grids: usize,
    /// Grids culled.
    pub culled: usize,
    /// Blades standing in the billboards drawn (those of the far grids drawn).
    pub billboard_blades: u64,
}

impl Plan {
    /// Blades drawn as single plants.
    pub fn blade_count(&self) -> u64 {
        self.blades.iter().map(|r| u64::from(r.end - r.start)).sum()
    }

    /// Flowers drawn.
    pub fn flower_count(&self) -> u64 {
        self.flowers.iter().map(|r| u64::from(r.end - r.start)).sum()
    }

    /// The plan of a frame seen from grid `camera` through `frustum` (`None`: no culling);
    /// `lod = false` draws single plants everywhere.
    pub fn new(
        layout: &Layout,
        index: &GridIndex,
        billboards: &Billboards,
        camera: IVec2,
        frustum: Option<&Frustum>,
        lod: bool,
    ) -> Self {
        let mut plan = Self::default();
        for k in 0..index.len() {
            let grid = index.id(k);
            let g = grid_offset(layout, grid, camera);
            let level = Level::at(g, lod);
            // The level one grid closer (what a border crossing can turn it into).
            let closer = Level::at(g.saturating_sub(1), lod);
            if closer == Level::Single {
                push_merged(&mut plan.animate_blades, index.blades(k));
                push_merged(&mut plan.animate_flowers, index.flowers(k));
            }
            let far_level = match (level, closer) {
                (Level::Billboard { step }, Level::Billboard { step: finer }) => {
                    let l = billboards.level(finer);
                    push_merged(
                        &mut plan.animate_anchors,
                        billboards.grids[grid as usize][l].anchors.clone(),
                    );
                    Some(billboards.level(step))
                }
                (Level::Billboard { step }, Level::Single) => {
                    let l = billboards.level(step);
                    push_merged(
                        &mut plan.animate_anchors,
                        billboards.grids[grid as usize][l].anchors.clone(),
                    );
                    Some(l)
                }
                _ => None,
            };
            if !frustum.is_none_or(|f| f.intersects_aabb(index.bounds(k))) {
                plan.culled += 1;
                continue;
            }
            plan.grids += 1;
            match far_level {
                None => {
                    push_merged(&mut plan.blades, index.blades(k));
                    push_merged(&mut plan.flowers, index.flowers(k));
                }
                Some(level) => {
                    let r = index.blades(k);
                    plan.billboard_blades += u64::from(r.end - r.start);
                    plan.far.push(FarGrid {
                        grid,
                        level,
                        offset: g,
                    });
                }
            }
        }
        plan
    }
}

/// Builds the wings of the far grids of `plan` into `out` (cleared first): bottom vertices at
/// the anchors' roots, top vertices at their animated top points (Sec. 4.2), scaled to the
/// billboard texture's `height` and swayed `1 + sway·(g − 2)` times as far from rest for a
/// grid `g` away (the horizontal offset is kept within `height`, so the culling boxes hold).
/// `rest` is each anchor's top point at rest, `fade(grid)` the alpha of Sec. 6.1.
#[allow(clippy::too_many_arguments)]
pub fn wings(
    plan: &Plan,
    billboards: &Billboards,
    anchors: &[BladeDynamic],
    rest: &[Vec3],
    height: f32,
    sway: f32,
    fade: impl Fn(u32) -> f32,
    out: &mut Vec<WingInstance>,
) {
    out.clear();
    for far in &plan.far {
        let gain = 1.0 + sway * far.offset.saturating_sub(2) as f32;
        let alpha = fade(far.grid);
        let top = |a: u32| {
            let a = a as usize;
            let p = &billboards.anchors[a];
            let tip = Vec3::from_slice(&anchors[a].p3[..3]);
            let (d0, d) = (
                (rest[a] - p.root) / p.height,
                (tip - p.root) / p.height,
            );
            let mut v = (d0 + gain * (d - d0)) * height;
            let side = v.x.hypot(v.z);
            if side > height {
                v.x *= height / side;
                v.z *= height / side;
            }
            v.y = v.y.clamp(0.1 * height, height);
            p.root + v
        };
        let level = &billboards.grids[far.grid as usize][far.level];
        for w in &level.wings {
            let (c, o) = (&billboards.anchors[w.centre as usize], &billboards.anchors[w.outer as usize]);
            out.push(WingInstance {
                centre_root: c.root.extend(w.u[0]).to_array(),
                outer_root: o.root.extend(w.u[1]).to_array(),
                centre_top: top(w.centre).extend(far.level as f32).to_array(),
                outer_top: top(w.outer).extend(w.density * alpha).to_array(),
            });
        }
    }
}

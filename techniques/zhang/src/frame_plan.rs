//! Everything `update` works out for a frame, kept for `prepare` and `encode`, and the
//! buffers reused from frame to frame: the grids' plan ([`frame::Plan`]: levels, culling,
//! what is animated and drawn), the billboards' wings, and with sorting the single plants far
//! to near (Sec. 5.4) with their instance data in that order.
//!
//! [`FramePlan::update`] is the frame's CPU work in order: plan the grids (Sec. 5.2-5.3, with
//! the fades of Sec. 6.1), step the blades and anchors together (Sec. 3.2, 6.2), build the
//! wings (Sec. 4.2), write the fading single plants' alpha, and order the single plants.

use std::time::{Duration, Instant};

use grassbench::FrameInputs;
use grassbench::camera::Frustum;
use grassbench::glam::{IVec2, Vec3};

use crate::animate::{self, StepRanges};
use crate::fade::Transition;
use crate::frame::{self, BladeLookup, Plan, WingScratch};
use crate::params::{Params, Sorting};
use crate::plants::{Plants, SortLookup};
use crate::shader_data::{BladeDynamic, BladeStatic, WingInstance};

/// One frame's plan and the per-frame buffers.
pub struct FramePlan {
    /// What the frame animates and draws, grid by grid (`update` → `prepare`, `encode`).
    pub plan: Plan,
    /// This frame's wings (`update` → `prepare`).
    pub wings: Vec<WingInstance>,
    /// Whether this frame has a point light (`update` → `encode`: the wings' pipeline).
    pub point_lit: bool,
    /// With sorting (Sec. 5.4): the frame's single plants far to near; `None` without.
    pub sorted: Option<SortedPlants>,
    /// CPU time of this frame's far-to-near ordering, ms (a statistic; 0 without sorting).
    pub sort_ms: f64,
    /// Scratch for [`frame::wings`].
    wing_scratch: WingScratch,
    /// With `hidden_half_rate = false`: drawn and hidden blades (then anchors) merged, all
    /// stepped in full every frame (the thesis's way).
    full_steps: [Vec<std::ops::Range<u32>>; 2],
}

/// The frame's single plants far to near (Sec. 5.4) and their instance data in that order.
#[derive(Default)]
pub struct SortedPlants {
    /// Blade instances in draw order.
    pub order: Vec<u32>,
    /// Their static instance data, in draw order.
    pub statics: Vec<BladeStatic>,
    /// Their control points, in draw order.
    pub dynamics: Vec<BladeDynamic>,
    /// Scratch for the line orders of [`frame::sorted_blades`].
    scratch: Vec<u32>,
}

impl FramePlan {
    /// The plan before the first frame: every grid as single plants, nothing culled.
    pub fn new(params: &Params, plants: &Plants) -> Self {
        let plan = Plan::new(
            &plants.layout,
            &plants.grids,
            &plants.billboards,
            &Transition::none(IVec2::MIN),
            None,
            (false, false),
        );
        Self {
            plan,
            wings: Vec::new(),
            point_lit: false,
            sorted: (params.sorting == Sorting::Sort).then(SortedPlants::default),
            sort_ms: 0.0,
            wing_scratch: WingScratch::default(),
            full_steps: [Vec::new(), Vec::new()],
        }
    }

    /// Plans the frame of `inputs`, steps `plants`' animation and builds what the frame draws.
    pub fn update(&mut self, params: &Params, plants: &mut Plants, inputs: &FrameInputs<'_>) {
        let p = params;
        let frustum = inputs.camera.frustum();
        let frustum = p.culling.then_some(&frustum);
        let eye = inputs.camera.eye;
        let radius = if p.lod { p.fade_radius } else { 0.0 };
        let transition = Transition::new(&plants.layout, eye, radius);
        // Sorting time is a statistic (the `sort_ms` counter), not an input of the frame.
        let sort_start = Instant::now();
        self.plan = Plan::new(
            &plants.layout,
            &plants.grids,
            &plants.billboards,
            &transition,
            frustum,
            (p.lod, self.sorted.is_some()),
        );
        let mut sort_time = sort_start.elapsed();
        let k = (p.wind_response, p.spring, p.damping);
        let plan = &self.plan;
        self.point_lit = inputs.lights().at(inputs.time).point.is_some();
        // Sec. 6.2: the scene's moving object is the interaction sphere.
        plants.blades.set_sphere(inputs.object());
        // Blades and anchors share one set of threads.
        // The thesis steps every animated blade every frame with the wind at each control
        // point; ours steps the hidden ones every other frame ([`StepRanges::hidden`]).
        let [full_blades, full_anchors] = &mut self.full_steps;
        let (blades, anchors) = if p.hidden_half_rate {
            (
                StepRanges {
                    drawn: &plan.animate_blades,
                    hidden: &plan.hidden_blades,
                    flowers: &plan.animate_flowers,
                },
                StepRanges {
                    drawn: &plan.animate_anchors,
                    hidden: &plan.hidden_anchors,
                    flowers: &[],
                },
            )
        } else {
            merge_sorted(&plan.animate_blades, &plan.hidden_blades, full_blades);
            merge_sorted(&plan.animate_anchors, &plan.hidden_anchors, full_anchors);
            (
                StepRanges {
                    drawn: full_blades,
                    hidden: &[],
                    flowers: &plan.animate_flowers,
                },
                StepRanges {
                    drawn: full_anchors,
                    hidden: &[],
                    flowers: &[],
                },
            )
        };
        animate::step_together(
            inputs.wind,
            inputs.time,
            inputs.dt,
            k,
            &mut [(&mut plants.blades, blades), (&mut plants.anchors, anchors)],
        );
        frame::wings(
            plan,
            &plants.billboards,
            plants.sorting.as_ref().map(|s| &s.orders),
            &plants.anchors.blade_out,
            &plants.anchor_rest,
            (plants.billboard_height, p.billboard_sway),
            &mut self.wing_scratch,
            &mut self.wings,
        );
        // Fading single plants (Sec. 6.1): `P2.w` carries how far each has faded out.
        for near in &plan.near {
            let out = &mut plants.blades.blade_out;
            let r = plants.grids.blades(near.k);
            for d in &mut out[r.start as usize..r.end as usize] {
                d.p2[3] = 1.0 - near.alpha;
            }
        }
        if let (Some(s), Some(lookup)) = (&mut self.sorted, &plants.sorting) {
            sort_time += order_single_plants(plan, plants, lookup, eye, frustum, s);
        }
        self.sort_ms = if self.sorted.is_some() {
            sort_time.as_secs_f64() * 1e3
        } else {
            0.0
        };
    }

    /// Single plants drawn (with sorting, after culling single plants, Sec. 5.3).
    pub fn blade_count(&self) -> u64 {
        self.sorted
            .as_ref()
            .map_or(self.plan.blade_count(), |s| s.order.len() as u64)
    }
}

/// Orders `plan`'s single plants far to near into `out` with their instance data; returns
/// the time the ordering took (not the copies).
fn order_single_plants(
    plan: &Plan,
    plants: &Plants,
    lookup: &SortLookup,
    eye: Vec3,
    frustum: Option<&Frustum>,
    out: &mut SortedPlants,
) -> Duration {
    let start = Instant::now();
    let look = BladeLookup {
        layout: &plants.layout,
        index: &plants.grids,
        slots: &lookup.slots,
        plants: &lookup.plants,
    };
    frame::sorted_blades(plan, &look, eye, frustum, &mut out.scratch, &mut out.order);
    let elapsed = start.elapsed();
    out.statics.clear();
    out.statics
        .extend(out.order.iter().map(|&b| lookup.statics[b as usize]));
    out.dynamics.clear();
    out.dynamics.extend(
        out.order
            .iter()
            .map(|&b| plants.blades.blade_out[b as usize]),
    );
    elapsed
}

/// `a` and `b` (each sorted, disjoint from the other) merged in order into `out`.
fn merge_sorted(
    a: &[std::ops::Range<u32>],
    b: &[std::ops::Range<u32>],
    out: &mut Vec<std::ops::Range<u32>>,
) {
    out.clear();
    out.extend(a.iter().chain(b).cloned());
    out.sort_unstable_by_key(|r| r.start);
}

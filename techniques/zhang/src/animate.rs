//! The per-frame CPU animation of every near blade and flower (Sec. 3.2, 3.4), writing the
//! instance data the vertex shader expands into quads.

use std::ops::Range;

use grassbench::glam::Vec3;
use grassbench::wind::WindField;

use crate::blade::{BladeState, Dynamics};
use crate::flower::FlowerState;
use crate::prairie::Planted;
use crate::shader_data::{BladeDynamic, FlowerInstance};

/// Longest Verlet step, s: longer frames are sub-stepped so the damped spring stays stable
/// (`ω·dt` = 0.21 at the default spring and 30 fps).
pub const MAX_STEP: f32 = 1.0 / 30.0;
/// Most Verlet sub-steps per frame.
pub const MAX_SUBSTEPS: u32 = 8;
/// Hidden blades (see [`StepRanges::hidden`]) are stepped every `HIDDEN_PERIOD` frames, half
/// of them (by instance parity) each frame, by the time of `HIDDEN_PERIOD` frames.
pub const HIDDEN_PERIOD: usize = 2;
/// Longest Verlet step of a hidden blade, s: one step per `HIDDEN_PERIOD` frames at 30 fps.
/// The undamped Verlet step of a spring is stable for `ω·dt < 2`; at the default spring
/// (`ω = √(40·stiffness)`, stiffness 0.7-1.3) `ω·dt` is at most 0.48 here, and the damping and
/// the length constraints only steady it further.
pub const HIDDEN_MAX_STEP: f32 = HIDDEN_PERIOD as f32 * MAX_STEP;

/// Every animated blade and flower, and the instance data of the last step.
#[derive(Clone, Debug)]
pub struct Animation {
    blades: Vec<BladeState>,
    flowers: Vec<FlowerState>,
    /// Per blade: `P1..P3` and the rotation θ (what the GPU reads).
    pub blade_out: Vec<BladeDynamic>,
    /// Per flower: petal centre, spin, stalk axis, texture layer.
    pub flower_out: Vec<FlowerInstance>,
    spins: Vec<(f32, u32)>,
    /// Sample points and wind of one frame (3 per blade, then 1 per flower), reused.
    points: Vec<Vec3>,
    winds: Vec<Vec3>,
    /// Threads the blade step may use (the machine's cores by default).
    threads: usize,
    /// The interaction sphere (centre, radius) of the next steps (Sec. 6.2), if any.
    sphere: Option<(Vec3, f32)>,
    /// One step's blade ranges in instance order, and whether each is hidden (reused).
    work: Vec<(Range<u32>, bool)>,
    /// Steps taken: which half of the hidden blades the next step moves.
    frame: u32,
    /// Whether the instance data carries the rotation θ of Sec. 3.2.5.
    rotations: bool,
}

impl Animation {
    /// Rest state of the planted blades; flowers weigh `flower_mass`.
    pub fn new(planted: &[Planted], flower_mass: f32) -> Self {
        let blades: Vec<BladeState> = planted
            .iter()
            .map(|p| BladeState::new(p.root, p.height, p.facing, p.lean.x, p.lean.y, p.stiffness))
            .collect();
        let (flowers, spins): (Vec<_>, Vec<_>) = planted
            .iter()
            .filter_map(|p| {
                let (h, spin, layer) = p.flower?;
                Some((FlowerState::new(p.root, h, flower_mass), (spin, layer)))
            })
            .unzip();
        let mut a = Self {
            blade_out: vec![BladeDynamic::default(); blades.len()],
            flower_out: vec![FlowerInstance::default(); flowers.len()],
            blades,
            flowers,
            spins,
            points: Vec::new(),
            winds: Vec::new(),
            threads: std::thread::available_parallelism().map_or(1, |t| t.get()),
            sphere: None,
            work: Vec::new(),
            frame: 0,
            rotations: true,
        };
        let samples = 3 * a.blades.len() + a.flowers.len();
        a.points = vec![Vec3::ZERO; samples];
        a.winds = vec![Vec3::ZERO; samples];
        a.write_out();
        a
    }

    /// Sets the threads the blade step may use (1 = on the caller's thread; at most 16).
    pub fn set_threads(&mut self, threads: usize) {
        self.threads = threads;
    }

    /// Sets whether the instance data carries the rotation θ of Sec. 3.2.5 (on by default;
    /// off for the billboards' anchors, whose wings read only the top points, Sec. 4.2).
    pub fn set_rotations(&mut self, rotations: bool) {
        self.rotations = rotations;
    }

    /// Sets the interaction sphere (centre, radius) the next steps push blades out of (Sec.
    /// 6.2); `None` for no interaction.
    pub fn set_sphere(&mut self, sphere: Option<(Vec3, f32)>) {
        self.sphere = sphere;
    }

    /// Blades animated.
    pub fn blade_count(&self) -> usize {
        self.blades.len()
    }

    /// Flowers animated.
    pub fn flower_count(&self) -> usize {
        self.flowers.len()
    }

    /// The blades' states.
    pub fn blades(&self) -> &[BladeState] {
        &self.blades
    }

    /// The flowers' states.
    pub fn flowers(&self) -> &[FlowerState] {
        &self.flowers
    }

    /// Advances every blade and flower by `dt` in `wind` at `time` (see [`Self::step_ranges`]).
    pub fn step(
        &mut self,
        wind: &dyn WindField,
        time: f32,
        dt: f32,
        wind_response: f32,
        spring: f32,
        damping: f32,
    ) {
        let all = 0..self.blades.len() as u32;
        let flowers = 0..self.flowers.len() as u32;
        let k = (wind_response, spring, damping);
        let ranges = StepRanges {
            drawn: std::slice::from_ref(&all),
            hidden: &[],
            flowers: std::slice::from_ref(&flowers),
        };
        self.step_ranges(wind, time, dt, k, ranges);
    }

    /// Advances the blades and flowers of `ranges` by `dt` in `wind` at `time`; the others
    /// keep their state (the level-of-detail choice animates only what it will draw or may
    /// draw soon, Sec. 5.2). For the drawn blades the wind is read once per frame at each
    /// moving control point (`P1..P3`; the root's wind is irrelevant, its inverse mass is 0)
    /// and at each petal, in batched [`WindField::velocities`] calls; then `ceil(dt /
    /// MAX_STEP)` Verlet steps follow, and the drawn blades' instance data is written. Half of
    /// the hidden blades are stepped (see [`StepRanges::hidden`]). `k` is (wind response,
    /// spring, damping). The blades are cut into one contiguous share per core (scoped
    /// threads, at least `MIN_CHUNK` blades each); the sample buffers are reused, so nothing
    /// is allocated but the threads and the piece lists. The result does not depend on the
    /// split. A `dt` that is not positive and finite does nothing; ranges beyond the blades
    /// are clipped.
    pub fn step_ranges(
        &mut self,
        wind: &dyn WindField,
        time: f32,
        dt: f32,
        k: (f32, f32, f32),
        ranges: StepRanges<'_>,
    ) {
        step_together(wind, time, dt, k, &mut [(self, ranges)]);
    }

    /// This step's work: drawn and hidden ranges merged in instance order (each list is
    /// sorted) into `self.work`, and what the pieces share.
    fn plan_step<'w>(
        &mut self,
        ranges: &StepRanges<'_>,
        (wind, time): (&'w dyn WindField, f32),
        dt: f32,
        (wind_response, spring, damping): (f32, f32, f32),
    ) -> Stepping<'w> {
        let work = &mut self.work;
        work.clear();
        let (mut drawn, mut hidden) = (ranges.drawn.iter().peekable(), ranges.hidden.iter());
        let mut next_hidden = hidden.next();
        loop {
            match (drawn.peek(), next_hidden) {
                (Some(d), Some(h)) if h.start < d.start => {
                    work.push((h.clone(), true));
                    next_hidden = hidden.next();
                }
                (Some(d), _) => {
                    work.push(((*d).clone(), false));
                    drawn.next();
                }
                (None, Some(h)) => {
                    work.push((h.clone(), true));
                    next_hidden = hidden.next();
                }
                (None, None) => break,
            }
        }
        let dynamics = |dt: f32, max: f32| {
            let steps = ((dt / max).ceil() as u32).clamp(1, MAX_SUBSTEPS);
            let k = Dynamics::new(dt / steps as f32, wind_response, spring, damping);
            (steps, k)
        };
        self.frame = self.frame.wrapping_add(1);
        Stepping {
            wind,
            time,
            drawn: dynamics(dt, MAX_STEP),
            hidden: dynamics(HIDDEN_PERIOD as f32 * dt, HIDDEN_MAX_STEP),
            phase: self.frame as usize % HIDDEN_PERIOD,
            sphere: self.sphere,
            rotation: self.rotations,
        }
    }

    /// Steps the flowers of `ranges` (after the blades, on the caller's thread).
    fn step_flowers(&mut self, ranges: &[Range<u32>], s: &Stepping<'_>) {
        let (m, n) = (self.flowers.len(), self.blades.len());
        let (steps, k) = &s.drawn;
        for r in ranges {
            let r = (r.start as usize).min(m)..(r.end as usize).min(m);
            let points = &mut self.points[3 * n..][r.clone()];
            let winds = &mut self.winds[3 * n..][r.clone()];
            for (p, f) in points.iter_mut().zip(&self.flowers[r.clone()]) {
                *p = f.pos;
            }
            s.wind.velocities(points, s.time, winds);
            for (f, &w) in self.flowers[r].iter_mut().zip(winds.iter()) {
                for _ in 0..*steps {
                    f.step(w, k);
                }
            }
        }
        self.write_flowers();
    }

    fn write_out(&mut self) {
        write_blades(&self.blades, &mut self.blade_out, self.rotations);
        self.write_flowers();
    }

    fn write_flowers(&mut self) {
        for ((out, f), &(spin, layer)) in self
            .flower_out
            .iter_mut()
            .zip(&self.flowers)
            .zip(&self.spins)
        {
            let axis = (f.pos - f.root).normalize_or(Vec3::Y);
            *out = FlowerInstance {
                pos_spin: [f.pos.x, f.pos.y, f.pos.z, spin],
                axis_layer: [axis.x, axis.y, axis.z, layer as f32],
            };
        }
    }
}

/// Most threads the blade step uses.
const MAX_THREADS: usize = 16;
/// Fewest (drawn) blades a thread takes (below that, spawning costs more than it saves).
const MIN_CHUNK: usize = 2048;
/// The work of a drawn blade in hidden ones (a hidden blade takes one wind sample instead of
/// three, every other frame, and writes no instance data), for the threads' shares.
const DRAWN_WEIGHT: usize = 4;

/// [`Animation::step_ranges`] for several animations at once (the blades and the billboard
/// anchors): their blades are cut into one contiguous share per core of all the work
/// together, in one set of scoped threads; the flowers follow on the caller's thread. Each
/// animation gets the same result as stepped alone.
pub fn step_together(
    wind: &dyn WindField,
    time: f32,
    dt: f32,
    k: (f32, f32, f32),
    jobs: &mut [(&mut Animation, StepRanges<'_>)],
) {
    if !(dt.is_finite() && dt > 0.0) {
        return;
    }
    let steppings: Vec<Stepping<'_>> = jobs
        .iter_mut()
        .map(|(a, r)| a.plan_step(r, (wind, time), dt, k))
        .collect();
    let threads = jobs
        .iter()
        .map(|(a, _)| a.threads)
        .max()
        .unwrap_or(1)
        .clamp(1, MAX_THREADS);
    let weight = |hidden: bool| if hidden { 1 } else { DRAWN_WEIGHT };
    let total: usize = jobs
        .iter()
        .flat_map(|(a, _)| a.work.iter().map(|(r, h)| r.len() * weight(*h)))
        .sum();
    let chunk = total.div_ceil(threads).max(MIN_CHUNK * DRAWN_WEIGHT);
    // Thread `t` takes the work `t·chunk..(t + 1)·chunk` of the ranges' concatenation, as
    // disjoint pieces (a range may be cut between threads): equal shares, whatever the
    // ranges' lengths and kinds.
    let mut buckets: Vec<Vec<(Piece<'_>, &Stepping<'_>)>> =
        (0..threads).map(|_| Vec::new()).collect();
    let mut done = 0usize;
    for ((a, _), stepping) in jobs.iter_mut().zip(&steppings) {
        let n = a.blades.len();
        let mut rest = (
            a.blades.as_mut_slice(),
            &mut a.points[..3 * n],
            &mut a.winds[..3 * n],
            a.blade_out.as_mut_slice(),
        );
        let mut offset = 0usize;
        for (r, hidden) in &a.work {
            let (start, end) = ((r.start as usize).max(offset), (r.end as usize).min(n));
            let mut at = start;
            while at < end {
                let (bucket, w) = (done / chunk, weight(*hidden));
                let len = (end - at).min((chunk * (bucket + 1) - done).div_ceil(w));
                let skip = at - offset;
                let (blades, points, winds, out) = rest;
                let (_, blades) = blades.split_at_mut(skip);
                let (piece_b, blades) = blades.split_at_mut(len);
                let (_, points) = points.split_at_mut(3 * skip);
                let (piece_p, points) = points.split_at_mut(3 * len);
                let (_, winds) = winds.split_at_mut(3 * skip);
                let (piece_w, winds) = winds.split_at_mut(3 * len);
                let (_, out) = out.split_at_mut(skip);
                let (piece_o, out) = out.split_at_mut(len);
                let piece = (piece_b, piece_p, piece_w, piece_o, hidden.then_some(at));
                buckets[bucket.min(threads - 1)].push((piece, stepping));
                done += len * w;
                rest = (blades, points, winds, out);
                offset = at + len;
                at = offset;
            }
        }
    }
    std::thread::scope(|scope| {
        let mut buckets = buckets.into_iter().filter(|b| !b.is_empty());
        // The first bucket runs on the caller's thread.
        let first = buckets.next();
        for bucket in buckets {
            scope.spawn(move || {
                for (piece, stepping) in bucket {
                    step_blades(piece, stepping);
                }
            });
        }
        for (piece, stepping) in first.into_iter().flatten() {
            step_blades(piece, stepping);
        }
    });
    for ((a, r), stepping) in jobs.iter_mut().zip(&steppings) {
        a.step_flowers(r.flowers, stepping);
    }
}

/// What [`Animation::step_ranges`] moves: sorted, disjoint instance ranges.
#[derive(Clone, Copy, Debug, Default)]
pub struct StepRanges<'a> {
    /// Blades drawn this frame: the wind at each moving control point, then their instance
    /// data ([`Animation::blade_out`]) is written.
    pub drawn: &'a [Range<u32>],
    /// Blades animated but not drawn this frame (in culled grids, or a grid away from the
    /// level they are drawn at: the level-of-detail margin of Sec. 5.2). They are kept in
    /// motion at a lower cost: every `HIDDEN_PERIOD` frames (those whose instance index is
    /// the step count modulo `HIDDEN_PERIOD` now, the others later) by the time of
    /// `HIDDEN_PERIOD` frames in steps of at most `HIDDEN_MAX_STEP`, with one wind sample
    /// (at `P2`) for all three control points, and their instance data is not written (it is
    /// written the frame they are drawn). The wind varies little along a blade and over two
    /// frames, so a blade coming into view is close to the pose and motion full steps would
    /// have given it (within 2 % of its height in the test breeze), and what remains decays
    /// with the damping.
    pub hidden: &'a [Range<u32>],
    /// Flowers (always at their petal).
    pub flowers: &'a [Range<u32>],
}

/// A thread's share of one blade range: states, sample points, winds, instance data, and
/// for a hidden range the instance index of its first blade.
type Piece<'a> = (
    &'a mut [BladeState],
    &'a mut [Vec3],
    &'a mut [Vec3],
    &'a mut [BladeDynamic],
    Option<usize>,
);

/// What every piece of one step shares.
struct Stepping<'a> {
    wind: &'a dyn WindField,
    time: f32,
    /// Sub-steps and constants of drawn blades (the frame's `dt`) and of hidden ones
    /// (`HIDDEN_PERIOD` frames).
    drawn: (u32, Dynamics),
    hidden: (u32, Dynamics),
    /// The hidden blades stepped now: instance index ≡ `phase` (mod `HIDDEN_PERIOD`).
    phase: usize,
    sphere: Option<(Vec3, f32)>,
    /// Whether to write θ.
    rotation: bool,
}

/// One chunk of the frame's blade step: gather the sample points (the moving control points,
/// or `P2` of the hidden blades due this frame), one batched wind query, the Verlet steps,
/// the sphere's push (Sec. 6.2), then the instance data of drawn blades.
fn step_blades((blades, points, winds, out, hidden): Piece<'_>, s: &Stepping<'_>) {
    let step = |b: &mut BladeState, w: &[Vec3; 3], (steps, k): &(u32, Dynamics)| {
        let ground = b.pos[0].y;
        for _ in 0..*steps {
            b.step(w, k, ground);
        }
        if let Some((centre, radius)) = s.sphere {
            b.interact(centre, radius, ground);
        }
    };
    if let Some(start) = hidden {
        let first = (s.phase + HIDDEN_PERIOD - start % HIDDEN_PERIOD) % HIDDEN_PERIOD;
        let due = blades.len().saturating_sub(first).div_ceil(HIDDEN_PERIOD);
        let (points, winds) = (&mut points[..due], &mut winds[..due]);
        let due_blades = blades.iter().skip(first).step_by(HIDDEN_PERIOD);
        for (p, b) in points.iter_mut().zip(due_blades) {
            *p = b.pos[2];
        }
        s.wind.velocities(points, s.time, winds);
        let blades = blades.iter_mut().skip(first).step_by(HIDDEN_PERIOD);
        for (b, &w) in blades.zip(winds.iter()) {
            step(b, &[w; 3], &s.hidden);
        }
        return;
    }
    for (p, b) in points.chunks_exact_mut(3).zip(blades.iter()) {
        p.copy_from_slice(&b.pos[1..]);
    }
    s.wind.velocities(points, s.time, winds);
    for (b, w) in blades.iter_mut().zip(winds.chunks_exact(3)) {
        step(b, &[w[0], w[1], w[2]], &s.drawn);
    }
    write_blades(blades, out, s.rotation);
}

/// `P1..P3` and the rotation θ of each blade, as the GPU reads them.
/// (θ = 0 without `rotation`).
fn write_blades(blades: &[BladeState], out: &mut [BladeDynamic], rotation: bool) {
    for (out, b) in out.iter_mut().zip(blades) {
        let rot = if rotation { b.rotation() } else { 0.0 };
        let v = |p: Vec3, w: f32| [p.x, p.y, p.z, w];
        *out = BladeDynamic {
            p1_rotation: v(b.pos[1], rot),
            p2: v(b.pos[2], 0.0),
            p3: v(b.pos[3], 0.0),
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::Params;
    use crate::prairie::plant;
    use grassbench::glam::Vec2;
    use grassbench::grass::GrassConfig;
    use grassbench::terrain::Terrain;
    use grassbench::wind::{Breeze, BreezeConfig};

    /// 4 x 4 grids of 24 x 24 blades with 10 % flowers on flat ground, and their parameters.
    fn prairie() -> (Params, Vec<crate::prairie::Planted>) {
        let terrain = Terrain::flat(Vec2::new(40.0, 40.0));
        let params = Params {
            grids: 4,
            blades_per_side: 24,
            flower_fraction: 0.1,
            ..Params::default()
        };
        let field = grassbench::grass::BladeField::new(GrassConfig::default(), 5);
        let planted = plant(&params, &field, &terrain, 5).1;
        (params, planted)
    }

    #[test]
    fn the_split_over_threads_does_not_change_the_result() {
        let (params, planted) = prairie();
        assert!(planted.len() > 3 * MIN_CHUNK, "too few blades to split");
        let wind = Breeze::new(BreezeConfig::default(), 5);
        let run = |threads| {
            let mut a = Animation::new(&planted, params.flower_mass);
            a.set_threads(threads);
            for f in 0..20 {
                a.step(&wind, f as f32 / 30.0, 1.0 / 30.0, 2.5, 40.0, 4.0);
            }
            (a.blade_out.clone(), a.flower_out.clone())
        };
        let one = run(1);
        assert_eq!(one, run(3));
        assert_eq!(one, run(16));
        // And the blades did move.
        let rest = Animation::new(&planted, params.flower_mass);
        assert_ne!(one.0, rest.blade_out);
    }

    #[test]
    fn hidden_blades_keep_moving_with_the_drawn_ones_and_write_nothing() {
        let (params, planted) = prairie();
        let wind = Breeze::new(BreezeConfig::default(), 5);
        let n = planted.len() as u32;
        let k = (2.5, 40.0, 4.0);
        let mut full = Animation::new(&planted, params.flower_mass);
        let mut mixed = full.clone();
        mixed.set_threads(3);
        let mut single = full.clone();
        single.set_threads(1);
        let rest = full.blade_out.clone();
        let (drawn, hidden, all) = ([0..500, 2000..n], 500..2000, 0..n);
        let (hidden, all) = (std::slice::from_ref(&hidden), std::slice::from_ref(&all));
        for f in 0..60 {
            let t = f as f32 / 30.0;
            let ranges = |drawn, hidden| StepRanges {
                drawn,
                hidden,
                flowers: &[],
            };
            full.step_ranges(&wind, t, 1.0 / 30.0, k, ranges(all, &[]));
            mixed.step_ranges(&wind, t, 1.0 / 30.0, k, ranges(&drawn, hidden));
            single.step_ranges(&wind, t, 1.0 / 30.0, k, ranges(&drawn, hidden));
        }
        assert_eq!(
            mixed.blades(),
            single.blades(),
            "the split changed the result"
        );
        let mut worst = 0.0f32;
        let states = full.blades().iter().zip(mixed.blades()).zip(&rest);
        for (b, ((a, m), rest)) in states.enumerate() {
            if hidden[0].contains(&(b as u32)) {
                // One wind sample per blade every other frame: within 2 % of the height of
                // the full step, and the constraints hold.
                let off = (a.pos[3] - m.pos[3]).length();
                worst = worst.max(off / a.height);
                assert!(off < 0.02 * a.height, "blade {b}: tip {off} m off");
                assert!(
                    (a.pos[3] - a.rest[3]).length() > 0.05 * a.height,
                    "blade {b} still"
                );
                for i in 1..4 {
                    let l = (m.pos[i] - m.pos[i - 1]).length();
                    assert!((l - m.segment).abs() < 1e-4, "blade {b} segment {i}");
                }
                assert_eq!(&mixed.blade_out[b], rest, "hidden blade {b} written");
            } else {
                assert_eq!(a, m, "drawn blade {b}");
                assert_eq!(full.blade_out[b], mixed.blade_out[b]);
            }
        }
        assert!(worst > 0.0);
    }

    #[test]
    fn step_ranges_moves_only_its_ranges_and_like_a_full_step() {
        let (params, planted) = prairie();
        let wind = Breeze::new(BreezeConfig::default(), 5);
        let mut full = Animation::new(&planted, params.flower_mass);
        let mut part = full.clone();
        part.set_threads(3);
        let n = planted.len() as u32;
        let ranges = [10..700, 900..901, 3000..n];
        let m = part.flower_count() as u32;
        let half = 0..m / 2;
        let flowers = std::slice::from_ref(&half);
        for f in 0..10 {
            let t = f as f32 / 30.0;
            full.step(&wind, t, 1.0 / 30.0, 2.5, 40.0, 4.0);
            let ranges = StepRanges {
                drawn: &ranges,
                hidden: &[],
                flowers,
            };
            part.step_ranges(&wind, t, 1.0 / 30.0, (2.5, 40.0, 4.0), ranges);
        }
        let rest = Animation::new(&planted, params.flower_mass);
        for b in 0..n as usize {
            let inside = ranges.iter().any(|r| r.contains(&(b as u32)));
            let expected = if inside {
                &full.blade_out[b]
            } else {
                &rest.blade_out[b]
            };
            assert_eq!(&part.blade_out[b], expected, "blade {b}");
        }
        for k in 0..m as usize {
            let expected = if k < (m / 2) as usize {
                &full.flower_out[k]
            } else {
                &rest.flower_out[k]
            };
            assert_eq!(&part.flower_out[k], expected, "flower {k}");
        }
    }
}

//! Running the calibration's micro-workloads ([`super::workloads`]) on a GPU: timing each
//! sample, reading the GPU's counters to check the work known in advance, and fitting the
//! unit costs ([`calibrate_units`]).
//!
//! - **Clock**: submit to the end of `poll(wait)`, wall time: the runner's `gpu_wall_ms`
//!   clock and the ground truth on lavapipe (compute timestamps there are wrong). For the
//!   upload workload `write_buffer` runs before the clock starts: its CPU copy into staging
//!   memory is the runner's `upload_ms`; the transfer the submission carries is timed.
//! - **Rounds**: every sample runs once as a warm-up (pipeline statistics on), then
//!   [`Options::repeats`] rounds over all samples (as the sweeps interleave techniques), each
//!   round in a new shuffled order, so a burst of load on a shared host spreads over all
//!   workloads instead of corrupting one, and no sample always follows the same one; a short
//!   sample runs once untimed before each timed run (see `SETTLE_BELOW_MS`). Each sample's
//!   time is its median.
//! - **Checks**: the coverage checks ([`super::checks`], [`Options::checks`]) run in the same
//!   rounds after the samples and the held-out mixes, are not fitted, and are priced with the
//!   fitted costs ([`UnitCosts::checks`]).
//! - **Scale**: the workloads are sized for lavapipe at 640x360. Before the rounds each
//!   family's largest size is timed once and, below [`Options::min_largest_ms`], the family
//!   grows by powers of two (up to [`super::workloads::Workload::max_scale`]): on a fast GPU
//!   a lavapipe-sized workload would drown in the fixed cost of a submission.
//! - **Fragments**: a lit blade fragment (the prelude's `shade_leaf` and `apply_fog`, as the
//!   reference's), so a fragment unit is what a technique's lit grass fragment costs; the
//!   vertex unit is a blade vertex with a sway, a normal and a projection. Techniques whose
//!   shaders do much more (texture lookups for wind or terrain) cost more per unit than this:
//!   their runs' residuals against the model say so.

use super::rig::{Counted, Rig};
use super::workloads::{self, Workload};
use super::{Sample, Term, UnitCosts, Work, fit};
use crate::target::Size;
use crate::technique::WorkCounter;
use crate::{Error, GpuContext, Result};

/// How to run the calibration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Timed rounds over all samples after the warm-up (the median is kept).
    pub repeats: usize,
    /// A family whose largest size takes less than this (ms) is scaled up.
    pub min_largest_ms: f64,
    /// Draw into a 4x multisampled target (as [`crate::RenderTarget::new`] makes one), so the
    /// costs price runs drawn with MSAA ([`UnitCosts::msaa`]).
    pub msaa: bool,
    /// Also time the coverage checks ([`super::checks`]) in the same rounds, held out, and
    /// price them ([`UnitCosts::checks`]).
    pub checks: bool,
}

impl Default for Options {
    /// Five rounds; 20 ms for the largest size (2-3% noise at worst for a sample timed with a
    /// 0.5 ms jitter, and lavapipe's sizes already exceed it, so there nothing is scaled).
    fn default() -> Self {
        Self {
            repeats: 5,
            min_largest_ms: 20.0,
            msaa: false,
            checks: true,
        }
    }
}

/// One sample as measured.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct MeasuredSample {
    /// The sample fitted: its median time, and its work as the GPU counted it where the
    /// adapter counts (draw calls and uploads, which no counter sees, as known), else as
    /// known in advance. Counted work is what a run's [`Work`] holds, so the costs are fitted
    /// in the units the runs measure: on lavapipe a fragment is one of the 4x4 block's 16
    /// the rasteriser shades (partly covered blocks count whole), and a triangle larger
    /// than the guard band is clipped into several.
    pub sample: Sample,
    /// The work known in advance from the workload's shape.
    pub known: Work,
    /// The work the GPU's pipeline-statistics counters measured in the warm-up run (draw
    /// calls and uploads copied from `known`); `None` where the adapter has no counters.
    pub counted: Option<Work>,
    /// Samples that passed the depth test and were not discarded in the warm-up run (an
    /// occlusion query; four a pixel where drawn with 4x MSAA); `None` without counters.
    #[serde(default)]
    pub samples_passed: Option<u64>,
    /// Every timed run, ms, in round order.
    pub runs_ms: Vec<f64>,
}

impl MeasuredSample {
    /// Counted over known amount of `term`: 1 when they agree (or both are 0), infinite when
    /// the GPU counted work where none was expected; `None` without counters.
    pub fn counter_ratio(&self, term: Term) -> Option<f64> {
        let (c, k) = (self.counted?.amount(term), self.known.amount(term));
        Some(if c == k { 1.0 } else { c / k })
    }
}

/// The terms the work counter measures (the others are known by construction: draws,
/// uploads, submissions): the GPU's pipeline-statistics counters, and instances, which the
/// harness counts into the counter's segments as it records the draws. Texture fetches,
/// transcendentals, arithmetic, barriers, storage words, integer divisions and mip blends are
/// the counted invocations times those of the shaders' entry points.
pub const COUNTED_TERMS: [Term; 25] = [
    Term::Vertex,
    Term::Primitive,
    Term::FragmentOpaque,
    Term::FragmentAlphaTested,
    Term::FragmentBlended,
    Term::Compute,
    Term::TextureLoad,
    Term::FloatTextureLoad,
    Term::TextureSample,
    Term::FloatTextureSample,
    Term::VertexTranscendental,
    Term::FragmentTranscendental,
    Term::ComputeTranscendental,
    Term::VertexArithmetic,
    Term::FragmentArithmetic,
    Term::ComputeArithmetic,
    Term::ComputeBarrier,
    Term::ComputeStorage,
    Term::VertexStorage,
    Term::ComputeDivision,
    Term::TextureMipBlend,
    Term::Instance,
    Term::PrimitiveInput,
    Term::TextureExplicitLevel,
    Term::HeadPrimitive,
];

/// What [`calibrate_units`] measured and fitted.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct UnitCalibration {
    /// The fitted unit costs.
    pub unit_costs: UnitCosts,
    /// The samples they were fitted to.
    pub samples: Vec<MeasuredSample>,
    /// The held-out mixes, timed with the samples but not fitted (see
    /// [`calibrate_units_with`]); none by default.
    #[serde(default)]
    pub held_out: Vec<MeasuredSample>,
    /// The coverage checks' samples ([`Options::checks`]), in
    /// [`super::checks::coverage_checks`]' order; their results are
    /// [`UnitCosts::checks`].
    #[serde(default)]
    pub check_samples: Vec<MeasuredSample>,
}

/// Clock description recorded with the costs.
fn clock(repeats: usize) -> String {
    format!("wall time, submit to poll(wait), median of {repeats} shuffled rounds after 1 warm-up")
}

/// Runs the micro-workloads at `size` with the default [`Options`] and fits the unit costs.
pub fn calibrate_units(gpu: &GpuContext, size: Size) -> Result<UnitCalibration> {
    calibrate_units_with(gpu, size, Options::default(), &[])
}

/// [`calibrate_units`] with explicit options, and `held_out` mixes: each a submission doing
/// all of its workloads together (render workloads in one pass, dispatches in a compute pass
/// after it, uploads before it), timed in the same interleaved rounds as the calibration's
/// samples (so under the same load) but not fitted: a check of [`UnitCosts::predict`] on
/// work no sample did alone ([`UnitCalibration::held_out`]).
pub fn calibrate_units_with(
    gpu: &GpuContext,
    size: Size,
    options: Options,
    held_out: &[Vec<Workload>],
) -> Result<UnitCalibration> {
    if options.repeats == 0 || options.min_largest_ms.is_nan() || options.min_largest_ms < 0.0 {
        return Err(Error::param(
            "calibration options",
            format!("{options:?}"),
            "at least one repeat and a non-negative minimum time",
        ));
    }
    let rig = Rig::new(gpu, size, options.msaa)?;
    let mut counter = WorkCounter::new(gpu);
    // Scale each family, then lay out every sample.
    let mut plan: Vec<Workload> = Vec::new();
    for family in workloads::families() {
        let mut scale = 1u32;
        // Compiles the pipeline (the first use costs 100-300 ms on lavapipe) at the smallest size.
        rig.run(&[family], None)?;
        for _ in 0..4 {
            if scale >= family.max_scale() {
                break;
            }
            let largest = workloads::sizes(&family, scale)
                .last()
                .copied()
                .unwrap_or(family);
            let (ms, _) = rig.run(&[largest], None)?;
            let step = scale_step(ms, options.min_largest_ms);
            if step == 1 {
                break;
            }
            scale = scale.saturating_mul(step).min(family.max_scale());
        }
        plan.extend(workloads::sizes(&family, scale));
    }
    // Every submission of a round: the samples one workload each, then the held-out mixes,
    // then the coverage checks.
    let checks = if options.checks {
        super::checks::coverage_checks()
    } else {
        Vec::new()
    };
    let submissions: Vec<Vec<Workload>> = plan
        .iter()
        .map(|w| vec![*w])
        .chain(held_out.iter().cloned())
        .chain(checks.iter().map(|c| c.mix.clone()))
        .collect();
    let mut counted = Vec::with_capacity(submissions.len());
    let mut settle = Vec::with_capacity(submissions.len());
    for mix in &submissions {
        let (ms, c) = rig.run(mix, counter.as_mut())?;
        counted.push(c);
        settle.push(ms < SETTLE_BELOW_MS);
    }
    let host_before = crate::runner::HostSample::now();
    let mut runs: Vec<Vec<f64>> = vec![Vec::with_capacity(options.repeats); submissions.len()];
    let mut order: Vec<usize> = (0..submissions.len()).collect();
    let mut rng = crate::rng::Rng::new(0x5eed_c057);
    for _ in 0..options.repeats {
        shuffle(&mut order, &mut rng);
        for &i in &order {
            if settle[i] {
                rig.run(&submissions[i], None)?;
            }
            runs[i].push(rig.run(&submissions[i], None)?.0);
        }
    }
    let host = host_before
        .zip(crate::runner::HostSample::now())
        .and_then(|(a, b)| a.load_until(&b));
    let mut measured_all: Vec<MeasuredSample> = submissions
        .iter()
        .zip(counted)
        .zip(runs)
        .map(|((mix, counted), runs_ms)| {
            let name = if mix.len() == 1 { mix[0].name } else { "mix" };
            let known = mix.iter().fold(Work::default(), |a, w| a + w.work(size));
            measured(name, known, counted, runs_ms)
        })
        .collect();
    let check_samples = measured_all.split_off(plan.len() + held_out.len());
    let held_out = measured_all.split_off(plan.len());
    let samples = measured_all;
    let fitted: Vec<Sample> = samples.iter().map(|s| s.sample.clone()).collect();
    let mut unit_costs = fit(&fitted, &size.to_string(), &clock(options.repeats))?;
    unit_costs.host_other_cores = host.map(|h| h.other_cores);
    unit_costs.msaa = options.msaa;
    unit_costs.checks = super::checks::results(&unit_costs, &checks, &check_samples);
    Ok(UnitCalibration {
        unit_costs,
        samples,
        held_out,
        check_samples,
    })
}

/// Samples whose warm-up took less than this (ms) run once untimed right before each timed
/// run. What a submission leaves behind (freed staging memory, evicted caches, sleeping
/// rasteriser threads) slows the next one by some tenths of a millisecond: lavapipe timed
/// four empty submissions in a row at 0.70, 0.44, 0.31 and 0.28 ms after a 64 MB upload.
/// Against a short sample that is a large error, and it depends on which sample came
/// before; a run of its own first puts the sample in the state a frame repeated frame after
/// frame (as the runner measures them) is in. Long samples do not need it.
const SETTLE_BELOW_MS: f64 = 10.0;

/// Fisher-Yates shuffle: each round visits the samples in a new order, so no sample always
/// follows the same one.
fn shuffle(order: &mut [usize], rng: &mut crate::rng::Rng) {
    for i in (1..order.len()).rev() {
        let j = (rng.next_u64() % (i as u64 + 1)) as usize;
        order.swap(i, j);
    }
}

/// A sample from its runs: the median time, fitted on the counted work where there is one.
fn measured(
    name: &str,
    known: Work,
    counted: Option<Counted>,
    runs_ms: Vec<f64>,
) -> MeasuredSample {
    let work = counted.as_ref().map(|c| c.work);
    MeasuredSample {
        sample: Sample {
            workload: name.to_owned(),
            measured_ms: crate::runner::Percentiles::of(runs_ms.iter().copied())
                .map_or(f64::NAN, |p| p.median),
            work: work.unwrap_or(known),
        },
        known,
        counted: work,
        samples_passed: counted.map(|c| c.samples_passed),
        runs_ms,
    }
}

/// The power of two by which to grow a workload whose largest size took `ms` to reach
/// `target_ms`; 1 when it already does (or took no measurable time: nothing to scale from).
pub fn scale_step(ms: f64, target_ms: f64) -> u32 {
    if ms.is_nan() || ms <= 0.0 || ms >= target_ms {
        return 1;
    }
    let k = (target_ms / ms).log2().ceil().clamp(0.0, 16.0);
    1u32 << (k as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_shuffle_is_a_permutation_and_changes_the_order() {
        let mut rng = crate::rng::Rng::new(1);
        let mut order: Vec<usize> = (0..36).collect();
        shuffle(&mut order, &mut rng);
        let mut sorted = order.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..36).collect::<Vec<_>>());
        assert_ne!(order, sorted);
    }

    #[test]
    fn scale_steps_are_powers_of_two_reaching_the_target() {
        assert_eq!(scale_step(40.0, 20.0), 1);
        assert_eq!(scale_step(20.0, 20.0), 1);
        assert_eq!(scale_step(10.0, 20.0), 2);
        assert_eq!(scale_step(9.0, 20.0), 4);
        assert_eq!(scale_step(0.1, 20.0), 256);
        assert_eq!(scale_step(0.0, 20.0), 1);
        assert_eq!(scale_step(f64::NAN, 20.0), 1);
        // Never more than 2^16 in one step.
        assert_eq!(scale_step(1e-9, 20.0), 1 << 16);
    }
}

//! The cost model (issue 20 §2-§4): a frame's GPU time explained as
//! `Σ unit cost × measured work`, with the unit costs of an adapter fitted from timed
//! micro-workloads whose work is known.
//!
//! - [`Work`]: what a frame made the GPU do (vertex invocations, primitives, fragments by
//!   [`FragmentKind`], draws and their instances, compute invocations, bytes uploaded), from the GPU's own
//!   counters and the harness's, and what its shaders did inside those invocations (texel
//!   loads and samples, those of floating-point texels and the vertex stage's loads apart,
//!   transcendentals and scalar arithmetic by stage, compute shaders' workgroup barriers, compute and vertex shaders' storage-buffer words,
//!   compute shaders' integer divisions, samples that blend two mip levels, samples at a level each invocation gives: the
//!   counted invocations times their entry points' operations,
//!   `crate::shaders::ShaderOps`);
//! - [`Term`]: the model's terms, one unit cost each, plus a fixed cost per submission;
//! - [`UnitCosts`]: an adapter's fitted costs with their standard errors and the fit's
//!   residuals; [`UnitCosts::predict`] gives a frame's time and where it goes
//!   ([`Prediction`]), on the adapter the costs were measured on, or projected onto another
//!   from the same work;
//! - [`fit()`]: the joint, weighted, non-negative least-squares fit of [`Sample`]s;
//! - [`workloads`]: the micro-workloads and their work known in advance; [`measure`] runs and
//!   times them on a GPU ([`calibrate_units`]) and checks their work against the counters;
//! - [`checks`]: the coverage checks, timed with the calibration and not fitted: blades on
//!   screen and hidden layers, fragments unlike the fitted layers', priced and compared;
//!
//! Costs are in the clock the samples were timed with: submit-to-`poll(wait)` wall time, the
//! ground truth on lavapipe (see `shared/PLATFORM.md`), the same clock as the runner's
//! `gpu_wall_ms`.

pub mod checks;
pub mod drift;
pub mod fit;
mod lstsq;
pub mod measure;
mod rig;
mod run;
mod term;
mod units;
mod work;
pub mod workloads;

pub use fit::{FitSummary, Sample, WorkloadResidual, fit};
pub use measure::{
    COUNTED_TERMS, MeasuredSample, Options, UnitCalibration, calibrate_units, calibrate_units_with,
};
pub use run::{apply_model, predict_run};
pub use term::Term;
pub use units::{Prediction, UnitCost, UnitCosts};
pub use work::{BYTES_PER_MB, FragmentKind, Work};

//! Scripted sweeps: a TOML file names scenes x techniques x parameter grids x resolutions x
//! repetitions; [`SweepSpec::expand`] turns it into an ordered list of [`PlannedRun`]s and
//! [`SweepStore`] keeps their results so an interrupted sweep resumes where it stopped.
//!
//! Order matters for honest timing: within a repetition every configuration runs once, and
//! techniques are interleaved (A B C A B C …) so slow drifts of the machine (thermal, other
//! jobs) spread evenly over the techniques instead of biasing whichever ran last.
//!
//! Every run is measured against the `reference` run of its group ([`compare_with_reference`]:
//! ratio, speed-up and the speed-up's 95 % bootstrap interval), by the sweep as the run
//! finishes and by the report for runs that could not be ([`fill_ratios`]).

mod reference;
mod spec;
mod store;

pub use reference::{REFERENCE, compare_with_reference, fill_ratios, ratio_to_reference};
pub use spec::{PlannedRun, SweepSpec, apply_overrides, config_id_of, sweep_key};
pub use store::{ParamRow, SweepStore, append_rows, image_path, read_column, read_rows};

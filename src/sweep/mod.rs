//! Scripted sweeps: a TOML file names scenes x techniques x parameter grids x resolutions x
//! repetitions; [`SweepSpec::expand`] turns it into an ordered list of [`PlannedRun`]s and
//! [`SweepStore`] keeps their results so an interrupted sweep resumes where it stopped.
//!
//! Order matters for honest timing: within a repetition every configuration runs once, and
//! techniques are interleaved (A B C A B C …) so slow drifts of the machine (thermal, other
//! jobs) spread evenly over the techniques instead of biasing whichever ran last.

mod spec;
mod store;

pub use spec::{PlannedRun, SweepSpec, apply_overrides};
pub use store::{ParamRow, SweepStore, append_rows, read_column};

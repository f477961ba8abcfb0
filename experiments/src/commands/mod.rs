//! The subcommands of `grassbench`.

mod calibrate;
mod compare;
mod list;
mod merge;
mod out_dir;
mod progress;
mod render;
mod report;
mod run;
mod sweep;
mod validate;

pub use calibrate::{CalibrateArgs, CalibrationFile, calibrate};
pub use compare::{CompareArgs, MOTIONS, compare};
pub use list::list;
pub use merge::{MergeArgs, merge};
pub use render::{RenderArgs, render};
pub use report::{REPORT_HTML, ReportArgs, report, write_html};
pub use run::{RunArgs, run};
pub use sweep::{SweepArgs, SweepMeta, parse_shard, sweep};
pub use validate::{ValidateArgs, validate};

use anyhow::Context as _;
use grassbench::GpuContext;
use grassbench::gpu::BackendChoice;

/// Options every GPU command shares.
#[derive(Clone, Debug, clap::Args)]
pub struct GpuArgs {
    /// Graphics backend: auto, vulkan, gl, metal, dx12 (default: $GRASSBENCH_BACKEND or auto).
    #[arg(long, global = true)]
    pub backend: Option<String>,
}

impl GpuArgs {
    /// Creates the GPU context the arguments ask for.
    pub fn context(&self) -> anyhow::Result<GpuContext> {
        let choice = match &self.backend {
            Some(b) => b.parse::<BackendChoice>()?,
            None => BackendChoice::from_env()?,
        };
        GpuContext::new(choice).context("cannot start the GPU")
    }
}

/// `v` with `digits` decimals, or a dash where nothing was measured.
pub(crate) fn fmt_opt(v: Option<f64>, digits: usize) -> String {
    v.map_or("–".to_owned(), |x| format!("{x:.digits$}"))
}

/// Parses repeated `--param key=value` into a table.
pub fn param_table(assignments: &[String]) -> anyhow::Result<toml::Table> {
    let mut table = toml::Table::new();
    for a in assignments {
        let (k, v) = grassbench::params::parse_assignment(a)?;
        table.insert(k, v);
    }
    Ok(table)
}

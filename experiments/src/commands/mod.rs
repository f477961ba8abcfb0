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
pub use sweep::{SweepArgs, SweepMeta, parse_shard, sweep, sweep_with};
pub use validate::{ValidateArgs, validate};

use anyhow::Context as _;
use grassbench::gpu::BackendChoice;
use grassbench::technique::TechniqueEntry;
use grassbench::{GpuContext, Scene};

/// The raw limits and unit costs a results folder's `meta.toml` recorded (a `run`'s or a
/// `sweep`'s), if any: what an interrupted run into `dir` resumes with, and what its report
/// shows of the calibration.
pub(crate) fn recorded_calibration(
    dir: &std::path::Path,
) -> Option<(
    Option<grassbench::calibration::Calibration>,
    Vec<grassbench::cost::UnitCosts>,
)> {
    let text = std::fs::read_to_string(dir.join("meta.toml")).ok()?;
    let table: toml::Table = toml::from_str(&text).ok()?;
    let costs: Vec<grassbench::cost::UnitCosts> =
        table.get("unit_costs")?.clone().try_into().ok()?;
    // Folders written before the raw limits were recorded have none.
    let calibration = table
        .get("calibration")
        .and_then(|c| c.clone().try_into().ok());
    (!costs.is_empty()).then_some((calibration, costs))
}

/// Options every GPU command shares.
#[derive(Clone, Debug, clap::Args)]
pub struct GpuArgs {
    /// Graphics backend: auto, vulkan, gl, metal, dx12 (default: $GRASSBENCH_BACKEND or auto).
    #[arg(long, global = true)]
    pub backend: Option<String>,
}

impl GpuArgs {
    /// Creates the GPU context the arguments ask for, its device requesting
    /// `wgpu::Limits::default()` (for commands that create no technique).
    pub fn context(&self) -> anyhow::Result<GpuContext> {
        self.context_for(&grassbench::wgpu::Limits::default())
    }

    /// Creates the GPU context the arguments ask for, its device requesting `needs` (what the
    /// command's techniques need: [`needs`]), lowered to what the adapter offers, and says on
    /// stderr which adapter it got and what that adapter cannot record.
    pub fn context_for(&self, needs: &grassbench::wgpu::Limits) -> anyhow::Result<GpuContext> {
        let choice = self.choice()?;
        let gpu = GpuContext::for_needs(choice, needs).context("cannot start the GPU")?;
        eprintln!("{}", gpu.summary.describe());
        for note in gpu.summary.notes(choice) {
            eprintln!("{note}");
        }
        Ok(gpu)
    }

    /// The backend the arguments (or `GRASSBENCH_BACKEND`) ask for.
    pub fn choice(&self) -> anyhow::Result<BackendChoice> {
        Ok(match &self.backend {
            Some(b) => b.parse::<BackendChoice>()?,
            None => BackendChoice::from_env()?,
        })
    }
}

/// The device limits a command needs to create each technique of `runs` (technique, scene,
/// overrides on top of the scene's `[techniques.<id>]`): the field-wise maximum of what each
/// declares, never less than `wgpu::Limits::default()`. Computed without GPU work.
pub fn needs<'a>(
    runs: impl IntoIterator<Item = (&'a TechniqueEntry, &'a Scene, &'a toml::Table)>,
) -> anyhow::Result<grassbench::wgpu::Limits> {
    let mut all = Vec::new();
    for (entry, scene, overrides) in runs {
        let params = scene.technique_params(entry.info.id, overrides);
        all.push(
            entry
                .required_limits(scene, &params)
                .with_context(|| format!("`{}` on scene `{}`", entry.info.id, scene.name()))?,
        );
    }
    Ok(grassbench::gpu::limits::needed_by(&all))
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

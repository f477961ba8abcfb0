//! `grassbench`: compare real-time grass techniques on the same scenes.

use std::process::ExitCode;

use clap::{Parser, Subcommand};
use grassbench_cli::commands::{
    self, CalibrateArgs, CompareArgs, MergeArgs, RenderArgs, ReportArgs, RunArgs, SweepArgs,
    ValidateArgs,
};

/// Compare real-time grass techniques on the same terrain, camera path, wind and GPU.
#[derive(Parser)]
#[command(name = "grassbench", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// List techniques (with their parameters) and built-in scenes.
    List,
    /// Render one frame of one technique to a PNG.
    Render(RenderArgs),
    /// Measure techniques on scenes: frames.csv, runs.csv, images, meta.toml, README.md.
    Run(RunArgs),
    /// Run a sweep file: `results/<sweep>/{runs,frames,params}.csv`, meta.toml; resumable.
    Sweep(SweepArgs),
    /// Join the outputs of sweep shards.
    Merge(MergeArgs),
    /// Measure the adapter's raw limits (triangles/s, fill rate, bandwidth).
    Calibrate(CalibrateArgs),
    /// Write REPORT.md with tables and plots for a sweep's results folder.
    Report(ReportArgs),
    /// Image differences: LOD fidelity, cross-technique matrix, temporal change (spurious / missing).
    Compare(CompareArgs),
    /// Check scene and sweep files without rendering.
    Validate(ValidateArgs),
    /// Open the side-by-side comparison window.
    Ui(grassbench_cli::ui::UiArgs),
}

fn main() -> ExitCode {
    steady_allocator();
    // The revision this binary was built from, for every meta.toml it writes.
    grassbench::runner::record_build_revision(env!("GRASSBENCH_BUILD_REVISION"));
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::List => commands::list(),
        Command::Render(args) => commands::render(args),
        Command::Run(args) => commands::run(args),
        Command::Sweep(args) => commands::sweep(args),
        Command::Merge(args) => commands::merge(args),
        Command::Calibrate(args) => commands::calibrate(args),
        Command::Report(args) => commands::report(args),
        Command::Compare(args) => commands::compare(args),
        Command::Validate(args) => commands::validate(args),
        Command::Ui(args) => grassbench_cli::ui::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

/// Starts the process again with glibc's heaps kept between frames, where the C library reads
/// its tunables only at start-up (`grassbench::runner::allocator`: lavapipe's per-frame
/// allocations otherwise put some processes in a state 1.2-1.3 times as slow). Returns where
/// nothing is to be done; where starting again fails, warns and goes on with the defaults,
/// which `meta.toml` then records.
fn steady_allocator() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        use grassbench::runner::allocator;
        use std::os::unix::process::CommandExt as _;

        let var = |name: &str| std::env::var(name).ok();
        let Some(tunables) = allocator::tunables_to_set(
            var("GLIBC_TUNABLES").as_deref(),
            var(allocator::OPT_OUT_VARIABLE).as_deref(),
        ) else {
            return;
        };
        let mut args = std::env::args_os();
        let program = args.next();
        let exe = match std::env::current_exe() {
            Ok(exe) => exe,
            Err(e) => {
                eprintln!(
                    "warning: glibc malloc keeps its defaults (no path to this program: {e})"
                );
                return;
            }
        };
        let mut command = std::process::Command::new(exe);
        if let Some(program) = program {
            command.arg0(program);
        }
        // `exec` returns only when it failed.
        let e = command.args(args).env("GLIBC_TUNABLES", tunables).exec();
        eprintln!(
            "warning: glibc malloc keeps its defaults (starting again with GLIBC_TUNABLES failed: {e}; set {}=system to skip the attempt)",
            allocator::OPT_OUT_VARIABLE
        );
    }
}

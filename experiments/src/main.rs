//! `grassbench`: compare real-time grass techniques on the same scenes.

use std::process::ExitCode;

use clap::{Parser, Subcommand};
use grassbench_cli::commands::{self, RenderArgs, RunArgs};

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
    /// Open the side-by-side comparison window.
    Ui(grassbench_cli::ui::UiArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::List => commands::list(),
        Command::Render(args) => commands::render(args),
        Command::Run(args) => commands::run(args),
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

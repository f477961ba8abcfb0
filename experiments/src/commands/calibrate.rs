//! `grassbench calibrate`: the adapter's raw limits.

use std::path::PathBuf;

use grassbench::calibration::calibrate as measure;
use grassbench::runner::{Provenance, write_atomic};
use grassbench::target::Size;

use super::GpuArgs;

/// Arguments of `calibrate`.
#[derive(Clone, Debug, clap::Args)]
pub struct CalibrateArgs {
    /// Target size WxH.
    #[arg(long, default_value = "640x360")]
    pub size: String,
    /// Also write the figures with provenance to this TOML file.
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// GPU options.
    #[command(flatten)]
    pub gpu: GpuArgs,
}

#[derive(serde::Serialize)]
struct CalibrationFile {
    calibration: grassbench::calibration::Calibration,
    provenance: Provenance,
}

/// Measures and prints the adapter's limits.
pub fn calibrate(args: &CalibrateArgs) -> anyhow::Result<()> {
    let size = Size::parse(&args.size)?;
    let gpu = args.gpu.context()?;
    let calibration = measure(&gpu, size)?;
    let file = CalibrationFile {
        calibration,
        provenance: Provenance::collect(&gpu.summary),
    };
    let text = toml::to_string_pretty(&file)?;
    std::io::Write::write_all(&mut std::io::stdout(), text.as_bytes())?;
    if let Some(path) = &args.out {
        write_atomic(path, |f| std::io::Write::write_all(f, text.as_bytes()))?;
    }
    Ok(())
}

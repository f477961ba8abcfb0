//! `grassbench calibrate`: the adapter's raw limits and its unit costs (issue 20 §2).

use std::path::PathBuf;

use anyhow::Context as _;
use grassbench::calibration::calibrate as measure;
use grassbench::cost::{
    COUNTED_TERMS, MeasuredSample, Options, ProbeReading, UnitCalibration, UnitCosts,
    calibrate_units, calibrate_units_with, probes_markdown, workloads,
};
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
    /// Also time the probes in the calibration's rounds, unfitted: strips whose vertices load
    /// texels (RGBA8 and `R32Float`), to say what a texel load costs in the vertex stage
    /// against the price fitted on fragment shaders' loads.
    #[arg(long)]
    pub probes: bool,
    /// GPU options.
    #[command(flatten)]
    pub gpu: GpuArgs,
}

/// What `calibrate` prints and writes: the raw limits, the unit costs with their fit, every
/// sample they were fitted to, and the provenance.
#[derive(serde::Serialize, serde::Deserialize)]
pub struct CalibrationFile {
    /// The raw limits (triangles/s, fill, bandwidth).
    pub calibration: grassbench::calibration::Calibration,
    /// The unit costs.
    pub unit_costs: UnitCosts,
    /// Provenance.
    pub provenance: Provenance,
    /// The samples, with their runs and counted work.
    pub samples: Vec<MeasuredSample>,
    /// With `--probes`: what each probe sample implies its term costs.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub probes: Vec<ProbeReading>,
    /// With `--probes`: the probe samples, with their runs and counted work.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub probe_samples: Vec<MeasuredSample>,
}

/// Measures, prints (TOML on stdout, a summary on stderr) and optionally writes.
pub fn calibrate(args: &CalibrateArgs) -> anyhow::Result<()> {
    let size = Size::parse(&args.size)?;
    let gpu = args.gpu.context()?;
    let calibration = measure(&gpu, size)?;
    let started = std::time::Instant::now();
    let probes = if args.probes {
        workloads::probes()
    } else {
        Vec::new()
    };
    let held_out: Vec<_> = probes.iter().map(|w| vec![*w]).collect();
    let UnitCalibration {
        unit_costs,
        samples,
        held_out: probe_samples,
    } = calibrate_units_with(&gpu, size, Options::default(), &held_out)
        .context("measuring the unit costs")?;
    eprint!("{}", summary(&unit_costs, &samples));
    let readings: Vec<ProbeReading> = probes
        .iter()
        .zip(&probe_samples)
        .filter_map(|(w, s)| ProbeReading::read(&unit_costs, &s.sample, w.term))
        .collect();
    if !probes.is_empty() {
        eprint!(
            "Probes (timed in the same rounds, not fitted; prices in ns per unit)\n\n{}",
            probes_markdown(&readings)
        );
    }
    eprintln!(
        "Unit costs measured in {:.1} s.",
        started.elapsed().as_secs_f64()
    );
    let file = CalibrationFile {
        calibration,
        unit_costs,
        provenance: Provenance::collect(&gpu.summary),
        samples,
        probes: readings,
        probe_samples,
    };
    let text = toml::to_string_pretty(&file)?;
    std::io::Write::write_all(&mut std::io::stdout(), text.as_bytes())?;
    if let Some(path) = &args.out {
        write_atomic(path, |f| std::io::Write::write_all(f, text.as_bytes()))?;
    }
    Ok(())
}

/// The adapter's unit costs at each distinct size of `sizes` (in their first order), each
/// fit's summary printed as it is measured: what `run` and `sweep` calibrate before measuring.
pub(crate) fn unit_costs_at(
    gpu: &grassbench::GpuContext,
    sizes: impl IntoIterator<Item = Size>,
) -> anyhow::Result<Vec<UnitCosts>> {
    let mut done: Vec<Size> = Vec::new();
    let mut all = Vec::new();
    for size in sizes {
        if done.contains(&size) {
            continue;
        }
        done.push(size);
        eprintln!("unit costs of {} at {size} …", gpu.summary.name);
        let units = calibrate_units(gpu, size)
            .with_context(|| format!("measuring the unit costs at {size}"))?;
        eprint!("{}", summary(&units.unit_costs, &units.samples));
        all.push(units.unit_costs);
    }
    Ok(all)
}

/// The costs' table and how the GPU's counters compare with the work known in advance.
pub(crate) fn summary(costs: &UnitCosts, samples: &[MeasuredSample]) -> String {
    let mut text = format!("Unit costs\n\n{}", costs.to_markdown());
    if samples.iter().all(|s| s.counted.is_none()) {
        text.push_str(
            "The adapter has no pipeline-statistics counters: fitted on the work as designed, unchecked.\n",
        );
        return text;
    }
    text.push_str("GPU counters over work known in advance, lowest and highest ratio:");
    for t in COUNTED_TERMS {
        let ratios: Vec<f64> = samples
            .iter()
            .filter(|s| s.known.amount(t) > 0.0 || s.counted.is_some_and(|c| c.amount(t) > 0.0))
            .filter_map(|s| s.counter_ratio(t))
            .collect();
        if let (Some(lo), Some(hi)) = (
            ratios.iter().copied().reduce(f64::min),
            ratios.iter().copied().reduce(f64::max),
        ) {
            text.push_str(&format!(" {t} {lo:.3}-{hi:.3};"));
        }
    }
    text.push_str(" (the fit uses the counted work).\n");
    text
}

//! `grassbench calibrate`: the adapter's raw limits and its unit costs (issue 20 §2).

use std::path::PathBuf;

use anyhow::Context as _;
use grassbench::calibration::{Calibration, calibrate as measure};
use grassbench::cost::{COUNTED_TERMS, MeasuredSample, Options, UnitCosts, calibrate_units_with};
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
    /// Draw the unit costs' workloads into a 4x multisampled target: the costs then price runs
    /// drawn with `--msaa` (and only those).
    #[arg(long)]
    pub msaa: bool,
    /// GPU options.
    #[command(flatten)]
    pub gpu: GpuArgs,
}

/// What `calibrate` prints and writes: the raw limits, the unit costs with their fit and their
/// coverage checks, every sample they were fitted to and every check's, and the provenance.
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
    /// The coverage checks' samples, with their runs and counted work (their results are
    /// the unit costs' `checks`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub check_samples: Vec<MeasuredSample>,
}

/// Measures, prints (TOML on stdout, a summary on stderr) and optionally writes.
pub fn calibrate(args: &CalibrateArgs) -> anyhow::Result<()> {
    let size = Size::parse(&args.size)?;
    let gpu = args.gpu.context()?;
    let calibration = measure(&gpu, size)?;
    let started = std::time::Instant::now();
    let units = calibrate_units_with(&gpu, size, options(args.msaa), &[])
        .context("measuring the unit costs")?;
    eprint!("{}", summary(&units.unit_costs, &units.samples));
    eprintln!(
        "Unit costs measured in {:.1} s.",
        started.elapsed().as_secs_f64()
    );
    let file = CalibrationFile {
        calibration,
        unit_costs: units.unit_costs,
        provenance: Provenance::collect(&gpu.summary),
        samples: units.samples,
        check_samples: units.check_samples,
    };
    let text = toml::to_string_pretty(&file)?;
    std::io::Write::write_all(&mut std::io::stdout(), text.as_bytes())?;
    if let Some(path) = &args.out {
        write_atomic(path, |f| std::io::Write::write_all(f, text.as_bytes()))?;
    }
    Ok(())
}

/// The calibration's options, drawing into a 4x multisampled target where `msaa`.
fn options(msaa: bool) -> Options {
    Options {
        msaa,
        ..Options::default()
    }
}

/// What `run` and `sweep` calibrate before measuring: the adapter's raw limits at `raw` (by
/// default the first of `targets`' sizes, or 640x360 where there is none), then its unit costs
/// for each distinct target of `targets` (size, and whether drawn with 4x MSAA; in their first
/// order), each figure printed as it is measured.
///
/// The raw limits come first, and not only for their figures: a process's first
/// primitive-heavy submissions on lavapipe find its rasteriser slow at triangle setup until a
/// large draw has run (its raw triangle workload draws 900 k triangles a submission). Measured
/// on the 2.6 GHz EPYC host, 2026-12-04: unit costs fitted first thing in a process priced a
/// primitive at 266-281 ns in five processes of six (115 in the sixth), after the raw limits
/// at 84-113 ns, every other term alike; the techniques' frames, which follow their warm-up
/// frames, ran at the second price (bakay on the meadow at 320x180 predicted at 65.9 ms with
/// the first, its frames 45.4 ms).
pub(crate) fn adapter_at(
    gpu: &grassbench::GpuContext,
    raw: Option<Size>,
    targets: &[(Size, bool)],
) -> anyhow::Result<(Calibration, Vec<UnitCosts>)> {
    let raw = raw.or(targets.first().map(|t| t.0)).unwrap_or(Size {
        width: 640,
        height: 360,
    });
    eprintln!("calibrating {} …", gpu.summary.name);
    let c = measure(gpu, raw).context("measuring the adapter's raw limits")?;
    eprintln!(
        "  {:.1} M triangles/s, {:.1} M blended pixels/s, {:.2} GB/s copy; raw reference blade {:.0} ns",
        c.triangles_per_s / 1e6,
        c.fill_pixels_per_s / 1e6,
        c.compute_bytes_per_s / 1e9,
        c.raw_blade_cost_ns
    );
    Ok((c, unit_costs_at(gpu, targets)?))
}

/// The raw limits (at `raw`'s size, where the runs had them) and the unit costs again, once the
/// runs are done: how far the host moved while they ran, for the raw blade rate the reference
/// is read against (issue 20 §6) as for the cost model.
pub(crate) fn adapter_after(
    gpu: &grassbench::GpuContext,
    raw: Option<&Calibration>,
    targets: &[(Size, bool)],
) -> anyhow::Result<(Option<Calibration>, Vec<UnitCosts>)> {
    let Some(before) = raw else {
        return Ok((None, unit_costs_at(gpu, targets)?));
    };
    let size = Size::parse(&before.size)
        .with_context(|| format!("the raw limits' size `{}`", before.size))?;
    let (after, costs) = adapter_at(gpu, Some(size), targets)?;
    Ok((Some(after), costs))
}

/// The adapter's unit costs for each distinct target of `targets` (size, MSAA; in their first
/// order), each fit's summary printed as it is measured.
pub(crate) fn unit_costs_at(
    gpu: &grassbench::GpuContext,
    targets: &[(Size, bool)],
) -> anyhow::Result<Vec<UnitCosts>> {
    let mut done: Vec<(Size, bool)> = Vec::new();
    let mut all = Vec::new();
    for &(size, msaa) in targets {
        if done.contains(&(size, msaa)) {
            continue;
        }
        done.push((size, msaa));
        let samples = if msaa { ", 4x MSAA" } else { "" };
        eprintln!("unit costs of {} at {size}{samples} …", gpu.summary.name);
        let units = calibrate_units_with(gpu, size, options(msaa), &[])
            .with_context(|| format!("measuring the unit costs at {size}{samples}"))?;
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

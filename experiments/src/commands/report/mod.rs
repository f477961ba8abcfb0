//! `grassbench report DIR`: `REPORT.md` with tables and SVG plots for a sweep's results.

mod configs;
mod drift;
mod html;
mod parameters;
mod plots;
mod projection;
mod raw_rate;

use std::fmt::Write as _;
use std::path::PathBuf;

use grassbench::runner::write_atomic;

use super::fmt_opt as fmt;
use super::sweep::SweepMeta;
use configs::{BUSY_HOST_CORES, Config, KERNEL_CORES, label, load, median};
use grassbench::runner::bootstrap::Interval;
use grassbench::sweep::REFERENCE;
use plots::{
    SPLIT_SEGMENTS, frame_time_plot, pareto_plot, scaling_plot, split_rows, time_split_plot,
};
use std::collections::BTreeMap;

pub use html::{REPORT_HTML, write_html};

/// Arguments of `report`.
#[derive(Clone, Debug, clap::Args)]
pub struct ReportArgs {
    /// A sweep's results folder.
    pub dir: PathBuf,
    /// Another adapter's calibration (its `meta.toml` from `run` or `sweep`, or a file from
    /// `grassbench calibrate -o`): adds each run's GPU time *predicted* there from the work
    /// measured here.
    #[arg(long)]
    pub calibration: Option<PathBuf>,
    /// Only the rows at one operating point: `paper` (each technique's `paper` variant, the
    /// reference beside them), `default` (rows without a variant), or any variant name a
    /// sweep's `variant` parameter used. Writes `REPORT-<variant>.md` and `plots-<variant>/`
    /// beside the full report instead of replacing it.
    #[arg(long)]
    pub variant: Option<String>,
}

/// "Which is faster": per group (scene, variant, size, MSAA), its configurations by speed-up
/// over the reference, joined by `>` where the 95 % intervals of neighbours do not overlap
/// and by `≈` where they do: one is called faster than another only where the intervals
/// separate them.
fn faster_than(md: &mut String, configs: &BTreeMap<String, Config>) {
    let mut groups: BTreeMap<(String, String, String, bool), Vec<&Config>> = BTreeMap::new();
    for c in configs.values().filter(|c| !c.gpu_wall.is_empty()) {
        groups
            .entry((c.scene.clone(), c.variant.clone(), c.size.clone(), c.msaa))
            .or_default()
            .push(c);
    }
    let interval = |c: &Config| {
        if c.technique == REFERENCE {
            // The unit every speed-up is measured in.
            Some(Interval {
                low: 1.0,
                high: 1.0,
            })
        } else {
            c.speedup_interval
        }
    };
    let mut lines = Vec::new();
    for ((scene, variant, size, msaa), mut members) in groups {
        members.retain(|c| interval(c).is_some());
        if members.len() < 2 {
            continue;
        }
        members.sort_by(|a, b| {
            let mid = |c: &Config| interval(c).map_or(0.0, |i| 0.5 * (i.low + i.high));
            mid(b).total_cmp(&mid(a))
        });
        let mut line = String::new();
        for (k, c) in members.iter().enumerate() {
            if k > 0 {
                let separated = match (interval(members[k - 1]), interval(c)) {
                    (Some(a), Some(b)) => a.separated_from(&b),
                    _ => false,
                };
                line.push_str(if separated { " > " } else { " ≈ " });
            }
            let _ = match interval(c) {
                Some(i) if c.technique != REFERENCE => {
                    write!(line, "{} ({:.2}–{:.2})", label(c), i.low, i.high)
                }
                _ => write!(line, "{} (1)", label(c)),
            };
        }
        let variant = if variant.is_empty() {
            String::new()
        } else {
            format!(" {variant}")
        };
        lines.push(format!(
            "- {scene}{variant} {size}{}: {line}",
            if msaa { " 4x" } else { "" }
        ));
    }
    if !lines.is_empty() {
        let _ = writeln!(
            md,
            "\n**Which is faster.** Speed-up over the reference with its 95 % bootstrap interval (frames and repetitions resampled); `>` only where neighbouring intervals do not overlap, `≈` where they do (no difference this measurement can show):\n"
        );
        for l in lines {
            let _ = writeln!(md, "{l}");
        }
    }
}

/// "Where the time goes" (issue 20 §3): per configuration with a cost model, the share of each
/// CPU stage and GPU term of the frame, the model's prediction against the measured time, and
/// the stacked bar of `plots/time_split.svg`.
fn where_the_time_goes(
    md: &mut String,
    configs: &[&Config],
    plots: &std::path::Path,
) -> anyhow::Result<()> {
    let link = plots_link(plots);
    let rows = split_rows(configs);
    if rows.is_empty() {
        return Ok(());
    }
    let _ = writeln!(md, "\n## Where the time goes\n");
    let _ = writeln!(
        md,
        "The cost model prices each run's measured work (pipeline statistics: vertices, primitives, fragments by kind, and the texel loads and texture samples of the shaders that ran them; the harness's draws and uploads) with the adapter's unit costs from the calibration above. *Measured / model* is the measured median GPU wall time over the prediction: near 1 where the counted work explains the time. Shares are of the CPU stages plus the predicted GPU time. Predicted, not measured: each GPU term is unit cost × work.\n"
    );
    let mut header = String::from(
        "| scene | size | technique | params | measured GPU ms | model ms | measured / model |",
    );
    let mut rule = String::from("|---|---|---|---|---|---|---|");
    for name in SPLIT_SEGMENTS {
        let _ = write!(header, " {name} |");
        rule.push_str("---|");
    }
    let _ = writeln!(md, "{header}\n{rule}");
    for row in &rows {
        let (c, split) = (row.config, row.split);
        let total: f64 = split.iter().sum();
        let mut line = format!(
            "| {} | {} | {} | {} | {} | {:.1} | {} |",
            c.scene,
            c.size,
            c.technique,
            c.label,
            fmt(median(&c.gpu_wall), 1),
            row.model_ms,
            fmt(median(&c.model_ratio), 2)
        );
        for v in split {
            let _ = write!(line, " {:.0} % |", 100.0 * v / total.max(1e-12));
        }
        let _ = writeln!(md, "{line}");
    }
    let modelled: Vec<&Config> = rows.iter().map(|r| r.config).collect();
    time_split_plot(&modelled, &plots.join("time_split.svg"))?;
    let _ = writeln!(md, "\n![Where the time goes]({link}/time_split.svg)\n");
    Ok(())
}

/// Writes REPORT.md, plots/*.svg and report.html for a sweep's folder; report.html alone for
/// a `run`'s or `compare`'s (their Markdown report is the README.md the command wrote).
pub fn report(args: &ReportArgs) -> anyhow::Result<()> {
    let dir = &args.dir;
    if !html::is_sweep_folder(dir)? {
        if args.calibration.is_some() {
            anyhow::bail!(
                "--calibration projects a sweep's runs; `{}` is not a sweep's results folder",
                dir.display()
            );
        }
        return write_html(dir);
    }
    // Read (and so check) the other adapter's calibration before writing anything.
    let other = args
        .calibration
        .as_deref()
        .map(projection::Calibration::load)
        .transpose()?;
    let mut configs = load(dir)?;
    if let Some(want) = &args.variant {
        configs.retain(|_, c| c.technique == REFERENCE || c.operating_point() == *want);
        if configs.values().all(|c| c.technique == REFERENCE) {
            anyhow::bail!(
                "--variant {want}: no run in {} is at that operating point (the rows' `variant=` parameter names it; `default` is rows without one)",
                dir.display()
            );
        }
    }
    let suffix = args
        .variant
        .as_ref()
        .map_or(String::new(), |v| format!("-{v}"));
    let meta: Option<SweepMeta> = std::fs::read_to_string(dir.join("meta.toml"))
        .ok()
        .and_then(|t| toml::from_str(&t).ok());
    let plots = dir.join(format!("plots{suffix}"));
    let link = plots_link(&plots);
    std::fs::create_dir_all(&plots)?;
    let mut md = String::new();
    let title = meta
        .as_ref()
        .map_or("sweep".to_owned(), |m| m.sweep.clone());
    let _ = writeln!(md, "# Report: {title}\n");
    if let Some(m) = &meta {
        let shard = format!("; shard: {}", m.shard);
        let _ = writeln!(md, "{}", m.provenance.to_markdown(&shard));
        if let Some(c) = &m.calibration {
            let _ = writeln!(
                md,
                "Calibration ({}, {}): {:.1} M triangles/s, {:.1} M blended pixels/s, {:.2} GB/s buffer copy; raw cost of a reference blade's 9 triangles {:.0} ns.\n",
                c.size,
                c.clock,
                c.triangles_per_s / 1e6,
                c.fill_pixels_per_s / 1e6,
                c.compute_bytes_per_s / 1e9,
                c.raw_blade_cost_ns
            );
        }
        for u in &m.unit_costs {
            let _ = writeln!(
                md,
                "Unit costs of this adapter at {}, fitted jointly over the calibration's micro-workloads (a frame's GPU time ≈ Σ cost × work):\n\n{}",
                u.size,
                u.to_markdown()
            );
        }
    }
    let _ = writeln!(
        md,
        "All times are medians over repetitions of per-run medians; GPU = wall time from submit to the end of `poll(wait)`. Speed-up = reference time / technique time in the same configuration and repetition. FLIP is the mean FLIP of the last measured frame against the reference's, at full resolution and after 4x downsampling (blade placement differs between techniques by design, so the reduced scale is the fairer one).\n"
    );

    let _ = writeln!(md, "## Cost and quality\n");
    let _ = writeln!(
        md,
        "| scene | variant | size | technique | params | GPU ms | frame ms | speed-up | 95 % interval | FLIP | FLIP 1/4 | blades drawn | blades represented | triangles | GPU MB | runs failed |"
    );
    let _ = writeln!(
        md,
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
    );
    for c in configs.values() {
        let _ = writeln!(
            md,
            "| {} | {} | {}{} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            c.scene,
            if c.variant.is_empty() {
                "–"
            } else {
                &c.variant
            },
            c.size,
            if c.msaa { " 4x" } else { "" },
            c.technique,
            c.label,
            fmt(median(&c.gpu_wall), 1),
            fmt(median(&c.frame), 1),
            fmt(median(&c.ratio).map(|r| 1.0 / r), 2),
            c.speedup_interval
                .map_or("–".to_owned(), |i| format!("{:.2}–{:.2}", i.low, i.high)),
            fmt(median(&c.flip), 3),
            fmt(median(&c.flip_quarter), 3),
            fmt(c.blades_drawn, 0),
            fmt(c.blades_represented, 0),
            fmt(c.triangles, 0),
            fmt(c.gpu_mb, 1),
            c.failed
        );
    }
    faster_than(&mut md, &configs);
    let disagreeing: Vec<(&Config, f64)> = configs
        .values()
        .filter_map(|c| Some((c, c.repetitions_disagree()?)))
        .collect();
    if !disagreeing.is_empty() {
        let _ = writeln!(
            md,
            "\n**Warning: repetitions that disagree.** In these configurations the median GPU times of the repetitions lie further apart than the p5-p95 band of any one repetition: something outside the configuration (the host's load or clock) changed between them, so compare them with care.\n"
        );
        for (c, spread) in &disagreeing {
            let _ = writeln!(
                md,
                "- {} on {} {}: repetition medians {} ms (spread {spread:.1} ms; widest p5-p95 of one repetition {:.1} ms)",
                label(c),
                c.scene,
                c.size,
                c.gpu_wall
                    .iter()
                    .map(|v| format!("{v:.1}"))
                    .collect::<Vec<_>>()
                    .join(", "),
                c.gpu_wall_band.iter().copied().fold(0.0, f64::max)
            );
        }
    }
    let flagged = |cores: fn(&Config) -> Option<f64>| -> Vec<(&Config, f64)> {
        configs
            .values()
            .filter_map(|c| Some((c, cores(c)?)))
            .collect()
    };
    warning(
        &mut md,
        &format!(
            "**Warning: a busy host.** Other processes kept more than {BUSY_HOST_CORES} of a core busy while these configurations measured (`host_other_cores` in runs.csv); on a software rasteriser that time is taken from the GPU, so their times are too slow by up to that share of the cores:"
        ),
        &flagged(Config::busy_host),
    );
    warning(
        &mut md,
        &format!(
            "**Warning: time in the kernel.** The process spent more than {KERNEL_CORES} of a core in the kernel while these configurations measured (`host_own_kernel_cores` in runs.csv), time their frames paid the operating system rather than their work: on frames of a few milliseconds mostly the rasteriser threads' wake-ups (`futex`), which the model's fixed cost per frame does not hold; in a process that returned memory and took it again every frame, fresh pages (`GRASSBENCH_ALLOCATOR`, README):"
        ),
        &flagged(Config::kernel_time),
    );
    parameters::section(&mut md, &configs);
    let _ = writeln!(md, "\n## CPU and GPU stages (ms)\n");
    let _ = writeln!(
        md,
        "| scene | size | technique | params | CPU update | CPU upload | CPU encode | GPU wall |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|---|---|");
    for c in configs.values() {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {} | {} |",
            c.scene,
            c.size,
            c.technique,
            c.label,
            fmt(median(&c.update), 3),
            fmt(median(&c.upload), 3),
            fmt(median(&c.encode), 3),
            fmt(median(&c.gpu_wall), 1)
        );
    }

    let ok: Vec<&Config> = configs
        .values()
        .filter(|c| !c.gpu_wall.is_empty())
        .collect();
    where_the_time_goes(&mut md, &ok, &plots)?;
    if let Some(m) = &meta {
        if let Some(c) = &m.calibration {
            raw_rate::raw_rate(&mut md, &ok, c, m.calibration_after.as_ref());
        }
        drift::drift(&mut md, &configs, &m.unit_costs, &m.unit_costs_after);
    }
    if let Some(other) = &other {
        projection::projection(&mut md, &configs, other)?;
    }
    let _ = writeln!(md, "\n## Plots\n");
    frame_time_plot(&ok, &plots.join("frame_time.svg"))?;
    let _ = writeln!(
        md,
        "![GPU time per technique and scene]({link}/frame_time.svg)\n"
    );
    if ok.iter().any(|c| !c.flip_quarter.is_empty()) {
        pareto_plot(&ok, &plots.join("pareto.svg"))?;
        let _ = writeln!(
            md,
            "![Quality against the reference versus cost]({link}/pareto.svg)\n"
        );
    }
    let distinct = |f: &dyn Fn(&Config) -> String| {
        ok.iter()
            .map(|c| f(c))
            .collect::<std::collections::BTreeSet<_>>()
            .len()
    };
    if distinct(&|c| c.variant.clone()) > 1 {
        scaling_plot(
            &ok,
            &|c| c.blades_shown().unwrap_or(0.0),
            "blades shown (drawn + represented)",
            &plots.join("scaling_blades.svg"),
        )?;
        let _ = writeln!(md, "![GPU time versus blades]({link}/scaling_blades.svg)\n");
    }
    if distinct(&|c| c.size.clone()) > 1 {
        let pixels = |c: &Config| {
            c.size
                .split_once('x')
                .and_then(|(w, h)| Some(w.parse::<f64>().ok()? * h.parse::<f64>().ok()?))
                .unwrap_or(0.0)
        };
        scaling_plot(
            &ok,
            &pixels,
            "pixels",
            &plots.join("scaling_resolution.svg"),
        )?;
        let _ = writeln!(
            md,
            "![GPU time versus resolution]({link}/scaling_resolution.svg)\n"
        );
    }
    let images: Vec<&Config> = configs.values().filter(|c| c.image.is_some()).collect();
    if !images.is_empty() {
        let _ = writeln!(md, "## Last frames\n");
        for c in images {
            let _ = writeln!(
                md,
                "**{} / {} {} {}** {}\n\n![]({})\n",
                c.scene,
                c.technique,
                c.size,
                c.variant,
                c.label,
                c.image.as_deref().unwrap_or_default()
            );
        }
    }
    let path = dir.join(format!("REPORT{suffix}.md"));
    write_atomic(&path, |f| std::io::Write::write_all(f, md.as_bytes()))?;
    eprintln!("wrote {}", path.display());
    write_html(dir)
}

/// A warning paragraph, then one line per flagged configuration with its figure in cores;
/// nothing where none is flagged.
fn warning(md: &mut String, text: &str, flagged: &[(&Config, f64)]) {
    if flagged.is_empty() {
        return;
    }
    let _ = writeln!(md, "\n{text}\n");
    for (c, cores) in flagged {
        let _ = writeln!(
            md,
            "- {} on {} {}: up to {cores:.2} cores",
            label(c),
            c.scene,
            c.size
        );
    }
}

/// The folder name of `plots` as REPORT.md links it (relative to the results folder).
fn plots_link(plots: &std::path::Path) -> String {
    plots
        .file_name()
        .map_or("plots".into(), |n| n.to_string_lossy().into_owned())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_warning_names_each_flagged_configuration_and_nothing_without_one() {
        let mut md = String::new();
        warning(&mut md, "**Warning: time in the kernel.**", &[]);
        assert_eq!(md, "");
        let c = Config {
            technique: "reference".into(),
            scene: "football_field".into(),
            size: "640x360".into(),
            ..Config::default()
        };
        warning(&mut md, "**Warning: time in the kernel.**", &[(&c, 0.18)]);
        assert_eq!(
            md,
            "\n**Warning: time in the kernel.**\n\n- reference on football_field 640x360: up to 0.18 cores\n"
        );
    }
}

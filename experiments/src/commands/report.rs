//! `grassbench report DIR`: `REPORT.md` with tables and SVG plots for a sweep's results.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};
use grassbench::runner::{Percentiles, write_atomic};
use plotters::prelude::*;

use super::sweep::SweepMeta;

/// Arguments of `report`.
#[derive(Clone, Debug, clap::Args)]
pub struct ReportArgs {
    /// A sweep's results folder.
    pub dir: PathBuf,
}

/// One configuration, its repetitions pooled.
#[derive(Clone, Debug, Default)]
struct Config {
    technique: String,
    scene: String,
    variant: String,
    size: String,
    msaa: bool,
    params: String,
    label: String,
    gpu_wall: Vec<f64>,
    frame: Vec<f64>,
    update: Vec<f64>,
    upload: Vec<f64>,
    encode: Vec<f64>,
    ratio: Vec<f64>,
    flip: Vec<f64>,
    flip_quarter: Vec<f64>,
    efficiency: Vec<f64>,
    blades: f64,
    triangles: f64,
    gpu_mb: f64,
    image: Option<String>,
    failed: usize,
}

fn median(v: &[f64]) -> Option<f64> {
    Percentiles::of(v.iter().copied()).map(|p| p.median)
}

fn fmt(v: Option<f64>, digits: usize) -> String {
    v.map_or("–".to_owned(), |x| format!("{x:.digits$}"))
}

/// Reads runs.csv into configurations keyed by configuration id.
fn load(dir: &Path) -> anyhow::Result<BTreeMap<String, Config>> {
    let path = dir.join("runs.csv");
    let mut reader = csv::Reader::from_path(&path)
        .with_context(|| format!("`{}` has no runs.csv: run a sweep first", dir.display()))?;
    let headers = reader.headers()?.clone();
    let col = |name: &str| {
        headers
            .iter()
            .position(|h| h == name)
            .with_context(|| format!("{} lacks column `{name}`", path.display()))
    };
    let (c_id, c_status, c_tech, c_scene, c_var) = (
        col("run_id")?,
        col("status")?,
        col("technique")?,
        col("scene")?,
        col("scene_variant")?,
    );
    let (c_w, c_h, c_msaa, c_params) =
        (col("width")?, col("height")?, col("msaa")?, col("params")?);
    let nums = [
        "gpu_wall_ms_median",
        "frame_ms_median",
        "update_ms_median",
        "upload_ms_median",
        "encode_ms_median",
        "gpu_wall_ratio_to_reference",
        "flip_vs_reference",
        "flip_vs_reference_quarter",
        "efficiency",
        "blades",
        "triangles",
        "gpu_bytes",
    ]
    .map(col)
    .into_iter()
    .collect::<anyhow::Result<Vec<_>>>()?;
    let records = reader.records().collect::<Result<Vec<_>, _>>()?;
    // The reference's GPU time per group (scene, variant, size, MSAA, repetition): a run
    // written before its group's reference (another shard's, after `merge`) has no ratio in
    // runs.csv, and gets it here.
    let c_rep = col("repetition")?;
    let group = |r: &csv::StringRecord| {
        [c_scene, c_var, c_w, c_h, c_msaa, c_rep].map(|k| r.get(k).unwrap_or_default().to_owned())
    };
    let reference: BTreeMap<_, f64> = records
        .iter()
        .filter(|r| r.get(c_tech) == Some("reference") && r.get(c_status) == Some("ok"))
        .filter_map(|r| Some((group(r), r.get(nums[0])?.parse().ok()?)))
        .collect();
    let mut configs: BTreeMap<String, Config> = BTreeMap::new();
    for r in &records {
        let get = |k: usize| r.get(k).unwrap_or_default();
        let num = |k: usize| get(nums[k]).parse::<f64>().ok();
        let id = get(c_id);
        let config_id = id.rsplit_once("-r").map_or(id, |(c, _)| c).to_owned();
        let c = configs.entry(config_id.clone()).or_default();
        c.technique = get(c_tech).to_owned();
        c.scene = get(c_scene).to_owned();
        c.variant = get(c_var).to_owned();
        c.size = format!("{}x{}", get(c_w), get(c_h));
        c.msaa = get(c_msaa) == "true";
        if get(c_status) != "ok" {
            c.failed += 1;
            continue;
        }
        c.params = get(c_params).to_owned();
        let push = |v: &mut Vec<f64>, k: usize| {
            if let Some(x) = num(k) {
                v.push(x);
            }
        };
        push(&mut c.gpu_wall, 0);
        push(&mut c.frame, 1);
        push(&mut c.update, 2);
        push(&mut c.upload, 3);
        push(&mut c.encode, 4);
        match num(5) {
            Some(ratio) => c.ratio.push(ratio),
            None => {
                if let (Some(t), Some(&t_ref)) = (num(0), reference.get(&group(r))) {
                    c.ratio.push(t / t_ref);
                }
            }
        }
        push(&mut c.flip, 6);
        push(&mut c.flip_quarter, 7);
        push(&mut c.efficiency, 8);
        c.blades = num(9).unwrap_or(0.0);
        c.triangles = num(10).unwrap_or(0.0);
        c.gpu_mb = num(11).unwrap_or(0.0) / 1e6;
        let img = dir.join("images").join(format!("{config_id}.png"));
        if img.exists() {
            c.image = Some(format!("images/{config_id}.png"));
        }
    }
    if configs.is_empty() {
        bail!("{} has no runs", path.display());
    }
    Ok(configs)
}

/// Writes REPORT.md and plots/*.svg.
pub fn report(args: &ReportArgs) -> anyhow::Result<()> {
    let dir = &args.dir;
    let mut configs = load(dir)?;
    // Labels show only the parameters that vary within a technique, not every default.
    shorten_params(&mut configs);
    let meta: Option<SweepMeta> = std::fs::read_to_string(dir.join("meta.toml"))
        .ok()
        .and_then(|t| toml::from_str(&t).ok());
    let plots = dir.join("plots");
    std::fs::create_dir_all(&plots)?;
    let mut md = String::new();
    let title = meta
        .as_ref()
        .map_or("sweep".to_owned(), |m| m.sweep.clone());
    let _ = writeln!(md, "# Report: {title}\n");
    if let Some(m) = &meta {
        let p = &m.provenance;
        let _ = writeln!(
            md,
            "Measured on `{}` ({}, {}; driver {} {}), CPU {} x{}, revision `{}` ({} build), {}.  ",
            p.adapter.name,
            p.adapter.backend,
            p.adapter.device_type,
            p.adapter.driver,
            p.adapter.driver_info,
            p.cpu,
            p.cpu_count,
            p.revision,
            p.build_profile,
            p.date
        );
        let _ = writeln!(md, "Command: `{}`; shard: {}.\n", p.command, m.shard);
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
    }
    let _ = writeln!(
        md,
        "All times are medians over repetitions of per-run medians; GPU = wall time from submit to the end of `poll(wait)`. Speed-up = reference time / technique time in the same configuration and repetition. FLIP is the mean FLIP of the last measured frame against the reference's, at full resolution and after 4x downsampling (blade placement differs between techniques by design, so the reduced scale is the fairer one).\n"
    );

    let _ = writeln!(md, "## Cost and quality\n");
    let _ = writeln!(
        md,
        "| scene | variant | size | technique | params | GPU ms | frame ms | speed-up | FLIP | FLIP 1/4 | efficiency | blades | triangles | GPU MB | runs failed |"
    );
    let _ = writeln!(
        md,
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
    );
    for c in configs.values() {
        let _ = writeln!(
            md,
            "| {} | {} | {}{} | {} | {} | {} | {} | {} | {} | {} | {} | {:.0} | {:.0} | {:.1} | {} |",
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
            fmt(median(&c.flip), 3),
            fmt(median(&c.flip_quarter), 3),
            fmt(median(&c.efficiency), 2),
            c.blades,
            c.triangles,
            c.gpu_mb,
            c.failed
        );
    }
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
    let _ = writeln!(md, "\n## Plots\n");
    frame_time_plot(&ok, &plots.join("frame_time.svg"))?;
    let _ = writeln!(
        md,
        "![GPU time per technique and scene](plots/frame_time.svg)\n"
    );
    if ok.iter().any(|c| !c.flip_quarter.is_empty()) {
        pareto_plot(&ok, &plots.join("pareto.svg"))?;
        let _ = writeln!(
            md,
            "![Quality against the reference versus cost](plots/pareto.svg)\n"
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
            &|c| c.blades,
            "blades represented",
            &plots.join("scaling_blades.svg"),
        )?;
        let _ = writeln!(md, "![GPU time versus blades](plots/scaling_blades.svg)\n");
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
            "![GPU time versus resolution](plots/scaling_resolution.svg)\n"
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
    write_atomic(&dir.join("REPORT.md"), |f| {
        std::io::Write::write_all(f, md.as_bytes())
    })?;
    eprintln!("wrote {}", dir.join("REPORT.md").display());
    Ok(())
}

/// Sets `label` of every configuration to the parameters that differ between configurations
/// of the same technique.
fn shorten_params(configs: &mut BTreeMap<String, Config>) {
    let split = |p: &str| -> BTreeMap<String, String> {
        p.split(';')
            .filter_map(|kv| kv.split_once('='))
            .map(|(k, v)| (k.to_owned(), v.to_owned()))
            .collect()
    };
    let mut values: BTreeMap<(String, String), std::collections::BTreeSet<String>> =
        BTreeMap::new();
    for c in configs.values() {
        for (k, v) in split(&c.params) {
            values
                .entry((c.technique.clone(), k))
                .or_default()
                .insert(v);
        }
    }
    for c in configs.values_mut() {
        c.label = split(&c.params)
            .into_iter()
            .filter(|(k, _)| {
                values
                    .get(&(c.technique.clone(), k.clone()))
                    .is_some_and(|v| v.len() > 1)
            })
            .map(|(k, v)| format!("{k}={v}"))
            .collect::<Vec<_>>()
            .join(" ");
    }
}

fn label(c: &Config) -> String {
    let mut l = c.technique.clone();
    for extra in [&c.label, &c.variant] {
        if !extra.is_empty() {
            l.push(' ');
            l.push_str(&extra.replace(';', " "));
        }
    }
    l
}

const COLORS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
];

fn plot_err<E: std::fmt::Debug>(e: E) -> anyhow::Error {
    anyhow::anyhow!("plotting failed: {e:?}")
}

/// GPU time of every configuration, grouped by scene.
fn frame_time_plot(configs: &[&Config], path: &Path) -> anyhow::Result<()> {
    let root = SVGBackend::new(path, (900, 420)).into_drawing_area();
    root.fill(&WHITE).map_err(plot_err)?;
    let max = configs
        .iter()
        .filter_map(|c| median(&c.gpu_wall))
        .fold(1.0, f64::max)
        * 1.15;
    let mut chart = ChartBuilder::on(&root)
        .caption("GPU time per frame (median, ms)", ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(30)
        .y_label_area_size(50)
        .build_cartesian_2d(-0.5f64..(configs.len() as f64 - 0.5), 0f64..max)
        .map_err(plot_err)?;
    chart
        .configure_mesh()
        .light_line_style(RGBColor(238, 238, 238))
        .bold_line_style(RGBColor(210, 210, 210))
        .disable_x_mesh()
        .x_labels(0)
        .y_desc("ms")
        .draw()
        .map_err(plot_err)?;
    let scenes: Vec<String> = configs
        .iter()
        .map(|c| c.scene.clone())
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .collect();
    for (k, c) in configs.iter().enumerate() {
        let color = COLORS[scenes.iter().position(|s| *s == c.scene).unwrap_or(0) % COLORS.len()];
        let v = median(&c.gpu_wall).unwrap_or(0.0);
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(k as f64 - 0.35, 0.0), (k as f64 + 0.35, v)],
                color.filled(),
            )))
            .map_err(plot_err)?;
        chart
            .draw_series(std::iter::once(Text::new(
                format!("{} {}", c.scene, label(c)),
                (k as f64 - 0.3, v + max * 0.02),
                ("sans-serif", 11),
            )))
            .map_err(plot_err)?;
    }
    root.present().map_err(plot_err)?;
    Ok(())
}

/// FLIP (1/4 scale) against GPU time, one point per configuration: lower-left is better.
fn pareto_plot(configs: &[&Config], path: &Path) -> anyhow::Result<()> {
    let root = SVGBackend::new(path, (800, 480)).into_drawing_area();
    root.fill(&WHITE).map_err(plot_err)?;
    let points: Vec<(f64, f64, String)> = configs
        .iter()
        .filter_map(|c| {
            Some((
                median(&c.gpu_wall)?,
                median(&c.flip_quarter)?,
                format!("{} · {}", c.scene, label(c)),
            ))
        })
        .collect();
    let xmax = points.iter().map(|p| p.0).fold(1.0, f64::max) * 1.2;
    let ymax = points.iter().map(|p| p.1).fold(0.05, f64::max) * 1.2;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            "Quality vs cost: mean FLIP against reference (1/4 scale) vs GPU ms",
            ("sans-serif", 16),
        )
        .margin(12)
        .x_label_area_size(35)
        .y_label_area_size(50)
        .build_cartesian_2d(0f64..xmax, 0f64..ymax)
        .map_err(plot_err)?;
    chart
        .configure_mesh()
        .light_line_style(RGBColor(238, 238, 238))
        .bold_line_style(RGBColor(210, 210, 210))
        .x_desc("GPU ms per frame")
        .y_desc("mean FLIP (lower is better)")
        .draw()
        .map_err(plot_err)?;
    for (k, (x, y, name)) in points.iter().enumerate() {
        let color = COLORS[k % COLORS.len()];
        chart
            .draw_series(std::iter::once(Circle::new((*x, *y), 5, color.filled())))
            .map_err(plot_err)?;
        chart
            .draw_series(std::iter::once(Text::new(
                name.clone(),
                (*x + xmax * 0.01, *y),
                ("sans-serif", 11),
            )))
            .map_err(plot_err)?;
    }
    root.present().map_err(plot_err)?;
    Ok(())
}

/// GPU time against `x`, one line per technique (and scene).
fn scaling_plot(
    configs: &[&Config],
    x: &dyn Fn(&Config) -> f64,
    x_desc: &str,
    path: &Path,
) -> anyhow::Result<()> {
    let mut series: BTreeMap<String, Vec<(f64, f64)>> = BTreeMap::new();
    for c in configs {
        if let Some(y) = median(&c.gpu_wall) {
            series
                .entry(format!("{} · {}", c.scene, label(c)))
                .or_default()
                .push((x(c), y));
        }
    }
    let xmax = series.values().flatten().map(|p| p.0).fold(1.0, f64::max) * 1.1;
    let ymax = series.values().flatten().map(|p| p.1).fold(1.0, f64::max) * 1.1;
    let root = SVGBackend::new(path, (800, 480)).into_drawing_area();
    root.fill(&WHITE).map_err(plot_err)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(format!("GPU time versus {x_desc}"), ("sans-serif", 16))
        .margin(12)
        .x_label_area_size(35)
        .y_label_area_size(50)
        .build_cartesian_2d(0f64..xmax, 0f64..ymax)
        .map_err(plot_err)?;
    chart
        .configure_mesh()
        .light_line_style(RGBColor(238, 238, 238))
        .bold_line_style(RGBColor(210, 210, 210))
        .x_desc(x_desc)
        .y_desc("GPU ms per frame")
        .draw()
        .map_err(plot_err)?;
    for (k, (name, mut pts)) in series.into_iter().enumerate() {
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let color = COLORS[k % COLORS.len()];
        chart
            .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
            .map_err(plot_err)?
            .label(name)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 16, y)], color.stroke_width(2))
            });
        chart
            .draw_series(pts.into_iter().map(|p| Circle::new(p, 3, color.filled())))
            .map_err(plot_err)?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(plot_err)?;
    root.present().map_err(plot_err)?;
    Ok(())
}

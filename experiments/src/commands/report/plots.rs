//! The report's SVG plots: GPU time per configuration, quality against cost, and GPU time
//! against blades or pixels.

use std::collections::BTreeMap;
use std::path::Path;

use plotters::prelude::*;

use super::configs::{Config, label, median};

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
pub(super) fn frame_time_plot(configs: &[&Config], path: &Path) -> anyhow::Result<()> {
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
pub(super) fn pareto_plot(configs: &[&Config], path: &Path) -> anyhow::Result<()> {
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
pub(super) fn scaling_plot(
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

/// Names of the stacked segments of [`time_split_plot`]: the CPU stages, then the cost
/// model's terms in the order of [`grassbench::cost::Term::ALL`].
pub(super) const SPLIT_SEGMENTS: [&str; 12] = [
    "CPU update",
    "CPU upload",
    "CPU encode",
    "GPU fixed",
    "GPU vertices",
    "GPU primitives",
    "GPU fragments opaque",
    "GPU fragments alpha-tested",
    "GPU fragments blended",
    "GPU draws",
    "GPU compute",
    "GPU uploads",
];

/// A configuration's frame split into [`SPLIT_SEGMENTS`], ms: its median CPU stages and the
/// cost model's GPU terms (`None` without a model).
pub(super) fn time_split(c: &Config) -> Option<[f64; 12]> {
    let terms = c.model_terms?;
    let mut out = [0.0; 12];
    out[0] = median(&c.update).unwrap_or(0.0);
    out[1] = median(&c.upload).unwrap_or(0.0);
    out[2] = median(&c.encode).unwrap_or(0.0);
    out[3..].copy_from_slice(&terms);
    Some(out)
}

/// "Where the time goes": per configuration with a model, one bar stacking its CPU stages and
/// the model's predicted GPU terms (ms, log-free so the parts add up), and a black tick at its
/// measured frame time (CPU stages + measured GPU wall time): the gap between the bar's top
/// and the tick is what the model does not explain.
pub(super) fn time_split_plot(configs: &[&Config], path: &Path) -> anyhow::Result<()> {
    let rows: Vec<(&Config, [f64; 12])> = configs
        .iter()
        .filter_map(|c| Some((*c, time_split(c)?)))
        .collect();
    let width = (220 + 70 * rows.len() as u32).max(700);
    let root = SVGBackend::new(path, (width, 520)).into_drawing_area();
    root.fill(&WHITE).map_err(plot_err)?;
    let measured = |c: &Config, split: &[f64; 12]| {
        split[..3].iter().sum::<f64>() + median(&c.gpu_wall).unwrap_or(0.0)
    };
    let max = rows
        .iter()
        .map(|(c, s)| s.iter().sum::<f64>().max(measured(c, s)))
        .fold(1.0, f64::max)
        * 1.1;
    let (plot, legend) = root.split_horizontally(width - 210);
    let mut chart = ChartBuilder::on(&plot)
        .caption(
            "Where the time goes: CPU stages + the cost model's GPU terms (ms); tick = measured",
            ("sans-serif", 15),
        )
        .margin(12)
        .x_label_area_size(90)
        .y_label_area_size(55)
        .build_cartesian_2d(-0.5f64..(rows.len() as f64 - 0.5), 0f64..max)
        .map_err(plot_err)?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_labels(0)
        .y_desc("ms per frame")
        .draw()
        .map_err(plot_err)?;
    let palette = |k: usize| -> RGBColor {
        const EXTRA: [RGBColor; 4] = [
            RGBColor(188, 189, 34),
            RGBColor(23, 190, 207),
            RGBColor(90, 90, 90),
            RGBColor(200, 200, 200),
        ];
        if k < COLORS.len() {
            COLORS[k]
        } else {
            EXTRA[(k - COLORS.len()) % EXTRA.len()]
        }
    };
    for (k, (c, split)) in rows.iter().enumerate() {
        let x = k as f64;
        let mut base = 0.0;
        for (s, v) in split.iter().enumerate() {
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(x - 0.35, base), (x + 0.35, base + v)],
                    palette(s).filled(),
                )))
                .map_err(plot_err)?;
            base += v;
        }
        let m = measured(c, split);
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(x - 0.45, m), (x + 0.45, m)],
                BLACK.stroke_width(3),
            )))
            .map_err(plot_err)?;
        chart
            .draw_series(std::iter::once(Text::new(
                format!("{} {}", c.scene, label(c)),
                (x - 0.3, -max * 0.02),
                ("sans-serif", 10)
                    .into_font()
                    .transform(FontTransform::Rotate90),
            )))
            .map_err(plot_err)?;
    }
    for (s, name) in SPLIT_SEGMENTS.iter().enumerate() {
        let y = 40 + 22 * s as i32;
        legend
            .draw(&Rectangle::new(
                [(10, y), (24, y + 14)],
                palette(s).filled(),
            ))
            .map_err(plot_err)?;
        legend
            .draw(&Text::new(*name, (30, y), ("sans-serif", 12)))
            .map_err(plot_err)?;
    }
    root.present().map_err(plot_err)?;
    Ok(())
}

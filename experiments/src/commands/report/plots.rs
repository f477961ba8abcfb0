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

/// One colour per technique, the same in every panel and plot of a report (techniques in
/// name order, the reference first).
pub(super) fn technique_colors(configs: &[&Config]) -> BTreeMap<String, RGBColor> {
    let mut ids: Vec<&str> = configs.iter().map(|c| c.technique.as_str()).collect();
    ids.sort_by_key(|id| (*id != grassbench::sweep::REFERENCE, *id));
    ids.dedup();
    ids.into_iter()
        .enumerate()
        .map(|(k, id)| (id.to_owned(), COLORS[k % COLORS.len()]))
        .collect()
}

/// One panel per scene (its variant and, where the report holds several, its size), each
/// with its configurations, the techniques in the legend's order.
fn by_scene<'a>(configs: &[&'a Config]) -> BTreeMap<String, Vec<&'a Config>> {
    let sizes: std::collections::BTreeSet<&str> = configs.iter().map(|c| c.size.as_str()).collect();
    let mut scenes: BTreeMap<String, Vec<&Config>> = BTreeMap::new();
    for c in configs {
        let mut scene = c.scene.clone();
        if !c.variant.is_empty() {
            scene = format!("{scene} {}", c.variant.replace(';', " "));
        }
        if sizes.len() > 1 {
            scene = format!("{scene} {}", c.size);
        }
        scenes.entry(scene).or_default().push(c);
    }
    for members in scenes.values_mut() {
        members.sort_by_key(|c| {
            (
                c.technique != grassbench::sweep::REFERENCE,
                c.technique.clone(),
                c.label.clone(),
            )
        });
    }
    scenes
}

/// Tick labels of a log-scale time axis: whole milliseconds, or one decimal below 10.
fn ms_label(v: &f64) -> String {
    if *v >= 10.0 {
        format!("{v:.0}")
    } else {
        format!("{v:.1}")
    }
}

/// p5, median and p95 of a configuration's per-frame GPU wall times, all repetitions pooled
/// (the median of the repetitions' medians where no frames were read).
pub(super) fn gpu_spread(c: &Config) -> Option<(f64, f64, f64)> {
    let median_of_runs = median(&c.gpu_wall)?;
    let p = grassbench::runner::Percentiles::of(c.frame_walls.values().flatten().copied());
    Some(
        p.map_or((median_of_runs, median_of_runs, median_of_runs), |p| {
            (p.p5, median_of_runs, p.p95)
        }),
    )
}

/// Indices of the points on the quality-against-cost frontier (cost, error; both lower is
/// better): sorted by cost, each point whose error is below every cheaper point's.
pub(super) fn pareto_frontier(points: &[(f64, f64)]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| {
        points[a]
            .0
            .total_cmp(&points[b].0)
            .then(points[a].1.total_cmp(&points[b].1))
    });
    let mut best = f64::INFINITY;
    let mut frontier = Vec::new();
    for k in order {
        if points[k].1 < best {
            best = points[k].1;
            frontier.push(k);
        }
    }
    frontier
}

/// A log-scale range covering `values` with some room (at least a decade's tenth).
fn log_range(values: impl IntoIterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) = values
        .into_iter()
        .filter(|v| *v > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(l, h), v| (l.min(v), h.max(v)));
    if !lo.is_finite() {
        return 0.1..10.0;
    }
    (lo / 1.5)..(hi * 1.5).max(lo * 2.0)
}

/// Rows and columns of panels for `n` scenes.
fn grid(n: usize) -> (usize, usize) {
    let cols = n.clamp(1, 3);
    (n.div_ceil(cols).max(1), cols)
}

/// GPU time per configuration, one panel per scene: a bar at the median, a whisker from p5 to
/// p95 of its frames, log-scale time, one colour per technique with a legend.
pub(super) fn frame_time_plot(configs: &[&Config], path: &Path) -> anyhow::Result<()> {
    let scenes = by_scene(configs);
    let colors = technique_colors(configs);
    let (rows, cols) = grid(scenes.len());
    let root =
        SVGBackend::new(path, (380 * cols as u32, 330 * rows as u32 + 40)).into_drawing_area();
    root.fill(&WHITE).map_err(plot_err)?;
    let (title, body) = root.split_vertically(40);
    title
        .titled(
            "GPU time per frame: median, whisker p5-p95 of the frames (ms, log scale)",
            ("sans-serif", 16),
        )
        .map_err(plot_err)?;
    let range = log_range(
        configs
            .iter()
            .filter_map(|c| gpu_spread(c))
            .flat_map(|(lo, _, hi)| [lo, hi]),
    );
    for ((scene, members), area) in scenes.iter().zip(body.split_evenly((rows, cols))) {
        let mut chart = ChartBuilder::on(&area)
            .caption(scene, ("sans-serif", 14))
            .margin(8)
            .x_label_area_size(10)
            .y_label_area_size(50)
            .build_cartesian_2d(
                -0.5f64..(members.len() as f64 - 0.5),
                range.clone().log_scale(),
            )
            .map_err(plot_err)?;
        chart
            .configure_mesh()
            .light_line_style(WHITE)
            .bold_line_style(RGBColor(210, 210, 210))
            .disable_x_mesh()
            .x_labels(0)
            .y_labels(6)
            .y_label_formatter(&ms_label)
            .y_desc("ms")
            .draw()
            .map_err(plot_err)?;
        for (k, c) in members.iter().enumerate() {
            let Some((lo, mid, hi)) = gpu_spread(c) else {
                continue;
            };
            let color = colors.get(&c.technique).copied().unwrap_or(BLACK);
            let x = k as f64;
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(x - 0.35, range.start), (x + 0.35, mid)],
                    color.filled(),
                )))
                .map_err(plot_err)?;
            chart
                .draw_series([
                    PathElement::new(vec![(x, lo), (x, hi)], BLACK.stroke_width(1)),
                    PathElement::new(vec![(x - 0.12, lo), (x + 0.12, lo)], BLACK.stroke_width(1)),
                    PathElement::new(vec![(x - 0.12, hi), (x + 0.12, hi)], BLACK.stroke_width(1)),
                ])
                .map_err(plot_err)?;
        }
    }
    legend(&root, &colors, cols)?;
    root.present().map_err(plot_err)?;
    Ok(())
}

/// The techniques' colours, drawn once in the top right corner of `root`.
fn legend(
    root: &DrawingArea<SVGBackend<'_>, plotters::coord::Shift>,
    colors: &BTreeMap<String, RGBColor>,
    cols: usize,
) -> anyhow::Result<()> {
    let mut ordered: Vec<(&String, &RGBColor)> = colors.iter().collect();
    ordered.sort_by_key(|(id, _)| (id.as_str() != grassbench::sweep::REFERENCE, id.as_str()));
    let x0 = 380 * cols as i32 - 100 * ordered.len().min(6) as i32 - 10;
    for (k, (id, color)) in ordered.iter().enumerate() {
        let x = x0 + 100 * (k % 6) as i32;
        let y = 28 + 14 * (k / 6) as i32;
        root.draw(&Rectangle::new(
            [(x, y - 8), (x + 10, y + 2)],
            color.filled(),
        ))
        .map_err(plot_err)?;
        root.draw(&Text::new(
            id.to_string(),
            (x + 14, y - 8),
            ("sans-serif", 12),
        ))
        .map_err(plot_err)?;
    }
    Ok(())
}

/// Quality against cost, one panel per scene: mean FLIP against the reference (1/4 scale)
/// over GPU time (log scale), one colour per technique with a legend, the frontier of the
/// configurations no other beats on both drawn as a line; lower-left is better.
pub(super) fn pareto_plot(configs: &[&Config], path: &Path) -> anyhow::Result<()> {
    let scenes = by_scene(configs);
    let colors = technique_colors(configs);
    let (rows, cols) = grid(scenes.len());
    let root =
        SVGBackend::new(path, (380 * cols as u32, 330 * rows as u32 + 40)).into_drawing_area();
    root.fill(&WHITE).map_err(plot_err)?;
    let (title, body) = root.split_vertically(40);
    title
        .titled(
            "Quality vs cost: mean FLIP against the reference (1/4 scale) vs GPU ms (log); line: frontier",
            ("sans-serif", 15),
        )
        .map_err(plot_err)?;
    for ((scene, members), area) in scenes.iter().zip(body.split_evenly((rows, cols))) {
        let points: Vec<(f64, f64, &Config)> = members
            .iter()
            .filter_map(|c| Some((median(&c.gpu_wall)?, median(&c.flip_quarter)?, *c)))
            .collect();
        let xs = log_range(points.iter().map(|p| p.0));
        let ymax = points.iter().map(|p| p.1).fold(0.02, f64::max) * 1.2;
        let mut chart = ChartBuilder::on(&area)
            .caption(scene, ("sans-serif", 14))
            .margin(8)
            .x_label_area_size(30)
            .y_label_area_size(45)
            .build_cartesian_2d(xs.log_scale(), 0f64..ymax)
            .map_err(plot_err)?;
        chart
            .configure_mesh()
            .light_line_style(WHITE)
            .bold_line_style(RGBColor(220, 220, 220))
            .x_labels(5)
            .x_label_formatter(&ms_label)
            .y_labels(6)
            .x_desc("GPU ms")
            .y_desc("FLIP 1/4")
            .draw()
            .map_err(plot_err)?;
        let frontier = pareto_frontier(&points.iter().map(|p| (p.0, p.1)).collect::<Vec<_>>());
        chart
            .draw_series(std::iter::once(PathElement::new(
                frontier
                    .iter()
                    .map(|&k| (points[k].0, points[k].1))
                    .collect::<Vec<_>>(),
                BLACK.mix(0.5).stroke_width(1),
            )))
            .map_err(plot_err)?;
        for (x, y, c) in &points {
            let color = colors.get(&c.technique).copied().unwrap_or(BLACK);
            chart
                .draw_series(std::iter::once(Circle::new((*x, *y), 5, color.filled())))
                .map_err(plot_err)?;
        }
    }
    legend(&root, &colors, cols)?;
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

/// Segments of a frame's split: the three CPU stages and the cost model's terms.
pub(super) const SPLIT_LEN: usize = 3 + grassbench::cost::Term::ALL.len();

/// Names of the stacked segments of [`time_split_plot`]: the CPU stages, then the cost
/// model's terms in the order of [`grassbench::cost::Term::ALL`].
pub(super) const SPLIT_SEGMENTS: [&str; SPLIT_LEN] = [
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
    "GPU texel loads",
    "GPU float texel loads",
    "GPU vertex texel loads (extra)",
    "GPU vertex float texel loads (extra)",
    "GPU texture samples",
    "GPU float texture samples",
    "GPU vertex transcendentals",
    "GPU fragment transcendentals",
    "GPU compute transcendentals",
    "GPU vertex arithmetic",
    "GPU fragment arithmetic",
    "GPU compute arithmetic",
    "GPU compute barriers",
    "GPU compute storage",
    "GPU vertex storage",
    "GPU compute divisions",
    "GPU texture mip blends",
    "GPU instances",
    "GPU primitive input slots",
    "GPU texture levels by lane",
    "GPU primitives of pass heads (extra)",
];

/// A configuration's frame split into [`SPLIT_SEGMENTS`], ms: its median CPU stages and the
/// cost model's GPU terms (`None` without a model).
pub(super) fn time_split(c: &Config) -> Option<[f64; SPLIT_LEN]> {
    let terms = c.model_terms?;
    let mut out = [0.0; SPLIT_LEN];
    out[0] = median(&c.update).unwrap_or(0.0);
    out[1] = median(&c.upload).unwrap_or(0.0);
    out[2] = median(&c.encode).unwrap_or(0.0);
    out[3..].copy_from_slice(&terms);
    Some(out)
}

/// One configuration's row of "where the time goes": its frame split into
/// [`SPLIT_SEGMENTS`] and the model's predicted GPU time (the sum of the GPU terms), ms.
pub(super) struct SplitRow<'a> {
    /// The configuration.
    pub(super) config: &'a Config,
    /// Its CPU stages and the model's GPU terms, ms ([`time_split`]).
    pub(super) split: [f64; SPLIT_LEN],
    /// The model's predicted GPU time, ms.
    pub(super) model_ms: f64,
}

/// The rows of "where the time goes" (the Markdown table, its bars and `report.html` all
/// read these): every configuration with a cost model, grouped as a reader compares them —
/// scene, size, the reference first, then by name.
pub(super) fn split_rows<'a>(configs: &[&'a Config]) -> Vec<SplitRow<'a>> {
    let mut modelled: Vec<&Config> = configs
        .iter()
        .copied()
        .filter(|c| c.model_terms.is_some())
        .collect();
    modelled.sort_by_key(|c| {
        (
            c.scene.clone(),
            c.variant.clone(),
            c.size.clone(),
            c.technique != grassbench::sweep::REFERENCE,
            c.technique.clone(),
            c.label.clone(),
        )
    });
    modelled
        .into_iter()
        .filter_map(|config| {
            let split = time_split(config)?;
            Some(SplitRow {
                config,
                split,
                model_ms: split[3..].iter().sum(),
            })
        })
        .collect()
}

/// The y of the legend's row `k` in [`time_split_plot`] (rows 22 px apart below a 40 px
/// margin).
fn legend_row_y(k: usize) -> i32 {
    40 + 22 * k as i32
}

/// Height of [`time_split_plot`]: the chart's 520 px, or the legend's every row where it needs
/// more (33 rows since the model's 30 terms: a fixed 520 px cut the last fifteen off).
const SPLIT_PLOT_HEIGHT: u32 = {
    let legend = 40 + 22 * SPLIT_LEN as u32 + 20;
    if legend > 520 { legend } else { 520 }
};

/// The colour of segment `k` of [`time_split_plot`]: the techniques' colours, twelve more
/// from the same family, then saturated dark tones a golden-ratio step of hue apart, so that
/// no two of the [`SPLIT_LEN`] segments share one (the twenty fixed colours repeated from the
/// twenty-first segment on before).
fn split_colour(k: usize) -> RGBColor {
    const EXTRA: [RGBColor; 12] = [
        RGBColor(188, 189, 34),
        RGBColor(23, 190, 207),
        RGBColor(0, 0, 128),
        RGBColor(200, 200, 200),
        RGBColor(255, 187, 120),
        RGBColor(152, 223, 138),
        RGBColor(197, 176, 213),
        RGBColor(196, 156, 148),
        RGBColor(247, 182, 210),
        RGBColor(219, 219, 141),
        RGBColor(158, 218, 229),
        RGBColor(57, 59, 121),
    ];
    if k < COLORS.len() {
        COLORS[k]
    } else if k < COLORS.len() + EXTRA.len() {
        EXTRA[k - COLORS.len()]
    } else {
        let step = (k - COLORS.len() - EXTRA.len()) as f64;
        let c = HSLColor((0.98 + 0.618_034 * step).fract(), 1.0, 0.3).to_rgba();
        RGBColor(c.0, c.1, c.2)
    }
}

/// "Where the time goes": per configuration with a model, one bar stacking its CPU stages and
/// the model's predicted GPU terms (ms, log-free so the parts add up), and a black tick at its
/// measured frame time (CPU stages + measured GPU wall time): the gap between the bar's top
/// and the tick is what the model does not explain.
pub(super) fn time_split_plot(configs: &[&Config], path: &Path) -> anyhow::Result<()> {
    let rows: Vec<(&Config, [f64; SPLIT_LEN])> = configs
        .iter()
        .filter_map(|c| Some((*c, time_split(c)?)))
        .collect();
    let width = (220 + 70 * rows.len() as u32).max(700);
    let root = SVGBackend::new(path, (width, SPLIT_PLOT_HEIGHT)).into_drawing_area();
    root.fill(&WHITE).map_err(plot_err)?;
    let measured = |c: &Config, split: &[f64; SPLIT_LEN]| {
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
    let palette = split_colour;
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
        let y = legend_row_y(s);
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_split_segment_has_its_own_colour_and_a_legend_row_in_the_plot() {
        let colours: Vec<(u8, u8, u8)> = (0..SPLIT_LEN)
            .map(|k| {
                let c = split_colour(k);
                (c.0, c.1, c.2)
            })
            .collect();
        for (i, a) in colours.iter().enumerate() {
            for (j, b) in colours.iter().enumerate().skip(i + 1) {
                // At least 24 apart in some channel: the twenty fixed colours' closest pair
                // (light grey and lavender); the repeated colours were 0 apart.
                let apart = [(a.0, b.0), (a.1, b.1), (a.2, b.2)]
                    .iter()
                    .any(|&(x, y)| x.abs_diff(y) >= 24);
                assert!(
                    apart,
                    "{} and {}: {a:?} {b:?}",
                    SPLIT_SEGMENTS[i], SPLIT_SEGMENTS[j]
                );
            }
        }
        // The last row's swatch (14 px) and text lie inside the plot.
        let last = legend_row_y(SPLIT_LEN - 1);
        assert!(
            last + 14 < SPLIT_PLOT_HEIGHT as i32,
            "{last} of {SPLIT_PLOT_HEIGHT}"
        );
    }

    #[test]
    fn the_frontier_keeps_what_nothing_cheaper_beats() {
        // (ms, FLIP): 10 ms at 0.2; 20 ms at 0.1 beats it on quality; 30 ms at 0.15 is beaten
        // by the 20 ms point on both; 40 ms at 0.05 is the best picture.
        let points = [(30.0, 0.15), (10.0, 0.2), (40.0, 0.05), (20.0, 0.1)];
        assert_eq!(pareto_frontier(&points), vec![1, 3, 2]);
        assert_eq!(pareto_frontier(&[]), Vec::<usize>::new());
    }

    #[test]
    fn colours_follow_the_technique_not_the_point() {
        let c = |t: &str, s: &str| Config {
            technique: t.into(),
            scene: s.into(),
            ..Config::default()
        };
        let (a, b, r, a2) = (
            c("zhang", "m"),
            c("bakay", "m"),
            c("reference", "m"),
            c("zhang", "f"),
        );
        let colors = technique_colors(&[&a, &b, &r, &a2]);
        assert_eq!(colors.len(), 3);
        assert_eq!(colors["reference"], COLORS[0]);
        assert_ne!(colors["zhang"], colors["bakay"]);
        assert_eq!(by_scene(&[&a, &b, &a2]).len(), 2);
    }

    #[test]
    fn whiskers_span_the_frames() {
        let mut c = Config {
            gpu_wall: vec![10.0],
            ..Config::default()
        };
        c.frame_walls.insert(0, (1..=21).map(f64::from).collect());
        let (lo, mid, hi) = gpu_spread(&c).unwrap();
        assert_eq!(mid, 10.0);
        assert!(
            (lo - 2.0).abs() < 1e-9 && (hi - 20.0).abs() < 1e-9,
            "{lo} {hi}"
        );
        assert_eq!(
            gpu_spread(&Config {
                gpu_wall: vec![5.0],
                ..Config::default()
            }),
            Some((5.0, 5.0, 5.0))
        );
    }

    #[test]
    fn log_ranges_cover_their_values() {
        let r = log_range([3.0, 300.0, 0.0]);
        assert!(r.start < 3.0 && r.end > 300.0);
        assert_eq!(log_range([]), 0.1..10.0);
    }
}

//! `grassbench run`: techniques x scenes x N frames, measured, with images and CSV.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};
use grassbench::calibration::Calibration;
use grassbench::cost::drift::{self, Drift};
use grassbench::cost::{UnitCosts, apply_model, predict_run};
use grassbench::metrics::grass_coverage;
use grassbench::runner::{
    self, FrameRecord, Harness, LevelRow, Provenance, RunOptions, RunSummary, write_atomic,
    write_csv,
};
use grassbench::sweep::{REFERENCE, compare_with_reference};
use grassbench::target::{Size, save_png};
use grassbench::technique::NoGrass;

use super::out_dir::Progress;
use super::{GpuArgs, fmt_opt, param_table};
use crate::{registry, scenes};
use grassbench::technique::label_params;

/// Arguments of `run`.
#[derive(Clone, Debug, clap::Args)]
pub struct RunArgs {
    /// Technique ids, comma-separated, or `all`.
    #[arg(long, short, default_value = "all")]
    pub technique: String,
    /// Scene names or paths, comma-separated, or `default` for the default comparison.
    #[arg(long, short, default_value = "default")]
    pub scene: String,
    /// Measured frames.
    #[arg(long, default_value_t = 30)]
    pub frames: u64,
    /// Warm-up frames before measuring.
    #[arg(long, default_value_t = 3)]
    pub warmup: u64,
    /// Frames to save as PNG, comma-separated (default: the first and last measured).
    #[arg(long, value_delimiter = ',')]
    pub capture: Vec<u64>,
    /// Output folder.
    #[arg(long, short)]
    pub out: PathBuf,
    /// Target size WxH (default: each scene's).
    #[arg(long)]
    pub size: Option<String>,
    /// 4x MSAA.
    #[arg(long)]
    pub msaa: bool,
    /// Technique parameter override KEY=VALUE, applied to every technique run (repeatable).
    #[arg(long = "param", short = 'p')]
    pub params: Vec<String>,
    /// Replace an existing non-empty output folder (without it, the folder of an interrupted
    /// `run` with the same arguments is resumed: its finished scenes are kept).
    #[arg(long)]
    pub force: bool,
    /// Measure the techniques' frames in turn (frame 0 of each, then frame 1 of each, ...)
    /// rather than one technique after the other, so ratios between them hold even when the
    /// machine's speed drifts during the run (a shared host). Same images.
    #[arg(long)]
    pub interleave: bool,
    /// Skip measuring the adapter's unit costs (then runs.csv has no `model_ms`).
    #[arg(long)]
    pub no_calibration: bool,
    /// GPU options.
    #[command(flatten)]
    pub gpu: GpuArgs,
}

/// A row of `images.csv`.
#[derive(serde::Serialize)]
struct ImageRow {
    technique: String,
    scene: String,
    frame: u64,
    png: String,
    /// Fraction of pixels where grass changed the background-only image.
    coverage: f64,
}

/// A row of `params.csv` (long format).
#[derive(serde::Serialize)]
struct ParamRow {
    technique: String,
    scene: String,
    key: String,
    value: String,
}

/// Runs every selected technique on every selected scene.
pub fn run(args: &RunArgs) -> anyhow::Result<()> {
    let entries = registry::select(&args.technique)?;
    // Load (and so validate) everything before touching the GPU or the output folder.
    let scenes = scenes::select(&args.scene)?;
    let overrides = param_table(&args.params)?;
    for scene in &scenes {
        for entry in &entries {
            entry
                .check(&scene.technique_params(entry.info.id, &overrides))
                .with_context(|| format!("`{}` on scene `{}`", entry.info.id, scene.name()))?;
        }
    }
    let size = args.size.as_deref().map(Size::parse).transpose()?;
    if args.frames == 0 {
        bail!("--frames must be at least 1");
    }
    let capture = if args.capture.is_empty() {
        vec![args.warmup, args.warmup + args.frames - 1]
    } else {
        args.capture.clone()
    };
    let scene_names: Vec<String> = scenes.iter().map(|s| s.name().to_owned()).collect();
    let flag = |on: bool| on.to_string();
    let mut arguments = super::out_dir::selection_arguments(&entries, &scene_names);
    arguments.extend([
        ("--frames".to_owned(), args.frames.to_string()),
        ("--warmup".to_owned(), args.warmup.to_string()),
        (
            "--capture".to_owned(),
            capture
                .iter()
                .map(u64::to_string)
                .collect::<Vec<_>>()
                .join(","),
        ),
        (
            "--size".to_owned(),
            size.map_or("scene".to_owned(), |s| s.to_string()),
        ),
        ("--msaa".to_owned(), flag(args.msaa)),
        (
            "--param".to_owned(),
            overrides
                .iter()
                .map(|(k, v)| format!("{k}={}", grassbench::params::format_value(v)))
                .collect::<Vec<_>>()
                .join(";"),
        ),
        ("--interleave".to_owned(), flag(args.interleave)),
        ("--no-calibration".to_owned(), flag(args.no_calibration)),
        (
            "--backend".to_owned(),
            format!("{:?}", args.gpu.choice()?).to_lowercase(),
        ),
    ]);
    let o = &overrides;
    let needs = super::needs(
        scenes
            .iter()
            .flat_map(|s| entries.iter().map(move |e| (*e, s, o))),
    )?;
    let mut progress = Progress::open(&args.out, args.force, "run", arguments, &scene_names)?;
    let gpu = args.gpu.context_for(&needs)?;
    let provenance = Provenance::collect(&gpu.summary);
    // The adapter's raw limits and its unit costs at every size rendered, so each run's time
    // can be set against the cost model's prediction from its measured work (issue 20 §3) and
    // the reference's blades against the raw blade rate (§6).
    // Unit costs for every target drawn: each scene's size, with MSAA where asked.
    let targets: Vec<(Size, bool)> = scenes
        .iter()
        .map(|scene| (size.unwrap_or(scene.resolution()), args.msaa))
        .collect();
    let (calibration, unit_costs): (Option<Calibration>, Vec<UnitCosts>) = if args.no_calibration {
        (None, Vec::new())
    } else if let Some(earlier) = progress
        .resumed()
        .then(|| super::recorded_calibration(&args.out))
        .flatten()
    {
        // The finished scenes' model figures were computed with these: keep them.
        earlier
    } else {
        let (c, costs) = super::calibrate::adapter_at(&gpu, None, &targets)?;
        (Some(c), costs)
    };
    write_meta(
        &args.out,
        &provenance,
        calibration.as_ref(),
        &unit_costs,
        &[],
        None,
    )?;

    let options = RunOptions {
        warmup: args.warmup,
        frames: args.frames,
        capture: capture.clone(),
        run_id: String::new(),
    };
    let mut failures = Vec::new();
    let mut all_runs: Vec<RunSummary> = Vec::new();
    let mut measured = false;
    for scene in scenes {
        let name = scene.name().to_owned();
        let dir = args.out.join(&name);
        if let Some(done) = progress.done(&name) {
            // Finished before an interruption: its runs join the folder's, unmeasured again.
            let runs: Vec<RunSummary> = grassbench::sweep::read_rows(&dir.join("runs.csv"))?;
            eprintln!(
                "{name}: already done in {} ({} runs)",
                dir.display(),
                runs.len()
            );
            failures.extend(done.failures.iter().cloned());
            all_runs.extend(runs);
            write_csv(&args.out.join("runs.csv"), &all_runs)?;
            continue;
        }
        let failed_before = failures.len();
        measured = true;
        let size = size.unwrap_or(scene.resolution());
        let mut harness = Harness::new(&gpu, scene, size, args.msaa)
            .with_context(|| format!("setting up scene `{name}`"))?;
        // Background-only frames: the baseline grass coverage is measured against.
        let mut backgrounds = Vec::new();
        for &f in &capture {
            let out = harness.frame(&mut NoGrass, f, true)?;
            if let Some(img) = out.image {
                save_png(&img, &dir.join(format!("none_frame{f:04}.png")))?;
                backgrounds.push((f, img));
            }
        }
        let mut out = SceneOutput {
            dir: &dir,
            name: &name,
            unit_costs: UnitCosts::for_target(&unit_costs, &size.to_string(), args.msaa),
            backgrounds: &backgrounds,
            frames: Vec::new(),
            levels: Vec::new(),
            runs: Vec::new(),
            images: Vec::new(),
            params: Vec::new(),
        };
        let mut fail = |id: &str, e: &dyn std::fmt::Display| {
            eprintln!("error: `{id}` on `{name}`: {e}");
            failures.push(format!("{id} on {name}: {e}"));
        };
        if args.interleave {
            let mut created = Vec::new();
            for entry in &entries {
                match harness.create(entry, &overrides) {
                    Ok(t) => created.push((entry.info.id, t)),
                    Err(e) => fail(entry.info.id, &e),
                }
            }
            let total = (options.warmup + options.frames) * created.len() as u64;
            let bar = super::progress::bar(total, "frames", &format!("{name} / interleaved"));
            let ids: Vec<&str> = created.iter().map(|(id, _)| *id).collect();
            let mut techniques: Vec<&mut dyn grassbench::GrassTechnique> = created
                .iter_mut()
                .map(|(_, t)| t.as_mut() as &mut dyn grassbench::GrassTechnique)
                .collect();
            let results = runner::run_interleaved(
                &mut harness,
                &mut techniques,
                &options,
                &mut |done, _| bar.set_position(done),
            )?;
            bar.finish_and_clear();
            for (id, result) in ids.into_iter().zip(results) {
                match result {
                    Ok(mut r) => {
                        let overrides = harness.world.scene.technique_params(id, &overrides);
                        r.summary.params = label_params(&overrides, &r.summary.params);
                        out.add(id, r)?
                    }
                    Err(e) => fail(id, &e),
                }
            }
        } else {
            for entry in &entries {
                let id = entry.info.id;
                let bar = super::progress::bar(
                    options.warmup + options.frames,
                    "frames",
                    &format!("{name} / {id}"),
                );
                let result = harness.create(entry, &overrides).and_then(|mut t| {
                    runner::run(&mut harness, t.as_mut(), &options, &mut |done, _| {
                        bar.set_position(done)
                    })
                });
                bar.finish_and_clear();
                match result {
                    Ok(mut r) => {
                        let overrides = harness.world.scene.technique_params(id, &overrides);
                        r.summary.params = label_params(&overrides, &r.summary.params);
                        out.add(id, r)?
                    }
                    Err(e) => fail(id, &e),
                }
            }
        }
        out.compare_with_reference()?;
        let runs = out.runs;
        all_runs.extend(runs);
        write_csv(&args.out.join("runs.csv"), &all_runs)?;
        progress.scene_done(&name, failures[failed_before..].to_vec())?;
    }
    // The unit costs again, now the runs are done: how far the host moved while they ran
    // (as a sweep does). The runs are recorded already; a calibration that fails here costs
    // only this comparison.
    let mut after = Vec::new();
    if measured && !unit_costs.is_empty() && all_runs.iter().any(|r| r.model_ms.is_some()) {
        match super::calibrate::adapter_after(&gpu, calibration.as_ref(), &targets) {
            Ok((raw_after, costs)) => {
                write_meta(
                    &args.out,
                    &provenance,
                    calibration.as_ref(),
                    &unit_costs,
                    &costs,
                    raw_after.as_ref(),
                )?;
                after = costs;
            }
            Err(e) => eprintln!(
                "the calibration after the runs failed ({e:#}); the runs are recorded, without it"
            ),
        }
    }
    let after_models = models_after(&args.out, &all_runs, &after)?;
    write_atomic(&args.out.join("README.md"), |f| {
        std::io::Write::write_all(
            f,
            report(&all_runs, &provenance, &capture, &unit_costs, &after_models).as_bytes(),
        )
    })?;
    super::write_html(&args.out).context("writing report.html")?;
    progress.finish()?;
    if !failures.is_empty() {
        bail!(
            "{} run(s) failed:\n  {}",
            failures.len(),
            failures.join("\n  ")
        );
    }
    Ok(())
}

/// Writes `meta.toml`: the provenance, then the raw limits and the unit costs fitted before the
/// runs and, once measured, after them (`unit_costs_after` and `calibration_after`, as a
/// sweep's).
fn write_meta(
    out: &Path,
    provenance: &Provenance,
    calibration: Option<&Calibration>,
    unit_costs: &[UnitCosts],
    unit_costs_after: &[UnitCosts],
    calibration_after: Option<&Calibration>,
) -> anyhow::Result<()> {
    write_atomic(&out.join("meta.toml"), |f| {
        let mut text = provenance.to_toml();
        #[derive(serde::Serialize)]
        struct Units<'a> {
            calibration: Option<&'a Calibration>,
            unit_costs: &'a [UnitCosts],
            #[serde(skip_serializing_if = "<[UnitCosts]>::is_empty")]
            unit_costs_after: &'a [UnitCosts],
            #[serde(skip_serializing_if = "Option::is_none")]
            calibration_after: Option<&'a Calibration>,
        }
        if !unit_costs.is_empty() {
            let units = toml::to_string_pretty(&Units {
                calibration,
                unit_costs,
                unit_costs_after,
                calibration_after,
            })
            .map_err(std::io::Error::other)?;
            text.push('\n');
            text.push_str(&units);
        }
        std::io::Write::write_all(f, text.as_bytes())
    })?;
    Ok(())
}

/// Each run's counted work priced with `after` (the unit costs fitted after the runs) from its
/// scene's `frames.csv`, in the order of `runs`; `None` where it has no counted work, no
/// costs priced its target, or there are no costs after.
fn models_after(
    out: &Path,
    runs: &[RunSummary],
    after: &[UnitCosts],
) -> anyhow::Result<Vec<Option<f64>>> {
    if after.is_empty() {
        return Ok(vec![None; runs.len()]);
    }
    let mut frames: std::collections::HashMap<String, Vec<FrameRecord>> = Default::default();
    let mut models = Vec::with_capacity(runs.len());
    for run in runs {
        if !frames.contains_key(&run.scene) {
            let path = out.join(&run.scene).join("frames.csv");
            frames.insert(
                run.scene.clone(),
                grassbench::sweep::read_rows(&path)
                    .with_context(|| format!("reading {}", path.display()))?,
            );
        }
        let own: Vec<FrameRecord> = frames[&run.scene]
            .iter()
            .filter(|f| f.technique == run.technique)
            .cloned()
            .collect();
        let size = format!("{}x{}", run.width, run.height);
        models.push(
            UnitCosts::for_target(after, &size, run.msaa)
                .and_then(|c| predict_run(c, &own))
                .map(|p| p.total_ms),
        );
    }
    Ok(models)
}

/// The README's paragraph on the calibration after the runs: each run's measured time against
/// the model with the costs before (`runs`' own `model_ms`) and with those after (`after`, in
/// the order of `runs`); empty without costs after.
fn drift_paragraph(runs: &[RunSummary], after: &[Option<f64>]) -> String {
    let priced: Vec<(&RunSummary, f64, f64, f64)> = runs
        .iter()
        .zip(after)
        .filter_map(|(r, a)| Some((r, r.gpu_wall_ms_median?, r.model_ms?, (*a)?)))
        .filter(|(_, _, b, a)| *b > 0.0 && *a > 0.0)
        .collect();
    let Some(d) = Drift::of(priced.iter().map(|&(_, m, b, a)| (m, b, a))) else {
        return String::new();
    };
    let out_with_both: Vec<String> = priced
        .iter()
        .filter(|&&(_, m, b, a)| !drift::within(m, b) && !drift::within(m, a))
        .map(|(r, m, b, a)| {
            format!(
                "{} on {} ({:.2}, {:.2})",
                r.technique,
                r.scene,
                m / b,
                m / a
            )
        })
        .collect();
    let mut s = format!(
        "\nThe unit costs were fitted again after the runs (`unit_costs_after` in `meta.toml`): on a shared host the two fits differ by how far its speed moved while the runs were measured. Priced with the fit after, these runs' work costs {:.2}-{:.2} times what the fit before says (median {:.2}); within ±{:.0} % of the model: {} of {} runs with the fit before, {} with the fit after, {} with one or the other.",
        d.moved.0,
        d.moved.2,
        d.moved.1,
        drift::TOLERANCE * 100.0,
        d.within_before,
        d.runs,
        d.within_after,
        d.within_either,
    );
    if !out_with_both.is_empty() {
        let _ = write!(
            s,
            " Out with both (measured / model before, after): {}.",
            out_with_both.join("; ")
        );
    }
    s.push('\n');
    s
}

/// One scene's output folder as runs come in: images, frames, runs and parameters, written
/// after every technique, so a later failure loses nothing already measured.
struct SceneOutput<'a> {
    dir: &'a Path,
    name: &'a str,
    /// The adapter's unit costs at this scene's size, for the model's prediction.
    unit_costs: Option<&'a UnitCosts>,
    /// Background-only frames (frame index, image): the baseline of grass coverage.
    backgrounds: &'a [(u64, image::RgbaImage)],
    frames: Vec<FrameRecord>,
    levels: Vec<LevelRow>,
    runs: Vec<RunSummary>,
    images: Vec<ImageRow>,
    params: Vec<ParamRow>,
}

impl SceneOutput<'_> {
    /// Saves `result`'s images and appends its rows; rewrites the scene's CSV files.
    fn add(&mut self, id: &str, mut result: runner::RunResult) -> anyhow::Result<()> {
        let (dir, name) = (self.dir, self.name);
        for (f, img) in &result.images {
            let png = format!("{id}_frame{f:04}.png");
            save_png(img, &dir.join(&png))?;
            let coverage = self
                .backgrounds
                .iter()
                .find(|(b, _)| b == f)
                .map(|(_, bg)| grass_coverage(img, bg, 6))
                .transpose()?
                .unwrap_or(f64::NAN);
            // The measured frame's fragments per grass-covered pixel.
            if let Some(record) = result.frames.iter_mut().find(|r| r.frame == *f)
                && coverage.is_finite()
            {
                let pixels = f64::from(img.width() * img.height());
                record.set_grass_pixels((coverage * pixels).round() as u64);
            }
            self.images.push(ImageRow {
                technique: id.into(),
                scene: name.to_owned(),
                frame: *f,
                png,
                coverage,
            });
        }
        if let Some(costs) = self.unit_costs {
            apply_model(&mut result.summary, costs, &result.frames);
        }
        result.summary.fragments_per_grass_pixel = runner::Percentiles::of(
            result
                .frames
                .iter()
                .filter_map(|r| r.fragments_per_grass_pixel),
        )
        .map(|p| p.median);
        let s = &result.summary;
        let count = |v: Option<u64>| fmt_opt(v.map(|n| n as f64), 0);
        eprintln!(
            "{name:>16} {id:<12} {:>8} ms/frame GPU wall (p5 {}, p95 {}), {} blades drawn, {} represented, {} triangles",
            fmt_opt(s.gpu_wall_ms_median, 1),
            fmt_opt(s.gpu_wall_ms_p5, 1),
            fmt_opt(s.gpu_wall_ms_p95, 1),
            count(s.blades_drawn),
            count(s.blades_represented),
            count(s.triangles)
        );
        for (key, value) in s.params.split(';').filter_map(|kv| kv.split_once('=')) {
            self.params.push(ParamRow {
                technique: id.into(),
                scene: name.to_owned(),
                key: key.into(),
                value: value.into(),
            });
        }
        self.levels.extend(LevelRow::of(&result.frames));
        self.frames.extend(result.frames);
        self.runs.push(result.summary);
        write_csv(&dir.join("frames.csv"), &self.frames)?;
        write_csv(&dir.join("levels.csv"), &self.levels)?;
        write_csv(&dir.join("runs.csv"), &self.runs)?;
        write_csv(&dir.join("images.csv"), &self.images)?;
        write_csv(&dir.join("params.csv"), &self.params)?;
        Ok(())
    }
}

impl SceneOutput<'_> {
    /// Gives every run its speed-up over the scene's reference run (where the reference ran),
    /// with the 95 % bootstrap interval from both runs' frames; rewrites runs.csv.
    fn compare_with_reference(&mut self) -> anyhow::Result<()> {
        let walls = |id: &str| -> Vec<f64> {
            self.frames
                .iter()
                .filter(|f| f.technique == id)
                .map(|f| f.gpu_wall_ms)
                .collect()
        };
        let Some(reference) = self.runs.iter().find(|r| r.technique == REFERENCE).cloned() else {
            return Ok(());
        };
        let reference_walls = walls(REFERENCE);
        let run_walls: Vec<Vec<f64>> = self.runs.iter().map(|r| walls(&r.technique)).collect();
        for (run, frames) in self.runs.iter_mut().zip(&run_walls) {
            compare_with_reference(run, &reference, frames, &reference_walls);
        }
        write_csv(&self.dir.join("runs.csv"), &self.runs)?;
        Ok(())
    }
}

/// The results folder's README: provenance, the table, the calibration's coverage checks, the
/// images.
fn report(
    runs: &[RunSummary],
    p: &Provenance,
    capture: &[u64],
    unit_costs: &[UnitCosts],
    after: &[Option<f64>],
) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# grassbench results\n");
    let _ = writeln!(s, "{}", p.to_markdown(""));
    let _ = writeln!(
        s,
        "GPU times are wall time from submit to the end of `poll(wait)` (the ground truth on software \
         rasterisers); timestamp-query figures are in `runs.csv` beside them. Frame = CPU stages + GPU wall. \
         Fragments and overdraw (fragment shader invocations of the technique's passes, and those per \
         target pixel) are counted by the GPU's pipeline-statistics queries; empty where the adapter has none. \
         *Kept* are the samples of those passes that passed the depth test and were not discarded (occlusion \
         queries): lavapipe counts every pixel of each 4x4 block a triangle touches, so thin blades keep few of \
         their counted fragments. \
         *Other processes* is how many CPU cores the rest of the host kept busy, on average, while the frames \
         were measured: on a software rasteriser that time is taken from the GPU; *kernel* how many this process \
         spent in the kernel meanwhile (the rasteriser threads' wake-ups on frames of a few milliseconds, \
         fresh pages where a process returns memory and takes it again every frame). Speed-up = the reference's \
         median GPU wall time over the technique's on the same scene, with its 95 % bootstrap interval over \
         both runs' frames: a technique is faster than another only where the intervals do not overlap. \
         *Model* is the GPU time the cost model predicts from the run's measured work (the adapter's unit costs, \
         calibrated at the start, times the work; `meta.toml` holds them), and *measured / model* its ratio: \
         near 1 where the work explains the time.\n"
    );
    let _ = writeln!(
        s,
        "| scene | technique | size | GPU wall ms (p5–p95) | speed-up (95 % interval) | model ms | measured / model | frame ms | blades drawn | blades represented | triangles | fragments (M) | kept (M) | overdraw | GPU MB | other processes (cores) | kernel (cores) |"
    );
    let _ = writeln!(
        s,
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
    );
    let count = |v: Option<u64>| fmt_opt(v.map(|n| n as f64), 0);
    for r in runs {
        let _ = writeln!(
            s,
            "| {} | {} | {}x{}{} | {} ({}–{}) | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.scene,
            r.technique,
            r.width,
            r.height,
            if r.msaa { " 4xMSAA" } else { "" },
            fmt_opt(r.gpu_wall_ms_median, 1),
            fmt_opt(r.gpu_wall_ms_p5, 1),
            fmt_opt(r.gpu_wall_ms_p95, 1),
            match (r.speedup, r.speedup_ci_low, r.speedup_ci_high) {
                (Some(v), Some(lo), Some(hi)) => format!("{v:.2} ({lo:.2}–{hi:.2})"),
                (v, _, _) => fmt_opt(v, 2),
            },
            fmt_opt(r.model_ms, 1),
            fmt_opt(r.model_ratio, 2),
            fmt_opt(r.frame_ms_median, 1),
            count(r.blades_drawn),
            count(r.blades_represented),
            count(r.triangles),
            fmt_opt(r.fragment_invocations.map(|f| f as f64 / 1e6), 2),
            fmt_opt(r.fragments_passed.map(|f| f as f64 / 1e6), 3),
            fmt_opt(r.overdraw, 2),
            fmt_opt(r.gpu_bytes.map(|b| b as f64 / 1e6), 1),
            fmt_opt(r.host_other_cores, 2),
            fmt_opt(r.host_own_kernel_cores, 2)
        );
    }
    s.push_str(&drift_paragraph(runs, after));
    for costs in unit_costs.iter().filter(|c| !c.checks.is_empty()) {
        let _ = writeln!(
            s,
            "\nCoverage checks of the calibration at {}{}, timed with it and not fitted: measured \
             over predicted for blades on screen, slivers and hidden layers, fragments unlike the \
             full-screen layers its fragment prices are fitted on (`results/cost_model/coverage/`):\n\n{}",
            costs.size,
            if costs.msaa { " with 4x MSAA" } else { "" },
            grassbench::cost::checks::to_markdown(&costs.checks)
        );
    }
    let _ = writeln!(
        s,
        "\n[report.html](report.html) holds the same runs as a page to open from disk: an image \
         viewer per scene (flip with `f`, swipe, side by side, zoom to pixels), quality against \
         cost, where the time goes and runs.csv as sortable tables."
    );
    let _ = writeln!(s, "\n## Images\n");
    let mut scenes: Vec<&str> = runs.iter().map(|r| r.scene.as_str()).collect();
    scenes.dedup();
    for scene in scenes {
        let _ = writeln!(s, "### {scene}\n");
        for r in runs.iter().filter(|r| r.scene == scene) {
            for f in capture {
                let _ = writeln!(
                    s,
                    "![{} frame {f}]({scene}/{}_frame{f:04}.png)",
                    r.technique, r.technique
                );
            }
        }
        let _ = writeln!(s);
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A run measured at `measured` ms whose model before the runs said `before`.
    fn run(technique: &str, measured: f64, before: f64) -> RunSummary {
        let mut r = RunSummary::failed("r", technique, "meadow", "");
        r.status = "ok".into();
        r.gpu_wall_ms_median = Some(measured);
        r.model_ms = Some(before);
        r
    }

    #[test]
    fn the_readme_sets_each_run_against_both_fits() {
        let runs = [
            run("both", 22.0, 20.0),
            run("before_only", 16.0, 20.0),
            run("after_only", 30.0, 20.0),
            run("neither", 40.0, 20.0),
            run("unpriced", 40.0, 20.0),
        ];
        // The fit after prices every run's work at 24 ms; the last run has no counted work.
        let after = [Some(24.0), Some(24.0), Some(24.0), Some(24.0), None];
        let text = drift_paragraph(&runs, &after);
        assert!(text.contains("costs 1.20-1.20 times"), "{text}");
        assert!(
            text.contains(
                "2 of 4 runs with the fit before, 2 with the fit after, 3 with one or the other"
            ),
            "{text}"
        );
        assert!(
            text.contains(
                "Out with both (measured / model before, after): neither on meadow (2.00, 1.67)."
            ),
            "{text}"
        );
        // Nothing without a fit after.
        assert!(drift_paragraph(&runs, &[None; 5]).is_empty());
    }
}

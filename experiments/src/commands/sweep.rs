//! `grassbench sweep FILE`: scenes x techniques x parameter grids x resolutions x repetitions,
//! appended run by run to `results/<sweep>/`, resumable, shardable.

use std::collections::HashMap;
use std::path::PathBuf;

use anyhow::Context as _;
use grassbench::calibration::Calibration;
use grassbench::cost::{UnitCosts, apply_model};
use grassbench::metrics::{downsample, flip};
use grassbench::runner::{self, Harness, Provenance, RunOptions, RunSummary};
use grassbench::sweep::{
    ParamRow, PlannedRun, REFERENCE, SweepSpec, SweepStore, apply_overrides,
    compare_with_reference, image_path, sweep_key,
};
use grassbench::target::save_png;
use grassbench::technique::TechniqueEntry;
use grassbench::{GpuContext, Scene};

use super::GpuArgs;
use crate::{registry, scenes};

/// Arguments of `sweep`.
#[derive(Clone, Debug, clap::Args)]
pub struct SweepArgs {
    /// The sweep file (TOML).
    pub file: PathBuf,
    /// Results folder (default: `results/<sweep name>`).
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// Run only shard I of N (`I/N`, I from 0): every N-th comparison group (a scene variant,
    /// size, MSAA and repetition with all its techniques and its reference), deterministic.
    #[arg(long)]
    pub shard: Option<String>,
    /// Replace a results folder that holds a different sweep.
    #[arg(long)]
    pub force: bool,
    /// Skip the calibration workloads.
    #[arg(long)]
    pub no_calibration: bool,
    /// GPU options.
    #[command(flatten)]
    pub gpu: GpuArgs,
}

/// Parses `I/N`.
pub fn parse_shard(text: &str) -> anyhow::Result<(usize, usize)> {
    let bad = || anyhow::anyhow!("--shard takes I/N with 0 <= I < N, e.g. 0/4 (got `{text}`)");
    let (i, n) = text.split_once('/').ok_or_else(bad)?;
    let (i, n): (usize, usize) = (
        i.trim().parse().map_err(|_| bad())?,
        n.trim().parse().map_err(|_| bad())?,
    );
    if n == 0 || i >= n {
        return Err(bad());
    }
    Ok((i, n))
}

/// What `meta.toml` of a sweep holds.
#[derive(serde::Serialize, serde::Deserialize)]
pub struct SweepMeta {
    /// Sweep name.
    pub sweep: String,
    /// Hash of the sweep file's text: a results folder holds one version of one sweep.
    pub sweep_key: String,
    /// `I/N` or `all`.
    pub shard: String,
    /// The sweep file, verbatim.
    pub sweep_file: String,
    /// Provenance.
    pub provenance: Provenance,
    /// Calibration, if measured.
    pub calibration: Option<Calibration>,
    /// The adapter's unit costs (issue 20 §2), one calibration per target size the sweep
    /// renders at (the fixed cost per frame depends on it); empty when not measured and in
    /// files written before them.
    #[serde(default)]
    pub unit_costs: Vec<UnitCosts>,
    /// The same unit costs fitted again once the runs were done (the process's last runs, for
    /// a sweep resumed): how far the host moved while the sweep measured. The report prices
    /// every run with both (`report/drift.rs`). Empty without calibration, when this process
    /// ran nothing, and in files written before them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub unit_costs_after: Vec<UnitCosts>,
    /// The raw limits measured again with them, at the same size: the report reads the
    /// reference against both raw blade rates. `None` where `unit_costs_after` is empty.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub calibration_after: Option<Calibration>,
}

/// Runs the sweep.
pub fn sweep(args: &SweepArgs) -> anyhow::Result<()> {
    sweep_with(args, registry::TECHNIQUES)
}

/// Runs the sweep with the techniques of `techniques` (the registry; a test adds techniques of
/// its own, e.g. ones that provoke a validation error or lose the device).
///
/// The device requests what the planned runs' techniques need (`commands::needs`). A run that
/// fails is recorded as failed with its error and the sweep goes on; where it failed on the
/// GPU (a validation error, out of memory, a lost device) or left an error behind, the device
/// is dropped and the following runs get a fresh one, so one fault never fails the rest.
pub fn sweep_with(args: &SweepArgs, techniques: &[TechniqueEntry]) -> anyhow::Result<()> {
    let text = std::fs::read_to_string(&args.file)
        .with_context(|| format!("cannot read sweep file `{}`", args.file.display()))?;
    let spec = SweepSpec::from_toml(&text, &args.file)?;
    let (plan, scene_cache) = load_plan(&spec, &args.file, techniques)?;
    let (shard_i, shard_n) = args
        .shard
        .as_deref()
        .map(parse_shard)
        .transpose()?
        .unwrap_or((0, 1));
    let mine: Vec<&PlannedRun> = plan
        .iter()
        .filter(|r| r.group_index % shard_n == shard_i)
        .collect();

    let out = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("results").join(&spec.name));
    let sweep_key = sweep_key(&text);
    let mut store = SweepStore::open(&out, &sweep_key, args.force)?;
    let mut planned = Vec::new();
    for run in &mine {
        let scene = scene_cache.get(&scene_key(run)).context("scene cache")?;
        planned.push((
            registry::find_in(techniques, &run.technique)?,
            scene,
            &run.params,
        ));
    }
    let needs = super::needs(planned)?;
    let mut gpu = args.gpu.context_for(&needs)?;
    let (calibration, unit_costs, targets) = if args.no_calibration {
        (None, Vec::new(), Vec::new())
    } else {
        let size_of = |run: &PlannedRun| -> anyhow::Result<grassbench::target::Size> {
            let scene = scene_cache.get(&scene_key(run)).context("scene cache")?;
            Ok(run.size.unwrap_or(scene.resolution()))
        };
        // The raw limits at the plan's first size (every shard alike).
        let raw = plan.first().map(size_of).transpose()?;
        // Unit costs for every target the shard draws: its size, with MSAA or without.
        let targets = mine
            .iter()
            .map(|run| Ok((size_of(run)?, run.msaa)))
            .collect::<anyhow::Result<Vec<_>>>()?;
        let (c, all) = super::calibrate::adapter_at(&gpu, raw, &targets)?;
        (Some(c), all, targets)
    };
    let mut meta = SweepMeta {
        sweep: spec.name.clone(),
        sweep_key,
        shard: if shard_n == 1 {
            "all".into()
        } else {
            format!("{shard_i}/{shard_n}")
        },
        sweep_file: text.clone(),
        provenance: Provenance::collect(&gpu.summary),
        calibration: calibration.clone(),
        unit_costs: unit_costs.clone(),
        unit_costs_after: Vec::new(),
        calibration_after: None,
    };
    store.write_meta(&toml::to_string_pretty(&meta)?)?;

    let todo: Vec<&PlannedRun> = mine
        .iter()
        .copied()
        .filter(|r| !store.is_finished(&r.id))
        .collect();
    eprintln!(
        "sweep `{}`: {} runs planned, {} in this shard, {} already done, {} to run → {}",
        spec.name,
        plan.len(),
        mine.len(),
        mine.len() - todo.len(),
        todo.len(),
        out.display()
    );
    let bar = super::progress::bar(todo.len() as u64, "runs", &spec.name);
    // Reference run and last image per group, for ratios and FLIP.
    let mut reference: HashMap<String, Reference> = HashMap::new();
    let mut failed = 0usize;
    let attempted = todo.len();
    for run in todo {
        bar.set_message(format!("{} on {}", run.technique, run.scene));
        let scene = scene_cache.get(&scene_key(run)).context("scene cache")?;
        match execute(
            &gpu,
            techniques,
            &spec,
            scene,
            run,
            &mut reference,
            store.dir(),
            &unit_costs,
        ) {
            Ok((row, frames, params)) => store.append(&row, &frames, &params)?,
            Err(e) => {
                // A failed run is recorded as failed and the sweep goes on.
                failed += 1;
                let mut row =
                    RunSummary::failed(&run.id, &run.technique, scene.name(), &format!("{e:#}"));
                row.repetition = run.repetition;
                row.scene_variant = run.scene_variant();
                store.append(&row, &[], &[])?;
                bar.println(format!(
                    "run {} ({} on {}) failed: {e:#}",
                    run.id, run.technique, run.scene
                ));
                // A device that faulted (or holds an error nobody caught) is not trusted with
                // the next run: it gets a fresh one.
                if is_device_fault(&e) || gpu.check("after a failed run").is_err() {
                    drop(gpu);
                    gpu = args
                        .gpu
                        .context_for(&needs)
                        .context("recreating the device after a failed run")?;
                    bar.println("  the following runs use a fresh device");
                }
            }
        }
        bar.inc(1);
    }
    bar.finish_and_clear();
    // The unit costs again, now the runs are done: how far the host moved while they ran. The
    // runs are recorded already; a calibration that fails here costs only this comparison.
    if !targets.is_empty() && attempted > failed {
        match super::calibrate::adapter_after(&gpu, calibration.as_ref(), &targets) {
            Ok((raw_after, after)) => {
                meta.calibration_after = raw_after;
                meta.unit_costs_after = after;
                store.write_meta(&toml::to_string_pretty(&meta)?)?;
            }
            Err(e) => eprintln!(
                "sweep `{}`: the calibration after the runs failed ({e:#}); the runs are recorded, without it",
                spec.name
            ),
        }
    }
    eprintln!(
        "sweep `{}`: {} runs recorded in {} ({failed} failed this time)",
        spec.name,
        store.finished_count(),
        out.display()
    );
    super::write_html(&out).context("writing report.html")?;
    if attempted > 0 && failed == attempted {
        anyhow::bail!(
            "every one of the {attempted} runs failed (their errors are in {}); nothing was measured",
            out.join("runs.csv").display()
        );
    }
    Ok(())
}

/// Expands a sweep into its runs and loads every scene variant they use, checking each run's
/// technique parameters (the scene file's `[techniques.<id>]` overlaid with the grid point)
/// through the technique's own check: a bad value anywhere in the grid refuses the file before
/// anything is measured. `sweep` and `validate` both go through here.
pub(crate) fn load_plan(
    spec: &SweepSpec,
    file: &std::path::Path,
    techniques: &[TechniqueEntry],
) -> anyhow::Result<(Vec<PlannedRun>, HashMap<String, Scene>)> {
    let ids: Vec<&str> = if spec.techniques.iter().any(|t| t == "all") {
        registry::ids_in(techniques)
    } else {
        spec.techniques
            .iter()
            .map(|t| registry::find_in(techniques, t).map(|e| e.info.id))
            .collect::<Result<_, _>>()
            .with_context(|| format!("{}: techniques", file.display()))?
    };
    for technique in spec.params.keys() {
        registry::find_in(techniques, technique)
            .with_context(|| format!("{}: [params.{technique}]", file.display()))?;
    }
    let plan = spec.expand(&ids)?;
    let mut scenes: HashMap<String, Scene> = HashMap::new();
    for run in &plan {
        let key = scene_key(run);
        if let std::collections::hash_map::Entry::Vacant(e) = scenes.entry(key.clone()) {
            let base = scenes::load(&run.scene)?;
            let mut config = apply_overrides(&base.config, &run.scene_overrides)
                .with_context(|| format!("{}: scene `{}`", file.display(), run.scene))?;
            if let Some(seed) = spec.seed {
                config.seed = seed;
            }
            let scene = Scene::from_config(config, base.base_dir.clone()).with_context(|| {
                format!(
                    "{}: scene `{}` with {}",
                    file.display(),
                    run.scene,
                    run.scene_variant()
                )
            })?;
            e.insert(scene);
        }
        let overrides = scenes[&key].technique_params(&run.technique, &run.params);
        registry::find_in(techniques, &run.technique)?
            .check(&overrides)
            .with_context(|| {
                format!(
                    "{}: run `{}` ({} on scene `{}`)",
                    file.display(),
                    run.id,
                    run.technique,
                    run.scene
                )
            })?;
    }
    Ok((plan, scenes))
}

/// Whether `e` is a fault of the device (a validation error, out of memory, a lost device)
/// rather than a refusal before any GPU work.
fn is_device_fault(e: &anyhow::Error) -> bool {
    e.chain()
        .filter_map(|c| c.downcast_ref::<grassbench::Error>())
        .any(grassbench::Error::is_device_fault)
}

fn scene_key(run: &PlannedRun) -> String {
    format!("{}|{}", run.scene, run.scene_variant())
}

type Executed = (RunSummary, Vec<runner::FrameRecord>, Vec<ParamRow>);

/// A group's reference run, its per-frame GPU wall times and its last frame.
type Reference = (RunSummary, Vec<f64>, Option<image::RgbaImage>);

/// One run: measure, compare with the group's reference, save its last frame for repetition 0.
#[allow(clippy::too_many_arguments)]
fn execute(
    gpu: &GpuContext,
    techniques: &[TechniqueEntry],
    spec: &SweepSpec,
    scene: &Scene,
    run: &PlannedRun,
    reference: &mut HashMap<String, Reference>,
    dir: &std::path::Path,
    unit_costs: &[UnitCosts],
) -> anyhow::Result<Executed> {
    let entry = registry::find_in(techniques, &run.technique)?;
    let size = run.size.unwrap_or(scene.resolution());
    let mut harness = Harness::new(gpu, scene.clone(), size, run.msaa)?;
    let mut technique = harness.create(entry, &run.params)?;
    let last = spec.warmup + spec.frames - 1;
    let options = RunOptions {
        warmup: spec.warmup,
        frames: spec.frames,
        capture: vec![last],
        run_id: run.id.clone(),
    };
    let result = runner::run(&mut harness, technique.as_mut(), &options, &mut |_, _| {})?;
    let mut row = result.summary;
    row.params = grassbench::technique::label_params(&run.params, &row.params);
    if let Some(costs) = UnitCosts::for_target(unit_costs, &size.to_string(), run.msaa) {
        apply_model(&mut row, costs, &result.frames);
    }
    row.repetition = run.repetition;
    row.scene_variant = run.scene_variant();
    let image = result.images.into_iter().next().map(|(_, img)| img);
    let walls: Vec<f64> = result.frames.iter().map(|f| f.gpu_wall_ms).collect();
    if run.technique == REFERENCE {
        reference.insert(
            run.group.clone(),
            (row.clone(), walls.clone(), image.clone()),
        );
    }
    if let Some((ref_row, ref_walls, ref_img)) = reference.get(&run.group) {
        compare_with_reference(&mut row, ref_row, &walls, ref_walls);
        if let (Some(img), Some(ref_img)) = (&image, ref_img) {
            row.flip_vs_reference = Some(f64::from(flip(ref_img, img)?.mean));
            row.flip_vs_reference_quarter = Some(f64::from(
                flip(&downsample(ref_img, 4), &downsample(img, 4))?.mean,
            ));
        }
    }
    if run.repetition == 0
        && let Some(img) = &image
    {
        save_png(img, &dir.join(image_path(&run.config_id)))?;
    }
    let mut params: Vec<ParamRow> = technique
        .param_table()
        .iter()
        .map(|(k, v)| ParamRow {
            run_id: run.id.clone(),
            owner: run.technique.clone(),
            key: k.clone(),
            value: grassbench::params::format_value(v),
        })
        .collect();
    params.extend(run.scene_overrides.iter().map(|(k, v)| ParamRow {
        run_id: run.id.clone(),
        owner: "scene".into(),
        key: k.clone(),
        value: grassbench::params::format_value(v),
    }));
    params.push(ParamRow {
        run_id: run.id.clone(),
        owner: "run".into(),
        key: "config_id".into(),
        value: run.config_id.clone(),
    });
    params.push(ParamRow {
        run_id: run.id.clone(),
        owner: "run".into(),
        key: "group".into(),
        value: run.group.clone(),
    });
    Ok((row, result.frames, params))
}

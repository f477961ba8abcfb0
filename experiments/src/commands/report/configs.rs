//! A sweep's `runs.csv` as the report sees it: one [`Config`] per configuration, its
//! repetitions pooled.

use std::collections::{BTreeMap, HashMap};
use std::path::Path;

use anyhow::{Context as _, bail};
use grassbench::runner::bootstrap::{Interval, speedup_interval};
use grassbench::runner::{FrameRecord, Percentiles, RunSummary};
use grassbench::sweep::{REFERENCE, config_id_of, fill_ratios, image_path, read_rows};
use grassbench::technique::VARIANT_KEY;

/// One configuration, its repetitions pooled.
#[derive(Clone, Debug, Default)]
pub(super) struct Config {
    /// Technique id.
    pub(super) technique: String,
    /// Scene name.
    pub(super) scene: String,
    /// Scene overrides (`key=value;...`).
    pub(super) variant: String,
    /// Target size, `WxH`.
    pub(super) size: String,
    /// 4x MSAA.
    pub(super) msaa: bool,
    /// Technique parameters, `key=value;...`.
    pub(super) params: String,
    /// The parameters that vary between configurations of the technique (`key=value ...`).
    pub(super) label: String,
    /// Median GPU wall time of each finished repetition, ms.
    pub(super) gpu_wall: Vec<f64>,
    /// Width of each finished repetition's own p5-p95 band of GPU wall time, ms.
    pub(super) gpu_wall_band: Vec<f64>,
    /// Median frame time of each finished repetition, ms.
    pub(super) frame: Vec<f64>,
    /// Median CPU update of each repetition, ms.
    pub(super) update: Vec<f64>,
    /// Median CPU upload of each repetition, ms.
    pub(super) upload: Vec<f64>,
    /// Median CPU encode of each repetition, ms.
    pub(super) encode: Vec<f64>,
    /// GPU time over the group reference's, per repetition.
    pub(super) ratio: Vec<f64>,
    /// Per-frame GPU wall times of each finished repetition, by repetition (from frames.csv).
    pub(super) frame_walls: BTreeMap<u32, Vec<f64>>,
    /// 95 % bootstrap interval of the speed-up over the group's reference, repetitions and
    /// frames resampled ([`grassbench::runner::bootstrap::speedup_interval`]).
    pub(super) speedup_interval: Option<Interval>,
    /// Mean FLIP against the reference, per repetition.
    pub(super) flip: Vec<f64>,
    /// Mean FLIP against the reference at 1/4 scale, per repetition.
    pub(super) flip_quarter: Vec<f64>,
    /// Cores other processes kept busy during each finished repetition (where recorded).
    pub(super) host_other_cores: Vec<f64>,
    /// Cores this process spent in the kernel during each finished repetition (where recorded).
    pub(super) host_own_kernel_cores: Vec<f64>,
    /// Blades drawn as geometry (the last finished repetition's).
    pub(super) blades_drawn: Option<f64>,
    /// Blades impostors stand for (the last finished repetition's).
    pub(super) blades_represented: Option<f64>,
    /// Triangles (the last finished repetition's).
    pub(super) triangles: Option<f64>,
    /// GPU memory held, MB (the last finished repetition's).
    pub(super) gpu_mb: Option<f64>,
    /// The mean measured work of a frame of the last finished repetition that has it (from
    /// frames.csv; empty without pipeline statistics).
    pub(super) work: Option<grassbench::cost::Work>,
    /// The cost model's prediction of the last finished repetition, ms per term in the order
    /// of [`grassbench::cost::Term::ALL`] (empty without unit costs or counted work).
    pub(super) model_terms: Option<[f64; grassbench::cost::Term::ALL.len()]>,
    /// Measured over predicted GPU time, per repetition.
    pub(super) model_ratio: Vec<f64>,
    /// The last frame of repetition 0, relative to the results folder.
    pub(super) image: Option<String>,
    /// Repetitions that failed.
    pub(super) failed: usize,
}

/// The median of a sample (`None` when empty).
pub(super) fn median(v: &[f64]) -> Option<f64> {
    Percentiles::of(v.iter().copied()).map(|p| p.median)
}

impl Config {
    /// Blades the configuration showed, drawn and represented (empty for rows written before
    /// the two counts were split).
    pub(super) fn blades_shown(&self) -> Option<f64> {
        Some(self.blades_drawn? + self.blades_represented?)
    }

    /// How far its repetitions' median GPU times lie apart (max − min, ms), when that exceeds
    /// the widest p5-p95 band a single repetition measured: the repetitions then disagree by
    /// more than each one's own frame-to-frame noise, so something outside the configuration
    /// (the host's load, its clock) moved between them and the median hides it.
    pub(super) fn repetitions_disagree(&self) -> Option<f64> {
        let (lo, hi) = self
            .gpu_wall
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        let band = self.gpu_wall_band.iter().copied().fold(0.0, f64::max);
        (self.gpu_wall.len() > 1 && hi - lo > band).then_some(hi - lo)
    }

    /// The most cores other processes took during one of its repetitions, when that is more
    /// than [`BUSY_HOST_CORES`]: its times then measure the host's load as well.
    pub(super) fn busy_host(&self) -> Option<f64> {
        most_above(&self.host_other_cores, BUSY_HOST_CORES)
    }

    /// The most cores the process spent in the kernel during one of its repetitions, when that
    /// is more than [`KERNEL_CORES`]: its times then include paying for memory.
    pub(super) fn kernel_time(&self) -> Option<f64> {
        most_above(&self.host_own_kernel_cores, KERNEL_CORES)
    }
}

/// The largest of `values` where it is above `bound`.
fn most_above(values: &[f64], bound: f64) -> Option<f64> {
    let most = values.iter().copied().fold(0.0, f64::max);
    (most > bound).then_some(most)
}

/// Cores other processes may take during a run before the report says its times are not the
/// configuration's alone: a quarter of a core (a quiet host measured 0.00-0.05 here; a
/// compile beside a run takes 1-2).
pub(super) const BUSY_HOST_CORES: f64 = 0.25;

/// Cores of kernel time a run's own process may take before the report says so: measured
/// during the measured frames on the 2.6 GHz EPYC, 0.00-0.015 for the reference, zhang and bakay
/// at 640x360 with glibc's heaps kept and 0.18 for the reference's pitch in the state that
/// trimmed and regrew a heap every frame (`grassbench::runner::allocator`); frames of a few
/// milliseconds read up to 0.2 with the heaps kept (bakay's pitch at 320x180: 99 % of its
/// system time in `futex`, the rasteriser threads' wake-ups, 150 calls a frame).
pub(super) const KERNEL_CORES: f64 = 0.05;

impl Config {
    /// Pools one row of runs.csv into the configuration: its identity, and its figures where
    /// it finished (`false` for a failed run, which is only counted).
    fn add_run(&mut self, r: &RunSummary) -> bool {
        let c = self;
        c.technique.clone_from(&r.technique);
        c.scene.clone_from(&r.scene);
        c.variant.clone_from(&r.scene_variant);
        c.size = format!("{}x{}", r.width, r.height);
        c.msaa = r.msaa;
        if !r.is_ok() {
            c.failed += 1;
            return false;
        }
        c.params.clone_from(&r.params);
        c.gpu_wall.extend(r.gpu_wall_ms_median);
        c.gpu_wall_band.extend(
            r.gpu_wall_ms_p95
                .zip(r.gpu_wall_ms_p5)
                .map(|(hi, lo)| hi - lo),
        );
        c.frame.extend(r.frame_ms_median);
        c.update.extend(r.update_ms_median);
        c.upload.extend(r.upload_ms_median);
        c.encode.extend(r.encode_ms_median);
        c.ratio.extend(r.gpu_wall_ratio_to_reference);
        c.flip.extend(r.flip_vs_reference);
        c.flip_quarter.extend(r.flip_vs_reference_quarter);
        c.host_other_cores.extend(r.host_other_cores);
        c.host_own_kernel_cores.extend(r.host_own_kernel_cores);
        c.blades_drawn = r.blades_drawn.map(|b| b as f64);
        c.blades_represented = r.blades_represented.map(|b| b as f64);
        c.triangles = r.triangles.map(|t| t as f64);
        c.gpu_mb = r.gpu_bytes.map(|b| b as f64 / 1e6);
        c.model_ratio.extend(r.model_ratio);
        c.model_terms = (|| {
            Some([
                r.model_fixed_ms?,
                r.model_vertex_ms?,
                r.model_primitive_ms?,
                r.model_fragment_opaque_ms?,
                r.model_fragment_alpha_tested_ms?,
                r.model_fragment_blended_ms?,
                r.model_draw_ms?,
                r.model_compute_ms?,
                r.model_upload_ms?,
                // Runs modelled before the fetch, transcendental and arithmetic terms priced
                // none.
                r.model_texture_load_ms.unwrap_or(0.0),
                r.model_float_texture_load_ms.unwrap_or(0.0),
                r.model_vertex_texture_load_ms.unwrap_or(0.0),
                r.model_vertex_float_texture_load_ms.unwrap_or(0.0),
                r.model_texture_sample_ms.unwrap_or(0.0),
                r.model_float_texture_sample_ms.unwrap_or(0.0),
                r.model_vertex_transcendental_ms.unwrap_or(0.0),
                r.model_fragment_transcendental_ms.unwrap_or(0.0),
                r.model_compute_transcendental_ms.unwrap_or(0.0),
                r.model_vertex_arithmetic_ms.unwrap_or(0.0),
                r.model_fragment_arithmetic_ms.unwrap_or(0.0),
                r.model_compute_arithmetic_ms.unwrap_or(0.0),
                r.model_compute_barrier_ms.unwrap_or(0.0),
                r.model_compute_storage_ms.unwrap_or(0.0),
                r.model_vertex_storage_ms.unwrap_or(0.0),
                r.model_compute_division_ms.unwrap_or(0.0),
                r.model_texture_mip_blend_ms.unwrap_or(0.0),
                // Runs modelled before the instance and primitive input terms priced their
                // instances with their vertices and primitives, and their primitives' input
                // slots with the primitives.
                r.model_instance_ms.unwrap_or(0.0),
                r.model_primitive_input_ms.unwrap_or(0.0),
                // Likewise the samples' levels picked lane by lane, with the samples.
                r.model_texture_explicit_level_ms.unwrap_or(0.0),
                // And a pass head's primitives, with the primitives.
                r.model_head_primitive_ms.unwrap_or(0.0),
            ])
        })()
        .or(c.model_terms);
        true
    }
}

/// The configurations of a `grassbench run` folder (its runs.csv has no run ids: one run per
/// scene and technique), keyed by scene, size and technique, for `report.html`. Frames,
/// images and speed-up intervals stay where `run` wrote them (the page reads runs.csv).
pub(super) fn load_run_folder(dir: &Path) -> anyhow::Result<BTreeMap<String, Config>> {
    let path = dir.join("runs.csv");
    let rows: Vec<RunSummary> =
        read_rows(&path).with_context(|| format!("reading {}", path.display()))?;
    let mut configs: BTreeMap<String, Config> = BTreeMap::new();
    for r in &rows {
        let key = format!(
            "{}/{}/{}x{}/{}/{}",
            r.scene, r.scene_variant, r.width, r.height, r.msaa, r.technique
        );
        configs.entry(key).or_default().add_run(r);
    }
    shorten_params(&mut configs);
    Ok(configs)
}

/// Reads runs.csv into configurations keyed by configuration id, repetitions pooled. A run
/// written before its group's reference (another shard's, after `merge`) has no ratio in
/// runs.csv, and gets it here.
pub(super) fn load(dir: &Path) -> anyhow::Result<BTreeMap<String, Config>> {
    let path = dir.join("runs.csv");
    if !path.exists() {
        bail!("`{}` has no runs.csv: run a sweep first", dir.display());
    }
    let mut rows: Vec<RunSummary> =
        read_rows(&path).with_context(|| format!("reading {}", path.display()))?;
    if rows.iter().any(|r| r.run_id.is_empty()) {
        bail!(
            "{} has runs without a run id: `report` reads a sweep's results (`grassbench sweep`)",
            path.display()
        );
    }
    let records = frame_records(dir)?;
    let frames: HashMap<String, Vec<f64>> = records
        .iter()
        .map(|(id, f)| (id.clone(), f.iter().map(|r| r.gpu_wall_ms).collect()))
        .collect();
    fill_ratios(&mut rows, &frames);
    let mut configs: BTreeMap<String, Config> = BTreeMap::new();
    for r in &rows {
        let config_id = config_id_of(&r.run_id);
        let c = configs.entry(config_id.to_owned()).or_default();
        if !c.add_run(r) {
            continue;
        }
        if let Some(walls) = frames.get(&r.run_id) {
            c.frame_walls.insert(r.repetition, walls.clone());
        }
        if let Some(work) = records
            .get(&r.run_id)
            .and_then(|f| grassbench::cost::Work::mean_of(f))
        {
            c.work = Some(work);
        }
        let image = image_path(config_id);
        if dir.join(&image).exists() {
            c.image = Some(image);
        }
    }
    if configs.is_empty() {
        bail!("{} has no runs", path.display());
    }
    // Labels show only the parameters that vary within a technique, not every default.
    shorten_params(&mut configs);
    set_speedup_intervals(&mut configs);
    Ok(configs)
}

/// The frames of every run in `dir/frames.csv`, by run id (empty without it).
fn frame_records(dir: &Path) -> anyhow::Result<HashMap<String, Vec<FrameRecord>>> {
    let path = dir.join("frames.csv");
    let mut out: HashMap<String, Vec<FrameRecord>> = HashMap::new();
    if path.exists() {
        let frames: Vec<FrameRecord> =
            read_rows(&path).with_context(|| format!("reading {}", path.display()))?;
        for f in frames {
            out.entry(f.run_id.clone()).or_default().push(f);
        }
    }
    Ok(out)
}

/// Gives every configuration the 95 % interval of its speed-up over its group's reference
/// (same scene, variant, size, MSAA), pairing repetitions by number.
fn set_speedup_intervals(configs: &mut BTreeMap<String, Config>) {
    let group = |c: &Config| (c.scene.clone(), c.variant.clone(), c.size.clone(), c.msaa);
    let references: HashMap<_, BTreeMap<u32, Vec<f64>>> = configs
        .values()
        .filter(|c| c.technique == REFERENCE)
        .map(|c| (group(c), c.frame_walls.clone()))
        .collect();
    for c in configs.values_mut().filter(|c| c.technique != REFERENCE) {
        let Some(reference) = references.get(&group(c)) else {
            continue;
        };
        let (r, t): (Vec<Vec<f64>>, Vec<Vec<f64>>) = c
            .frame_walls
            .iter()
            .filter_map(|(rep, walls)| Some((reference.get(rep)?.clone(), walls.clone())))
            .unzip();
        c.speedup_interval = speedup_interval(&r, &t);
    }
}

/// Sets `label` of every configuration to the parameters that differ between configurations
/// of the same technique.
fn shorten_params(configs: &mut BTreeMap<String, Config>) {
    let mut values: BTreeMap<(String, String), std::collections::BTreeSet<String>> =
        BTreeMap::new();
    for c in configs.values() {
        for (k, v) in split_params(&c.params) {
            values
                .entry((c.technique.clone(), k))
                .or_default()
                .insert(v);
        }
    }
    for c in configs.values_mut() {
        let params = split_params(&c.params);
        let variant = params.get(VARIANT_KEY).cloned();
        // What the row's operating point sets by itself: a row at `variant=paper` is labelled
        // `variant=paper` and only the keys it changes beyond the paper's settings, not every
        // key the paper's settings change.
        let baseline = params_at(&c.technique, variant.as_deref());
        let changed = params.iter().filter(|(k, v)| {
            *k != VARIANT_KEY
                && values
                    .get(&(c.technique.clone(), (*k).clone()))
                    .is_some_and(|v| v.len() > 1)
                && baseline.get(*k) != Some(*v)
        });
        c.label = variant
            .iter()
            .map(|v| format!("{VARIANT_KEY}={v}"))
            .chain(changed.map(|(k, v)| format!("{k}={v}")))
            .collect::<Vec<_>>()
            .join(" ");
    }
}

/// The parameter values (`key` → value as `runs.csv` writes it) of `technique` at `variant`
/// (its defaults for none or `default`); empty for a technique or variant this build does not
/// know (a results folder from another revision), which then labels every varying key.
fn params_at(technique: &str, variant: Option<&str>) -> BTreeMap<String, String> {
    let Ok(entry) = crate::registry::find(technique) else {
        return BTreeMap::new();
    };
    let mut overrides = toml::Table::new();
    if let Some(v) = variant {
        // `runs.csv` writes strings quoted.
        overrides.insert(VARIANT_KEY.into(), v.trim_matches('"').into());
    }
    entry
        .check(&overrides)
        .map(|t| {
            t.iter()
                .map(|(k, v)| (k.clone(), grassbench::params::format_value(v)))
                .collect()
        })
        .unwrap_or_default()
}

impl Config {
    /// The operating point the row was measured at: the `variant` its parameters name, or
    /// `default`.
    pub(super) fn operating_point(&self) -> String {
        split_params(&self.params)
            .remove(VARIANT_KEY)
            .map_or(grassbench::technique::DEFAULT_VARIANT.to_owned(), |v| {
                v.trim_matches('"').to_owned()
            })
    }
}

/// A `key=value;...` parameter string (runs.csv's `params`) as a map.
fn split_params(params: &str) -> BTreeMap<String, String> {
    params
        .split(';')
        .filter_map(|kv| kv.split_once('='))
        .map(|(k, v)| (k.to_owned(), v.to_owned()))
        .collect()
}

/// The configuration's name in plots: technique, varying parameters, scene variant.
pub(super) fn label(c: &Config) -> String {
    let mut l = c.technique.clone();
    for extra in [&c.label, &c.variant] {
        if !extra.is_empty() {
            l.push(' ');
            l.push_str(&extra.replace(';', " "));
        }
    }
    l
}

#[cfg(test)]
mod tests {
    use super::*;

    fn config(medians: &[f64], bands: &[f64], other: &[f64]) -> Config {
        Config {
            gpu_wall: medians.to_vec(),
            gpu_wall_band: bands.to_vec(),
            host_other_cores: other.to_vec(),
            ..Config::default()
        }
    }

    #[test]
    fn repetitions_disagree_beyond_their_own_noise() {
        // 60 ms and 195 ms with bands of 10 ms (issue 19 §8's football field): flagged.
        let c = config(&[60.0, 195.0, 190.0], &[10.0, 8.0, 9.0], &[]);
        assert_eq!(c.repetitions_disagree(), Some(135.0));
        // Within one repetition's band: not flagged; one repetition: nothing to compare.
        assert_eq!(
            config(&[60.0, 65.0], &[10.0, 8.0], &[]).repetitions_disagree(),
            None
        );
        assert_eq!(config(&[60.0], &[1.0], &[]).repetitions_disagree(), None);
    }

    #[test]
    fn a_busy_host_is_named() {
        assert_eq!(config(&[1.0], &[0.1], &[0.02, 1.3]).busy_host(), Some(1.3));
        assert_eq!(config(&[1.0], &[0.1], &[0.02, 0.2]).busy_host(), None);
        assert_eq!(config(&[1.0], &[0.1], &[]).busy_host(), None);
    }

    #[test]
    fn kernel_time_beyond_a_quiet_process_is_named() {
        let kernel = |cores: &[f64]| Config {
            host_own_kernel_cores: cores.to_vec(),
            ..Config::default()
        };
        assert_eq!(kernel(&[0.01, 0.18]).kernel_time(), Some(0.18));
        assert_eq!(kernel(&[0.01, 0.015]).kernel_time(), None);
        assert_eq!(kernel(&[]).kernel_time(), None);
    }

    /// A row at `paper` is labelled by its variant and what it changes beyond it, not by every
    /// key the paper's settings change; a default row by what it changes beyond the defaults.
    #[test]
    fn variant_rows_are_labelled_by_their_operating_point() {
        let entry = crate::registry::find("bakay").unwrap();
        let row = |overrides: &str| {
            let overrides: toml::Table = overrides.parse().unwrap();
            let params = grassbench::technique::label_params(
                &overrides,
                &entry
                    .check(&overrides)
                    .unwrap()
                    .iter()
                    .map(|(k, v)| format!("{k}={}", grassbench::params::format_value(v)))
                    .collect::<Vec<_>>()
                    .join(";"),
            );
            Config {
                technique: "bakay".into(),
                params,
                ..Config::default()
            }
        };
        let mut configs = BTreeMap::new();
        configs.insert("a".into(), row(""));
        configs.insert("b".into(), row("variant = \"paper\""));
        configs.insert("c".into(), row("variant = \"paper\"\nmipmaps = \"custom\""));
        configs.insert("d".into(), row("shells = 9"));
        shorten_params(&mut configs);
        let labels: Vec<&str> = configs.values().map(|c| c.label.as_str()).collect();
        assert_eq!(
            labels,
            [
                "",
                "variant=paper",
                "variant=paper mipmaps=custom",
                "shells=9"
            ]
        );
        let points: Vec<String> = configs.values().map(Config::operating_point).collect();
        assert_eq!(points, ["default", "paper", "paper", "default"]);
    }
}

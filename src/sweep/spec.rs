//! The sweep file and its expansion into runs.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::REFERENCE;
use crate::target::Size;
use crate::{Error, Result};

/// A sweep file (`experiments/*.toml`).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SweepSpec {
    /// Name; results go to `results/<name>/` by default.
    pub name: String,
    /// What the sweep measures.
    #[serde(default)]
    pub description: String,
    /// Scene names or paths.
    pub scenes: Vec<String>,
    /// Technique ids, or `["all"]`.
    #[serde(default = "all")]
    pub techniques: Vec<String>,
    /// Target sizes `WxH`, or `"scene"` for each scene's own.
    #[serde(default = "scene_resolution")]
    pub resolutions: Vec<String>,
    /// MSAA settings to try.
    #[serde(default = "no_msaa")]
    pub msaa: Vec<bool>,
    /// Repetitions of the whole grid.
    #[serde(default = "one")]
    pub repetitions: u32,
    /// Warm-up frames per run.
    #[serde(default = "three")]
    pub warmup: u64,
    /// Measured frames per run.
    #[serde(default = "ten")]
    pub frames: u64,
    /// Seed replacing every scene's own (absent: scenes keep theirs).
    #[serde(default)]
    pub seed: Option<u64>,
    /// Technique parameter grids: `[params.<technique>]` with `key = [values…]` (or one value).
    #[serde(default)]
    pub params: toml::Table,
    /// Scene parameter grid: dotted scene keys with lists of values, e.g.
    /// `"grass.density" = [20.0, 40.0]`.
    #[serde(default)]
    pub scene_params: toml::Table,
}

fn all() -> Vec<String> {
    vec!["all".to_owned()]
}
fn scene_resolution() -> Vec<String> {
    vec!["scene".to_owned()]
}
fn no_msaa() -> Vec<bool> {
    vec![false]
}
fn one() -> u32 {
    1
}
fn three() -> u64 {
    3
}
fn ten() -> u64 {
    10
}

/// Most runs one sweep may plan (a typo in a grid should not plan a month of work).
pub const MAX_RUNS: usize = 100_000;

/// One run of a sweep: a configuration and a repetition.
#[derive(Clone, Debug, PartialEq)]
pub struct PlannedRun {
    /// Position in the sweep's order.
    pub index: usize,
    /// Position of its group among the sweep's groups, in order: `--shard I/N` deals out
    /// whole groups (every N-th group from I), so a technique always runs in the same process
    /// as its group's reference and its ratio and FLIP are measured as in an unsharded sweep.
    pub group_index: usize,
    /// `<configuration hash>-r<repetition>`: stable across restarts and machines.
    pub id: String,
    /// The configuration's hash, shared by its repetitions.
    pub config_id: String,
    /// Group of runs compared with each other (same scene variant, size, MSAA, repetition):
    /// ratios to the reference are taken within a group.
    pub group: String,
    /// Repetition, from 0.
    pub repetition: u32,
    /// Scene name or path.
    pub scene: String,
    /// Dotted scene overrides.
    pub scene_overrides: Vec<(String, toml::Value)>,
    /// Target size, or `None` for the scene's.
    pub size: Option<Size>,
    /// 4x MSAA.
    pub msaa: bool,
    /// Technique id.
    pub technique: String,
    /// Technique parameter overrides.
    pub params: toml::Table,
}

impl PlannedRun {
    /// The scene overrides as `key=value;...`.
    pub fn scene_variant(&self) -> String {
        self.scene_overrides
            .iter()
            .map(|(k, v)| format!("{k}={}", crate::params::format_value(v)))
            .collect::<Vec<_>>()
            .join(";")
    }
}

impl SweepSpec {
    /// Parses a sweep file; errors name the file, the line and the key.
    pub fn from_toml(text: &str, origin: &Path) -> Result<Self> {
        let spec: Self = toml::from_str(text).map_err(|e| Error::InvalidFile {
            path: origin.to_owned(),
            message: format!("not a valid sweep file: {e}"),
        })?;
        spec.validate().map_err(|e| Error::InvalidFile {
            path: origin.to_owned(),
            message: e.to_string(),
        })?;
        Ok(spec)
    }

    /// Reads a sweep file.
    pub fn load(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| Error::io("cannot read sweep file", path, e))?;
        Self::from_toml(&text, path)
    }

    /// Checks names, counts and grids.
    pub fn validate(&self) -> Result<()> {
        if self.name.is_empty()
            || !self
                .name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
        {
            return Err(Error::param(
                "name",
                &self.name,
                "a non-empty name of letters, digits, '_' and '-' (it names the results folder)",
            ));
        }
        for (key, list) in [
            ("scenes", &self.scenes),
            ("techniques", &self.techniques),
            ("resolutions", &self.resolutions),
        ] {
            if list.is_empty() {
                return Err(Error::param(key, "[]", "at least one entry"));
            }
        }
        for r in &self.resolutions {
            if r != "scene" {
                Size::parse(r)?;
            }
        }
        if self.msaa.is_empty() {
            return Err(Error::param("msaa", "[]", "at least one of true, false"));
        }
        crate::params::check_int("repetitions", self.repetitions, 1..=1000)?;
        crate::params::check_int("warmup", self.warmup, 0..=100_000)?;
        crate::params::check_int("frames", self.frames, 1..=1_000_000)?;
        for (technique, grid) in &self.params {
            if configurations(grid).is_none() {
                return Err(Error::param(
                    format!("params.{technique}"),
                    grid,
                    "a table of parameter = [values…], or an array of such tables \
                     (`[[params.<technique>]]`, one configuration grid each)",
                ));
            }
        }
        let planned = self.count(self.techniques.len());
        if planned > MAX_RUNS as f64 {
            return Err(Error::param(
                "sweep",
                format!("{planned:.0} runs"),
                format!("at most {MAX_RUNS} runs; shrink the grids"),
            ));
        }
        Ok(())
    }

    fn count(&self, techniques: usize) -> f64 {
        let grid = |t: &toml::Table| {
            t.values()
                .map(|v| v.as_array().map_or(1, Vec::len).max(1) as f64)
                .product::<f64>()
        };
        let params: f64 = self
            .params
            .values()
            .filter_map(configurations)
            .map(|tables| tables.iter().map(&grid).sum::<f64>())
            .fold(1.0, f64::max);
        self.scenes.len() as f64
            * grid(&self.scene_params)
            * self.resolutions.len() as f64
            * self.msaa.len() as f64
            * techniques as f64
            * params
            * f64::from(self.repetitions)
    }

    /// The runs in execution order, for the resolved technique ids. Within each group (scene,
    /// scene variant, resolution, MSAA, repetition) `reference` runs first, whatever the file's
    /// order, so every other run of the group can be divided by it and compared with its image
    /// as it finishes.
    pub fn expand(&self, techniques: &[&str]) -> Result<Vec<PlannedRun>> {
        let techniques: Vec<&str> = techniques
            .iter()
            .filter(|&&t| t == REFERENCE)
            .chain(techniques.iter().filter(|&&t| t != REFERENCE))
            .copied()
            .collect();
        let scene_grid = cartesian(&self.scene_params);
        let mut runs = Vec::new();
        let mut group_index = 0;
        for repetition in 0..self.repetitions {
            for scene in &self.scenes {
                for scene_overrides in &scene_grid {
                    for resolution in &self.resolutions {
                        let size = if resolution == "scene" {
                            None
                        } else {
                            Some(Size::parse(resolution)?)
                        };
                        for &msaa in &self.msaa {
                            let group_key =
                                format!("{scene}|{scene_overrides:?}|{resolution}|{msaa}");
                            let groups_before = runs.len();
                            for &technique in &techniques {
                                let grids = self
                                    .params
                                    .get(technique)
                                    .and_then(configurations)
                                    .unwrap_or_else(|| vec![toml::Table::new()]);
                                for params in grids.iter().flat_map(cartesian) {
                                    let params: toml::Table = params.into_iter().collect();
                                    let config_key = format!("{group_key}|{technique}|{params}");
                                    let config_id = format!("{:012x}", fnv(&config_key) >> 16);
                                    runs.push(PlannedRun {
                                        index: runs.len(),
                                        group_index,
                                        id: run_id(&config_id, repetition),
                                        config_id,
                                        group: format!(
                                            "{:012x}-r{repetition}",
                                            fnv(&group_key) >> 16
                                        ),
                                        repetition,
                                        scene: scene.clone(),
                                        scene_overrides: scene_overrides.clone(),
                                        size,
                                        msaa,
                                        technique: technique.to_owned(),
                                        params,
                                    });
                                }
                            }
                            if runs.len() > groups_before {
                                group_index += 1;
                            }
                        }
                    }
                }
            }
        }
        Ok(runs)
    }
}

/// The id of repetition `repetition` of configuration `config_id`.
fn run_id(config_id: &str, repetition: u32) -> String {
    format!("{config_id}-r{repetition}")
}

/// The configuration of a run id (the id itself when it is not `<configuration>-r<repetition>`).
pub fn config_id_of(run_id: &str) -> &str {
    run_id
        .rsplit_once("-r")
        .map_or(run_id, |(config, _)| config)
}

/// The key a results folder records its sweep file by: a hash of the file's text, so a folder
/// holds one version of one sweep.
pub fn sweep_key(text: &str) -> String {
    format!("{:016x}", fnv(text))
}

/// A technique's `[params.<id>]`: one grid table, or an array of grid tables
/// (`[[params.<id>]]`) whose configurations follow each other (so "the paper's settings, then
/// each with one key changed" needs no product of every key); `None` for anything else.
fn configurations(value: &toml::Value) -> Option<Vec<toml::Table>> {
    match value {
        toml::Value::Table(t) => Some(vec![t.clone()]),
        toml::Value::Array(a) if !a.is_empty() => a.iter().map(|v| v.as_table().cloned()).collect(),
        _ => None,
    }
}

/// Every combination of a table of `key = [values…]` (a scalar counts as one value), in key
/// order; one empty combination for an empty table.
fn cartesian(table: &toml::Table) -> Vec<Vec<(String, toml::Value)>> {
    let mut combos: Vec<Vec<(String, toml::Value)>> = vec![Vec::new()];
    for (key, value) in table {
        let values = match value {
            toml::Value::Array(a) if !a.is_empty() => a.clone(),
            other => vec![other.clone()],
        };
        combos = combos
            .into_iter()
            .flat_map(|c| {
                values.iter().map(move |v| {
                    let mut c = c.clone();
                    c.push((key.clone(), v.clone()));
                    c
                })
            })
            .collect();
    }
    combos
}

/// FNV-1a, for stable ids from text (the same on every machine and build).
fn fnv(text: &str) -> u64 {
    text.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// Applies dotted overrides (`grass.density`, `terrain.size`) to a scene file's table form.
pub fn apply_overrides(
    config: &crate::scene::SceneConfig,
    overrides: &[(String, toml::Value)],
) -> Result<crate::scene::SceneConfig> {
    let mut table = toml::Table::try_from(config)
        .map_err(|e| Error::param("scene", &config.name, e.to_string()))?;
    for (key, value) in overrides {
        let mut node = &mut table;
        let parts: Vec<&str> = key.split('.').collect();
        let (last, path) = parts
            .split_last()
            .ok_or_else(|| Error::param("scene_params", key, "a dotted scene key"))?;
        for p in path {
            node = node
                .get_mut(*p)
                .and_then(|v| v.as_table_mut())
                .ok_or_else(|| {
                    Error::param(
                        format!("scene_params.\"{key}\""),
                        p,
                        "a path to an existing scene table, e.g. grass.density",
                    )
                })?;
        }
        if !node.contains_key(*last) {
            return Err(Error::param(
                format!("scene_params.\"{key}\""),
                last,
                "an existing scene key (see the scene files)",
            ));
        }
        node.insert((*last).to_owned(), value.clone());
    }
    toml::Value::Table(table)
        .try_into()
        .map_err(|e: toml::de::Error| {
            Error::param(
                "scene_params",
                e.message(),
                "values of the scene key's type",
            )
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    const SPEC: &str = r#"
name = "t"
scenes = ["a", "b"]
techniques = ["x", "y"]
resolutions = ["64x32"]
repetitions = 2
[params.y]
k = [1, 2, 3]
[scene_params]
"grass.density" = [5.0, 10.0]
"#;

    #[test]
    fn an_array_of_tables_lists_configurations_one_after_another() {
        let spec = SweepSpec::from_toml(
            r#"
name = "t"
scenes = ["a"]
techniques = ["y"]
[[params.y]]
variant = "paper"
[[params.y]]
variant = "paper"
k = [1, 2]
"#,
            Path::new("t.toml"),
        )
        .unwrap();
        let runs = spec.expand(&["y"]).unwrap();
        let params: Vec<String> = runs.iter().map(|r| r.params.to_string()).collect();
        // 1 + 2 configurations, in the file's order, not the product of every key.
        assert_eq!(runs.len(), 3, "{params:?}");
        assert!(!params[0].contains('k'), "{params:?}");
        assert!(
            params[1].contains("k = 1") && params[2].contains("k = 2"),
            "{params:?}"
        );
        assert!(runs.iter().all(|r| r.params.get("variant").is_some()));
        assert_eq!(spec.count(1), 3.0);
        // Distinct configurations, distinct ids.
        assert_ne!(runs[0].config_id, runs[1].config_id);
        let bad = SweepSpec::from_toml(
            "name = \"t\"\nscenes = [\"a\"]\n[params]\ny = [1, 2]\n",
            Path::new("t.toml"),
        )
        .unwrap_err()
        .to_string();
        assert!(bad.contains("params.y"), "{bad}");
    }

    #[test]
    fn expands_the_grid_interleaved_with_stable_ids() {
        let spec = SweepSpec::from_toml(SPEC, Path::new("t.toml")).unwrap();
        let runs = spec.expand(&["x", "y"]).unwrap();
        // 2 reps x 2 scenes x 2 densities x (x + 3 y) = 32.
        assert_eq!(runs.len(), 32);
        assert_eq!(runs[0].technique, "x");
        assert_eq!(runs[1].technique, "y");
        assert_eq!(runs[4].technique, "x");
        // Repetition 1 repeats repetition 0's configurations in the same order.
        for k in 0..16 {
            assert_eq!(runs[k].config_id, runs[k + 16].config_id);
            assert_ne!(runs[k].id, runs[k + 16].id);
        }
        let again = spec.expand(&["x", "y"]).unwrap();
        assert_eq!(runs, again);
        // `reference` first in every group, wherever the file lists it.
        let with_reference = spec.expand(&["y", "reference", "x"]).unwrap();
        assert_eq!(with_reference.len(), 40);
        let groups: Vec<&[PlannedRun]> =
            with_reference.chunk_by(|a, b| a.group == b.group).collect();
        // 2 reps x 2 scenes x 2 densities = 8 groups, numbered in order (shards deal them out).
        assert_eq!(groups.len(), 8);
        for (k, group) in groups.iter().enumerate() {
            assert_eq!(group[0].technique, "reference", "{group:?}");
            assert_eq!(group[1].technique, "y");
            assert!(group.iter().all(|r| r.group_index == k), "{group:?}");
        }
        for run in &runs {
            assert_eq!(config_id_of(&run.id), run.config_id);
        }
        let mut ids: Vec<_> = runs.iter().map(|r| r.id.clone()).collect();
        ids.sort();
        ids.dedup();
        assert_eq!(ids.len(), 32, "ids must be unique");
    }

    #[test]
    fn rejects_bad_files_with_line_and_key() {
        let e = SweepSpec::from_toml(
            "name = \"t\"\nscenes = [\"a\"]\nframez = 3\n",
            Path::new("s.toml"),
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("s.toml") && e.contains("framez") && e.contains("line 3"),
            "{e}"
        );
        let e = SweepSpec::from_toml(
            "name = \"t\"\nscenes = [\"a\"]\nresolutions = [\"big\"]\n",
            Path::new("s.toml"),
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("WIDTHxHEIGHT"), "{e}");
        let e = SweepSpec::from_toml(
            "name = \"t\"\nscenes = [\"a\"]\nframes = 0\n",
            Path::new("s.toml"),
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("frames"), "{e}");
        let e = SweepSpec::from_toml("name = \"../x\"\nscenes = [\"a\"]\n", Path::new("s.toml"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("name"), "{e}");
    }
}

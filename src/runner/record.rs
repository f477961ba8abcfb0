//! Rows of `frames.csv` and `runs.csv`: flat structs (the csv crate cannot flatten), with
//! technique parameters recorded separately in long format.
//!
//! Both are read back by name (`report`, `merge`), including files written by older builds:
//! columns added since (`run_id`, `repetition`, `status`, `error`, `scene_variant`,
//! `counters`, the levels of detail, the comparisons with the reference) are optional there,
//! and a `runs.csv` row without `status` is a run that finished (older builds wrote no rows
//! for failed runs).

use super::Percentiles;
use crate::technique::LevelBlades;

/// One measured frame (a row of `frames.csv`).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FrameRecord {
    /// Run this frame belongs to (empty outside sweeps).
    #[serde(default)]
    pub run_id: String,
    /// Technique id.
    pub technique: String,
    /// Scene name.
    pub scene: String,
    /// Target width.
    pub width: u32,
    /// Target height.
    pub height: u32,
    /// 4x MSAA on.
    pub msaa: bool,
    /// Frame index.
    pub frame: u64,
    /// Scene time, s.
    pub time_s: f32,
    /// CPU: advancing and baking the wind (core work, the same for every technique; done once
    /// per frame by the world, and reported to every view drawing that frame), ms.
    pub wind_ms: f64,
    /// CPU: `update`, ms.
    pub update_ms: f64,
    /// CPU: core + technique uploads (`prepare`), ms.
    pub upload_ms: f64,
    /// CPU: recording commands (background + technique `encode`), ms.
    pub encode_ms: f64,
    /// Wall time from submit to the end of `poll(wait)`, ms (background included).
    pub gpu_wall_ms: f64,
    /// Timestamp-query time of the core's background pass, ms (empty without timestamps).
    pub gpu_ts_background_ms: Option<f64>,
    /// Timestamp-query time of the technique's render passes, ms.
    pub gpu_ts_render_ms: Option<f64>,
    /// Timestamp-query time of compute passes, ms (wrong on lavapipe: cross-check with wall).
    pub gpu_ts_compute_ms: Option<f64>,
    /// Blades represented.
    pub blades: u64,
    /// Triangles submitted.
    pub triangles: u64,
    /// Draw calls.
    pub draw_calls: u64,
    /// GPU memory held by the technique, bytes.
    pub gpu_bytes: u64,
    /// The technique's own counts ([`GrassTechnique::counters`]), `name=value;...`.
    ///
    /// [`GrassTechnique::counters`]: crate::GrassTechnique::counters
    #[serde(default)]
    pub counters: String,
    /// Blades per level of detail, in the technique's own levels (written to `levels.csv` in
    /// long format, not to `frames.csv`).
    #[serde(skip)]
    pub levels: Vec<LevelBlades>,
}

/// A row of `levels.csv`: blades one level of detail drew or stood for in one frame (long
/// format, since every technique names its own levels).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LevelRow {
    /// Run id.
    pub run_id: String,
    /// Technique id.
    pub technique: String,
    /// Frame number.
    pub frame: u64,
    /// The technique's name for the level.
    pub level: String,
    /// Blades.
    pub blades: u64,
}

impl LevelRow {
    /// The level rows of measured frames, in frame order.
    pub fn of(frames: &[FrameRecord]) -> Vec<Self> {
        frames
            .iter()
            .flat_map(|f| {
                f.levels.iter().map(|l| Self {
                    run_id: f.run_id.clone(),
                    technique: f.technique.clone(),
                    frame: f.frame,
                    level: l.level.to_owned(),
                    blades: l.blades,
                })
            })
            .collect()
    }
}

/// `name=value;...` of a technique's counters.
pub fn format_counters(counters: &[(&'static str, f64)]) -> String {
    counters
        .iter()
        .map(|(k, v)| format!("{k}={v}"))
        .collect::<Vec<_>>()
        .join(";")
}

/// A run summarised (a row of `runs.csv`).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RunSummary {
    /// Run id (`<configuration>-r<repetition>` in sweeps, empty otherwise).
    #[serde(default)]
    pub run_id: String,
    /// Repetition, from 0.
    #[serde(default)]
    pub repetition: u32,
    /// `ok`, or `failed` (then `error` says why and the figures are zero).
    #[serde(default = "status_ok")]
    pub status: String,
    /// Why the run failed.
    #[serde(default)]
    pub error: String,
    /// Scene overrides of this configuration (`key=value;...`).
    #[serde(default)]
    pub scene_variant: String,
    /// Technique id.
    pub technique: String,
    /// Scene name.
    pub scene: String,
    /// Target width.
    pub width: u32,
    /// Target height.
    pub height: u32,
    /// 4x MSAA on.
    pub msaa: bool,
    /// Measured frames.
    pub frames: usize,
    /// Median CPU update, ms.
    pub update_ms_median: f64,
    /// Median CPU upload, ms.
    pub upload_ms_median: f64,
    /// Median CPU encode, ms.
    pub encode_ms_median: f64,
    /// Median GPU wall time, ms.
    pub gpu_wall_ms_median: f64,
    /// 5th percentile GPU wall time, ms.
    pub gpu_wall_ms_p5: f64,
    /// 95th percentile GPU wall time, ms.
    pub gpu_wall_ms_p95: f64,
    /// Median timestamp time of the technique's render passes, ms.
    pub gpu_ts_render_ms_median: Option<f64>,
    /// Median timestamp time of compute passes, ms.
    pub gpu_ts_compute_ms_median: Option<f64>,
    /// Median timestamp time of the background, ms.
    pub gpu_ts_background_ms_median: Option<f64>,
    /// Median CPU + GPU wall time of a frame, ms.
    pub frame_ms_median: f64,
    /// 5th percentile frame time, ms.
    pub frame_ms_p5: f64,
    /// 95th percentile frame time, ms.
    pub frame_ms_p95: f64,
    /// Median blades.
    pub blades: u64,
    /// Median triangles.
    pub triangles: u64,
    /// Median draw calls.
    pub draw_calls: u64,
    /// Largest GPU memory held, bytes.
    pub gpu_bytes: u64,
    /// Technique parameters, `key=value;...` (also in long format in `params.csv`).
    pub params: String,
    /// Median GPU wall time over the reference's in the same configuration and repetition.
    pub gpu_wall_ratio_to_reference: Option<f64>,
    /// Mean FLIP of the last frame against the reference's, full resolution.
    pub flip_vs_reference: Option<f64>,
    /// Mean FLIP against the reference after 4x downsampling (placement-insensitive).
    pub flip_vs_reference_quarter: Option<f64>,
    /// GPU wall time per blade represented, ns.
    pub blade_cost_ns: Option<f64>,
    /// The adapter's raw cost of a reference blade's triangles from calibration, ns.
    pub raw_blade_cost_ns: Option<f64>,
    /// `raw_blade_cost_ns / blade_cost_ns`: 1 = as fast as the rasteriser allows.
    pub efficiency: Option<f64>,
}

/// The status of a finished run, and of a row written before runs had a status.
fn status_ok() -> String {
    "ok".to_owned()
}

impl RunSummary {
    /// Whether the run finished (its figures are measurements, not zeros).
    pub fn is_ok(&self) -> bool {
        self.status == "ok"
    }

    /// Summarises measured frames (at least one).
    pub fn from_frames(frames: &[FrameRecord], params: &toml::Table) -> Self {
        let pct = |f: &dyn Fn(&FrameRecord) -> f64| {
            Percentiles::of(frames.iter().map(f)).unwrap_or_default()
        };
        let opt = |f: &dyn Fn(&FrameRecord) -> Option<f64>| {
            Percentiles::of(frames.iter().filter_map(f)).map(|p| p.median)
        };
        let median_u64 =
            |f: &dyn Fn(&FrameRecord) -> u64| pct(&|r| f(r) as f64).median.round() as u64;
        let wall = pct(&|r| r.gpu_wall_ms);
        let total = pct(&|r| r.wind_ms + r.update_ms + r.upload_ms + r.encode_ms + r.gpu_wall_ms);
        let first = frames.first();
        let blades = median_u64(&|r| r.blades);
        Self {
            run_id: first.map(|r| r.run_id.clone()).unwrap_or_default(),
            repetition: 0,
            status: status_ok(),
            error: String::new(),
            scene_variant: String::new(),
            technique: first.map(|r| r.technique.clone()).unwrap_or_default(),
            scene: first.map(|r| r.scene.clone()).unwrap_or_default(),
            width: first.map_or(0, |r| r.width),
            height: first.map_or(0, |r| r.height),
            msaa: first.is_some_and(|r| r.msaa),
            frames: frames.len(),
            update_ms_median: pct(&|r| r.update_ms).median,
            upload_ms_median: pct(&|r| r.upload_ms).median,
            encode_ms_median: pct(&|r| r.encode_ms).median,
            gpu_wall_ms_median: wall.median,
            gpu_wall_ms_p5: wall.p5,
            gpu_wall_ms_p95: wall.p95,
            gpu_ts_render_ms_median: opt(&|r| r.gpu_ts_render_ms),
            gpu_ts_compute_ms_median: opt(&|r| r.gpu_ts_compute_ms),
            gpu_ts_background_ms_median: opt(&|r| r.gpu_ts_background_ms),
            frame_ms_median: total.median,
            frame_ms_p5: total.p5,
            frame_ms_p95: total.p95,
            blades,
            triangles: median_u64(&|r| r.triangles),
            draw_calls: median_u64(&|r| r.draw_calls),
            gpu_bytes: frames.iter().map(|r| r.gpu_bytes).max().unwrap_or(0),
            params: params
                .iter()
                .map(|(k, v)| format!("{k}={}", crate::params::format_value(v)))
                .collect::<Vec<_>>()
                .join(";"),
            gpu_wall_ratio_to_reference: None,
            flip_vs_reference: None,
            flip_vs_reference_quarter: None,
            blade_cost_ns: (blades > 0).then(|| wall.median * 1e6 / blades as f64),
            raw_blade_cost_ns: None,
            efficiency: None,
        }
    }

    /// The row of a run that failed before producing frames.
    pub fn failed(run_id: &str, technique: &str, scene: &str, error: &str) -> Self {
        let mut row = Self::from_frames(&[], &toml::Table::new());
        row.run_id = run_id.to_owned();
        row.technique = technique.to_owned();
        row.scene = scene.to_owned();
        row.status = "failed".to_owned();
        row.error = error.to_owned();
        row
    }
}

#[cfg(test)]
mod tests {
    use std::path::{Path, PathBuf};

    use super::*;

    /// Every file under `dir` whose name ends with `suffix`, sorted.
    fn files(dir: &Path, suffix: &str) -> Vec<PathBuf> {
        let mut found = Vec::new();
        let mut stack = vec![dir.to_owned()];
        while let Some(d) = stack.pop() {
            for entry in std::fs::read_dir(&d).unwrap() {
                let path = entry.unwrap().path();
                if path.is_dir() {
                    stack.push(path);
                } else if path.to_string_lossy().ends_with(suffix) {
                    found.push(path);
                }
            }
        }
        found.sort();
        found
    }

    /// The committed result files named `*<suffix>`, and the test fixtures'.
    fn committed(suffix: &str) -> Vec<PathBuf> {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let mut all = files(&root.join("results"), suffix);
        all.extend(files(&root.join("experiments/tests/fixtures"), suffix));
        all
    }

    /// Reads `path` into typed rows, checks none is lost, and, when the file has today's
    /// columns, that writing the rows again gives back the file byte for byte.
    fn read_back<T: serde::Serialize + serde::de::DeserializeOwned>(path: &Path) -> Vec<T> {
        let bytes = std::fs::read(path).unwrap();
        let rows: Vec<T> = csv::Reader::from_reader(bytes.as_slice())
            .deserialize()
            .collect::<Result<_, _>>()
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let records = csv::Reader::from_reader(bytes.as_slice()).records().count();
        assert_eq!(rows.len(), records, "{}", path.display());
        let mut w = csv::Writer::from_writer(Vec::new());
        for row in &rows {
            w.serialize(row).unwrap();
        }
        let again = w.into_inner().unwrap();
        let header = |b: &[u8]| b.split(|&c| c == b'\n').next().map(<[u8]>::to_vec);
        if !rows.is_empty() && header(&again) == header(&bytes) {
            assert!(
                again == bytes,
                "{} changes when read and written",
                path.display()
            );
        }
        rows
    }

    #[test]
    fn every_committed_runs_csv_reads_back_into_its_type() {
        let paths = committed("runs.csv");
        assert!(!paths.is_empty());
        for path in &paths {
            let rows: Vec<RunSummary> = read_back(path);
            assert!(!rows.is_empty(), "{}", path.display());
        }
        // Today's columns, from a sweep.
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("results");
        let rows: Vec<RunSummary> = read_back(&root.join("zhang_target/runs.csv"));
        let (reference, zhang) = (&rows[0], &rows[1]);
        assert_eq!(
            (reference.technique.as_str(), reference.gpu_wall_ms_median),
            ("reference", 819.534429)
        );
        assert_eq!(reference.gpu_wall_ratio_to_reference, Some(1.0));
        assert_eq!(reference.gpu_ts_compute_ms_median, None);
        assert_eq!(zhang.run_id, "4bf71ea71ee3-r0");
        assert_eq!(zhang.technique, "zhang");
        assert!(zhang.is_ok());
        // The oldest columns: no run id, status, levels of detail or comparisons.
        let rows: Vec<RunSummary> = read_back(&root.join("bakay_vs_reference/runs.csv"));
        assert_eq!(rows[1].technique, "bakay");
        assert!(rows[1].is_ok() && rows[1].run_id.is_empty() && rows[1].repetition == 0);
        assert_eq!(rows[1].gpu_wall_ratio_to_reference, None);
        assert!(rows[1].params.contains("lod=\"minor_axis\""));
    }

    #[test]
    fn every_committed_frames_csv_reads_back_into_its_type() {
        let paths = committed("frames.csv");
        assert!(!paths.is_empty());
        for path in &paths {
            let _: Vec<FrameRecord> = read_back(path);
        }
    }

    #[test]
    fn failed_rows_are_not_ok() {
        let row = RunSummary::failed("x-r0", "reference", "meadow", "boom");
        assert!(!row.is_ok());
        assert!(RunSummary::from_frames(&[], &toml::Table::new()).is_ok());
    }
}

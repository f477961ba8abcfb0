//! Rows of `frames.csv` and `runs.csv`: flat structs (the csv crate cannot flatten), with
//! technique parameters recorded separately in long format.

use super::Percentiles;

/// One measured frame (a row of `frames.csv`).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct FrameRecord {
    /// Run this frame belongs to (empty outside sweeps).
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
    /// Blades drawn as geometry (empty for techniques without levels of detail).
    pub blades_geometry: Option<u64>,
    /// Blades represented by vertical slices (empty without levels of detail).
    pub blades_vertical_slices: Option<u64>,
    /// Blades represented by horizontal slices (empty without levels of detail).
    pub blades_horizontal_slices: Option<u64>,
    /// Triangles submitted.
    pub triangles: u64,
    /// Draw calls.
    pub draw_calls: u64,
    /// GPU memory held by the technique, bytes.
    pub gpu_bytes: u64,
    /// The technique's own counts ([`GrassTechnique::counters`]), `name=value;...`.
    ///
    /// [`GrassTechnique::counters`]: crate::GrassTechnique::counters
    pub counters: String,
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
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct RunSummary {
    /// Run id (`<configuration>-r<repetition>` in sweeps, empty otherwise).
    pub run_id: String,
    /// Repetition, from 0.
    pub repetition: u32,
    /// `ok`, or `failed` (then `error` says why and the figures are zero).
    pub status: String,
    /// Why the run failed.
    pub error: String,
    /// Scene overrides of this configuration (`key=value;...`).
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
    /// Median blades drawn as geometry (empty without levels of detail).
    pub blades_geometry: Option<u64>,
    /// Median blades represented by vertical slices.
    pub blades_vertical_slices: Option<u64>,
    /// Median blades represented by horizontal slices.
    pub blades_horizontal_slices: Option<u64>,
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

impl RunSummary {
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
        let median_opt_u64 = |f: &dyn Fn(&FrameRecord) -> Option<u64>| {
            Percentiles::of(frames.iter().filter_map(f).map(|v| v as f64))
                .map(|p| p.median.round() as u64)
        };
        let wall = pct(&|r| r.gpu_wall_ms);
        let total = pct(&|r| r.wind_ms + r.update_ms + r.upload_ms + r.encode_ms + r.gpu_wall_ms);
        let first = frames.first();
        let blades = median_u64(&|r| r.blades);
        Self {
            run_id: first.map(|r| r.run_id.clone()).unwrap_or_default(),
            repetition: 0,
            status: "ok".to_owned(),
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
            blades_geometry: median_opt_u64(&|r| r.blades_geometry),
            blades_vertical_slices: median_opt_u64(&|r| r.blades_vertical_slices),
            blades_horizontal_slices: median_opt_u64(&|r| r.blades_horizontal_slices),
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

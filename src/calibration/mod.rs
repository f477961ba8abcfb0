//! Calibration: the adapter's raw limits, measured with micro-workloads, so every technique's
//! cost can be read against what the hardware (or software rasteriser) can do at best.
//!
//! - **triangles/s**: instanced blade-like strips of 9 tiny triangles (2 x 10 pixels),
//!   depth-tested like blades; their time per instance is the raw cost of a reference blade;
//! - **fill rate**: full-screen triangles alpha-blended over each other (pixels/s);
//! - **bandwidth**: a compute shader copying a 32 MiB buffer (bytes read + written per s).
//!
//! Every figure is submit-to-`poll(wait)` wall time, the lower of two rounds' medians of five
//! runs, after one warm-up (timestamps are not used: on lavapipe compute-pass timestamps are
//! wrong). Two rounds because a process's first large submissions may all run slow: lavapipe
//! in a fresh process drew the triangle workload at 5.9 M triangles/s in one process of three
//! and at 8.8-10.1 M in the others (one round each, 2026-12-05), and these are the first
//! submissions of every `run` and `sweep` ([`crate::cost`]'s unit costs follow them). A slow
//! round can only read slower, so the lower median is the adapter's. The raw blade cost is a
//! lower bound: real blades cover more pixels and are shaded.

mod workloads;

use workloads::Workloads;

use crate::target::Size;
use crate::{GpuContext, Result};

/// Triangles of a reference blade at its default 5 segments (`2·5 − 1`).
pub const REFERENCE_BLADE_TRIANGLES: f64 = 9.0;

/// An adapter's measured limits.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Calibration {
    /// Target size used.
    pub size: String,
    /// Tiny depth-tested triangles per second, drawn as 9-triangle instanced strips.
    pub triangles_per_s: f64,
    /// Blended pixels per second.
    pub fill_pixels_per_s: f64,
    /// Bytes read plus written per second by a compute copy.
    pub compute_bytes_per_s: f64,
    /// `REFERENCE_BLADE_TRIANGLES / triangles_per_s`, ns.
    pub raw_blade_cost_ns: f64,
    /// Which clock: always submit-to-poll wall time.
    pub clock: String,
}

/// Instances (9-triangle strips) in the triangle workload.
const STRIPS: u32 = 100_000;
/// Layers in the fill workload.
const LAYERS: u32 = 24;
/// Bytes in each buffer of the bandwidth workload.
const COPY_BYTES: u64 = 32 << 20;
/// Timed rounds of each workload (the lower median is kept: the module's documentation).
const ROUNDS: usize = 2;
/// Timed submissions in a round.
const RUNS: usize = 5;

/// Runs the three workloads at `size`.
pub fn calibrate(gpu: &GpuContext, size: Size) -> Result<Calibration> {
    let workloads = Workloads::new(gpu, size)?;
    let time = |label: &str, record: &dyn Fn(&mut wgpu::CommandEncoder)| -> Result<f64> {
        workloads.time(label, record)?; // the warm-up
        let mut lowest = f64::NAN;
        for _ in 0..ROUNDS {
            let samples = (0..RUNS)
                .map(|_| workloads.time(label, record))
                .collect::<Result<Vec<f64>>>()?;
            if let Some(p) = crate::runner::Percentiles::of(samples) {
                lowest = lowest.min(p.median);
            }
        }
        Ok(lowest)
    };
    let tri_s = time("calibration: triangles", &|e| workloads.triangles(e))?;
    let fill_s = time("calibration: fill", &|e| workloads.fill(e))?;
    let copy_s = time("calibration: bandwidth", &|e| workloads.copy(e))?;
    let triangles_per_s = REFERENCE_BLADE_TRIANGLES * f64::from(STRIPS) / tri_s;
    Ok(Calibration {
        size: size.to_string(),
        triangles_per_s,
        fill_pixels_per_s: f64::from(LAYERS) * f64::from(size.width) * f64::from(size.height)
            / fill_s,
        compute_bytes_per_s: 2.0 * COPY_BYTES as f64 / copy_s,
        raw_blade_cost_ns: REFERENCE_BLADE_TRIANGLES / triangles_per_s * 1e9,
        clock: format!(
            "wall time, submit to poll(wait), the lower of {ROUNDS} rounds' medians of {RUNS} after 1 warm-up"
        ),
    })
}

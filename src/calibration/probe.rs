//! The host probe: a small, fixed piece of the calibration's triangle workload, timed at both
//! ends of every measured run, so each run carries a reading of how fast the host ran while it
//! was measured.
//!
//! On a software rasteriser the GPU is the CPU, and a virtual machine's CPU does not keep one
//! speed: in one sweep, nothing else running, the reference's runs of its middle minutes took
//! 1.13 and 1.15 times the same work's time in the previous version, its first and last 0.94
//! and 1.02 (`results/papers/README.md`, at `713f717`).
//! `host_other_cores` and `host_steal` see other processes and the hypervisor's accounting; a
//! slower host that neither shows (a neighbour on the physical cores, a frequency change) only
//! shows in the time of known work. The probe is that known work: the same 10 000 strips at
//! 320x180 whatever the run draws, so its times are comparable across a folder. A run's
//! `host_probe_ms` above the folder's median says its times were taken on a slower host; the
//! report names the configurations where it is (`grassbench report`).

use super::Workloads;
use crate::target::Size;
use crate::{GpuContext, Result};

/// Strips drawn by the probe: 90 000 tiny triangles. On lavapipe on a 2.6 GHz 2-vCPU EPYC a
/// submission took 10.7-15.8 ms (the median of six) between the runs of a `grassbench run`, and
/// 21-35 ms in a process doing nothing else (45 submissions; 30 000 strips 55-79 ms, 100 000,
/// the calibration's, 79-147 ms; 2026-12-06): a small submission pays the rasteriser's threads
/// waking, which the runs' frames pay too, so the probe reads a process's state as well as the
/// host's, and one sample is good to about a quarter. Six samples a run, ten times fewer strips
/// than the calibration's, keep it under 0.2 s a run.
const STRIPS: u32 = 10_000;
/// The probe's target side lengths: fixed, so every run's probe draws the same work.
const SIZE: (u32, u32) = (320, 180);
/// Submissions timed at each end of a run.
pub const PROBE_SUBMISSIONS: usize = 3;

/// The probe's GPU objects, built once per process and timed around every run.
pub struct HostProbe<'g> {
    workloads: Workloads<'g>,
}

impl<'g> HostProbe<'g> {
    /// Builds the probe and submits it once (its first submission compiles the shaders).
    pub fn new(gpu: &'g GpuContext) -> Result<Self> {
        let probe = Self {
            workloads: Workloads::new(gpu, Size::new(SIZE.0, SIZE.1)?, STRIPS, 16)?,
        };
        probe.once()?;
        Ok(probe)
    }

    /// Times [`PROBE_SUBMISSIONS`] submissions of the probe: submit to idle, wall time, ms each.
    pub fn sample(&self) -> Result<Vec<f64>> {
        (0..PROBE_SUBMISSIONS).map(|_| self.once()).collect()
    }

    fn once(&self) -> Result<f64> {
        let w = &self.workloads;
        Ok(w.time("host probe", &|e| w.triangles(e))? * 1e3)
    }
}

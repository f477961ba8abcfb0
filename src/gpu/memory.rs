//! GPU memory: what a run will allocate, estimated before any GPU work and checked against the
//! adapter, so that an absurd configuration is refused with the numbers instead of failing
//! half-way (or taking the machine down) inside the driver.
//!
//! Two checks. Every single buffer must fit the adapter's `max_buffer_size` limit, which wgpu
//! reports for every backend. The total must fit a *budget*: wgpu exposes no portable query of
//! video memory, so the budget is `GRASSBENCH_GPU_MEMORY_MB` when set, otherwise, for an adapter
//! that runs on the CPU (lavapipe, llvmpipe, WARP), the memory the system has available; for a
//! hardware adapter without the variable only the per-buffer limit is checked, and the driver's
//! own out-of-memory error (caught by [`GpuContext::scoped`]) is the last line.

use crate::{Error, GpuContext, Result};

/// Environment variable: the GPU memory budget in MiB.
pub const BUDGET_ENV: &str = "GRASSBENCH_GPU_MEMORY_MB";

/// Bytes a technique (or any part of a run) will hold on the GPU.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GpuEstimate {
    /// All buffers and textures, bytes.
    pub bytes: u64,
    /// The largest single buffer, bytes (checked against `max_buffer_size`).
    pub largest_buffer: u64,
}

impl GpuEstimate {
    /// One buffer of `bytes`.
    pub fn buffer(bytes: u64) -> Self {
        Self {
            bytes,
            largest_buffer: bytes,
        }
    }

    /// Textures (or anything that is not a buffer) of `bytes` in all.
    pub fn textures(bytes: u64) -> Self {
        Self {
            bytes,
            largest_buffer: 0,
        }
    }

    /// Both estimates together.
    #[must_use]
    pub fn plus(self, other: Self) -> Self {
        Self {
            bytes: self.bytes.saturating_add(other.bytes),
            largest_buffer: self.largest_buffer.max(other.largest_buffer),
        }
    }
}

impl std::iter::Sum for GpuEstimate {
    fn sum<I: Iterator<Item = Self>>(iter: I) -> Self {
        iter.fold(Self::default(), Self::plus)
    }
}

/// Where a budget came from, for the error message.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Budget {
    /// Bytes.
    pub bytes: u64,
    /// "GRASSBENCH_GPU_MEMORY_MB", "available system memory (CPU adapter)".
    pub source: String,
}

/// The total budget for `gpu`, if one is known (see the module documentation).
pub fn budget(gpu: &GpuContext) -> Result<Option<Budget>> {
    if let Ok(text) = std::env::var(BUDGET_ENV) {
        let mib: f64 = text
            .trim()
            .parse()
            .map_err(|_| Error::param(BUDGET_ENV, &text, "a positive number of MiB, e.g. 4096"))?;
        if !(mib.is_finite() && mib > 0.0) {
            return Err(Error::param(
                BUDGET_ENV,
                text,
                "a positive number of MiB, e.g. 4096",
            ));
        }
        return Ok(Some(Budget {
            bytes: (mib * 1024.0 * 1024.0) as u64,
            source: BUDGET_ENV.to_owned(),
        }));
    }
    if gpu.adapter.get_info().device_type == wgpu::DeviceType::Cpu {
        return Ok(available_system_memory().map(|bytes| Budget {
            bytes,
            source: "the system's available memory (the adapter runs on the CPU)".to_owned(),
        }));
    }
    Ok(None)
}

/// `MemAvailable` of `/proc/meminfo`, where there is one.
fn available_system_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    parse_mem_available(&text)
}

fn parse_mem_available(meminfo: &str) -> Option<u64> {
    let line = meminfo.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// Refuses `estimate` for `what` when a buffer exceeds the adapter's limit or the total exceeds
/// the budget; the error gives both numbers and the fix.
pub fn check(gpu: &GpuContext, what: &str, estimate: GpuEstimate) -> Result<()> {
    check_against(
        what,
        estimate,
        gpu.device.limits().max_buffer_size,
        budget(gpu)?,
        &gpu.summary.name,
    )
}

fn check_against(
    what: &str,
    estimate: GpuEstimate,
    max_buffer: u64,
    budget: Option<Budget>,
    adapter: &str,
) -> Result<()> {
    let mib = |b: u64| b as f64 / (1024.0 * 1024.0);
    if estimate.largest_buffer > max_buffer {
        return Err(Error::Unsupported {
            adapter: adapter.to_owned(),
            what: what.to_owned(),
            missing: format!(
                "it needs a {:.1} MiB buffer and the adapter allows {:.1} MiB (max_buffer_size). \
                 Fix: lower grass.density, the terrain size or the technique's parameters",
                mib(estimate.largest_buffer),
                mib(max_buffer)
            ),
        });
    }
    if let Some(b) = budget
        && estimate.bytes > b.bytes
    {
        return Err(Error::Unsupported {
            adapter: adapter.to_owned(),
            what: what.to_owned(),
            missing: format!(
                "it needs about {:.1} MiB of GPU memory and the budget is {:.1} MiB ({}). \
                 Fix: lower the resolution, grass.density or the technique's parameters, or set \
                 {BUDGET_ENV} if the budget is wrong",
                mib(estimate.bytes),
                mib(b.bytes),
                b.source
            ),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sums_keep_the_largest_buffer() {
        let e: GpuEstimate = [
            GpuEstimate::buffer(10),
            GpuEstimate::textures(100),
            GpuEstimate::buffer(30),
        ]
        .into_iter()
        .sum();
        assert_eq!(
            e,
            GpuEstimate {
                bytes: 140,
                largest_buffer: 30
            }
        );
    }

    #[test]
    fn refusals_name_the_numbers_and_the_fix() {
        let big = GpuEstimate::buffer(3 << 30);
        let e = check_against("reference", big, 1 << 30, None, "test").unwrap_err();
        let text = e.to_string();
        assert!(
            text.contains("3072.0 MiB buffer") && text.contains("1024.0 MiB"),
            "{text}"
        );
        assert!(text.contains("grass.density"), "{text}");
        let budget = Budget {
            bytes: 1 << 30,
            source: BUDGET_ENV.to_owned(),
        };
        let total = GpuEstimate::textures(2 << 30);
        let text = check_against("x", total, u64::MAX, Some(budget.clone()), "test")
            .unwrap_err()
            .to_string();
        assert!(
            text.contains("2048.0 MiB of GPU memory") && text.contains(BUDGET_ENV),
            "{text}"
        );
        assert!(
            check_against(
                "x",
                GpuEstimate::textures(1 << 29),
                u64::MAX,
                Some(budget),
                "t"
            )
            .is_ok()
        );
    }

    #[test]
    fn reads_mem_available() {
        let text = "MemTotal:       24000000 kB\nMemFree:  100 kB\nMemAvailable:   20000000 kB\n";
        assert_eq!(parse_mem_available(text), Some(20_000_000 * 1024));
        assert_eq!(parse_mem_available("MemTotal: 5 kB\n"), None);
    }
}

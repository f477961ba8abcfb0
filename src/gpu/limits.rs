//! Device limits: what a run asks the adapter for, and the check that refuses a technique the
//! device cannot serve before any of its GPU work.
//!
//! A device requests [`wgpu::Limits::default`], the limits WebGPU guarantees on any GPU, raised
//! only where a technique declares that it needs more ([`crate::technique::Technique::required_limits`],
//! plus its largest buffer from its memory estimate): a software rasteriser's generous limits
//! never leak into a technique silently, so what runs here runs on a real GPU. A run takes the
//! field-wise maximum of what its techniques need ([`needed_by`]), clamped to what the adapter
//! offers ([`request`]); where the adapter offers less than a technique needs, [`check`] refuses
//! that technique (and only it) with the limit, both numbers and the fix.

use crate::{Error, Result};

/// The field-wise maximum of `needs` (for maximum limits the larger value, for alignments the
/// smaller), never below [`wgpu::Limits::default`]: what a device serving all of them needs.
pub fn needed_by<'a>(needs: impl IntoIterator<Item = &'a wgpu::Limits>) -> wgpu::Limits {
    needs.into_iter().fold(wgpu::Limits::default(), |all, one| {
        all.or_better_values_from(one)
    })
}

/// The limits to request from an adapter offering `adapter` for a run that needs `needs`:
/// `needs`, lowered to the adapter's value wherever it offers less (the device can then be
/// created, and [`check`] refuses each technique that needed more).
pub fn request(needs: &wgpu::Limits, adapter: &wgpu::Limits) -> wgpu::Limits {
    needs.clone().or_worse_values_from(adapter)
}

/// Refuses technique `technique` when the device (`device`: its limits) offers less than it
/// `needs`, naming every limit short, what it needs, what the device and the adapter
/// (`adapter`, named `adapter_name`) offer, and the fix. Pure: no GPU work.
pub fn check(
    technique: &str,
    needs: &wgpu::Limits,
    device: &wgpu::Limits,
    adapter: &wgpu::Limits,
    adapter_name: &str,
) -> Result<()> {
    let mut short = Vec::new();
    needs.check_limits_with_fail_fn(device, false, |name, needed, offered| {
        short.push((name, needed, offered));
    });
    if short.is_empty() {
        return Ok(());
    }
    let mut adapter_short = false;
    let parts: Vec<String> = short
        .iter()
        .map(|&(name, needed, on_device)| {
            let mut on_adapter = None;
            needs.check_limits_with_fail_fn(adapter, false, |n, _, offered| {
                if n == name {
                    on_adapter = Some(offered);
                }
            });
            match on_adapter {
                Some(offered) => {
                    adapter_short = true;
                    format!("{name} = {needed}, and the adapter offers {offered}")
                }
                None => format!(
                    "{name} = {needed}; the device was created with {on_device} (the adapter \
                     offers enough)"
                ),
            }
        })
        .collect();
    let fix = if adapter_short {
        "Fix: run it on an adapter that offers this, or lower what makes it need so much \
         (grass.density, the terrain size, the technique's parameters)"
    } else {
        "Fix: create the device with what the techniques need \
         (`GpuContext::for_needs` with `gpu::limits::needed_by`, as every grassbench command does)"
    };
    Err(Error::Unsupported {
        adapter: adapter_name.to_owned(),
        what: technique.to_owned(),
        missing: format!("it needs {}. {fix}", parts.join("; ")),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The defaults with a larger storage binding, as a technique with many blades declares.
    fn wide() -> wgpu::Limits {
        wgpu::Limits {
            max_storage_buffer_binding_size: 512 << 20,
            ..wgpu::Limits::default()
        }
    }

    #[test]
    fn a_technique_needing_more_than_the_adapter_offers_is_refused_naming_the_limit() {
        let adapter = wgpu::Limits::default();
        let device = request(&wide(), &adapter);
        assert_eq!(device, adapter, "the request is clamped to the adapter");
        let text = check("greedy", &wide(), &device, &adapter, "small gpu")
            .unwrap_err()
            .to_string();
        for part in [
            "greedy",
            "small gpu",
            "max_storage_buffer_binding_size",
            &(512u64 << 20).to_string(),
            &(128u64 << 20).to_string(),
            "Fix:",
        ] {
            assert!(text.contains(part), "`{part}` missing from: {text}");
        }
        // Only the limit that is short is named.
        assert!(!text.contains("max_buffer_size"), "{text}");
    }

    #[test]
    fn a_device_created_for_less_than_the_adapter_offers_says_so() {
        let adapter = wide();
        let device = wgpu::Limits::default();
        let text = check("greedy", &wide(), &device, &adapter, "big gpu")
            .unwrap_err()
            .to_string();
        assert!(
            text.contains("the device was created with") && text.contains("needed_by"),
            "{text}"
        );
    }

    #[test]
    fn what_fits_passes_and_alignments_count_the_right_way() {
        let adapter = wide();
        check(
            "modest",
            &wgpu::Limits::default(),
            &adapter,
            &adapter,
            "gpu",
        )
        .unwrap();
        // A larger alignment is *less* capable: an adapter needing 512-byte offsets cannot serve
        // a technique that relies on 256.
        let coarse = wgpu::Limits {
            min_uniform_buffer_offset_alignment: 512,
            ..wgpu::Limits::default()
        };
        let text = check("aligned", &wgpu::Limits::default(), &coarse, &coarse, "gpu")
            .unwrap_err()
            .to_string();
        assert!(
            text.contains("min_uniform_buffer_offset_alignment"),
            "{text}"
        );
    }

    #[test]
    fn the_run_needs_the_largest_of_each_limit_and_never_less_than_the_defaults() {
        let small = wgpu::Limits {
            max_bind_groups: 1,
            ..wgpu::Limits::default()
        };
        let all = needed_by([&small, &wide()]);
        assert_eq!(all.max_storage_buffer_binding_size, 512 << 20);
        assert_eq!(all.max_bind_groups, wgpu::Limits::default().max_bind_groups);
        assert_eq!(needed_by([]), wgpu::Limits::default());
    }
}

//! Limits a GPU will have (issue 24 §2): every registered technique is created and draws a
//! frame of every canonical scene on a device that requests only `wgpu::Limits::default()`
//! (what WebGPU guarantees on any GPU), with no validation error, and its picture is the one
//! it draws under the adapter's own (lavapipe's generous) limits. (Checked that it can fail:
//! under `Limits::downlevel_webgl2_defaults()`, which has no storage buffers, bakay and
//! jahrmann are refused naming the limit and boulanger and perbet fail with a validation
//! error, on every scene.)

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use grassbench::GpuContext;
use grassbench::gpu::BackendChoice;
use grassbench_tests::{TEST_SIZE, gpu, scene};

/// The test suite's density: a quarter of the scenes' blades (software rasteriser).
const DENSITY: f32 = 0.25;
/// The frame drawn.
const FRAME: u64 = 10;

#[test]
fn every_technique_runs_under_the_default_limits() -> anyhow::Result<()> {
    let generous = gpu()?;
    let strict = GpuContext::with_limits(
        BackendChoice::from_env()?,
        Some(grassbench::wgpu::Limits::default()),
    )?;
    let mut failures = Vec::new();
    for name in ["meadow", "football_field", "prairie_flyover"] {
        let scene = scene(name, DENSITY)?;
        for entry in grassbench_cli::registry::TECHNIQUES {
            let id = entry.info.id;
            let table = toml::Table::new();
            let under_default =
                grassbench::compare::render(&strict, &scene, entry, &table, FRAME, TEST_SIZE);
            match under_default {
                Err(e) => failures.push(format!("{id} on {name}: {e:#}")),
                Ok(image) => {
                    let reference = grassbench::compare::render(
                        &generous, &scene, entry, &table, FRAME, TEST_SIZE,
                    )?;
                    if image != reference {
                        failures.push(format!(
                            "{id} on {name}: another picture under the default limits"
                        ));
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    Ok(())
}

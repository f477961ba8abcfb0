//! GPU memory estimates (`TechniqueEntry::estimate`, checked by the harness before a technique
//! is created) against what every technique reports holding once created.

use grassbench::runner::Harness;
use grassbench_tests::{TEST_SIZE, gpu, scene};

#[test]
fn estimates_bound_what_techniques_hold() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let mut failures = Vec::new();
    for name in ["meadow", "football_field", "prairie_flyover"] {
        let scene = scene(name, 0.25)?;
        for entry in grassbench_cli::registry::TECHNIQUES {
            let id = entry.info.id;
            let params = scene.technique_overrides(id);
            let estimate = entry.estimate(&scene, &params)?;
            let harness = Harness::new(&gpu, scene.clone(), TEST_SIZE, false)?;
            let technique = harness.create(entry, &toml::Table::new())?;
            let held = technique.stats().gpu_bytes;
            let ratio = estimate.bytes as f64 / held.max(1) as f64;
            eprintln!(
                "measured: {id} on {name}: estimate {} B, holds {held} B (x{ratio:.2}), largest buffer {} B",
                estimate.bytes, estimate.largest_buffer
            );
            // Never under what is held; at most 3x over it. The largest overestimate measured
            // is the reference's and zhang's (one blade per candidate where the density map
            // thins them: x1.8 on the prairie); the others are within a few percent.
            if !(1.0..=3.0).contains(&ratio) {
                failures.push(format!(
                    "{id} on {name}: estimate {} B against {held} B held",
                    estimate.bytes
                ));
            }
            if estimate.largest_buffer > estimate.bytes {
                failures.push(format!("{id} on {name}: largest buffer above the total"));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    Ok(())
}

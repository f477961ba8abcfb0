//! The host probe: known work timed around every measured run, so each run carries a reading
//! of the host's speed (`host_probe_ms` in runs.csv).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::cell::Cell;

use grassbench::calibration::HostProbe;
use grassbench::runner::{self, Harness, RunOptions};
use grassbench_tests::{TEST_SIZE, gpu, scene};

/// The runner times the probe exactly twice, before the first measured frame and after the
/// last, and records the median of everything it returned; without a probe the column stays
/// empty. A stand-in probe returns known times, so the arithmetic is checked, not the host.
#[test]
fn a_run_records_the_median_of_its_probes_taken_at_both_ends() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let mut harness = Harness::new(&gpu, scene("meadow", 0.01)?, TEST_SIZE, false)?;
    let entry = grassbench_cli::registry::find("reference")?;
    let mut technique = harness.create(entry, &toml::Table::new())?;
    let calls = Cell::new(0u32);
    // Frames counted when the probe is called: the first call must come after the warm-up.
    let frames_seen = Cell::new(Vec::new());
    let frames_done = Cell::new(0u64);
    let probe = || -> grassbench::Result<Vec<f64>> {
        calls.set(calls.get() + 1);
        let mut seen = frames_seen.take();
        seen.push(frames_done.get());
        frames_seen.set(seen);
        // Before: 1, 2, 9 ms; after: 3, 4, 5 ms. The median of the six is 3.5.
        Ok(if calls.get() == 1 {
            vec![1.0, 2.0, 9.0]
        } else {
            vec![3.0, 4.0, 5.0]
        })
    };
    let options = RunOptions {
        warmup: 2,
        frames: 3,
        capture: Vec::new(),
        run_id: "probe".into(),
        probe: Some(&probe),
    };
    let result = runner::run(
        &mut harness,
        technique.as_mut(),
        &options,
        &mut |done, _| frames_done.set(done),
    )?;
    assert_eq!(calls.get(), 2);
    assert_eq!(
        frames_seen.take(),
        vec![2, 5],
        "after the warm-up, after the last frame"
    );
    assert_eq!(result.summary.host_probe_ms, Some(3.5));
    assert_eq!(result.frames.len(), 3);

    let unprobed = RunOptions {
        probe: None,
        ..options
    };
    let result = runner::run(&mut harness, technique.as_mut(), &unprobed, &mut |_, _| {})?;
    assert_eq!(result.summary.host_probe_ms, None);
    Ok(())
}

/// The probe itself builds, validates and times its draw: three submissions, each a finite
/// positive time. The times are not held to a figure: the host's speed is what the probe
/// reads.
#[test]
fn the_probe_times_a_real_draw() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let probe = HostProbe::new(&gpu)?;
    let once = probe.sample()?;
    assert_eq!(once.len(), grassbench::calibration::PROBE_SUBMISSIONS);
    assert!(once.iter().all(|t| t.is_finite() && *t > 0.0), "{once:?}");
    Ok(())
}

//! `scripts/gpu-run.sh` (issue 24 §4), the one command for a machine with a GPU and no
//! toolchain, run end to end here at toy sizes: every step writes its folder under the
//! adapter's name, and a missing binary is refused with the fix.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::{Path, PathBuf};
use std::process::Command;

fn script() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scripts/gpu-run.sh")
}

/// Rows of `path` whose `column` equals `value`.
fn rows_with(path: &Path, column: &str, value: &str) -> usize {
    let mut r = csv::Reader::from_path(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let k = r
        .headers()
        .unwrap()
        .iter()
        .position(|h| h == column)
        .unwrap();
    r.records()
        .filter(|x| x.as_ref().unwrap().get(k) == Some(value))
        .count()
}

#[test]
fn gpu_run_script_measures_every_step_into_the_adapters_folder() {
    let out = std::env::temp_dir().join(format!("grassbench-gpu-run-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let status = Command::new("bash")
        .arg(script())
        .env("GRASSBENCH", env!("CARGO_BIN_EXE_grassbench"))
        .env("GPU_RUN_SIZES", "96x54 128x72")
        .env("GPU_RUN_FRAMES", "2")
        .env("GPU_RUN_SCENES", "meadow")
        .env("GPU_RUN_MOTION", "2")
        .env(
            "GPU_RUN_SWEEPS",
            "experiments/tests/fixtures/smoke_sweep.toml",
        )
        .env("GPU_RUN_OUT", &out)
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&status.stdout);
    assert!(
        status.status.success(),
        "{log}\n{}",
        String::from_utf8_lossy(&status.stderr)
    );
    for size in ["96x54", "128x72"] {
        let calibration = std::fs::read_to_string(out.join(format!("calibration_{size}.toml")))
            .unwrap_or_else(|e| panic!("calibration at {size}: {e}\n{log}"));
        assert!(calibration.contains("[unit_costs]"), "{calibration}");
        // With the vertex stage's texel loads priced.
        assert!(
            calibration.contains("[unit_costs.vertex_float_texture_load_ns]")
                && calibration.contains("workload = \"vertex_float_texture_loads\""),
            "{calibration}"
        );
        let runs = out.join(format!("default_{size}/runs.csv"));
        for id in grassbench_cli::registry::ids() {
            assert_eq!(rows_with(&runs, "technique", id), 1, "{id} at {size}");
        }
        let meta = std::fs::read_to_string(out.join(format!("default_{size}/meta.toml"))).unwrap();
        assert!(
            meta.contains("[adapter]") && meta.contains("command"),
            "{meta}"
        );
    }
    assert!(out.join("compare/meadow/temporal.csv").exists(), "{log}");
    assert!(
        out.join("smoke_sweep/runs.csv").exists() && out.join("smoke_sweep/REPORT.md").exists()
    );
    let written = std::fs::read_to_string(out.join("gpu-run.log")).unwrap();
    assert!(
        written.contains("status 0") && !written.contains("FAILED"),
        "{written}"
    );
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn gpu_run_script_without_a_binary_names_the_fix() {
    let status = Command::new("bash")
        .arg(script())
        .env("GRASSBENCH", "/nonexistent/grassbench")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&status.stderr);
    assert_eq!(status.status.code(), Some(2), "{err}");
    assert!(
        err.contains("no grassbench binary") && err.contains("GRASSBENCH"),
        "{err}"
    );
}

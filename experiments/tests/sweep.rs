//! Sweeps end to end: a tiny sweep runs; an interrupted sweep resumes to exactly the rows of an
//! uninterrupted one; shards merge into the unsharded run set; reports are generated.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

const SMOKE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/smoke_sweep.toml"
);

fn temp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("grassbench-sweep-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn grassbench(args: &[&str]) -> (bool, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_grassbench"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Column `name` of every row of a CSV file.
fn column(path: &Path, name: &str) -> Vec<String> {
    let mut r = csv::Reader::from_path(path).unwrap();
    let k = r.headers().unwrap().iter().position(|h| h == name).unwrap();
    r.records()
        .map(|x| x.unwrap().get(k).unwrap().to_owned())
        .collect()
}

/// Run id → number of rows, for a CSV file.
fn counts(path: &Path) -> BTreeMap<String, usize> {
    let mut m = BTreeMap::new();
    for id in column(path, "run_id") {
        *m.entry(id).or_default() += 1;
    }
    m
}

#[test]
fn tiny_sweep_runs_and_reports() {
    let out = temp("full");
    let (ok, err) = grassbench(&["sweep", SMOKE, "-o", out.to_str().unwrap()]);
    assert!(ok, "{err}");
    let runs = counts(&out.join("runs.csv"));
    // 2 repetitions x 2 scenes x reference with 2 segment counts (+ other techniques' 1 each).
    let techniques = grassbench_cli::registry::ids().len();
    assert_eq!(runs.len(), 2 * 2 * (2 + techniques - 1), "{runs:?}");
    assert!(runs.values().all(|&n| n == 1));
    let frames = counts(&out.join("frames.csv"));
    assert_eq!(
        frames.keys().collect::<Vec<_>>(),
        runs.keys().collect::<Vec<_>>()
    );
    assert!(
        frames.values().all(|&n| n == 2),
        "2 measured frames per run: {frames:?}"
    );
    assert!(
        column(&out.join("runs.csv"), "status")
            .iter()
            .all(|s| s == "ok")
    );
    let ratio = column(&out.join("runs.csv"), "gpu_wall_ratio_to_reference");
    assert!(
        ratio.iter().all(|r| !r.is_empty()),
        "every run has a reference in its group"
    );
    // Every speed-up has its 95 % bootstrap interval, which holds it (the reference's row
    // has none: its speed-up is 1 by definition).
    let runs_csv = out.join("runs.csv");
    let techniques_col = column(&runs_csv, "technique");
    let number = |name: &str| -> Vec<Option<f64>> {
        column(&runs_csv, name)
            .iter()
            .map(|v| v.parse::<f64>().ok())
            .collect()
    };
    let (speedup, low, high) = (
        number("speedup"),
        number("speedup_ci_low"),
        number("speedup_ci_high"),
    );
    for (k, technique) in techniques_col.iter().enumerate() {
        if technique == "reference" {
            assert_eq!((speedup[k], low[k], high[k]), (Some(1.0), None, None));
        } else {
            let (s, lo, hi) = (speedup[k].unwrap(), low[k].unwrap(), high[k].unwrap());
            assert!(lo <= s && s <= hi && lo > 0.0, "{technique}: {lo} {s} {hi}");
        }
    }
    // The cost model's prediction beside every measured time where the adapter counts the
    // work (lavapipe does; GL has no pipeline statistics, and then the model stays empty
    // rather than predicting from no work).
    let meta = std::fs::read_to_string(out.join("meta.toml")).unwrap();
    let counted = meta.contains("pipeline_statistics = true");
    let (model, model_ratio) = (number("model_ms"), number("model_ratio"));
    for k in 0..techniques_col.len() {
        if counted {
            let (m, r) = (model[k].unwrap(), model_ratio[k].unwrap());
            assert!(
                m > 0.0 && r > 0.0,
                "{}: model {m} ratio {r}",
                techniques_col[k]
            );
        } else {
            assert_eq!(
                (model[k], model_ratio[k]),
                (None, None),
                "{}",
                techniques_col[k]
            );
        }
    }
    assert!(
        meta.contains("[calibration]")
            && meta.contains("triangles_per_s")
            && meta.contains("[[unit_costs]]")
            && meta.contains("fragment_alpha_tested_ns")
            && meta.contains("sweep_file"),
        "{meta}"
    );

    let (ok, err) = grassbench(&["report", out.to_str().unwrap()]);
    assert!(ok, "{err}");
    let report = std::fs::read_to_string(out.join("REPORT.md")).unwrap();
    assert!(
        report.contains("| meadow |")
            && report.contains("Unit costs of this adapter")
            && report.contains("reference")
            && report.contains("**Which is faster.**")
            && report.contains("plots/frame_time.svg"),
        "{report}"
    );
    assert!(out.join("plots/frame_time.svg").exists() && out.join("plots/pareto.svg").exists());
    assert_eq!(
        report.contains("## Where the time goes") && out.join("plots/time_split.svg").exists(),
        counted,
        "{report}"
    );
    // The reference's cost per blade against the calibration's raw rate (issue 20 §6).
    assert!(
        report.contains("## The reference against the raw blade rate")
            && report.contains("share of raw rate"),
        "{report}"
    );
    // The unit costs fitted again after the runs, for the same targets, and every run with
    // counted work priced with both (issue 20 §3: how far the host moved while they ran).
    let table: toml::Table = toml::from_str(&meta).unwrap();
    let sizes = |key: &str| -> Vec<(String, bool)> {
        let costs: Vec<grassbench::cost::UnitCosts> = table[key].clone().try_into().unwrap();
        costs.into_iter().map(|c| (c.size, c.msaa)).collect()
    };
    assert_eq!(sizes("unit_costs_after"), sizes("unit_costs"));
    // The raw limits measured again with them, at the same size, and the reference's share
    // read against both (issue 20 §6).
    let raw = |key: &str| -> grassbench::calibration::Calibration {
        table[key].clone().try_into().unwrap()
    };
    let (before, after) = (raw("calibration"), raw("calibration_after"));
    assert!(
        after.size == before.size && after.raw_blade_cost_ns > 0.0,
        "{after:?}"
    );
    assert!(report.contains("share of raw rate after"), "{report}");
    if counted {
        let section = report
            .split("## The calibration after the runs")
            .nth(1)
            .unwrap_or_else(|| panic!("no calibration after the runs in {report}"));
        let priced = section
            .lines()
            .filter(|l| l.starts_with("| meadow") || l.starts_with("| football"))
            .count();
        assert_eq!(
            priced,
            runs.len() / 2,
            "one row per configuration: {section}"
        );
        assert!(
            section.contains(&format!("of {priced} runs within ±25 %")),
            "{section}"
        );
    }
    // Projected onto the adapter this sweep calibrated (its own meta.toml), every run's
    // predicted time is its model_ms: the same work, the same costs (where work was counted).
    if counted {
        let meta_path = out.join("meta.toml");
        let (ok, err) = grassbench(&[
            "report",
            out.to_str().unwrap(),
            "--calibration",
            meta_path.to_str().unwrap(),
        ]);
        assert!(ok, "{err}");
        let report = std::fs::read_to_string(out.join("REPORT.md")).unwrap();
        let section = report
            .split("## Predicted on ")
            .nth(1)
            .unwrap_or_else(|| panic!("no projection in {report}"));
        let predicted: Vec<f64> = section
            .lines()
            .filter(|l| l.starts_with("| meadow") || l.starts_with("| football"))
            .map(|l| l.split('|').nth(6).unwrap().trim().parse().unwrap())
            .collect();
        let expected: Vec<f64> = model.iter().map(|m| m.unwrap()).collect();
        // One row per configuration, which pools two repetitions; its work is its last
        // repetition's, so its prediction is that run's model_ms (to the table's rounding).
        assert_eq!(2 * predicted.len(), expected.len(), "{section}");
        for p in &predicted {
            assert!(
                expected.iter().any(|e| (e - p).abs() <= 0.01 + 1e-3 * e),
                "predicted {p} is no run's model_ms {expected:?}"
            );
        }
        // Its runs.csv beside it: the projection is checked against what was measured
        // there, here the same runs, so each row's predicted / measured there is its
        // predicted over its measured time here.
        assert!(
            section.contains("**Checked against what was measured there**"),
            "{section}"
        );
        for l in section
            .lines()
            .filter(|l| l.starts_with("| meadow") || l.starts_with("| football"))
        {
            let cell = |k: usize| -> f64 { l.split('|').nth(k).unwrap().trim().parse().unwrap() };
            let (here, predicted, there, ratio) = (cell(5), cell(6), cell(7), cell(8));
            assert_eq!(here, there, "{l}");
            // The table rounds times to 0.1 ms and predictions to 0.01 ms: allow for both.
            let tolerance = 0.01 + ratio * (0.05 / there + 0.005 / predicted);
            assert!((ratio - predicted / there).abs() <= tolerance, "{l}");
        }
    }
    // A file without unit costs is refused, naming the fix.
    let (ok, err) = grassbench(&[
        "report",
        out.to_str().unwrap(),
        "--calibration",
        out.join("runs.csv").to_str().unwrap(),
    ]);
    assert!(
        !ok && (err.contains("not TOML") || err.contains("no unit costs")),
        "{err}"
    );

    // Running the finished sweep again does nothing and changes nothing.
    let before = std::fs::read(out.join("runs.csv")).unwrap();
    let (ok, err) = grassbench(&[
        "sweep",
        SMOKE,
        "-o",
        out.to_str().unwrap(),
        "--no-calibration",
    ]);
    assert!(ok && err.contains("0 to run"), "{err}");
    assert_eq!(before, std::fs::read(out.join("runs.csv")).unwrap());
    std::fs::remove_dir_all(&out).unwrap();
}

/// How a running sweep is stopped.
#[derive(Clone, Copy)]
enum Stop {
    /// SIGKILL: no chance to clean up.
    Kill,
    /// SIGINT, as Ctrl-C sends it.
    Interrupt,
}

#[test]
fn killed_sweep_resumes_to_the_same_rows() {
    stopped_sweep_resumes_to_the_same_rows(Stop::Kill, "killed");
}

#[test]
fn interrupted_sweep_resumes_to_the_same_rows() {
    stopped_sweep_resumes_to_the_same_rows(Stop::Interrupt, "interrupted");
}

fn stopped_sweep_resumes_to_the_same_rows(stop: Stop, name: &str) {
    let full = temp(&format!("uninterrupted-{name}"));
    assert!(
        grassbench(&[
            "sweep",
            SMOKE,
            "-o",
            full.to_str().unwrap(),
            "--no-calibration"
        ])
        .0
    );
    let expected = counts(&full.join("runs.csv"));

    let out = temp(name);
    let bin = env!("CARGO_BIN_EXE_grassbench");
    let args = [
        "sweep",
        SMOKE,
        "-o",
        out.to_str().unwrap(),
        "--no-calibration",
    ];
    let mut command = match stop {
        Stop::Kill => Command::new(bin),
        // A job started in the background of a non-interactive shell (as CI may start this
        // suite) inherits SIGINT ignored, and so would the sweep; Ctrl-C reaches a program
        // with the default disposition, so the sweep is started as a terminal would start
        // it: perl (Debian's essential perl-base) restores the default and execs it, keeping
        // the pid the signal is sent to.
        Stop::Interrupt => {
            let mut c = Command::new("perl");
            c.args([
                "-e",
                "$SIG{INT} = 'DEFAULT'; exec @ARGV or die \"exec: $!\"",
                bin,
            ]);
            c
        }
    };
    let mut child = command.args(args).stderr(Stdio::null()).spawn().unwrap();
    // Stop it once a few runs are recorded.
    let runs = out.join("runs.csv");
    let start = std::time::Instant::now();
    loop {
        let rows = std::fs::read_to_string(&runs)
            .map(|t| t.lines().count())
            .unwrap_or(0);
        if rows >= 3 || start.elapsed().as_secs() > 120 {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    match stop {
        Stop::Kill => child.kill().unwrap(),
        Stop::Interrupt => {
            // The shell's built-in kill: a fresh machine may have no kill program.
            let sent = Command::new("sh")
                .args(["-c", &format!("kill -INT {}", child.id())])
                .status()
                .unwrap();
            assert!(sent.success(), "kill -INT failed");
        }
    }
    let status = child.wait().unwrap();
    assert!(!status.success(), "a stopped sweep must not report success");
    let partial = counts(&runs);
    assert!(
        partial.len() < expected.len(),
        "the sweep finished before it could be stopped"
    );
    // A crash in the middle of an append leaves a torn line: simulate one.
    std::fs::OpenOptions::new()
        .append(true)
        .open(out.join("frames.csv"))
        .and_then(|mut f| std::io::Write::write_all(&mut f, b"torn,row,with"))
        .unwrap();

    let (ok, err) = grassbench(&[
        "sweep",
        SMOKE,
        "-o",
        out.to_str().unwrap(),
        "--no-calibration",
    ]);
    assert!(ok, "{err}");
    assert_eq!(
        counts(&runs),
        expected,
        "resumed sweep has other runs than an uninterrupted one"
    );
    let frames = counts(&out.join("frames.csv"));
    assert_eq!(
        frames,
        counts(&full.join("frames.csv")),
        "frames lost or duplicated"
    );
    let params = counts(&out.join("params.csv"));
    assert_eq!(params, counts(&full.join("params.csv")));
    std::fs::remove_dir_all(&out).unwrap();
    std::fs::remove_dir_all(&full).unwrap();
}

#[test]
fn shards_merge_into_the_whole_sweep_and_mixing_is_refused() {
    let whole = temp("whole");
    assert!(
        grassbench(&[
            "sweep",
            SMOKE,
            "-o",
            whole.to_str().unwrap(),
            "--no-calibration"
        ])
        .0
    );
    // Three shards under GNU parallel, each the README's Slurm array task
    // (experiments/slurm/job.sh) with the task id parallel hands it.
    let shards: Vec<PathBuf> = (0..3).map(|i| temp(&format!("shard-{i}"))).collect();
    let merged = temp("merged");
    let prefix = temp("shard");
    let job = Path::new(env!("CARGO_MANIFEST_DIR")).join("slurm/job.sh");
    let status = Command::new("parallel")
        .env("GRASSBENCH", env!("CARGO_BIN_EXE_grassbench"))
        .env("SLURM_ARRAY_TASK_COUNT", "3")
        .args([
            "-j3",
            "--halt",
            "now,fail=1",
            &format!(
                "SLURM_ARRAY_TASK_ID={{}} bash {} {SMOKE} {} --no-calibration",
                job.display(),
                prefix.display()
            ),
            ":::",
            "0",
            "1",
            "2",
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .expect("GNU parallel is missing: install package `parallel` (`make setup` does)");
    assert!(status.success(), "a shard failed under parallel");
    for s in &shards {
        assert!(
            !counts(&s.join("runs.csv")).is_empty(),
            "{} ran nothing",
            s.display()
        );
    }
    let mut args = vec!["merge".to_owned()];
    args.extend(shards.iter().map(|s| s.to_str().unwrap().to_owned()));
    args.extend(["-o".to_owned(), merged.to_str().unwrap().to_owned()]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (ok, err) = grassbench(&args);
    assert!(ok, "{err}");
    // The same runs and frames as the unsharded sweep ...
    assert_eq!(
        counts(&merged.join("runs.csv")),
        counts(&whole.join("runs.csv"))
    );
    assert_eq!(
        counts(&merged.join("frames.csv")),
        counts(&whole.join("frames.csv"))
    );
    // ... with every comparison kept: whole groups were dealt out, so each technique ran
    // beside its group's reference; FLIP against it is the same to the bit (rendering is
    // deterministic), and a ratio exists wherever the unsharded sweep has one.
    let by_id = |dir: &Path, name: &str| -> BTreeMap<String, String> {
        column(&dir.join("runs.csv"), "run_id")
            .into_iter()
            .zip(column(&dir.join("runs.csv"), name))
            .collect()
    };
    assert_eq!(
        by_id(&merged, "flip_vs_reference"),
        by_id(&whole, "flip_vs_reference")
    );
    let present = |m: BTreeMap<String, String>| -> BTreeMap<String, bool> {
        m.into_iter().map(|(k, v)| (k, !v.is_empty())).collect()
    };
    let ratios = present(by_id(&merged, "gpu_wall_ratio_to_reference"));
    assert_eq!(
        ratios,
        present(by_id(&whole, "gpu_wall_ratio_to_reference"))
    );
    assert!(ratios.values().all(|&r| r), "{ratios:?}");
    let images = |dir: &Path| {
        let mut v: Vec<String> = std::fs::read_dir(dir.join("images"))
            .map(|d| {
                d.map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                    .collect()
            })
            .unwrap_or_default();
        v.sort();
        v
    };
    assert_eq!(images(&merged), images(&whole));
    let a = shards[0].clone();

    // A shard of another sweep is refused.
    let other = temp("other");
    let spec = std::fs::read_to_string(SMOKE)
        .unwrap()
        .replace("frames = 2", "frames = 1");
    let other_file = other.with_extension("toml");
    std::fs::write(&other_file, spec).unwrap();
    assert!(
        grassbench(&[
            "sweep",
            other_file.to_str().unwrap(),
            "-o",
            other.to_str().unwrap(),
            "--no-calibration"
        ])
        .0
    );
    let (ok, err) = grassbench(&[
        "merge",
        a.to_str().unwrap(),
        other.to_str().unwrap(),
        "-o",
        temp("bad").to_str().unwrap(),
    ]);
    assert!(!ok && err.contains("another sweep"), "{err}");
    // And a results folder is never silently reused for another sweep.
    let (ok, err) = grassbench(&[
        "sweep",
        other_file.to_str().unwrap(),
        "-o",
        a.to_str().unwrap(),
        "--no-calibration",
    ]);
    assert!(!ok && err.contains("--force"), "{err}");
    for d in shards.into_iter().chain([whole, merged, other]) {
        std::fs::remove_dir_all(d).unwrap();
    }
    std::fs::remove_file(other_file).unwrap();
}

#[test]
fn report_on_a_fixture_writes_tables_and_plots() {
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/report");
    let out = temp("report");
    std::fs::create_dir_all(&out).unwrap();
    for f in ["runs.csv", "meta.toml"] {
        std::fs::copy(fixture.join(f), out.join(f)).unwrap();
    }
    let (ok, err) = grassbench(&["report", out.to_str().unwrap()]);
    assert!(ok, "{err}");
    let report = std::fs::read_to_string(out.join("REPORT.md")).unwrap();
    for needle in [
        "# Report: fixture",
        "| football_field |",
        "| bakay |",
        "## CPU and GPU stages",
        "plots/pareto.svg",
        "plots/scaling_blades.svg",
        "llvmpipe",
    ] {
        assert!(
            report.contains(needle),
            "REPORT.md lacks `{needle}`:\n{report}"
        );
    }
    for plot in ["frame_time.svg", "pareto.svg", "scaling_blades.svg"] {
        let svg = std::fs::read_to_string(out.join("plots").join(plot)).unwrap();
        assert!(
            svg.starts_with("<svg") && (svg.contains("<circle") || svg.contains("<rect")),
            "{plot}"
        );
    }
    // A failed run is counted, not plotted.
    assert!(report.contains("| 1 |"), "{report}");
    std::fs::remove_dir_all(&out).unwrap();
}

/// A run written before its group's reference (the reference in another shard, joined by
/// `merge`) has no ratio in runs.csv; the report divides by the group's reference itself.
#[test]
fn report_fills_speed_ups_from_the_group_reference() {
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/report");
    let out = temp("report-ratio");
    std::fs::create_dir_all(&out).unwrap();
    std::fs::copy(fixture.join("meta.toml"), out.join("meta.toml")).unwrap();
    let mut reader = csv::Reader::from_path(fixture.join("runs.csv")).unwrap();
    let headers = reader.headers().unwrap().clone();
    let ratio = headers
        .iter()
        .position(|h| h == "gpu_wall_ratio_to_reference")
        .unwrap();
    let technique = headers.iter().position(|h| h == "technique").unwrap();
    let mut writer = csv::Writer::from_path(out.join("runs.csv")).unwrap();
    writer.write_record(&headers).unwrap();
    for record in reader.records() {
        let record = record.unwrap();
        let blank = &record[technique] != "reference";
        let fields = record
            .iter()
            .enumerate()
            .map(|(k, v)| if blank && k == ratio { "" } else { v });
        writer.write_record(fields).unwrap();
    }
    writer.flush().unwrap();
    let (ok, err) = grassbench(&["report", out.to_str().unwrap()]);
    assert!(ok, "{err}");
    let report = std::fs::read_to_string(out.join("REPORT.md")).unwrap();
    // bakay at density 10: 4 ms against 20, 5 against 21 → 1 / median(0.2, 0.238) = 4.57;
    // at density 40 (its second repetition failed): 5 against 70 → 14.00.
    for row in ["| 4.57 |", "| 14.00 |"] {
        assert!(report.contains(row), "REPORT.md lacks `{row}`:\n{report}");
    }
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn bad_sweep_files_are_refused_with_the_reason() {
    let d = temp("bad");
    std::fs::create_dir_all(&d).unwrap();
    let cases = [
        (
            "name = \"x\"\nscenes = [\"meadow\"]\ntechniques = [\"nope\"]\n",
            "unknown technique `nope`",
        ),
        (
            "name = \"x\"\nscenes = [\"nowhere\"]\n",
            "unknown scene `nowhere`",
        ),
        (
            "name = \"x\"\nscenes = [\"meadow\"]\n[scene_params]\n\"grass.densty\" = [1.0]\n",
            "grass.densty",
        ),
        (
            "name = \"x\"\nscenes = [\"meadow\"]\n[params.reference]\nsegmentz = [1]\n",
            "reference.segmentz",
        ),
        (
            "name = \"x\"\nscenes = [\"meadow\"]\nrepetitions = 0\n",
            "repetitions",
        ),
        ("name = \"x\"\nscenes = [\"meadow\"\n", "line"),
    ];
    for (k, (text, needle)) in cases.iter().enumerate() {
        let f = d.join(format!("bad{k}.toml"));
        std::fs::write(&f, text).unwrap();
        let (ok, err) = grassbench(&[
            "sweep",
            f.to_str().unwrap(),
            "-o",
            d.join(format!("out{k}")).to_str().unwrap(),
            "--no-calibration",
        ]);
        assert!(
            !ok && err.contains(needle) && !err.contains("panicked"),
            "case {k}: {err}"
        );
    }
    assert!(
        !grassbench(&[
            "sweep",
            SMOKE,
            "--shard",
            "2/2",
            "-o",
            d.join("s").to_str().unwrap()
        ])
        .0
    );
    std::fs::remove_dir_all(&d).unwrap();
}

/// A sweep in which every run fails (here: a 1 MiB GPU memory budget refuses the reference's
/// 20 MB of blades on the meadow) records each failure and exits non-zero, naming the file
/// that holds the errors.
#[test]
fn a_sweep_whose_runs_all_fail_exits_non_zero() {
    let out = temp("all-failed");
    std::fs::create_dir_all(&out).unwrap();
    let file = out.with_extension("toml");
    std::fs::write(
        &file,
        "name = \"all_failed\"\nscenes = [\"meadow\"]\ntechniques = [\"reference\"]\n\
         resolutions = [\"320x180\"]\nrepetitions = 2\nwarmup = 0\nframes = 1\n",
    )
    .unwrap();
    let result = Command::new(env!("CARGO_BIN_EXE_grassbench"))
        .args([
            "sweep",
            file.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--force",
            "--no-calibration",
        ])
        .env("GRASSBENCH_GPU_MEMORY_MB", "1")
        .stdout(Stdio::null())
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&result.stderr);
    assert!(!result.status.success(), "exited 0: {err}");
    assert!(
        err.contains("every one of the") && err.contains("runs.csv"),
        "{err}"
    );
    let status = column(&out.join("runs.csv"), "status");
    assert!(
        !status.is_empty() && status.iter().all(|s| s == "failed"),
        "{status:?}"
    );
}

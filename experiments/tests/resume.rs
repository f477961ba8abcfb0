//! `run` and `compare` stopped by Ctrl-C (SIGINT) resume with the same command line: the
//! scenes finished before the signal are kept as they are (not rendered again), the others are
//! redone, and the folder ends with every scene and technique; the same folder with another
//! argument is refused, naming it.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::collections::BTreeMap;
use std::os::unix::process::ExitStatusExt as _;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant, SystemTime};

/// The manifest `run` and `compare` keep in their output folder.
const PROGRESS: &str = ".grassbench-progress.toml";
const SCENES: &str = "meadow,football_field";
const TECHNIQUES: &str = "reference,jahrmann";

fn temp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("grassbench-resume-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn grassbench(args: &[String]) -> (bool, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_grassbench"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Starts grassbench as a terminal would, SIGINT at its default disposition: a job started in
/// the background of a non-interactive shell (as CI may start this suite) inherits SIGINT
/// ignored, so perl restores the default and execs it, keeping the pid the signal goes to.
fn start_interruptible(args: &[String]) -> Child {
    Command::new("perl")
        .args([
            "-e",
            "$SIG{INT} = 'DEFAULT'; exec @ARGV or die \"exec: $!\"",
            env!("CARGO_BIN_EXE_grassbench"),
        ])
        .args(args)
        .stderr(Stdio::null())
        .spawn()
        .unwrap()
}

/// The scenes the manifest in `dir` records as done, and whether it says finished.
fn manifest(dir: &Path) -> (Vec<String>, bool) {
    let Some(table) = std::fs::read_to_string(dir.join(PROGRESS))
        .ok()
        .and_then(|t| toml::from_str::<toml::Table>(&t).ok())
    else {
        return (Vec::new(), false);
    };
    let done = table
        .get("done")
        .and_then(|d| d.as_array())
        .map(|a| {
            a.iter()
                .filter_map(|d| d.get("scene")?.as_str().map(str::to_owned))
                .collect()
        })
        .unwrap_or_default();
    let finished = table
        .get("finished")
        .and_then(toml::Value::as_bool)
        .unwrap_or(false);
    (done, finished)
}

/// Waits until `scene` is done in `dir` (its folder complete), then sends SIGINT as Ctrl-C
/// would, and checks the process died of it with `scene` done and the other scenes not.
fn interrupt_after(mut child: Child, dir: &Path, scene: &str) {
    let start = Instant::now();
    while !manifest(dir).0.iter().any(|s| s == scene) {
        if let Some(status) = child.try_wait().unwrap() {
            panic!("exited ({status}) before `{scene}` was done");
        }
        assert!(
            start.elapsed() < Duration::from_secs(180),
            "`{scene}` not done after 180 s"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
    // The shell's built-in kill: a fresh machine may have no kill program.
    let sent = Command::new("sh")
        .args(["-c", &format!("kill -INT {}", child.id())])
        .status()
        .unwrap();
    assert!(sent.success(), "kill -INT failed");
    let status = child.wait().unwrap();
    assert_eq!(
        status.signal(),
        Some(2),
        "not ended by SIGINT: {status} (finished before the signal?)"
    );
    let (done, finished) = manifest(dir);
    assert_eq!(done, [scene], "stopped too late to test resuming");
    assert!(!finished);
}

/// Every file under `dir` (relative path) with its modification time.
fn mtimes(dir: &Path) -> BTreeMap<PathBuf, SystemTime> {
    let mut m = BTreeMap::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let entry = entry.unwrap();
        let path = entry.path();
        if path.is_dir() {
            for (p, t) in mtimes(&path) {
                m.insert(Path::new(&entry.file_name()).join(p), t);
            }
        } else {
            m.insert(
                entry.file_name().into(),
                entry.metadata().unwrap().modified().unwrap(),
            );
        }
    }
    m
}

/// Column `name` of every row of a CSV file.
fn column(path: &Path, name: &str) -> Vec<String> {
    let mut r = csv::Reader::from_path(path).unwrap();
    let k = r.headers().unwrap().iter().position(|h| h == name).unwrap();
    r.records()
        .map(|x| x.unwrap().get(k).unwrap().to_owned())
        .collect()
}

fn strings(args: &[&str]) -> Vec<String> {
    args.iter().map(|s| (*s).to_owned()).collect()
}

#[test]
fn interrupted_run_resumes_with_the_same_command() {
    let out = temp("run");
    let o = out.to_str().unwrap();
    let args = |frames: &str, out: &str| {
        strings(&[
            "run",
            "-t",
            TECHNIQUES,
            "-s",
            SCENES,
            "--size",
            "160x90",
            "--frames",
            frames,
            "--warmup",
            "1",
            "--no-calibration",
            "-o",
            out,
        ])
    };
    interrupt_after(start_interruptible(&args("2", o)), &out, "meadow");
    let meadow = mtimes(&out.join("meadow"));
    assert!(meadow.contains_key(Path::new("runs.csv")), "{meadow:?}");

    // Another argument on the same folder is refused, naming it; the folder is untouched.
    let (ok, err) = grassbench(&args("3", o));
    assert!(!ok);
    for needle in ["--frames is `2` there, `3` here", "unfinished", "--force"] {
        assert!(err.contains(needle), "lacks `{needle}`: {err}");
    }
    assert_eq!(mtimes(&out.join("meadow")), meadow);

    let (ok, err) = grassbench(&args("2", o));
    assert!(ok, "{err}");
    assert!(
        err.contains("resuming: 1 of 2 scenes already done"),
        "{err}"
    );
    assert!(
        !err.contains("meadow reference"),
        "meadow measured again: {err}"
    );
    assert_eq!(
        mtimes(&out.join("meadow")),
        meadow,
        "the finished scene's files were written again"
    );
    assert!(manifest(&out).1, "not marked finished");

    // The same rows (all but timing) as an uninterrupted run's.
    let full = temp("run-full");
    let (ok, err) = grassbench(&args("2", full.to_str().unwrap()));
    assert!(ok, "{err}");
    for name in [
        "scene",
        "technique",
        "status",
        "blades_drawn",
        "blades_represented",
        "triangles",
        "params",
    ] {
        assert_eq!(
            column(&out.join("runs.csv"), name),
            column(&full.join("runs.csv"), name),
            "runs.csv column {name}"
        );
    }
    let techniques = column(&out.join("runs.csv"), "technique");
    assert_eq!(
        techniques,
        ["reference", "jahrmann", "reference", "jahrmann"]
    );
    let readme = std::fs::read_to_string(out.join("README.md")).unwrap();
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    for scene in ["meadow", "football_field"] {
        for technique in ["reference", "jahrmann"] {
            let image = format!("{scene}/{technique}_frame0002.png");
            assert!(readme.contains(&image), "README.md lacks {image}");
            assert!(out.join(&image).exists(), "{image}");
        }
        assert!(html.contains(scene), "report.html lacks {scene}");
    }
    assert!(out.join("meta.toml").exists());

    // A finished folder is not resumed.
    let (ok, err) = grassbench(&args("2", o));
    assert!(
        !ok && err.contains("finished") && err.contains("--force"),
        "{err}"
    );
    std::fs::remove_dir_all(&out).unwrap();
    std::fs::remove_dir_all(&full).unwrap();
}

#[test]
fn interrupted_compare_resumes_with_the_same_command() {
    let out = temp("compare");
    let o = out.to_str().unwrap();
    let args = |motion_frames: &str| {
        strings(&[
            "compare",
            "-t",
            TECHNIQUES,
            "-s",
            SCENES,
            "--size",
            "160x90",
            "--frame",
            "3",
            "--motion-frames",
            motion_frames,
            "-o",
            o,
        ])
    };
    interrupt_after(start_interruptible(&args("2")), &out, "meadow");
    let meadow = mtimes(&out.join("meadow"));
    assert!(meadow.contains_key(Path::new("temporal.csv")), "{meadow:?}");

    let (ok, err) = grassbench(&args("3"));
    assert!(!ok);
    for needle in [
        "--motion-frames is `2` there, `3` here",
        "unfinished",
        "--force",
    ] {
        assert!(err.contains(needle), "lacks `{needle}`: {err}");
    }

    let (ok, err) = grassbench(&args("2"));
    assert!(ok, "{err}");
    assert!(
        err.contains("resuming: 1 of 2 scenes already done"),
        "{err}"
    );
    assert!(
        !err.contains("meadow: rendering"),
        "meadow rendered again: {err}"
    );
    assert_eq!(
        mtimes(&out.join("meadow")),
        meadow,
        "the finished scene's files were written again"
    );
    assert!(manifest(&out).1, "not marked finished");
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    for scene in ["meadow", "football_field"] {
        let dir = out.join(scene);
        let lod = column(&dir.join("lod.csv"), "technique");
        assert_eq!(lod, ["reference", "jahrmann"], "{scene}/lod.csv");
        let mut temporal = column(&dir.join("temporal.csv"), "technique");
        temporal.sort();
        temporal.dedup();
        assert_eq!(temporal, ["jahrmann", "reference"], "{scene}/temporal.csv");
        assert_eq!(
            column(&dir.join("matrix.csv"), "a").len(),
            1,
            "{scene}/matrix.csv"
        );
        assert!(dir.join("diff_reference_jahrmann.png").exists(), "{scene}");
        assert!(html.contains(scene), "report.html lacks {scene}");
    }
    assert!(out.join("meta.toml").exists());
    std::fs::remove_dir_all(&out).unwrap();
}

//! The `grassbench` binary: bad input gives a clear message and a non-zero exit, never a panic;
//! good input writes what it says.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::Path;
use std::process::Command;

fn grassbench(args: &[&str]) -> (bool, String, String) {
    grassbench_in(Path::new("."), args)
}

/// `grassbench args` run in `dir`.
fn grassbench_in(dir: &Path, args: &[&str]) -> (bool, String, String) {
    grassbench_with(dir, args, &[])
}

/// `grassbench args` run in `dir` with the environment variables `env` set.
fn grassbench_with(dir: &Path, args: &[&str], env: &[(&str, &str)]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_grassbench"))
        .args(args)
        .current_dir(dir)
        .envs(env.iter().copied())
        .output()
        .expect("binary runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn temp(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("grassbench-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs a failing command and checks its message mentions every `needle`, and no panic.
fn fails_with(args: &[&str], needles: &[&str]) {
    let (ok, _, err) = grassbench(args);
    assert!(!ok, "{args:?} succeeded");
    assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: message lacks `{n}`: {err}");
    }
}

/// Every sweep and scene file the project ships validates (`grassbench validate`: parses,
/// expands, every scene variant builds, every parameter is one the technique knows), so a
/// sweep in `experiments/` cannot rot unnoticed until someone spends an hour running it.
#[test]
fn every_shipped_sweep_and_scene_file_validates() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for dir in [
        root.to_path_buf(),
        root.join("scenes"),
        root.join("boulanger_views"),
        root.join("departures"),
    ] {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            if name.ends_with(".toml") && name != "Cargo.toml" {
                files.push(path.to_string_lossy().into_owned());
            }
        }
    }
    assert!(files.len() >= 10, "{files:?}");
    // From the repository's root, as the README runs them (sweeps name scene files by their
    // path from there).
    let mut args = vec!["validate"];
    args.extend(files.iter().map(String::as_str));
    let (ok, _, err) = grassbench_in(root.parent().unwrap(), &args);
    assert!(ok, "{err}");
    assert!(err.contains("sweep `zhang_target`"), "{err}");
    assert!(err.contains("sweep `departures_zhang`"), "{err}");
}

#[test]
fn list_shows_techniques_and_scenes() {
    let (ok, out, _) = grassbench(&["list"]);
    assert!(ok);
    for name in [
        "reference",
        "segments",
        "meadow",
        "football_field",
        "prairie_flyover",
    ] {
        assert!(out.contains(name), "missing {name}: {out}");
    }
}

#[test]
fn bad_names_list_valid_ones() {
    fails_with(
        &["render", "-t", "nope", "-o", "/tmp/x.png"],
        &["unknown technique `nope`", "reference"],
    );
    fails_with(
        &[
            "render",
            "-t",
            "reference",
            "-s",
            "nowhere",
            "-o",
            "/tmp/x.png",
        ],
        &["unknown scene `nowhere`", "meadow"],
    );
    fails_with(
        &[
            "render",
            "-t",
            "reference",
            "--backend",
            "glide",
            "-o",
            "/tmp/x.png",
        ],
        &["unknown backend `glide`", "vulkan"],
    );
}

#[test]
fn bad_sizes_and_params_are_refused_before_gpu_work() {
    fails_with(
        &[
            "render",
            "-t",
            "reference",
            "--size",
            "100000x100000",
            "-o",
            "/tmp/x.png",
        ],
        &["resolution.width"],
    );
    fails_with(
        &[
            "render",
            "-t",
            "reference",
            "--size",
            "0x10",
            "-o",
            "/tmp/x.png",
        ],
        &["resolution.width"],
    );
    fails_with(
        &[
            "render",
            "-t",
            "reference",
            "--size",
            "big",
            "-o",
            "/tmp/x.png",
        ],
        &["WIDTHxHEIGHT"],
    );
    fails_with(
        &[
            "render",
            "-t",
            "reference",
            "-p",
            "segmentz=3",
            "--size",
            "32x32",
            "-o",
            "/tmp/x.png",
        ],
        &["reference.segmentz", "reference.segments"],
    );
    fails_with(
        &[
            "render",
            "-t",
            "reference",
            "-p",
            "segments=1000000",
            "--size",
            "32x32",
            "-o",
            "/tmp/x.png",
        ],
        &["reference.segments"],
    );
    fails_with(
        &[
            "render",
            "-t",
            "reference",
            "-p",
            "wind_response=nan",
            "--size",
            "32x32",
            "-o",
            "/tmp/x.png",
        ],
        &["reference.wind_response"],
    );
}

#[test]
fn bad_scene_files_name_file_and_problem() {
    let d = temp("scenes");
    let malformed = d.join("malformed.toml");
    std::fs::write(&malformed, "name = \"x\"\n[terrain\nsize = 3").unwrap();
    fails_with(
        &[
            "render",
            "-t",
            "reference",
            "-s",
            malformed.to_str().unwrap(),
            "-o",
            "/tmp/x.png",
        ],
        &["malformed.toml", "line"],
    );
    let absurd = d.join("absurd.toml");
    std::fs::write(
        &absurd,
        "name = \"absurd\"\n[terrain]\nsize = [1000.0, 1000.0]\n[grass]\ndensity = 5e4\n[camera.path]\nkind = \"fixed\"\neye = [0.0, 2.0, 0.0]\nlook_at = [1.0, 0.0, 0.0]\n",
    )
    .unwrap();
    fails_with(
        &[
            "render",
            "-t",
            "reference",
            "-s",
            absurd.to_str().unwrap(),
            "-o",
            "/tmp/x.png",
        ],
        &["absurd.toml", "grass.density", "blades"],
    );
    let wrong_map = d.join("map.toml");
    std::fs::write(d.join("rgb.png"), []).unwrap();
    std::fs::write(
        &wrong_map,
        "name = \"map\"\n[terrain]\nsize = [10.0, 10.0]\nheight = { kind = \"png\", path = \"rgb.png\" }\n[camera.path]\nkind = \"fixed\"\neye = [0.0, 2.0, 0.0]\nlook_at = [1.0, 0.0, 0.0]\n",
    )
    .unwrap();
    fails_with(
        &[
            "render",
            "-t",
            "reference",
            "-s",
            wrong_map.to_str().unwrap(),
            "-o",
            "/tmp/x.png",
        ],
        &["rgb.png", "PNG"],
    );
}

#[test]
fn run_writes_csv_images_and_meta_and_refuses_to_overwrite() {
    let d = temp("run");
    let out = d.join("out");
    let out_s = out.to_str().unwrap();
    // `-p` applies to every technique run, and `segments` is a reference parameter: with more
    // than one technique registered, `-t all` would (rightly) refuse it for the others.
    let args = [
        "run",
        "-t",
        "reference",
        "-s",
        "football_field",
        "--frames",
        "2",
        "--warmup",
        "1",
        "--size",
        "96x64",
        "-p",
        "segments=3",
        "-o",
        out_s,
    ];
    let (ok, _, err) = grassbench(&args);
    assert!(ok, "{err}");
    for f in [
        "meta.toml",
        "runs.csv",
        "README.md",
        "report.html",
        "football_field/frames.csv",
        "football_field/runs.csv",
        "football_field/params.csv",
        "football_field/images.csv",
        "football_field/reference_frame0001.png",
        "football_field/none_frame0002.png",
    ] {
        assert!(out.join(f).exists(), "missing {f}");
    }
    let frames = std::fs::read_to_string(out.join("football_field/frames.csv")).unwrap();
    // A header, then the 2 measured frames of the one technique run.
    assert_eq!(frames.lines().count(), 1 + 2, "{frames}");
    let header = frames.lines().next().unwrap();
    assert!(
        header.contains("gpu_wall_ms") && header.ends_with(",counters"),
        "{header}"
    );
    let meta = std::fs::read_to_string(out.join("meta.toml")).unwrap();
    assert!(
        meta.contains("revision") && meta.contains("[adapter]"),
        "{meta}"
    );
    // The adapter's raw limits, measured before its unit costs as a sweep measures them (a
    // process's first primitive-heavy submissions find lavapipe slow: `calibrate::adapter_at`),
    // and recorded with them at the run's size.
    let table: toml::Table = toml::from_str(&meta).unwrap();
    // The revision the binary was built from, beside the tree's it ran in: the same commit
    // here (the test's build is of this tree), `+dirty` on either side as the tree was then.
    let commit = |key: &str| {
        let revision = table[key].as_str().unwrap_or_default();
        revision.trim_end_matches("+dirty").to_owned()
    };
    assert!(!commit("build_revision").is_empty(), "{meta}");
    assert_eq!(commit("build_revision"), commit("revision"), "{meta}");
    let raw: grassbench::calibration::Calibration =
        table["calibration"].clone().try_into().unwrap();
    assert_eq!(raw.size, "96x64");
    assert!(raw.raw_blade_cost_ns > 0.0, "{raw:?}");
    let costs: Vec<grassbench::cost::UnitCosts> = table["unit_costs"].clone().try_into().unwrap();
    assert_eq!(costs.len(), 1);
    assert_eq!(costs[0].size, "96x64");
    // Fitted again once the runs were done, at the same size, and the README sets the runs
    // against both fits.
    let after: Vec<grassbench::cost::UnitCosts> =
        table["unit_costs_after"].clone().try_into().unwrap();
    assert_eq!(
        after.iter().map(|c| (&c.size, c.msaa)).collect::<Vec<_>>(),
        [(&"96x64".to_owned(), false)]
    );
    // The raw limits measured again with them, at the same size.
    let raw_after: grassbench::calibration::Calibration =
        table["calibration_after"].clone().try_into().unwrap();
    assert!(
        raw_after.size == "96x64" && raw_after.raw_blade_cost_ns > 0.0,
        "{raw_after:?}"
    );
    // With the calibration's coverage checks, priced, in meta.toml and the README.
    assert_eq!(
        costs[0].checks.len(),
        grassbench::cost::checks::coverage_checks().len()
    );
    let (raw_at, costs_at) = (
        err.find("triangles/s").expect("the raw limits printed"),
        err.find("unit costs of").expect("the unit costs printed"),
    );
    assert!(raw_at < costs_at, "{err}");
    // The command names the program, not the path it was started from.
    assert!(
        meta.contains("command = \"grassbench run -t reference -s football_field "),
        "{meta}"
    );
    let readme = std::fs::read_to_string(out.join("README.md")).unwrap();
    assert!(
        readme.contains("Command: `grassbench run -t reference -s football_field ")
            && readme.contains("Measured on `")
            && !readme.contains(env!("CARGO_BIN_EXE_grassbench"))
            && readme.contains("Coverage checks of the calibration at 96x64")
            && readme.contains("The unit costs were fitted again after the runs")
            && readme.contains("| hidden_alpha_tested |"),
        "{readme}"
    );
    let params = std::fs::read_to_string(out.join("football_field/params.csv")).unwrap();
    assert!(params.contains("segments,3"), "{params}");
    // The program started itself again with glibc's heaps kept, and says so.
    let allocator = table["allocator"].as_str().unwrap_or_default();
    assert_eq!(allocator, expected_allocator(None), "{meta}");
    assert!(
        readme.contains(&format!("; allocator: {allocator}.")),
        "{readme}"
    );
    // A second run into the same folder is refused without --force.
    fails_with(&args, &["not empty", "--force"]);
    let mut forced = args.to_vec();
    forced.push("--force");
    assert!(grassbench(&forced).0);
}

/// What a `grassbench` started from this test's environment (with `GRASSBENCH_ALLOCATOR` set to
/// `opt_out` where given) must record as its allocator: glibc's heaps kept where this build's C
/// library reads tunables and neither the environment's own malloc tunables nor an opt-out stop
/// it, the defaults or the environment's setting otherwise.
fn expected_allocator(opt_out: Option<&str>) -> String {
    use grassbench::runner::allocator::{OPT_OUT_VARIABLE, TUNABLE, describe, tunables_to_set};
    let current = std::env::var("GLIBC_TUNABLES").ok();
    let opt_out = opt_out
        .map(str::to_owned)
        .or_else(|| std::env::var(OPT_OUT_VARIABLE).ok());
    let after = match tunables_to_set(current.as_deref(), opt_out.as_deref()) {
        Some(set) if TUNABLE => Some(set),
        _ => current,
    };
    describe(TUNABLE, after.as_deref(), opt_out.as_deref())
}

/// `GRASSBENCH_ALLOCATOR=system` leaves glibc's malloc at its defaults, recorded as such.
#[test]
fn the_allocator_opt_out_is_recorded() {
    let d = temp("allocator");
    let out = d.join("out");
    let args: Vec<&str> = "run -t reference -s football_field --frames 1 --warmup 0 \
                           --size 96x64 --no-calibration -o out"
        .split_whitespace()
        .collect();
    let (ok, _, err) = grassbench_with(&d, &args, &[("GRASSBENCH_ALLOCATOR", "system")]);
    assert!(ok, "{err}");
    let meta: toml::Table =
        toml::from_str(&std::fs::read_to_string(out.join("meta.toml")).unwrap()).unwrap();
    assert_eq!(
        meta["allocator"].as_str().unwrap_or_default(),
        expected_allocator(Some("system"))
    );
    if grassbench::runner::allocator::TUNABLE
        && std::env::var("GLIBC_TUNABLES").map_or(true, |t| !t.contains("glibc.malloc."))
    {
        assert_eq!(
            meta["allocator"].as_str().unwrap_or_default(),
            "glibc malloc, its defaults (GRASSBENCH_ALLOCATOR=system)"
        );
    }
}

#[test]
fn interleaved_runs_give_the_same_images_and_every_technique_its_rows() {
    // `--interleave` measures frame 0 of each technique, then frame 1 of each, ...: each
    // technique sees the frame sequence of a plain run, so its images are the same bytes.
    let d = temp("interleave");
    let run = |extra: &[&str], name: &str| {
        let out = d.join(name);
        let mut args = vec![
            "run",
            "-t",
            "reference,zhang,boulanger",
            "-s",
            "football_field",
            "--frames",
            "2",
            "--warmup",
            "1",
            "--size",
            "96x64",
            "-o",
        ];
        let out_s = out.to_str().unwrap().to_owned();
        args.push(&out_s);
        args.extend_from_slice(extra);
        let (ok, _, err) = grassbench(&args);
        assert!(ok, "{err}");
        out.join("football_field")
    };
    let plain = run(&[], "plain");
    let interleaved = run(&["--interleave"], "interleaved");
    for id in ["reference", "zhang", "boulanger"] {
        for f in [1, 2] {
            let png = format!("{id}_frame{f:04}.png");
            let a = std::fs::read(plain.join(&png)).unwrap();
            let b = std::fs::read(interleaved.join(&png)).unwrap();
            assert!(a == b, "{png} differs between plain and interleaved runs");
        }
    }
    let frames = std::fs::read_to_string(interleaved.join("frames.csv")).unwrap();
    // A header, then 2 measured frames of each of the three techniques.
    assert_eq!(frames.lines().count(), 1 + 3 * 2, "{frames}");
    let runs = std::fs::read_to_string(interleaved.join("runs.csv")).unwrap();
    for id in ["reference", "zhang", "boulanger"] {
        assert!(runs.contains(&format!(",{id},")), "no row for {id}: {runs}");
    }
    // Every technique's speed-up over the scene's reference, with its 95 % interval.
    let mut rows = csv::Reader::from_path(interleaved.join("runs.csv")).unwrap();
    let headers = rows.headers().unwrap().clone();
    let at = |name: &str| headers.iter().position(|h| h == name).unwrap();
    let (technique, speedup, low, high) = (
        at("technique"),
        at("speedup"),
        at("speedup_ci_low"),
        at("speedup_ci_high"),
    );
    for row in rows.records() {
        let row = row.unwrap();
        let number = |k: usize| row[k].parse::<f64>().ok();
        if &row[technique] == "reference" {
            assert_eq!(number(speedup), Some(1.0));
        } else {
            let (s, lo, hi) = (
                number(speedup).unwrap(),
                number(low).unwrap(),
                number(high).unwrap(),
            );
            assert!(lo <= s && s <= hi, "{}: {lo} {s} {hi}", &row[technique]);
        }
    }
    let readme = std::fs::read_to_string(d.join("interleaved/README.md")).unwrap();
    assert!(readme.contains("speed-up (95 % interval)"), "{readme}");
}

#[test]
fn missing_backend_names_the_fix() {
    // No machine this runs on has Metal and DX12 at once; on Linux, neither.
    let backend = if cfg!(target_os = "macos") {
        "dx12"
    } else {
        "metal"
    };
    fails_with(
        &[
            "render",
            "-t",
            "reference",
            "--backend",
            backend,
            "--size",
            "32x32",
            "-o",
            "/tmp/x.png",
        ],
        &["no GPU adapter", "mesa-vulkan-drivers"],
    );
}

#[test]
fn gpu_memory_budget_refuses_with_the_numbers_before_creating_anything() {
    let out = temp("budget");
    let png = out.join("x.png");
    let (ok, _, err) = grassbench_with(
        &out,
        &[
            "render",
            "-t",
            "reference",
            "-s",
            "meadow",
            "--size",
            "64x36",
            "-o",
            "x.png",
        ],
        &[("GRASSBENCH_GPU_MEMORY_MB", "1")],
    );
    assert!(!ok, "a 1 MiB budget was accepted");
    assert!(!err.contains("panicked"), "{err}");
    for needle in [
        "MiB of GPU memory",
        "budget is 1.0 MiB",
        "GRASSBENCH_GPU_MEMORY_MB",
        "grass.density",
    ] {
        assert!(err.contains(needle), "message lacks `{needle}`: {err}");
    }
    assert!(!png.exists(), "an image was written anyway");
    // A budget that is not a number is named as such.
    let (ok, _, err) = grassbench_with(
        &out,
        &[
            "render",
            "-t",
            "reference",
            "--size",
            "32x32",
            "-o",
            "x.png",
        ],
        &[("GRASSBENCH_GPU_MEMORY_MB", "lots")],
    );
    assert!(!ok && err.contains("GRASSBENCH_GPU_MEMORY_MB"), "{err}");
}

/// A value a technique rejects anywhere in a sweep's grid refuses the file in `validate` and
/// in `sweep` (through the technique's own parameter check), before anything is measured.
#[test]
fn bad_grid_values_are_refused_before_anything_is_measured() {
    let dir = temp("bad-grid");
    let file = dir.join("bad.toml");
    std::fs::write(
        &file,
        "name = \"bad\"\nscenes = [\"meadow\"]\ntechniques = [\"bakay\"]\n\
         resolutions = [\"320x180\"]\nframes = 1\nwarmup = 0\n\
         [params.bakay]\nshells = [8, -4]\n",
    )
    .unwrap();
    let path = file.to_str().unwrap();
    fails_with(&["validate", path], &["bakay", "shells = -4"]);
    let out = dir.join("out");
    fails_with(
        &[
            "sweep",
            path,
            "-o",
            out.to_str().unwrap(),
            "--no-calibration",
        ],
        &["bakay", "shells = -4"],
    );
    assert!(!out.join("runs.csv").exists(), "a run was measured");
}

/// `list` prints parameters as the values they hold and every variant with what it sets.
#[test]
fn list_shows_values_as_written_and_variants() {
    let (ok, out, _) = grassbench(&["list"]);
    assert!(ok);
    assert!(out.contains("flutter = 0.15\n"), "{out}");
    assert!(out.contains("variant finest"), "{out}");
    assert!(
        out.contains("variant no_transitions  transitions = false"),
        "{out}"
    );
    // Each paper's operating point, with what it sets.
    assert!(
        out.contains("variant paper           shells = 16, wind = \"point_source\""),
        "{out}"
    );
    assert_eq!(out.matches("variant paper ").count(), 4, "{out}");
    // Each parameter explains itself on the line after its default: valid range (with the
    // unit its description names) or choices, then the description's first sentence.
    for line in [
        "      flutter = 0.15\n          [0, 1]  Per-blade flutter amplitude, relative to the wind push.\n",
        "      petal_size = 0.07\n          [0.001, 10] m  Petal quad side, m.\n",
        "      sorting = sort\n          \"sort\" | \"alpha_to_coverage\"  Far-to-near sorting",
        "      source_position = [",
        "          each [-1000000, 1000000]  `point_source` wind: world position of the source.\n",
        "      max_tilt = 0.4\n          [0, 1.5] radians  Largest launch angle",
        "      lod = true\n          Level of detail (Sec. 5.2): the camera grid",
    ] {
        assert!(out.contains(line), "missing {line:?} in:\n{out}");
    }
    // Every parameter line has its explanation.
    let lines: Vec<&str> = out.lines().collect();
    for (i, line) in lines.iter().enumerate() {
        if line.starts_with("      ") && !line.starts_with("          ") && line.contains(" = ") {
            let next = lines.get(i + 1).copied().unwrap_or_default();
            assert!(
                next.starts_with("          ") && next.trim().len() > 3,
                "no explanation after {line:?}: {next:?}"
            );
        }
    }
}

/// `calibrate -o` writes the raw limits, the unit costs with their fit, every sample with its
/// counted work, and the provenance; the file reads back. At 64x36 the fragment workloads
/// are too small to time and are scaled up (the path a fast GPU takes). The strips that load
/// texels in their vertex shader did so as counted: the GPU's vertex invocations times the
/// shader's loads are the work known in advance, all of it the vertex stage's, and no
/// fragment. The coverage checks are timed with the samples and priced.
#[test]
fn calibrate_writes_unit_costs_samples_and_provenance() {
    let dir = temp("calibrate");
    let file = dir.join("calibration.toml");
    let (ok, out, err) =
        grassbench(&["calibrate", "--size", "64x36", "-o", file.to_str().unwrap()]);
    assert!(ok, "{err}");
    assert!(err.contains("| fragment_blended |"), "{err}");
    assert!(err.contains("| vertex_float_texture_load |"), "{err}");
    let text = std::fs::read_to_string(&file).unwrap();
    assert_eq!(text, out, "the file holds what was printed");
    let read: grassbench_cli::commands::CalibrationFile = toml::from_str(&text).unwrap();
    assert_eq!(read.unit_costs.size, "64x36");
    assert_eq!(read.samples.len(), read.unit_costs.fit.samples);
    // The checks: held out (not among the fitted samples), each timed and priced.
    let checks = grassbench::cost::checks::coverage_checks();
    assert_eq!(read.unit_costs.checks.len(), checks.len());
    assert_eq!(read.check_samples.len(), checks.len());
    assert!(err.contains("| slivers_alpha_tested |"), "{err}");
    for (c, r) in checks.iter().zip(&read.unit_costs.checks) {
        assert_eq!(c.name, r.check);
        assert!(r.ratio.is_finite() && r.ratio > 0.0, "{r:?}");
        assert!(r.kept_per_fragment.is_some(), "lavapipe counts: {r:?}");
    }
    assert!(read.provenance.command.starts_with("grassbench calibrate"));
    assert!(!read.provenance.adapter.name.is_empty());
    // The layers were scaled: 2 layers of 64x36 are some 0.5 ms on lavapipe, under the
    // 20 ms the largest size must reach, so the smallest of them holds more than 2 layers.
    let opaque = read
        .samples
        .iter()
        .find(|s| s.sample.workload == "fragments_opaque")
        .unwrap();
    assert!(
        opaque.known.fragments_opaque > 2.0 * 64.0 * 36.0,
        "{opaque:?}"
    );
    // The vertex stage's loads.
    let vertex_loads: Vec<_> = read
        .samples
        .iter()
        .filter(|s| {
            s.sample.workload.starts_with("vertex_") && s.sample.workload.ends_with("_loads")
        })
        .collect();
    assert_eq!(vertex_loads.len(), 8, "two workloads at four sizes");
    for s in vertex_loads {
        let counted = s.counted.expect("lavapipe counts");
        let (loads, vertex_loads) = (
            counted.texture_loads + counted.float_texture_loads,
            counted.vertex_texture_loads + counted.vertex_float_texture_loads,
        );
        assert!(loads > 0.0, "{}", s.sample.workload);
        assert_eq!(vertex_loads, loads, "{}", s.sample.workload);
        assert_eq!(counted, s.known, "{}", s.sample.workload);
        assert_eq!(counted.fragments_opaque, 0.0, "off screen: no fragment");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The default comparison, small, on wgpu's GL backend (issue 24 §1): every technique runs
/// there and gets its rows, and the work columns that need pipeline statistics (which GL does
/// not have) are empty, never zeros.
#[test]
fn the_default_comparison_runs_on_gl_too() {
    let out = temp("gl-run");
    let out_s = out.to_str().unwrap();
    let (ok, _, err) = grassbench(&[
        "run",
        "-t",
        "all",
        "-s",
        "meadow",
        "--frames",
        "2",
        "--warmup",
        "1",
        "--size",
        "160x90",
        "--no-calibration",
        "--backend",
        "gl",
        "-o",
        out_s,
        "--force",
    ]);
    assert!(ok, "{err}");
    let runs = std::fs::read_to_string(out.join("meadow/runs.csv")).unwrap();
    let mut rows = csv::Reader::from_reader(runs.as_bytes());
    let header = rows.headers().unwrap().clone();
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let (technique, status, fragments) =
        (col("technique"), col("status"), col("fragment_invocations"));
    let mut seen = Vec::new();
    for row in rows.records() {
        let row = row.unwrap();
        assert_eq!(&row[status], "ok", "{runs}");
        assert_eq!(&row[fragments], "", "GL has no statistics: {runs}");
        seen.push(row[technique].to_owned());
    }
    for id in [
        "reference",
        "zhang",
        "boulanger",
        "bakay",
        "perbet",
        "jahrmann",
    ] {
        assert!(seen.iter().any(|s| s == id), "{id} missing: {runs}");
    }
    let meta = std::fs::read_to_string(out.join("meta.toml")).unwrap();
    assert!(meta.to_lowercase().contains("gl"), "{meta}");
}

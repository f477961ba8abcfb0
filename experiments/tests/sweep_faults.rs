//! Faults during a sweep (issue 24 §3): a validation error inside one run's `encode`, and a
//! device lost inside another run, each mark only that run failed with its error in
//! `runs.csv`, and the sweep goes on on a fresh device: the later runs succeed and write their
//! rows. The two faulty techniques exist only here, in a registry the test extends
//! (`commands::sweep_with`); the command's registry never lists them.
//!
//! (Checked that it can fail: with the device kept after a failed run instead of recreated,
//! every run after the lost device fails with it and this test reports them.)

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::{Path, PathBuf};

use grassbench::gpu::GpuEstimate;
use grassbench::technique::{
    FrameEncoder, GrassTechnique, InitContext, NoParams, Technique, TechniqueInfo, TechniqueStats,
    Variants,
};
use grassbench::{FrameInputs, GpuContext, Scene};
use grassbench_cli::commands::{GpuArgs, SweepArgs, sweep_with};

/// Draws without setting a pipeline: a validation error while its frame is encoded.
struct InvalidDraw;

impl Technique for InvalidDraw {
    type Params = NoParams;
    const INFO: TechniqueInfo = TechniqueInfo {
        id: "fault_validation",
        name: "draws without a pipeline",
        paper: "-",
        gpu_state: false,
        debug_views: &[],
    };
    const VARIANTS: Variants = Variants {
        finest: "",
        others: &[],
    };
    fn new(_: &InitContext<'_>, _: NoParams) -> grassbench::Result<Self> {
        Ok(Self)
    }
    fn estimate(_: &Scene, _: &NoParams) -> grassbench::Result<GpuEstimate> {
        Ok(GpuEstimate::default())
    }
    fn params(&self) -> &NoParams {
        &NoParams {}
    }
}

impl GrassTechnique for InvalidDraw {
    fn encode(&self, encoder: &mut FrameEncoder<'_>) {
        let mut pass = encoder.render_pass("no pipeline");
        pass.draw(0..3, 0..1);
    }
    fn stats(&self) -> TechniqueStats {
        TechniqueStats::default()
    }
}

/// Destroys the device while preparing its second frame: the device is lost mid-run.
struct LosesDevice;

impl Technique for LosesDevice {
    type Params = NoParams;
    const INFO: TechniqueInfo = TechniqueInfo {
        id: "fault_lost",
        name: "destroys the device",
        paper: "-",
        gpu_state: false,
        debug_views: &[],
    };
    const VARIANTS: Variants = Variants {
        finest: "",
        others: &[],
    };
    fn new(_: &InitContext<'_>, _: NoParams) -> grassbench::Result<Self> {
        Ok(Self)
    }
    fn estimate(_: &Scene, _: &NoParams) -> grassbench::Result<GpuEstimate> {
        Ok(GpuEstimate::default())
    }
    fn params(&self) -> &NoParams {
        &NoParams {}
    }
}

impl GrassTechnique for LosesDevice {
    fn prepare(&mut self, gpu: &GpuContext, inputs: &FrameInputs<'_>) -> grassbench::Result<()> {
        if inputs.frame == 1 {
            gpu.device.destroy();
        }
        Ok(())
    }
    fn encode(&self, _: &mut FrameEncoder<'_>) {}
    fn stats(&self) -> TechniqueStats {
        TechniqueStats::default()
    }
}

fn temp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("grassbench-faults-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// Every row of `runs.csv` as (run_id, technique, status, error, gpu_wall_ms_median).
fn rows(path: &Path) -> Vec<[String; 5]> {
    let mut r = csv::Reader::from_path(path).unwrap();
    let headers = r.headers().unwrap().clone();
    let col = |name: &str| headers.iter().position(|h| h == name).unwrap();
    let cols = [
        col("run_id"),
        col("technique"),
        col("status"),
        col("error"),
        col("gpu_wall_ms_median"),
    ];
    r.records()
        .map(|x| {
            let x = x.unwrap();
            cols.map(|k| x.get(k).unwrap().to_owned())
        })
        .collect()
}

#[test]
fn a_validation_error_or_a_lost_device_fails_only_its_run_and_the_sweep_goes_on() {
    let out = temp("out");
    std::fs::create_dir_all(&out).unwrap();
    let file = out.with_extension("toml");
    // Per repetition: the reference, the validation error, the lost device, the reference
    // again at another density (a second group); the second repetition runs after both
    // faults.
    std::fs::write(
        &file,
        "name = \"faults\"\nscenes = [\"meadow\"]\n\
         techniques = [\"fault_validation\", \"fault_lost\", \"reference\"]\n\
         resolutions = [\"96x54\"]\nrepetitions = 2\nwarmup = 1\nframes = 2\n\
         [scene_params]\n\"grass.density\" = [1.0, 2.0]\n",
    )
    .unwrap();
    let mut techniques = grassbench_cli::registry::TECHNIQUES.to_vec();
    techniques.push(grassbench::technique::entry::<InvalidDraw>());
    techniques.push(grassbench::technique::entry::<LosesDevice>());
    let args = SweepArgs {
        file: file.clone(),
        out: Some(out.clone()),
        shard: None,
        force: true,
        no_calibration: true,
        gpu: GpuArgs { backend: None },
    };
    sweep_with(&args, &techniques).unwrap();

    let rows = rows(&out.join("runs.csv"));
    assert_eq!(rows.len(), 2 * 2 * 3, "{rows:?}");
    let of = |id: &str| -> Vec<&[String; 5]> { rows.iter().filter(|r| r[1] == id).collect() };
    for r in of("fault_validation") {
        assert_eq!(r[2], "failed", "{r:?}");
        assert!(
            r[3].contains("validation error") && r[3].contains("frame"),
            "the error names the fault and the frame: {r:?}"
        );
        // wgpu's error chain, not a bare "Validation Error".
        assert!(r[3].to_lowercase().contains("pipeline"), "{r:?}");
    }
    for r in of("fault_lost") {
        assert_eq!(r[2], "failed", "{r:?}");
        assert!(
            r[3].to_lowercase().contains("lost") || r[3].to_lowercase().contains("destroy"),
            "the error names the lost device: {r:?}"
        );
    }
    // Every reference run — those after each fault included — measured, on a fresh device.
    let references = of("reference");
    assert_eq!(references.len(), 4);
    for r in references {
        assert_eq!(r[2], "ok", "{r:?}");
        assert!(r[3].is_empty(), "{r:?}");
        assert!(r[4].parse::<f64>().unwrap() > 0.0, "{r:?}");
    }
    // Their frames are in frames.csv.
    let mut frames = csv::Reader::from_path(out.join("frames.csv")).unwrap();
    let k = frames
        .headers()
        .unwrap()
        .iter()
        .position(|h| h == "technique")
        .unwrap();
    let measured = frames
        .records()
        .filter(|x| x.as_ref().unwrap().get(k) == Some("reference"))
        .count();
    assert_eq!(measured, 4 * 2);
    // The command's own registry does not know the faulty techniques.
    assert!(grassbench_cli::registry::find("fault_lost").is_err());
    std::fs::remove_dir_all(&out).unwrap();
    let _ = std::fs::remove_file(&file);
}

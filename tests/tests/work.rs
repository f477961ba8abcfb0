//! Measured work (issue 20 §1): the GPU's pipeline-statistics queries around every pass the
//! frame encoder opens give what a frame did, for every technique alike. Checked against work
//! known in advance (the reference's bend pass and triangle strips, bakay's bend dispatch), and
//! left empty, never zero, on a backend that cannot count.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use anyhow::Context as _;
use grassbench::gpu::BackendChoice;
use grassbench::runner::{FrameRecord, Harness};
use grassbench::{GpuContext, Scene};
use grassbench_tests::{TEST_SIZE, gpu, render_record, repo_root};

fn lawn() -> anyhow::Result<Scene> {
    Ok(Scene::load(&repo_root().join("tests/scenes/counts.toml"))?)
}

fn frame_of(gpu: &GpuContext, id: &str, overrides: &str) -> anyhow::Result<FrameRecord> {
    let entry = grassbench_cli::registry::find(id)?;
    let mut harness = Harness::new(gpu, lawn()?, TEST_SIZE, false)?;
    let mut technique = harness.create(entry, &overrides.parse()?)?;
    Ok(render_record(&mut harness, technique.as_mut(), 2)?.1)
}

#[test]
fn pass_statistics_count_the_work_each_frame_submits() -> anyhow::Result<()> {
    let gpu = gpu()?;
    assert!(
        gpu.has_pipeline_statistics(),
        "lavapipe has PIPELINE_STATISTICS_QUERY (shared/PLATFORM.md); this adapter ({}) does not",
        gpu.summary.name
    );
    // The reference draws every blade as one instance of a triangle strip of 2s + 1 vertices
    // (s segments: 2s - 1 triangles), with no index buffer: every vertex runs the shader once
    // and every triangle reaches the clipper.
    for segments in [2u64, 4] {
        let r = frame_of(&gpu, "reference", &format!("segments = {segments}"))?;
        let blades = r.blades_drawn.context("blades drawn")?;
        assert!(blades > 2000, "{blades} blades");
        assert_eq!(r.vertex_invocations, Some(blades * (2 * segments + 1)));
        assert_eq!(r.clipper_invocations, Some(blades * (2 * segments - 1)));
        assert_eq!(r.clipper_invocations, Some(r.triangles));
        // One instance a blade (the encoder's count of its draws' instance ranges); the
        // background's draws are counted apart.
        assert_eq!(r.instances, Some(blades));
        // Every primitive rasterised sets up the three slots its fragment shader reads
        // (`world_ao`, `normal`, `albedo`).
        assert_eq!(r.primitive_inputs, r.clipper_primitives_out.map(|n| 3 * n));
        // Its pass draws fewer than a pass's head (`PASS_HEAD_PRIMITIVES`): all of them in
        // it, and the background's likewise (the heads of passes past it are checked in the
        // calibration's test, `cost_model.rs`, on strips of up to 2.88 M triangles).
        assert_eq!(r.head_primitives, r.clipper_primitives_out);
        assert_eq!(r.background_head_primitives, r.background_primitives);
        assert!(r.background_instances.is_some_and(|n| n > 0), "{r:?}");
        // Its bend pass runs once per blade, in whole 64-wide workgroups (one chunk here).
        assert_eq!(
            r.compute_invocations,
            Some(blades.div_ceil(64) * 64),
            "{blades} blades"
        );
        // Fragments: some, and the overdraw is their share of the target's pixels.
        let fs = r.fragment_invocations.context("fragments")?;
        let pixels = f64::from(TEST_SIZE.width * TEST_SIZE.height);
        assert!(fs > 0 && r.overdraw == Some(fs as f64 / pixels), "{r:?}");
        // The clipper lets through at most what it received (the lawn is in view: most).
        let out = r.clipper_primitives_out.context("primitives out")?;
        assert!(
            out <= r.triangles && out > r.triangles / 4,
            "{out} of {}",
            r.triangles
        );
        // The core's background (sky, ground) is counted apart: its full-screen sky alone runs
        // a fragment for every pixel.
        assert!(r.background_fragment_invocations.context("background")? >= pixels as u64);
    }
    // bakay bends its shells' vertices in a compute pass of 64-wide workgroups, a chunk drawn
    // at a time: each chunk's (CHUNK + 1)² vertices rounded up to whole workgroups.
    let b = frame_of(&gpu, "bakay", "")?;
    let cs = b.compute_invocations.context("compute")?;
    let per_chunk = 64 * u64::from(grassbench_bakay::BEND_WORKGROUPS_PER_CHUNK);
    assert!(cs > 0 && cs % per_chunk == 0, "{cs} compute invocations");
    Ok(())
}

/// A loop bounded by a pipeline-overridable constant is counted for as many trips as the
/// pipeline's value says (`shaders::trips`): bakay's bend pass walks up its `SHELLS` shells,
/// writing each shell's offset (a `vec2`, 2 words) after reading its chunk's first cell (a
/// `vec2<u32>`, 2), its vertex's ground point and normal (6) and writing its wind (a `vec4`,
/// 4), so its storage words an invocation follow the shell count the technique was created
/// with.
#[test]
fn loops_count_the_trips_their_pipeline_sets() -> anyhow::Result<()> {
    let gpu = gpu()?;
    for shells in [8u64, 16] {
        let b = frame_of(&gpu, "bakay", &format!("shells = {shells}"))?;
        let cs = b.compute_invocations.context("compute")?;
        let words = b.compute_storage.context("compute storage words")?;
        assert!(cs > 0, "{b:?}");
        assert_eq!(words, cs * (2 + 6 + 4 + 2 * shells), "{shells} shells");
    }
    Ok(())
}

/// A compute pipeline's texture fetches are counted like a render pipeline's (issue 20 §3):
/// jahrmann's simulation reads the wind texture for every blade, so its floating-point texel
/// loads (the wind is `Rgba32Float`) are at least its compute invocations times the loads
/// `cs_simulate` makes, as the naga IR counts them.
#[test]
fn compute_shaders_texture_fetches_are_counted() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let module = grassbench::shaders::module(&gpu.device, "jahrmann", grassbench_jahrmann::SHADER);
    let per_invocation = module.ops("cs_simulate", &[]).float_loads;
    assert!(
        per_invocation >= 4,
        "cs_simulate's wind lookup is bilinear: {per_invocation} loads"
    );
    let r = frame_of(&gpu, "jahrmann", "")?;
    let cs = r.compute_invocations.context("compute")?;
    let loads = r
        .float_texture_loads
        .context("floating-point texture loads")?;
    assert!(cs > 0, "{r:?}");
    assert!(
        loads >= cs * per_invocation,
        "{loads} loads for {cs} invocations"
    );
    Ok(())
}

/// Fragments are counted by the kind of the pipeline that drew them (issue 20 §1-§2: the cost
/// model prices opaque, alpha-tested and blended fragments apart): the kinds add up to the
/// total for every technique, the reference's opaque strips are all opaque, bakay's shells
/// (which discard the texels no blade reaches) alpha-tested, and zhang's sorted billboards
/// blended.
#[test]
fn fragments_are_split_by_the_kind_of_their_pipeline() -> anyhow::Result<()> {
    let gpu = gpu()?;
    for entry in grassbench_cli::registry::TECHNIQUES {
        let id = entry.info.id;
        let r = frame_of(&gpu, id, "")?;
        let total = r.fragment_invocations.context("fragments")?;
        let kinds = [
            r.fragments_opaque.context("opaque")?,
            r.fragments_alpha_tested.context("alpha-tested")?,
            r.fragments_blended.context("blended")?,
        ];
        assert_eq!(
            kinds.iter().sum::<u64>(),
            total,
            "{id}: {kinds:?} of {total}"
        );
        match id {
            "reference" => assert_eq!(kinds, [total, 0, 0], "reference"),
            "bakay" => assert!(kinds[1] > total / 2, "bakay: {kinds:?}"),
            "zhang" => assert!(kinds[2] > 0, "zhang: {kinds:?}"),
            _ => {}
        }
    }
    Ok(())
}

/// Occlusion queries around the same segments count the samples each technique's passes
/// kept: those that passed the depth test and were not discarded. Never more than the
/// fragments counted (one sample a fragment without MSAA), some for every technique that
/// draws grass on the lawn, far fewer than its fragments for bakay, whose shells discard the
/// texels no blade reaches, and the same frame after frame for a still scene.
#[test]
fn occlusion_queries_count_the_fragments_kept() -> anyhow::Result<()> {
    let gpu = gpu()?;
    for entry in grassbench_cli::registry::TECHNIQUES {
        let id = entry.info.id;
        let r = frame_of(&gpu, id, "")?;
        let fragments = r.fragment_invocations.context("fragments")?;
        let passed = r.fragments_passed.context("fragments passed")?;
        eprintln!("{id}: {passed} kept of {fragments} fragments");
        assert!(
            passed > 0 && passed <= fragments,
            "{id}: {passed} of {fragments}"
        );
        if id == "bakay" {
            // Measured on lavapipe (the counts lawn at the tests' size, 2026-12-05): 126 kept
            // of 153 312 (the reference 372 of 5 984: lavapipe counts a fragment for every
            // pixel of each 4x4 block a triangle touches, and a blade covers few of them).
            assert!(passed * 20 < fragments, "bakay: {passed} of {fragments}");
        }
    }
    Ok(())
}

/// Uploads are counted by the harness: the reference uploads nothing per frame, so its frame
/// uploads exactly the core's wind texture, frame globals and the ground chunks it draws.
#[test]
fn uploads_are_counted_for_every_frame() -> anyhow::Result<()> {
    let gpu = gpu()?;
    let entry = grassbench_cli::registry::find("reference")?;
    let mut harness = Harness::new(&gpu, lawn()?, TEST_SIZE, false)?;
    let mut technique = harness.create(entry, &toml::Table::new())?;
    let r = render_record(&mut harness, technique.as_mut(), 2)?.1;
    let scene = lawn()?;
    let (w, h) = grassbench::wind::WindTexture::resolution_for(&scene.terrain);
    let camera = harness.world.camera(&harness.view, 2);
    let scene_gpu = &harness.world.scene_gpu;
    let ground = scene_gpu
        .terrain
        .chunks
        .plan(&camera, TEST_SIZE.height, scene_gpu.ground_lod)
        .instances;
    assert!(!ground.is_empty(), "the lawn's ground is in view");
    let core = u64::from(w * h * 16)
        + std::mem::size_of::<grassbench::frame::FrameGlobals>() as u64
        + std::mem::size_of_val(ground.as_slice()) as u64;
    assert_eq!(r.upload_bytes, Some(core));
    // zhang uploads its near blades' control points every frame.
    let z = frame_of(&gpu, "zhang", "")?;
    assert!(z.upload_bytes.context("upload")? > core, "{z:?}");
    Ok(())
}

/// No technique writes to the GPU behind the harness's back: per-frame uploads go through
/// `GpuContext::write_buffer` / `write_texture`, which count their bytes (`upload_bytes`).
#[test]
fn no_technique_bypasses_the_upload_count() -> anyhow::Result<()> {
    let mut offenders = Vec::new();
    let mut stack = vec![repo_root().join("techniques")];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).with_context(|| format!("{}", dir.display()))? {
            let path = entry?.path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let text = std::fs::read_to_string(&path)?;
                for (k, line) in text.lines().enumerate() {
                    if line.contains("queue.write_buffer") || line.contains("queue.write_texture") {
                        offenders.push(format!("{}:{}: {}", path.display(), k + 1, line.trim()));
                    }
                }
            }
        }
    }
    assert!(
        offenders.is_empty(),
        "write through GpuContext::write_buffer / write_texture so the bytes are counted:\n{}",
        offenders.join("\n")
    );
    Ok(())
}

#[test]
fn a_backend_without_statistics_leaves_the_work_empty() -> anyhow::Result<()> {
    // wgpu's GL backend has no pipeline-statistics queries (llvmpipe through EGL here).
    let gpu = GpuContext::new(BackendChoice::Gl)
        .context("the GL backend (Mesa's llvmpipe through EGL: `make setup` installs it)")?;
    assert!(!gpu.has_pipeline_statistics(), "{}", gpu.summary.name);
    let r = frame_of(&gpu, "reference", "")?;
    assert!(r.blades_drawn.is_some_and(|b| b > 0));
    assert_eq!(
        (
            r.vertex_invocations,
            r.fragment_invocations,
            r.compute_invocations,
            r.overdraw,
            r.instances
        ),
        (None, None, None, None, None),
        "no statistics on GL: empty, never zero"
    );
    Ok(())
}

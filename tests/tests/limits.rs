//! Limits a GPU will have (issue 24 §2).
//!
//! - Every registered technique is created and draws a frame of every canonical scene on the
//!   device every command creates (`GpuContext::new`, which requests `wgpu::Limits::default()`,
//!   what WebGPU guarantees on any GPU, raised only for what techniques declare), with no
//!   validation error, and its picture is the one it draws under the adapter's own (lavapipe's
//!   generous) limits. (Checked that it can fail: under `Limits::downlevel_webgl2_defaults()`,
//!   which has no storage buffers, every technique is refused naming the limits it lacks.)
//! - A technique declaring more than the adapter offers is refused before any of its GPU work,
//!   with the technique, the limit, both numbers and the fix; the device is still created.
//! - Under webgl2's limits, the refusal names the limits; and where a technique's own
//!   creation is let through anyway, wgpu's validation error says which call, resource and
//!   limit (its whole error chain), not a bare "Validation Error".

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::sync::atomic::{AtomicBool, Ordering};

use grassbench::gpu::{BackendChoice, GpuEstimate};
use grassbench::runner::Harness;
use grassbench::technique::{
    FrameEncoder, GrassTechnique, InitContext, NoParams, Technique, TechniqueInfo, TechniqueStats,
    Variants,
};
use grassbench::{GpuContext, Scene, wgpu};
use grassbench_tests::{TEST_SIZE, gpu, scene};

/// The test suite's density: a quarter of the scenes' blades (software rasteriser).
const DENSITY: f32 = 0.25;
/// The frame drawn.
const FRAME: u64 = 10;

#[test]
fn every_technique_runs_under_the_default_limits() -> anyhow::Result<()> {
    let generous = GpuContext::with_limits(BackendChoice::from_env()?, None)?;
    // The device every command creates for techniques that declare nothing beyond the
    // defaults: exactly the defaults, where the adapter offers them (lavapipe does).
    let strict = gpu()?;
    if wgpu::Limits::default().check_limits(&strict.adapter.limits()) {
        assert_eq!(strict.device.limits(), wgpu::Limits::default());
    }
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

/// Set when [`Greedy::new`] runs: a refused technique must never get that far.
static GREEDY_CREATED: AtomicBool = AtomicBool::new(false);

/// Declares far more bind groups than any adapter offers.
struct Greedy;

/// What [`Greedy`] declares it needs.
const GREEDY_BIND_GROUPS: u32 = 1 << 20;

impl Technique for Greedy {
    type Params = NoParams;
    const INFO: TechniqueInfo = TechniqueInfo {
        id: "greedy",
        name: "needs more than any adapter",
        paper: "-",
        gpu_state: false,
        debug_views: &[],
    };
    const VARIANTS: Variants = Variants {
        finest: "",
        others: &[],
    };
    fn new(_: &InitContext<'_>, _: NoParams) -> grassbench::Result<Self> {
        GREEDY_CREATED.store(true, Ordering::SeqCst);
        Ok(Self)
    }
    fn estimate(_: &Scene, _: &NoParams) -> grassbench::Result<GpuEstimate> {
        Ok(GpuEstimate::default())
    }
    fn required_limits(_: &Scene, _: &NoParams) -> wgpu::Limits {
        wgpu::Limits {
            max_bind_groups: GREEDY_BIND_GROUPS,
            ..wgpu::Limits::default()
        }
    }
    fn params(&self) -> &NoParams {
        &NoParams {}
    }
}

impl GrassTechnique for Greedy {
    fn encode(&self, _: &mut FrameEncoder<'_>) {}
    fn stats(&self) -> TechniqueStats {
        TechniqueStats::default()
    }
}

#[test]
fn a_technique_needing_more_than_the_adapter_offers_is_refused_before_its_gpu_work()
-> anyhow::Result<()> {
    let entry = grassbench::technique::entry::<Greedy>();
    let scene = scene("meadow", 0.01)?;
    let none = toml::Table::new();
    // The command asks for what its techniques need; the device is created all the same, with
    // what the adapter offers.
    let needs = grassbench_cli::commands::needs([(&entry, &scene, &none)])?;
    assert_eq!(needs.max_bind_groups, GREEDY_BIND_GROUPS);
    let gpu = GpuContext::for_needs(BackendChoice::from_env()?, &needs)?;
    let offered = gpu.adapter.limits().max_bind_groups;
    assert_eq!(gpu.device.limits().max_bind_groups, offered);
    let harness = Harness::new(&gpu, scene, TEST_SIZE, false)?;
    let err = harness
        .create(&entry, &none)
        .err()
        .expect("must be refused");
    let text = err.to_string();
    assert!(
        matches!(err, grassbench::Error::Unsupported { .. }),
        "{text}"
    );
    for part in [
        "greedy",
        "max_bind_groups",
        &GREEDY_BIND_GROUPS.to_string(),
        &format!("the adapter offers {offered}"),
        &gpu.summary.name,
        "Fix:",
    ] {
        assert!(text.contains(part), "`{part}` missing from: {text}");
    }
    assert!(
        !GREEDY_CREATED.load(Ordering::SeqCst),
        "the technique was created"
    );
    // The device is untouched: a technique that fits is created on it.
    harness.create(grassbench_cli::registry::find("reference")?, &none)?;
    Ok(())
}

#[test]
fn under_webgl2_limits_errors_name_the_limit_and_the_resource() -> anyhow::Result<()> {
    let gpu = GpuContext::with_limits(
        BackendChoice::from_env()?,
        Some(wgpu::Limits::downlevel_webgl2_defaults()),
    )?;
    let harness = Harness::new(&gpu, scene("meadow", 0.01)?, TEST_SIZE, false)?;
    let none = toml::Table::new();
    for id in ["boulanger", "perbet"] {
        let entry = grassbench_cli::registry::find(id)?;
        // Refused before any GPU work, naming the storage-buffer limit webgl2 lacks.
        let refused = harness.create(entry, &none).err().expect("must be refused");
        let text = refused.to_string();
        assert!(
            text.contains(id) && text.contains("max_storage_buffers_per_shader_stage = "),
            "{text}"
        );
        // Let through anyway, its creation fails inside wgpu: the message carries wgpu's
        // error chain (the call, the resource's label, the limit), not just a heading.
        let during = format!("creating `{id}` past the check");
        let ctx = harness.init_context();
        let failed = gpu
            .scoped(&during, || entry.create(&ctx, &none))
            .and_then(|created| created)
            .err()
            .expect("must fail under webgl2 limits");
        let text = failed.to_string();
        assert!(
            matches!(failed, grassbench::Error::Validation { .. }),
            "{text}"
        );
        let message = text
            .split_once(&format!("{during}: "))
            .map(|(_, m)| m)
            .unwrap_or_default();
        assert!(
            message.len() > "Validation Error".len() + 20
                && message.contains("In ")
                && message.to_lowercase().contains("limit"),
            "{text}"
        );
        assert!(!message.contains('\n'), "one line: {text}");
    }
    Ok(())
}

/// jahrmann binds each half of its draw list (32 bytes a blade) whole as one storage buffer:
/// it declares a wider binding than the default 128 MiB only where the scene's blades need one.
#[test]
fn jahrmann_declares_a_wider_storage_binding_only_past_the_default() -> anyhow::Result<()> {
    let entry = grassbench_cli::registry::find("jahrmann")?;
    let none = toml::Table::new();
    let default = wgpu::Limits::default().max_storage_buffer_binding_size;
    let meadow = scene("meadow", 1.0)?;
    let needs = entry.required_limits(&meadow, &none)?;
    assert_eq!(needs.max_storage_buffer_binding_size, default);
    let candidates = meadow.blades.candidate_count(&meadow.terrain);
    // Candidates for 1.1 times the blades the default binding holds, of which the meadow
    // grows about three in four: the blades fit, and the default is all it asks for.
    let scale = (1.1 * (default / 32) as f64 / candidates as f64) as f32;
    let fits = scene("meadow", scale)?;
    let grown = fits.blades.all_blades(&fits.terrain).len() as u64;
    assert!(
        fits.blades.candidate_count(&fits.terrain) * 32 > default && grown * 32 <= default,
        "{grown} blades"
    );
    let needs = entry.required_limits(&fits, &none)?;
    assert_eq!(needs.max_storage_buffer_binding_size, default);
    // One and a half times as many: the blades themselves pass it (the candidates' halves
    // stay within the default max_buffer_size of 256 MiB), and it asks for their size exactly.
    let dense = scene("meadow", 1.5 * scale)?;
    let blades = dense.blades.all_blades(&dense.terrain).len() as u64;
    assert!(blades * 32 > default, "{blades} blades");
    let needs = entry.required_limits(&dense, &none)?;
    assert_eq!(needs.max_storage_buffer_binding_size, blades * 32);
    // The other limits stay the defaults.
    assert_eq!(
        wgpu::Limits {
            max_storage_buffer_binding_size: default,
            ..needs
        },
        wgpu::Limits::default()
    );
    Ok(())
}

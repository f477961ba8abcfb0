//! The compute pass alone (simulation, culling, compaction) by wall clock, submission to the
//! end of the wait, at about 1e5, 1e6 and 4e6 blades on the meadow (its grass density scaled)
//! at 640x360: lavapipe's compute timestamps are wrong (`shared/PLATFORM.md`), so a frame's
//! `gpu_ts_compute_ms` cannot say what the pass costs. Throughput is blades per second.
//! Run: `cargo bench -p grassbench-jahrmann --bench compute`;
//! `GRASSBENCH_BENCH_SMALL=1` runs one small population (for CI's smoke run).

#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;
use std::time::{Duration, Instant};

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use grassbench::runner::Harness;
use grassbench::target::Size;
use grassbench::technique::Technique as _;
use grassbench::{FrameEncoder, FrameInputs, GpuContext, GrassTechnique as _, Scene};
use grassbench_jahrmann::{Jahrmann, Params};

fn small() -> bool {
    std::env::var("GRASSBENCH_BENCH_SMALL").is_ok_and(|v| v == "1")
}

fn compute(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../experiments/scenes/meadow.toml");
    let base = Scene::load(&path).unwrap();
    let gpu = GpuContext::new(grassbench::gpu::BackendChoice::from_env().unwrap()).unwrap();
    let size = Size {
        width: 640,
        height: 360,
    };
    // Blades/m² where the density map is 1: 4 819 blades per unit on the meadow.
    let densities: &[f32] = if small() {
        &[2.0]
    } else {
        &[20.75, 207.5, 830.0]
    };
    let mut group = c.benchmark_group("jahrmann_compute");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(if small() { 1 } else { 8 }));
    for &density in densities {
        let mut config = base.config.clone();
        config.grass.density = density;
        let scene = Scene::from_config(config, base.base_dir.clone()).unwrap();
        let blades = scene.blades.all_blades(&scene.terrain).len() as u64;
        let harness = Harness::new(&gpu, scene, size, false).unwrap();
        let mut technique = Jahrmann::new(&harness.init_context(), Params::default()).unwrap();
        let mut frame = 0u64;
        group.throughput(Throughput::Elements(blades));
        group.bench_function(format!("{blades} blades"), |b| {
            b.iter_custom(|iters| {
                let mut total = Duration::ZERO;
                for _ in 0..iters {
                    let scene = &harness.world.scene;
                    let inputs = FrameInputs {
                        frame,
                        time: scene.time_of(frame),
                        dt: scene.dt(),
                        camera: harness.camera(frame),
                        scene,
                        wind: harness.wind(),
                        size,
                        debug_view: 0,
                    };
                    frame += 1;
                    technique.update(&inputs).unwrap();
                    harness.world.scene_gpu.upload(&gpu, &inputs);
                    technique.prepare(&gpu, &inputs).unwrap();
                    let mut encoder = FrameEncoder::new(
                        &gpu,
                        &harness.view.target,
                        &harness.world.scene_gpu,
                        None,
                        None,
                        "jahrmann.",
                    );
                    technique.encode_compute(&mut encoder);
                    let commands = encoder.finish().finish();
                    let start = Instant::now();
                    gpu.queue.submit([commands]);
                    gpu.wait_idle("the compute pass").unwrap();
                    total += start.elapsed();
                }
                total
            });
        });
    }
    group.finish();
}

criterion_group!(benches, compute);
criterion_main!(benches);

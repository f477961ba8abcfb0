//! Criterion benchmarks of every registered technique, stage by stage, on the meadow:
//! `update` (CPU), `prepare` + `encode` (recording, no submission) and a whole GPU frame
//! (submit to `poll(wait)`). Plus the core's CPU kernels with throughput.
//!
//! `GRASSBENCH_BENCH_SMALL=1` shrinks the workload (fewer blades, 160x90) so CI can smoke-run
//! the benchmarks: `cargo test --release -p grassbench-cli --bench techniques`.
//! Full run: `cargo bench -p grassbench-cli --bench techniques`.

#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use grassbench::glam::Vec3;
use grassbench::runner::Harness;
use grassbench::target::Size;
use grassbench::{GpuContext, Scene};
use grassbench_cli::{registry, scenes};

fn small() -> bool {
    std::env::var("GRASSBENCH_BENCH_SMALL").is_ok_and(|v| v == "1")
}

fn scene() -> Scene {
    let base = scenes::load("meadow").unwrap();
    let mut config = base.config.clone();
    if small() {
        config.grass.density *= 0.02;
    }
    Scene::from_config(config, base.base_dir).unwrap()
}

fn techniques(c: &mut Criterion) {
    let gpu = GpuContext::new(grassbench::gpu::BackendChoice::from_env().unwrap()).unwrap();
    let size = if small() {
        Size {
            width: 160,
            height: 90,
        }
    } else {
        Size {
            width: 640,
            height: 360,
        }
    };
    for entry in registry::TECHNIQUES {
        let id = entry.info.id;
        let mut harness = Harness::new(&gpu, scene(), size, false).unwrap();
        let mut technique = harness.create(entry, &toml::Table::new()).unwrap();
        // Warm up: shader compilation, caches.
        for f in 0..3 {
            harness.frame(technique.as_mut(), f, false).unwrap();
        }
        let mut group = c.benchmark_group(id);
        group
            .sample_size(10)
            .warm_up_time(Duration::from_millis(500))
            .measurement_time(Duration::from_secs(if small() { 1 } else { 5 }));
        let blades = technique.stats().blades_shown();
        group.throughput(Throughput::Elements(blades.max(1)));
        let mut frame = 3;
        group.bench_function("update", |b| {
            b.iter(|| {
                frame += 1;
                harness.update_only(technique.as_mut(), frame).unwrap();
            });
        });
        group.bench_function("prepare+encode", |b| {
            b.iter(|| harness.record(technique.as_mut(), frame).unwrap());
        });
        group.bench_function("gpu frame", |b| {
            b.iter(|| {
                frame += 1;
                harness.frame(technique.as_mut(), frame, false).unwrap()
            });
        });
        group.finish();
    }
}

fn kernels(c: &mut Criterion) {
    let scene = scene();
    let mut group = c.benchmark_group("kernels");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(if small() { 1 } else { 3 }));
    let wind = scene.wind().unwrap();
    let points: Vec<Vec3> = (0..10_000)
        .map(|i| {
            Vec3::new(
                (i % 100) as f32 * 0.7 - 35.0,
                0.5,
                (i / 100) as f32 * 0.7 - 35.0,
            )
        })
        .collect();
    group.throughput(Throughput::Elements(points.len() as u64));
    group.bench_function("breeze velocity", |b| {
        b.iter(|| {
            points
                .iter()
                .map(|p| wind.velocity(*p, 1.5))
                .fold(Vec3::ZERO, |a, v| a + v)
        });
    });
    let area = grassbench::glam::Vec2::splat(if small() { 5.0 } else { 20.0 });
    let count = scene.blades.blades_in(-area, area, &scene.terrain).len() as u64;
    group.throughput(Throughput::Elements(count));
    group.bench_function("blade field generation", |b| {
        b.iter(|| scene.blades.blades_in(-area, area, &scene.terrain))
    });
    group.finish();
}

criterion_group!(benches, techniques, kernels);
criterion_main!(benches);

//! Perbet's start-up pre-computation (Sec. 2.2 and 3.2): building the patches' 3D blades,
//! painting their strip and 2D textures with mip chains, and simulating the postures, for the
//! three quality presets on the meadow scene. Issue 7's target: under 10 s here. Run:
//! `cargo bench -p grassbench-perbet --bench precompute`.

use std::path::Path;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use grassbench::Scene;
use grassbench_perbet::precompute::Precomputed;
use grassbench_perbet::{Density, Params, Quality};

fn bench_precompute(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../experiments/scenes/meadow.toml");
    let Ok(scene) = Scene::load(&path) else {
        return;
    };
    let mut group = c.benchmark_group("perbet_precompute");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(5));
    for (name, quality) in [
        ("low", Quality::Low),
        ("medium", Quality::Medium),
        ("high", Quality::High),
    ] {
        let params = Params {
            quality,
            density: Density::Preset,
            ..Params::default()
        };
        group.bench_function(name, |b| b.iter(|| Precomputed::new(&scene, &params)));
    }
    group.finish();
}

criterion_group!(benches, bench_precompute);
criterion_main!(benches);

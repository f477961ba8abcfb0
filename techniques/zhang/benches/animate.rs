//! CPU blade animation throughput (Zhang Sec. 3.2): one frame of `Animation::step` over a
//! prairie of 4 x 4 grass grids of 32 x 32 blades on flat ground (16 384 blades, 3 moving
//! control points each, plus ~2 % flowers), in three winds: the fluid field of the thesis
//! (tiled 8³ Stam solver, trilinear sampling), the core's breeze (procedural, costlier per
//! sample) and calm air (the physics alone). Throughput in blades per second; control-point
//! updates per second are 3x that. Run: `cargo bench -p grassbench-zhang --bench animate`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use grassbench::glam::Vec2;
use grassbench::grass::{BladeField, GrassConfig};
use grassbench::terrain::Terrain;
use grassbench::wind::{Breeze, BreezeConfig, Calm, FluidConfig, FluidWind, WindField};
use grassbench_zhang::{Animation, Params, prairie};

fn bench_animate(c: &mut Criterion) {
    let terrain = Terrain::flat(Vec2::new(20.0, 20.0));
    // The thesis' lattice (32 x 32 a grid), whatever the density.
    let params = Params {
        grids: 4,
        blades_per_side: 32,
        ..Params::default()
    };
    let field = BladeField::new(GrassConfig::default(), 1);
    let (_, planted) = prairie::plant(&params, &field, &terrain, 1);
    let Ok(mut fluid) = FluidWind::new(FluidConfig::default(), 1, &terrain) else {
        return;
    };
    for f in 0..60 {
        fluid.advance(f as f32 / 30.0, 1.0 / 30.0);
    }
    let winds: [(&str, Box<dyn WindField>); 3] = [
        ("fluid", Box::new(fluid)),
        ("breeze", Box::new(Breeze::new(BreezeConfig::default(), 1))),
        ("calm", Box::new(Calm)),
    ];
    let mut group = c.benchmark_group("zhang_animate");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(3));
    group.throughput(Throughput::Elements(planted.len() as u64));
    for (name, wind) in &winds {
        let mut animation = Animation::new(&planted, params.flower_mass);
        let mut time = 0.0;
        group.bench_function(*name, |b| {
            b.iter(|| {
                time += 1.0 / 30.0;
                animation.step(
                    wind.as_ref(),
                    black_box(time),
                    1.0 / 30.0,
                    params.wind_response,
                    params.spring,
                    params.damping,
                );
            });
        });
    }
    group.finish();
}

criterion_group!(benches, bench_animate);
criterion_main!(benches);

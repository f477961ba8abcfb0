//! Steps per second of the 3D Stam solver (Zhang Ch. 2) for N = 8, 16, 32, 64, default
//! parameters (consistent projection, 20 Gauss–Seidel sweeps). Throughput is reported in
//! interior cells (N³) per second; the time per iteration is one `step` (sources + vel_step +
//! dens_step). Run: `cargo bench -p grassbench-cli --bench stam`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use grassbench::wind::fluid::{Poisson, StamParams, StamSolver};

fn bench_step(c: &mut Criterion) {
    for poisson in [Poisson::Consistent, Poisson::Compact] {
        let mut group = c.benchmark_group(format!("stam_step_{poisson:?}").to_lowercase());
        group.sample_size(10);
        group.warm_up_time(Duration::from_millis(500));
        group.measurement_time(Duration::from_secs(2));
        for n in [8usize, 16, 32, 64] {
            let params = StamParams {
                n,
                source_cell: [n / 2; 3],
                poisson,
                ..StamParams::default()
            };
            let Ok(mut solver) = StamSolver::new(params) else {
                continue;
            };
            // Develop a non-trivial flow first.
            for _ in 0..10 {
                solver.step(0.1);
            }
            group.throughput(Throughput::Elements((n * n * n) as u64));
            group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
                b.iter(|| solver.step(black_box(0.1)));
            });
        }
        group.finish();
    }
}

criterion_group!(benches, bench_step);
criterion_main!(benches);

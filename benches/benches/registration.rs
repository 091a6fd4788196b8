//! One pseudo-measurement update of the stacked bias estimate (seed 004 eqs (33)-(35)) at
//! S = 2, 4, 8, 16 sensors (bias state 4S, measurement 2(S-1)), stack (nalgebra) vs faer.

use argus_core_math::faer::Mat;
use argus_core_math::{Matrix, Vector};
use argus_registration::{Backend, BiasEstimator, PseudoMeasurement};
use criterion::{BatchSize, BenchmarkId, Criterion, criterion_group, criterion_main};

fn measurement(s: usize) -> Option<PseudoMeasurement> {
    let d = 4 * s;
    let m = 2 * (s - 1);
    let h = Mat::from_fn(m, d, |i, j| ((i * 7 + j * 3) % 11) as f64 * 0.1 - 0.5);
    let z = Mat::from_fn(m, 1, |i, _| i as f64 * 0.3);
    let r = Mat::from_fn(m, m, |i, j| {
        if i == j {
            200.0
        } else if i % 2 == j % 2 {
            100.0
        } else {
            0.0
        }
    });
    PseudoMeasurement::new(z, h, r).ok()
}

fn pseudo_update(c: &mut Criterion) {
    let mut g = c.benchmark_group("registration/pseudo_update");
    let prior = Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(1e4, 0.04, 1e-4, 1e-2));
    for s in [2usize, 4, 8, 16] {
        let (Some(pm), Ok(est)) = (measurement(s), BiasEstimator::new(s, &prior)) else {
            continue;
        };
        for (name, backend) in [("stack", Backend::Stack), ("faer", Backend::Faer)] {
            let mut e = est.clone();
            e.set_backend(backend);
            g.bench_with_input(BenchmarkId::new(name, s), &pm, |b, pm| {
                b.iter_batched(
                    || e.clone(),
                    |mut x| {
                        let _ = x.update(std::hint::black_box(pm));
                        x
                    },
                    BatchSize::SmallInput,
                );
            });
        }
    }
    g.finish();
}

criterion_group!(benches, pseudo_update);
criterion_main!(benches);

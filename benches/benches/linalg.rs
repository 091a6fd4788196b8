//! nalgebra (stack, const-generic) vs faer (heap, run-time sized) Cholesky
//! factor + solve of an SPD system, at 4×4, 8×8 and 64×64.
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use faer::linalg::solvers::Solve;
use faer::{Mat, Side};
use nalgebra::{SMatrix, SVector};

/// The configuration shared by every group in this file.
fn config() -> Criterion {
    Criterion::default()
        .sample_size(60)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
}

/// A well-conditioned SPD matrix `A = M Mᵀ + n I`, `M[i][j] = sin(i + 2j + 1)`.
fn spd_entry(n: usize, i: usize, j: usize) -> f64 {
    let m = |a: usize, b: usize| ((a + 2 * b + 1) as f64).sin();
    let dot: f64 = (0..n).map(|k| m(i, k) * m(j, k)).sum();
    dot + if i == j { n as f64 } else { 0.0 }
}

fn nalgebra_case<const N: usize>(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
) {
    let a = SMatrix::<f64, N, N>::from_fn(|i, j| spd_entry(N, i, j));
    let b = SVector::<f64, N>::from_fn(|i, _| i as f64 + 1.0);
    g.bench_with_input(
        BenchmarkId::new("nalgebra_static", N),
        &(a, b),
        |bch, (a, b)| {
            bch.iter(|| black_box(*a).cholesky().unwrap().solve(black_box(b)));
        },
    );
}

fn faer_case(g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>, n: usize) {
    let a = Mat::<f64>::from_fn(n, n, |i, j| spd_entry(n, i, j));
    let b = Mat::<f64>::from_fn(n, 1, |i, _| i as f64 + 1.0);
    g.bench_with_input(BenchmarkId::new("faer", n), &(a, b), |bch, (a, b)| {
        bch.iter(|| black_box(a).llt(Side::Lower).unwrap().solve(black_box(b)));
    });
}

fn cholesky_solve(c: &mut Criterion) {
    let mut g = c.benchmark_group("cholesky_solve");
    nalgebra_case::<4>(&mut g);
    faer_case(&mut g, 4);
    nalgebra_case::<8>(&mut g);
    faer_case(&mut g, 8);
    nalgebra_case::<64>(&mut g);
    faer_case(&mut g, 64);
    g.finish();
}

criterion_group! {
    name = benches;
    config = config();
    targets = cholesky_solve
}
criterion_main!(benches);

//! Filter steps (predict + update) on a 2-D constant-velocity state `[x, vx, y, vy]`.
//!
//! Targets (issue 2) on the 2-core project machine: KF step ≤ 150 ns (2-D position
//! plot), EKF step ≤ 300 ns (polar plot), UKF step ≤ 1.5 µs (polar plot).
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use std::hint::black_box;
use std::time::Duration;

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{CovarianceForm, Ekf, GaussianFilter, Kf, Ukf, UtParams};
use argus_motion_models::Cv2D;
use argus_sensors::{CartesianPosition, MeasurementModel, Polar2D, RadarNoise};
use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};

/// The configuration shared by every group in this file.
fn config() -> Criterion {
    Criterion::default()
        .sample_size(60)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
}

fn prior() -> Gaussian<4> {
    #[rustfmt::skip]
    let p = Matrix::<4, 4>::new(
        900.0, 60.0, 100.0, 0.0,
        60.0, 100.0, 0.0, 5.0,
        100.0, 0.0, 900.0, 60.0,
        0.0, 5.0, 60.0, 100.0,
    );
    Gaussian::new(Vector::<4>::new(20_000.0, -100.0, 10_000.0, 50.0), p).unwrap()
}

/// One step: predict over `dt`, then update with plot `z`.
fn step<F: GaussianFilter<4>, Me: MeasurementModel<4, 2>>(
    f: &F,
    est: &Gaussian<4>,
    meas: &Me,
    z: &Vector<2>,
) -> Gaussian<4> {
    let pred = f.predict(est, 2.0).unwrap();
    f.update(&pred, meas, z).unwrap().0
}

fn filters(c: &mut Criterion) {
    let cv = Cv2D::discrete(0.5).unwrap();
    let est = prior();
    let pos = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::new(400.0, 50.0, 50.0, 300.0)).unwrap();
    let z_pos = Vector::<2>::new(19_810.0, 10_095.0);
    let polar = Polar2D::cv([0.0, 0.0], RadarNoise::constant(30.0, 0.01, 0.0).unwrap()).unwrap();
    let z_polar = polar.predict(&Vector::<4>::new(19_810.0, -100.0, 10_095.0, 50.0));

    let mut g = c.benchmark_group("filters");
    for (label, form) in [
        ("joseph", CovarianceForm::Joseph),
        ("standard", CovarianceForm::Standard),
    ] {
        let kf = Kf::with_form(cv, form);
        g.bench_with_input(BenchmarkId::new("kf_step_pos2", label), &est, |b, e| {
            b.iter(|| step(&kf, black_box(e), &pos, black_box(&z_pos)));
        });
        let ekf = Ekf::with_form(cv, form);
        g.bench_with_input(BenchmarkId::new("ekf_step_polar", label), &est, |b, e| {
            b.iter(|| step(&ekf, black_box(e), &polar, black_box(&z_polar)));
        });
    }
    let ukf = Ukf::new(cv, UtParams::default()).unwrap();
    g.bench_with_input(
        BenchmarkId::new("ukf_step_polar", "default"),
        &est,
        |b, e| {
            b.iter(|| step(&ukf, black_box(e), &polar, black_box(&z_polar)));
        },
    );
    g.finish();
}

criterion_group! {
    name = benches;
    config = config();
    targets = filters
}
criterion_main!(benches);

//! GLRT maneuver detection (seed 001): one detector step against the onset window
//! length `M` (5, 20, 50), and one adaptive-filter step against one plain KF step, on
//! the 1-D maneuver scenario (T = 0.05 s, R = 36 m²).
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use std::hint::black_box;

use argus_adaptive::{
    Compensation, FailureKind, Glrt, GlrtConfig, ManeuverFilter, ManeuverState, ModelInput,
    StepLinearization,
};
use argus_core_math::{Gaussian, Matrix, SpdFactor, Vector};
use argus_filters::{GaussianFilter, Kf};
use argus_motion_models::Cv1D;
use argus_sensors::CartesianPosition;
use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};

const T: f64 = 0.05;

fn glrt_step(c: &mut Criterion) {
    let mut group = c.benchmark_group("glrt_step");
    let phi = Matrix::<2, 2>::new(1.0, T, 0.0, 1.0);
    let gamma = Matrix::<2, 1>::new(0.5 * T * T, T);
    let h = Matrix::<1, 2>::new(1.0, 0.0);
    let gain = Matrix::<2, 1>::new(0.3, 1.2);
    let s = SpdFactor::new(&Matrix::<1, 1>::new(50.0), "S").unwrap();
    for m in [5usize, 20, 50] {
        // Threshold out of reach: the window stays full, every step costs M + 1 updates.
        let mut glrt =
            Glrt::<2, 1, 1>::new(GlrtConfig::new(m, 0, 1e300, FailureKind::Persistent).unwrap());
        let mut k = 0u64;
        group.bench_with_input(BenchmarkId::from_parameter(m), &m, |b, _| {
            b.iter(|| {
                k += 1;
                let r = Vector::<1>::new(((k % 7) as f64 - 3.0) * 2.0);
                let out = glrt
                    .step(&StepLinearization {
                        phi: &phi,
                        gamma: &gamma,
                        h: &h,
                        gain: &gain,
                        s_factor: &s,
                        residual: &r,
                    })
                    .unwrap();
                glrt.commit();
                black_box(out)
            });
        });
    }
    group.finish();
}

fn adaptive_vs_kf(c: &mut Criterion) {
    let model = Cv1D::discrete(5.0).unwrap();
    let kf = Kf::new(model);
    let meas = CartesianPosition::<2, 1>::new([0], Matrix::<1, 1>::new(36.0)).unwrap();
    let init = Gaussian::new(
        Vector::<2>::new(2000.0, 70.0),
        Matrix::<2, 2>::identity() * 100.0,
    )
    .unwrap();
    let mut group = c.benchmark_group("adaptive_step_1d");
    group.bench_function("plain_kf", |b| {
        let mut est = init;
        let mut k = 0u64;
        b.iter(|| {
            k += 1;
            let z = Vector::<1>::new(2000.0 + 70.0 * T * k as f64);
            let pred = kf.predict(&est, T).unwrap();
            est = kf.update(&pred, &meas, &z).unwrap().0;
            black_box(&est);
        });
    });
    for comp in [Compensation::Glrt, Compensation::GlrtMras] {
        let ad = ManeuverFilter::new(
            Kf::new(model),
            ModelInput::new(model, Matrix::<2, 1>::new(0.0, 1.0)).unwrap(),
            comp,
        );
        let cfg = GlrtConfig::new(20, 5, 1e300, FailureKind::Persistent).unwrap();
        group.bench_function(BenchmarkId::new("adaptive_m20", format!("{comp:?}")), |b| {
            let mut st = ManeuverState::<2, 1, 1>::new(init, cfg);
            let mut k = 0u64;
            b.iter(|| {
                k += 1;
                let z = Vector::<1>::new(2000.0 + 70.0 * T * k as f64);
                black_box(ad.step(&mut st, T, &meas, &z).unwrap());
            });
        });
    }
    group.finish();
}

criterion_group!(benches, glrt_step, adaptive_vs_kf);
criterion_main!(benches);

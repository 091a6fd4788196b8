//! Data association in clutter (seed 002): gate + PDA update with 1, 3, 10, 30 and 100 plots
//! in the gate, one PSN update with 10 gated plots, and the HYCA (own gain and the plain
//! NN's Kalman gain) and PDA-IRF recursions to steady state (2-D CV, σ = 20 m,
//! σ_a = 1 m/s², γ = 16, P_D = 0.9, λ = 1e-5 m⁻²).
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use std::hint::black_box;

use argus_association::{
    AmplitudeModel, Associator, Candidate, ClutterModel, Gate, LinearSystem, Pda,
    PerformancePredictor, PredictedFilter, Psn,
};
use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{GaussianFilter, Kf};
use argus_motion_models::{Cv2D, LinearMotionModel, MotionModel};
use argus_sensors::CartesianPosition;
use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};

/// `n` plots spread inside the gate (deterministic spiral, all with NIS < γ).
fn plots(center: &Vector<2>, s_sd: f64, n: usize) -> Vec<Candidate<2>> {
    (0..n)
        .map(|i| {
            let r = 3.5 * s_sd * ((i as f64 + 0.5) / n as f64).sqrt();
            let th = 2.399_963 * i as f64;
            Candidate::with_amplitude(
                center + Vector::<2>::new(r * th.cos(), r * th.sin()),
                3.0 + (i % 5) as f64,
            )
        })
        .collect()
}

fn association(c: &mut Criterion) {
    let kf = Kf::new(Cv2D::discrete(1.0).unwrap());
    let radar = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 400.0).unwrap();
    let gate = Gate::from_threshold(16.0, 2).unwrap();
    let prior = Gaussian::new(
        Vector::<4>::new(0.0, 20.0, 0.0, 10.0),
        Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(250.0, 30.0, 250.0, 30.0)),
    )
    .unwrap();
    let pred = kf.predict(&prior, 1.0).unwrap();
    let mp = kf.predict_measurement(&pred, &radar).unwrap();
    let s_sd = mp.s()[(0, 0)].sqrt();
    let pda = Pda::new(gate, 0.9, ClutterModel::Poisson { density: 1e-5 }).unwrap();
    let mut group = c.benchmark_group("pda_update");
    for n in [1usize, 3, 10, 30, 100] {
        let z = plots(mp.z_pred(), s_sd, n);
        assert_eq!(pda.associate(&pred, &mp, &radar, &z).unwrap().gated, n);
        group.bench_with_input(BenchmarkId::from_parameter(n), &z, |b, z| {
            b.iter(|| black_box(pda.associate(&pred, &mp, &radar, black_box(z)).unwrap()));
        });
    }
    group.finish();
    let amp = AmplitudeModel::from_detection_probability(10.0, 0.9).unwrap();
    let psn = Psn::new(gate, amp, 1e-5).unwrap();
    let z: Vec<_> = plots(mp.z_pred(), s_sd, 10)
        .into_iter()
        .map(|c| Candidate::with_amplitude(c.z, c.amplitude.unwrap() + amp.threshold()))
        .collect();
    c.bench_function("psn_update/10", |b| {
        b.iter(|| black_box(psn.associate(&pred, &mp, &radar, black_box(&z)).unwrap()));
    });
    let model = Cv2D::discrete(1.0).unwrap();
    let sys = LinearSystem::new(
        model.transition(1.0),
        model.process_noise(&Vector::<4>::zeros(), 1.0),
        Matrix::<2, 4>::new(1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0),
        Matrix::<2, 2>::identity() * 400.0,
    )
    .unwrap();
    let p0 = Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(400.0, 100.0, 400.0, 100.0));
    for (name, f) in [
        ("hyca_steady_state", PredictedFilter::NearestNeighbour),
        (
            "nn_kalman_gain_steady_state",
            PredictedFilter::NearestNeighbourKalmanGain,
        ),
        ("pda_irf_steady_state", PredictedFilter::Pda),
    ] {
        let pp = PerformancePredictor::new(sys, gate, 0.9, 1e-5, f).unwrap();
        c.bench_function(name, |b| {
            b.iter(|| black_box(pp.steady_state(black_box(&p0), 1e-9, 20_000).unwrap()));
        });
    }
}

criterion_group!(benches, association);
criterion_main!(benches);

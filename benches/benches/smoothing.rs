//! Smoothing (issue 19): the RTS / URTS backward pass over a 10 000-step track next to the
//! forward step that records it, and the IMM smoother's forward record and backward pass.
//! Rows `*_10000` are whole passes; divide by 10 000 for the cost per step.
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use std::hint::black_box;
use std::time::Duration;

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{Kf, RtsTrack, SmoothingFilter, Ukf, rts_step};
use argus_imm::{Imm, ImmEstimate, ImmTrack, MarkovMatrix};
use argus_motion_models::{CoordinatedTurn, Cv2D, PlanarModel};
use argus_sensors::CartesianPosition;
use criterion::{BatchSize, BenchmarkId, Criterion, criterion_group, criterion_main};

const STEPS: usize = 10_000;

/// The configuration shared by every group in this file.
fn config() -> Criterion {
    Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
}

fn prior() -> Gaussian<4> {
    let p = Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(900.0, 100.0, 900.0, 100.0));
    Gaussian::new(Vector::<4>::new(20_000.0, -100.0, 10_000.0, 50.0), p).unwrap()
}

fn plot(k: usize) -> (f64, Vector<2>) {
    let t = 2.0 * k as f64;
    let wobble = 20.0 * (0.1 * t).sin();
    (
        t,
        Vector::<2>::new(20_000.0 - 100.0 * t + wobble, 10_000.0 + 50.0 * t - wobble),
    )
}

fn record<F: SmoothingFilter<4>>(f: &F, pos: &CartesianPosition<4, 2>) -> RtsTrack<4> {
    let mut track = RtsTrack::with_capacity(0.0, prior(), STEPS + 1).unwrap();
    for k in 1..=STEPS {
        let (t, z) = plot(k);
        track.step(f, t, pos, &z).unwrap();
    }
    track
}

fn smoothing(c: &mut Criterion) {
    let cv = Cv2D::discrete(0.5).unwrap();
    let pos = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::new(400.0, 50.0, 50.0, 300.0)).unwrap();
    let kf = Kf::new(cv);
    let ukf = Ukf::with_defaults(cv).unwrap();
    let mut g = c.benchmark_group("smoothing");
    for (label, urts) in [("rts_kf", false), ("urts_ukf", true)] {
        let track = if urts {
            record(&ukf, &pos)
        } else {
            record(&kf, &pos)
        };
        let mut out = vec![prior(); STEPS + 1];
        g.bench_function(BenchmarkId::new("backward_10000", label), |b| {
            b.iter(|| track.smooth_into(black_box(&mut out)).unwrap());
        });
        // One recorded forward step (predict with cross covariance + update + push); the
        // track's construction and drop are outside the timing.
        let (t, z) = plot(1);
        g.bench_function(BenchmarkId::new("forward_step", label), |b| {
            b.iter_batched(
                || RtsTrack::with_capacity(0.0, prior(), 2).unwrap(),
                |mut tr| {
                    if urts {
                        tr.step(&ukf, t, &pos, black_box(&z)).unwrap();
                    } else {
                        tr.step(&kf, t, &pos, black_box(&z)).unwrap();
                    }
                    tr
                },
                BatchSize::SmallInput,
            );
        });
        // One backward step alone.
        let (s1, s0) = (&track.steps()[1], &track.steps()[0]);
        let tr = *s1.transition().unwrap();
        g.bench_function(BenchmarkId::new("backward_step", label), |b| {
            b.iter(|| rts_step(black_box(s0.filtered()), &tr, black_box(s1.filtered())).unwrap());
        });
    }

    // The IMM of seed 000 (CV + 2 CT) on position plots.
    let ct = |w: f64| {
        Kf::new(PlanarModel::from(
            CoordinatedTurn::from_degrees_per_second(w, 0.5).unwrap(),
        ))
    };
    let imm = Imm::new(
        [
            Kf::new(PlanarModel::from(Cv2D::discrete(0.1).unwrap())),
            ct(3.0),
            ct(-3.0),
        ],
        MarkovMatrix::new([[0.95, 0.025, 0.025], [0.05, 0.95, 0.0], [0.05, 0.0, 0.95]]).unwrap(),
    )
    .unwrap();
    let start = ImmEstimate::from_common(prior(), [1.0 / 3.0; 3]).unwrap();
    let mut track = ImmTrack::new(*imm.markov(), 0.0, start).unwrap();
    track.reserve(STEPS);
    for k in 1..=STEPS {
        let (t, z) = plot(k);
        track.step(&imm, t, &pos, &z).unwrap();
    }
    g.bench_function(BenchmarkId::new("backward_10000", "imm_cv_2ct"), |b| {
        b.iter(|| track.smooth().unwrap());
    });
    let (t, z) = plot(1);
    g.bench_function(BenchmarkId::new("forward_step", "imm_cv_2ct"), |b| {
        b.iter_batched(
            || {
                let mut tr = ImmTrack::new(*imm.markov(), 0.0, start).unwrap();
                tr.reserve(1);
                tr
            },
            |mut tr| {
                tr.step(&imm, t, &pos, black_box(&z)).unwrap();
                tr
            },
            BatchSize::SmallInput,
        );
    });
    g.finish();
}

criterion_group! {
    name = benches;
    config = config();
    targets = smoothing
}
criterion_main!(benches);

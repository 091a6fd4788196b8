//! The multi-target tracker (issue 9): one scan at 100, 1 000 and 10 000 targets with
//! 10 % clutter (as many clutter plots as a tenth of the targets, uniform over the
//! coverage), P_D = 1, with GNN and with JPDA (exact events up to 1 000 per cluster). Targets sit on a 3 km grid with random headings
//! at 150–250 m/s, 5 s scans, σ = 50 m; the tracker has run 5 scans so every target
//! has a confirmed track. The timed part is one `process_scan` on a clone of that
//! tracker (the clone is made outside the timing).
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use std::hint::black_box;

use argus_core_math::{Matrix, Vector};
use argus_tracker::{AssociationConfig, Plot, SensorId, Tracker, TrackerConfig};
use criterion::{BatchSize, BenchmarkId, Criterion, criterion_group, criterion_main};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

const T: f64 = 5.0;
const SIGMA: f64 = 50.0;
const SPACING: f64 = 3000.0;

fn gauss(rng: &mut ChaCha8Rng) -> f64 {
    // Box–Muller: enough for a bench's plot noise.
    let u1: f64 = 1.0 - rng.random::<f64>();
    let u2: f64 = rng.random::<f64>();
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// The scan at time `t` of `n` targets (positions `p0 + v t`) plus `n / 10` clutter plots.
fn scan(rng: &mut ChaCha8Rng, targets: &[(Vector<2>, Vector<2>)], t: f64, side: f64) -> Vec<Plot> {
    let cov = Matrix::<2, 2>::identity() * (SIGMA * SIGMA);
    let mut plots: Vec<Plot> = targets
        .iter()
        .map(|(p0, v)| {
            Plot::cartesian(
                t,
                SensorId(0),
                p0 + v * t + Vector::<2>::new(SIGMA * gauss(rng), SIGMA * gauss(rng)),
                cov,
            )
        })
        .collect();
    for _ in 0..targets.len() / 10 {
        plots.push(Plot::cartesian(
            t,
            SensorId(0),
            Vector::<2>::new(side * rng.random::<f64>(), side * rng.random::<f64>()),
            cov,
        ));
    }
    plots
}

fn one_scan(c: &mut Criterion) {
    for jpda in [false, true] {
        scans(c, jpda);
    }
}

fn scans(c: &mut Criterion, jpda: bool) {
    let mut group = c.benchmark_group(if jpda {
        "tracker_jpda_scan"
    } else {
        "tracker_gnn_scan"
    });
    group.sample_size(10);
    for n in [100usize, 1_000, 10_000] {
        let mut rng = ChaCha8Rng::seed_from_u64(9);
        let per_side = (n as f64).sqrt().ceil() as usize;
        let side = per_side as f64 * SPACING;
        let targets: Vec<(Vector<2>, Vector<2>)> = (0..n)
            .map(|k| {
                let p0 = Vector::<2>::new(
                    (k % per_side) as f64 * SPACING,
                    (k / per_side) as f64 * SPACING,
                );
                let speed = 150.0 + 100.0 * rng.random::<f64>();
                let heading = std::f64::consts::TAU * rng.random::<f64>();
                (
                    p0,
                    Vector::<2>::new(speed * heading.cos(), speed * heading.sin()),
                )
            })
            .collect();
        let mut cfg = TrackerConfig::new(vec![SensorId(0)]);
        if jpda {
            cfg.association = AssociationConfig::Jpda {
                p_detection: 0.99,
                clutter_density: (n / 10).max(1) as f64 / (side * side),
                max_exact_events: 1000,
            };
        }
        let mut tracker = Tracker::new(cfg).unwrap();
        for k in 0..5 {
            let t = T * f64::from(k);
            tracker
                .process_scan(t, SensorId(0), &scan(&mut rng, &targets, t, side))
                .unwrap();
            tracker.take_deleted();
        }
        let t = 5.0 * T;
        let next = scan(&mut rng, &targets, t, side);
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter_batched(
                || tracker.clone(),
                |mut tr| black_box(tr.process_scan(t, SensorId(0), &next).unwrap()),
                BatchSize::LargeInput,
            );
        });
    }
    group.finish();
}

criterion_group!(benches, one_scan);
criterion_main!(benches);

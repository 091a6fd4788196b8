//! The multi-target tracker (issue 9): one scan at 100, 1 000 and 10 000 targets with
//! 10 % clutter (as many clutter plots as a tenth of the targets, uniform over the
//! coverage), P_D = 1, with GNN and with JPDA (exact events up to 1 000 per cluster).
//! Targets sit on a 3 km grid with random headings at 150–250 m/s, 5 s scans, σ = 50 m;
//! the tracker has run 5 scans so every target has a confirmed track.
//!
//! `tracker_aircraft_gnn_scan`: the same targets (100 and 1 000) as polar plots of one
//! radar 20 km off the grid's corner (σr = 50 m, σθ = 1 mrad, no clutter), tracked with
//! the aircraft IMM per track (`EstimatorConfig::Aircraft`, default tuning) and GNN.
//!
//! The timed part is one `process_scan` of a tracker in operation: a tracker runs the
//! following scans one after the other, each timed alone. Every `CYCLE` scans it is
//! replaced (untimed) by a clone of the warmed-up tracker, whose first scan is run
//! untimed too: a fresh clone's buffers have no spare capacity, so its first scan pays
//! for growing them, which a running tracker does not. (An earlier version timed one
//! scan of a fresh clone and also its drop: at 10 000 targets that measured the
//! allocator and page faults more than the tracker.)
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use std::hint::black_box;

use argus_core_math::{Matrix, Vector};
use argus_tracker::{
    AircraftTuning, AssociationConfig, EstimatorConfig, Plot, SensorConfig, SensorId, Tracker,
    TrackerConfig,
};
use std::time::{Duration, Instant};

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

const T: f64 = 5.0;
const SIGMA: f64 = 50.0;
const SPACING: f64 = 3000.0;
/// Scans run by one tracker before it is replaced by a fresh clone.
const CYCLE: usize = 8;

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
            .unwrap()
        })
        .collect();
    for _ in 0..targets.len() / 10 {
        plots.push(
            Plot::cartesian(
                t,
                SensorId(0),
                Vector::<2>::new(side * rng.random::<f64>(), side * rng.random::<f64>()),
                cov,
            )
            .unwrap(),
        );
    }
    plots
}

fn one_scan(c: &mut Criterion) {
    for jpda in [false, true] {
        scans(c, jpda);
    }
    aircraft_scans(c);
}

/// The radar of the aircraft bench, off the grid's corner.
const RADAR: [f64; 2] = [-20_000.0, -20_000.0];
const SIGMA_R: f64 = 50.0;
const SIGMA_AZ: f64 = 1e-3;

/// The polar scan at time `t` of `targets` from [`RADAR`].
fn polar_scan(rng: &mut ChaCha8Rng, targets: &[(Vector<2>, Vector<2>)], t: f64) -> Vec<Plot> {
    targets
        .iter()
        .map(|(p0, v)| {
            let p = p0 + v * t;
            let (dx, dy) = (p[0] - RADAR[0], p[1] - RADAR[1]);
            Plot::polar(
                t,
                SensorId(0),
                dx.hypot(dy) + SIGMA_R * gauss(rng),
                dy.atan2(dx) + SIGMA_AZ * gauss(rng),
            )
            .unwrap()
        })
        .collect()
}

fn aircraft_scans(c: &mut Criterion) {
    let mut group = c.benchmark_group("tracker_aircraft_gnn_scan");
    group.sample_size(10);
    for n in [100usize, 1_000] {
        let mut rng = ChaCha8Rng::seed_from_u64(9);
        let targets = grid_targets(&mut rng, n);
        let mut cfg =
            TrackerConfig::new([SensorConfig::polar(SensorId(0), RADAR, SIGMA_R, SIGMA_AZ)]);
        cfg.estimator = EstimatorConfig::Aircraft {
            tuning: AircraftTuning::default(),
        };
        let mut tracker = Tracker::new(cfg).unwrap();
        for k in 0..5 {
            let t = T * f64::from(k);
            tracker
                .process_scan(t, SensorId(0), &polar_scan(&mut rng, &targets, t))
                .unwrap();
            tracker.take_deleted();
        }
        let next: Vec<(f64, Vec<Plot>)> = (0..CYCLE)
            .map(|k| {
                let t = T * (5.0 + k as f64);
                (t, polar_scan(&mut rng, &targets, t))
            })
            .collect();
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            time_scans(b, &tracker, &next);
        });
    }
    group.finish();
}

/// `n` targets on the 3 km grid, random headings at 150–250 m/s.
fn grid_targets(rng: &mut ChaCha8Rng, n: usize) -> Vec<(Vector<2>, Vector<2>)> {
    let per_side = (n as f64).sqrt().ceil() as usize;
    (0..n)
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
        .collect()
}

/// Times one `process_scan` of a running tracker (module docs): `next[0]` of each cycle
/// is the untimed warm-up of a fresh clone of `tracker`.
fn time_scans(b: &mut criterion::Bencher<'_>, tracker: &Tracker, next: &[(f64, Vec<Plot>)]) {
    let mut running = tracker.clone();
    let mut at = CYCLE;
    b.iter_custom(|iters| {
        let mut total = Duration::ZERO;
        for _ in 0..iters {
            if at == CYCLE {
                running = tracker.clone();
                let (t0, plots) = &next[0];
                running.process_scan(*t0, SensorId(0), plots).unwrap();
                at = 1;
            }
            let (t, plots) = &next[at];
            let start = Instant::now();
            black_box(running.process_scan(*t, SensorId(0), plots).unwrap());
            total += start.elapsed();
            running.take_deleted();
            at += 1;
        }
        total
    });
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
        // The next CYCLE scans, made once; scan 0 of each cycle is the untimed warm-up.
        let next: Vec<(f64, Vec<Plot>)> = (0..CYCLE)
            .map(|k| {
                let t = T * (5.0 + k as f64);
                (t, scan(&mut rng, &targets, t, side))
            })
            .collect();
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            let mut running = tracker.clone();
            let mut at = CYCLE;
            b.iter_custom(|iters| {
                let mut total = Duration::ZERO;
                for _ in 0..iters {
                    if at == CYCLE {
                        running = tracker.clone();
                        let (t0, plots) = &next[0];
                        running.process_scan(*t0, SensorId(0), plots).unwrap();
                        at = 1;
                    }
                    let (t, plots) = &next[at];
                    let start = Instant::now();
                    black_box(running.process_scan(*t, SensorId(0), plots).unwrap());
                    total += start.elapsed();
                    running.take_deleted();
                    at += 1;
                }
                total
            });
        });
    }
    group.finish();
}

criterion_group!(benches, one_scan);
criterion_main!(benches);

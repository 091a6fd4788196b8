//! The multi-target tracker on a rotating radar (issue 18): 1 000 aircraft within 150 km
//! of a clockwise 5-s radar (σr 70 m, σθ 0.08°, P_D = 1) and 100 clutter plots per
//! revolution, each plot at the time the beam crosses it, processed by sectors of 1/8
//! revolution (the default). The targets are uniform over the disc (20–150 km) with random
//! headings at 150–250 m/s; the tracker has run 6 revolutions, so every target has a
//! confirmed track.
//!
//! `tracker_sector_step/1000` times one sector: `process` of its plots and `advance_to`
//! its end (which processes it), on a tracker in operation. `tracker_sector_revolution/1000`
//! times the 8 sectors of one revolution. `session_sector_revolution/1000` times the same
//! revolution fed through an `argus_tracker::Session` (each plot an `Input::Plot`, each
//! sector end an `Input::Marker`), whose outputs are one `TrackSnapshot` per track per
//! sector: the tracker's work plus the session's (grouping, snapshots). As in the tracker bench, the tracker timed is a
//! clone of the warmed-up one that has first run one revolution untimed, so that its
//! buffers have the capacity a running tracker's have.
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use std::f64::consts::TAU;
use std::hint::black_box;
use std::time::{Duration, Instant};

use argus_tracker::{
    Input, Output, Plot, Rotation, SensorConfig, SensorId, Session, Tracker, TrackerConfig,
};
use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

const P: f64 = 5.0;
const SIGMA_R: f64 = 70.0;
const SIGMA_AZ: f64 = 0.08 * std::f64::consts::PI / 180.0;
const SECTORS: usize = 8;
/// Revolutions run before the timed ones.
const WARM: u32 = 6;

fn gauss(rng: &mut ChaCha8Rng) -> f64 {
    // Box–Muller: enough for a bench's plot noise.
    let u1: f64 = 1.0 - rng.random::<f64>();
    let u2: f64 = rng.random::<f64>();
    (-2.0 * u1.ln()).sqrt() * (TAU * u2).cos()
}

/// The plots of revolutions `[0, revs)`, in time order.
fn plots(n: usize, revs: u32) -> Vec<Plot> {
    let rot = Rotation::clockwise(P);
    let mut rng = ChaCha8Rng::seed_from_u64(18);
    let targets: Vec<([f64; 2], [f64; 2])> = (0..n)
        .map(|_| {
            let r = (20_000.0_f64.powi(2)
                + rng.random::<f64>() * (150_000.0_f64.powi(2) - 20_000.0_f64.powi(2)))
            .sqrt();
            let a = TAU * rng.random::<f64>();
            let speed = 150.0 + 100.0 * rng.random::<f64>();
            let h = TAU * rng.random::<f64>();
            (
                [r * a.cos(), r * a.sin()],
                [speed * h.cos(), speed * h.sin()],
            )
        })
        .collect();
    let end = P * f64::from(revs);
    let mut timed: Vec<(f64, f64, f64)> = Vec::new();
    for (p0, v) in &targets {
        let at = |t: f64| [p0[0] + v[0] * t, p0[1] + v[1] * t];
        let az = |t: f64| {
            let p = at(t);
            p[1].atan2(p[0])
        };
        let mut t = rot.crossing_after(az(0.0), 0.0);
        while t < end {
            for _ in 0..4 {
                t = rot.crossing_after(az(t), t - 0.5 * P);
            }
            let p = at(t);
            timed.push((
                t,
                p[0].hypot(p[1]) + SIGMA_R * gauss(&mut rng),
                az(t) + SIGMA_AZ * gauss(&mut rng),
            ));
            t = rot.crossing_after(az(t + 0.5 * P), t + 0.5 * P);
        }
    }
    for _ in 0..(n / 10) * revs as usize {
        let t = end * rng.random::<f64>();
        let r = 150_000.0 * rng.random::<f64>().sqrt();
        timed.push((t, r.max(1_000.0), rot.beam_azimuth(t)));
    }
    timed.sort_by(|a, b| a.0.total_cmp(&b.0));
    timed
        .into_iter()
        .map(|(t, r, a)| Plot::polar(t, SensorId(1), r, a).unwrap())
        .collect()
}

/// The plots of sector `k` (of the whole run), from `all`.
fn sector(all: &[Plot], k: usize) -> Vec<Plot> {
    let len = P / SECTORS as f64;
    let (a, b) = (k as f64 * len, (k + 1) as f64 * len);
    all.iter()
        .filter(|p| p.time() >= a && p.time() < b)
        .copied()
        .collect()
}

/// One sector through a session: its plots, then a marker at its end; the outputs' rows.
fn session_step(session: &mut Session, plots: &[Plot], end: f64, out: &mut Vec<Output>) -> usize {
    out.clear();
    for (tag, plot) in (0..).zip(plots) {
        session.push(Input::Plot { plot: *plot, tag }, out).unwrap();
    }
    session.push(Input::Marker(end), out).unwrap();
    out.len()
}

/// One sector: its plots, then time up to its end.
fn step(tracker: &mut Tracker, plots: &[Plot], end: f64) -> usize {
    tracker.process(plots).unwrap().len() + tracker.advance_to(end).unwrap().len()
}

fn sectors(c: &mut Criterion) {
    let n = 1_000;
    let all = plots(n, WARM + 2);
    let len = P / SECTORS as f64;
    let cfg = TrackerConfig::new([
        SensorConfig::polar(SensorId(1), [0.0, 0.0], SIGMA_R, SIGMA_AZ)
            .with_rotation(Rotation::clockwise(P)),
    ]);
    let mut warmed = Tracker::new(cfg.clone()).unwrap();
    let warm_sectors = WARM as usize * SECTORS;
    for k in 0..warm_sectors {
        step(&mut warmed, &sector(&all, k), (k + 1) as f64 * len);
        warmed.take_deleted();
    }
    let confirmed = warmed
        .tracks()
        .iter()
        .filter(|t| t.status() == argus_tracker::TrackStatus::Confirmed)
        .count();
    assert!(confirmed >= n * 95 / 100, "{confirmed} confirmed tracks");
    // Revolution WARM (untimed, to grow a clone's buffers) and WARM + 1 (timed).
    let untimed: Vec<(Vec<Plot>, f64)> = (warm_sectors..warm_sectors + SECTORS)
        .map(|k| (sector(&all, k), (k + 1) as f64 * len))
        .collect();
    let timed: Vec<(Vec<Plot>, f64)> = (warm_sectors + SECTORS..warm_sectors + 2 * SECTORS)
        .map(|k| (sector(&all, k), (k + 1) as f64 * len))
        .collect();
    let ready = || {
        let mut t = warmed.clone();
        for (p, end) in &untimed {
            step(&mut t, p, *end);
            t.take_deleted();
        }
        t
    };

    let mut group = c.benchmark_group("tracker_sector_step");
    group.sample_size(10);
    group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
        let mut running = ready();
        let mut at = 0;
        b.iter_custom(|iters| {
            let mut total = Duration::ZERO;
            for _ in 0..iters {
                if at == SECTORS {
                    running = ready();
                    at = 0;
                }
                let (p, end) = &timed[at];
                let start = Instant::now();
                black_box(step(&mut running, p, *end));
                total += start.elapsed();
                running.take_deleted();
                at += 1;
            }
            total
        });
    });
    group.finish();

    let mut group = c.benchmark_group("tracker_sector_revolution");
    group.sample_size(10);
    group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
        b.iter_custom(|iters| {
            let mut total = Duration::ZERO;
            for _ in 0..iters {
                let mut running = ready();
                let start = Instant::now();
                for (p, end) in &timed {
                    black_box(step(&mut running, p, *end));
                }
                total += start.elapsed();
            }
            total
        });
    });
    group.finish();

    // The same revolutions through a session warmed up the same way.
    let mut warm_session = Session::new(cfg).unwrap();
    let mut out = Vec::new();
    for k in 0..warm_sectors {
        session_step(
            &mut warm_session,
            &sector(&all, k),
            (k + 1) as f64 * len,
            &mut out,
        );
    }
    let ready_session = || {
        let mut s = warm_session.clone();
        let mut out = Vec::new();
        for (p, end) in &untimed {
            session_step(&mut s, p, *end, &mut out);
        }
        (s, out)
    };
    let mut group = c.benchmark_group("session_sector_revolution");
    group.sample_size(10);
    group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
        b.iter_custom(|iters| {
            let mut total = Duration::ZERO;
            for _ in 0..iters {
                let (mut running, mut out) = ready_session();
                let start = Instant::now();
                for (p, end) in &timed {
                    black_box(session_step(&mut running, p, *end, &mut out));
                }
                total += start.elapsed();
            }
            total
        });
    });
    group.finish();
}

criterion_group!(benches, sectors);
criterion_main!(benches);

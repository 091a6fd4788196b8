//! A sector's aircraft-IMM tracks allocate nothing per track: the state saved before a
//! track's look prediction is copied into a reused buffer, not cloned into a new box.
//!
//! Counting allocations needs a global allocator (`stats_alloc`, as the filters' no-alloc
//! test explains); this binary holds a single test so no other thread allocates while the
//! region is measured. The tracker itself allocates per sector for its reports, so the
//! check is that the allocations of a revolution do not grow with the number of tracks.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::alloc::System;

use argus_tracker::{
    AircraftTuning, EstimatorConfig, Plot, Rotation, SensorConfig, SensorId, Tracker, TrackerConfig,
};
use stats_alloc::{INSTRUMENTED_SYSTEM, Region, StatsAlloc};

#[global_allocator]
static GLOBAL: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

const P: f64 = 5.0;
const S1: SensorId = SensorId(1);

/// `n` aircraft 30–100 km out, spread in azimuth, flying straight at 200 m/s.
fn targets(n: usize) -> Vec<([f64; 2], [f64; 2])> {
    (0..n)
        .map(|k| {
            let az = 0.3 + 5.5 * k as f64 / n as f64;
            let r = 30_000.0 + 70_000.0 * ((k * 7) % n) as f64 / n as f64;
            let h = az + 1.0;
            (
                [r * az.cos(), r * az.sin()],
                [200.0 * h.cos(), 200.0 * h.sin()],
            )
        })
        .collect()
}

/// Noise-free plots where the beam crosses each aircraft in `[0, end)`, in time order.
fn plots(rotation: Rotation, targets: &[([f64; 2], [f64; 2])], end: f64) -> Vec<Plot> {
    let at = |(p, v): ([f64; 2], [f64; 2]), t: f64| [p[0] + v[0] * t, p[1] + v[1] * t];
    let az = |p: [f64; 2]| p[1].atan2(p[0]);
    let mut timed = Vec::new();
    for &tg in targets {
        let mut after = 0.0;
        loop {
            // Fixed point of t = crossing(azimuth(t)): the aircraft's angular rate is ~1 %
            // of the beam's, so a few steps converge to round-off.
            let mut t = rotation.crossing_after(az(at(tg, after)), after);
            for _ in 0..6 {
                t = rotation.crossing_after(az(at(tg, t)), t - 0.5 * P);
            }
            if t >= end {
                break;
            }
            let p = at(tg, t);
            timed.push(Plot::polar(t, S1, p[0].hypot(p[1]), az(p)).unwrap());
            after = t + 0.5 * P;
        }
    }
    timed.sort_by(|a, b| a.time().total_cmp(&b.time()));
    timed
}

/// Allocations while the tracker processes the last `measured` revolutions of `n`
/// aircraft, per revolution (the tracks confirmed long before).
fn allocations_per_revolution(n: usize) -> f64 {
    let rotation = Rotation::clockwise(P);
    let (warm, measured) = (20.0, 10.0);
    let all = plots(rotation, &targets(n), (warm + measured) * P);
    let split = all.partition_point(|p| p.time() < warm * P);
    let mut cfg =
        TrackerConfig::new([
            SensorConfig::polar(S1, [0.0, 0.0], 70.0, 0.08_f64.to_radians())
                .with_rotation(rotation),
        ]);
    cfg.estimator = EstimatorConfig::Aircraft {
        tuning: AircraftTuning::default(),
    };
    let mut tracker = Tracker::new(cfg).unwrap();
    for p in &all[..split] {
        tracker.process(std::slice::from_ref(p)).unwrap();
    }
    assert_eq!(tracker.tracks().len(), n, "one track per aircraft");
    let region = Region::new(GLOBAL);
    let mut reports = 0;
    for p in &all[split..] {
        reports += tracker.process(std::slice::from_ref(p)).unwrap().len();
    }
    let allocs = region.change().allocations;
    assert!(reports > 0, "sectors were concluded while measured");
    assert_eq!(tracker.tracks().len(), n, "no track lost while measured");
    allocs as f64 / measured
}

#[test]
fn a_sector_of_aircraft_tracks_allocates_nothing_per_track() {
    let few = allocations_per_revolution(8);
    let many = allocations_per_revolution(40);
    // 32 more tracks looked at every revolution: one allocation per track and look (the
    // clone this test guards against) would add 32 per revolution. Report vectors that
    // grow by doubling add a few at most (log₂ of the count); 8 is well below 32.
    assert!(
        many - few < 8.0,
        "allocations per revolution: {few} with 8 tracks, {many} with 40"
    );
}

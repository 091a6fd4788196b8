//! No heap allocation per smoothing step: recording into a track with room for its steps,
//! the RTS / URTS backward pass into a given output, and the fixed-lag smoother once its
//! window has filled run on stack matrices only. Counting allocator as in `no_alloc.rs`
//! (the `stats_alloc` crate; one test per binary so no other thread allocates).

// A test binary: a panic on an unexpected error is the failure report.
#![allow(clippy::unwrap_used)]

use std::alloc::System;

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{FixedLagSmoother, Kf, Lag, RtsTrack, SmoothingFilter, Ukf};
use argus_motion_models::Cv2D;
use argus_sensors::CartesianPosition;
use stats_alloc::{INSTRUMENTED_SYSTEM, Region, StatsAlloc};

#[global_allocator]
static GLOBAL: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

const STEPS: usize = 200;

fn prior() -> Gaussian<4> {
    let p = Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(400.0, 25.0, 400.0, 25.0));
    Gaussian::new(Vector::<4>::new(20_000.0, -100.0, 10_000.0, 50.0), p).unwrap()
}

fn plot(k: usize) -> (f64, Vector<2>) {
    let t = k as f64;
    (
        t,
        Vector::<2>::new(
            20_000.0 - 100.0 * t + 3.0 * (t * 0.7).sin(),
            10_000.0 + 50.0 * t,
        ),
    )
}

fn record<F: SmoothingFilter<4>>(f: &F, pos: &CartesianPosition<4, 2>, track: &mut RtsTrack<4>) {
    for k in 1..=STEPS {
        let (t, z) = plot(k);
        track.step(f, t, pos, &z).unwrap();
    }
}

#[test]
fn smoothing_does_not_allocate_per_step() {
    let cv = Cv2D::discrete(0.5).unwrap();
    let pos = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 100.0).unwrap();
    let kf = Kf::new(cv);
    let ukf = Ukf::with_defaults(cv).unwrap();

    // Control: the counter sees an allocation.
    let region = Region::new(GLOBAL);
    let v = std::hint::black_box(vec![1u8; 16]);
    assert_eq!(region.change().allocations, 1);
    drop(v);

    for (name, urts) in [("RTS", false), ("URTS", true)] {
        let mut track = RtsTrack::with_capacity(0.0, prior(), STEPS + 1).unwrap();
        let mut out = vec![prior(); STEPS + 1];
        let region = Region::new(GLOBAL);
        if urts {
            record(&ukf, &pos, &mut track);
        } else {
            record(&kf, &pos, &mut track);
        }
        let recording = region.change();
        let region = Region::new(GLOBAL);
        track.smooth_into(&mut out).unwrap();
        let backward = region.change();
        assert!(out.iter().all(|g| g.mean().iter().all(|v| v.is_finite())));
        assert_eq!(
            recording.allocations + recording.reallocations,
            0,
            "{name} forward: {recording:?}"
        );
        assert_eq!(
            backward.allocations + backward.reallocations,
            0,
            "{name} backward: {backward:?}"
        );
    }

    // Fixed lag: the window fills in the first steps; after that nothing is allocated.
    let mut fl = FixedLagSmoother::new(Lag::Steps(10), 0.0, prior()).unwrap();
    let mut warm = 0;
    for k in 1..=30 {
        let (t, z) = plot(k);
        fl.step(&kf, t, &pos, &z).unwrap();
        while fl.pop().is_some() {
            warm += 1;
        }
    }
    let region = Region::new(GLOBAL);
    let mut n = 0;
    for k in 31..=STEPS {
        let (t, z) = plot(k);
        fl.step(&kf, t, &pos, &z).unwrap();
        while let Some(l) = fl.pop() {
            n += usize::from(l.estimate.mean()[0].is_finite());
        }
    }
    let stats = region.change();
    // Steps 0 … 20 are out after step 30 (lag 10), one more per step after that.
    assert_eq!(warm, 21);
    assert_eq!(n, STEPS - 30);
    assert_eq!(
        stats.allocations + stats.reallocations,
        0,
        "fixed lag: {stats:?}"
    );
}

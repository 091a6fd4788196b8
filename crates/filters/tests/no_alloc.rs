//! No heap allocation per filter step: KF, EKF and UKF predict + update run on
//! stack matrices only.
//!
//! Counting allocations needs a `#[global_allocator]`; implementing `GlobalAlloc`
//! takes `unsafe impl`, which the workspace forbids (`unsafe_code = "forbid"`
//! cannot be relaxed by a local `allow`). The counting allocator therefore comes
//! from the `stats_alloc` crate; declaring it as the global allocator is safe code.
//! This binary holds a single test so that no other test thread allocates while
//! the region is measured.

// A test binary: a panic on an unexpected error is the failure report.
#![allow(clippy::unwrap_used)]

use std::alloc::System;

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{Ekf, GaussianFilter, Kf, Ukf, UtParams};
use argus_motion_models::Cv2D;
use argus_sensors::{CartesianPosition, Polar2D, RadarNoise};
use stats_alloc::{INSTRUMENTED_SYSTEM, Region, StatsAlloc};

#[global_allocator]
static GLOBAL: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

fn prior() -> Gaussian<4> {
    let p = Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(400.0, 25.0, 400.0, 25.0));
    Gaussian::new(Vector::<4>::new(20_000.0, -100.0, 10_000.0, 50.0), p).unwrap()
}

fn steps<F: GaussianFilter<4>>(
    f: &F,
    pos: &CartesianPosition<4, 2>,
    polar: &Polar2D<4>,
) -> Gaussian<4> {
    let mut est = prior();
    for k in 0..10 {
        let pred = f.predict(&est, 1.0).unwrap();
        let t = f64::from(k);
        let z = Vector::<2>::new(20_000.0 - 100.0 * t, 10_000.0 + 50.0 * t);
        est = f.update(&pred, pos, &z).unwrap().0;
        let pred = f.predict(&est, 1.0).unwrap();
        let zp = Vector::<2>::new(22_360.0, 0.4636);
        est = f.update(&pred, polar, &zp).unwrap().0;
    }
    est
}

#[test]
fn filter_steps_do_not_allocate() {
    let cv = Cv2D::discrete(0.5).unwrap();
    let pos = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 100.0).unwrap();
    let polar = Polar2D::cv([0.0, 0.0], RadarNoise::constant(30.0, 0.01, 0.0).unwrap()).unwrap();
    let kf = Kf::new(cv);
    let ekf = Ekf::new(cv);
    let ukf = Ukf::new(cv, UtParams::default()).unwrap();
    // Warm up (lazy statics, if any, allocate once outside the measured region).
    let _ = steps(&kf, &pos, &polar);
    let _ = steps(&ekf, &pos, &polar);
    let _ = steps(&ukf, &pos, &polar);

    // Control: the counter sees an allocation.
    let region = Region::new(GLOBAL);
    let v = std::hint::black_box(vec![1u8; 16]);
    assert_eq!(region.change().allocations, 1);
    drop(v);

    for (name, run) in [
        (
            "KF",
            &(|| steps(&kf, &pos, &polar)) as &dyn Fn() -> Gaussian<4>,
        ),
        ("EKF", &|| steps(&ekf, &pos, &polar)),
        ("UKF", &|| steps(&ukf, &pos, &polar)),
    ] {
        let region = Region::new(GLOBAL);
        let out = std::hint::black_box(run());
        let stats = region.change();
        assert!(out.mean().iter().all(|v| v.is_finite()));
        assert_eq!(stats.allocations, 0, "{name}: {stats:?}");
        assert_eq!(stats.reallocations, 0, "{name}: {stats:?}");
    }
}

//! No heap allocation per aircraft-IMM step (mixing across the two state sizes, EKF
//! predictions, polar updates, combination), counted with `stats_alloc` as in
//! crates/filters/tests/no_alloc.rs. One test in this binary, so that no other test
//! thread allocates while the region is measured.

// A test binary: a panic on an unexpected error is the failure report.
#![allow(clippy::unwrap_used, missing_docs)]

use std::alloc::System;

use argus_core_math::Vector;
use argus_imm::{AircraftEkf, AircraftEstimate, AircraftRadar, AircraftTuning};
use argus_sensors::RadarNoise;
use stats_alloc::{INSTRUMENTED_SYSTEM, Region, StatsAlloc};

#[global_allocator]
static GLOBAL: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

fn steps(
    imm: &AircraftEkf<2, 3>,
    radar: &AircraftRadar,
    start: &AircraftEstimate<2, 3>,
) -> AircraftEstimate<2, 3> {
    let mut est = *start;
    for k in 0..20 {
        let a = 0.3 + 0.01 * f64::from(k);
        let z = Vector::<2>::new(60_000.0 + 100.0 * f64::from(k), a);
        est = imm.step(&est, 5.0, radar, &z).unwrap().estimate;
        let pred = imm.predict(&est, 5.0).unwrap();
        let _ = pred.modes().combined().unwrap();
        est = pred.into_estimate();
    }
    let _ = est.combined().unwrap();
    est
}

#[test]
fn aircraft_imm_steps_do_not_allocate() {
    let tuning = AircraftTuning::<2, 3>::default();
    let imm = tuning.build().unwrap();
    let radar = AircraftRadar::new(
        [0.0, 0.0],
        RadarNoise::constant(70.0, 0.08_f64.to_radians(), 0.0).unwrap(),
    )
    .unwrap();
    let start = tuning
        .start(
            &radar,
            &Vector::<2>::new(59_000.0, 0.29),
            &Vector::<2>::new(59_500.0, 0.295),
            5.0,
        )
        .unwrap();
    let _ = steps(&imm, &radar, &start);

    // Control: the counter sees an allocation.
    let region = Region::new(GLOBAL);
    let v = std::hint::black_box(vec![1u8; 16]);
    assert_eq!(region.change().allocations, 1);
    drop(v);

    let region = Region::new(GLOBAL);
    let out = std::hint::black_box(steps(&imm, &radar, &start));
    let stats = region.change();
    assert!(out.combined().unwrap().mean().iter().all(|v| v.is_finite()));
    assert_eq!(stats.allocations, 0, "{stats:?}");
    assert_eq!(stats.reallocations, 0, "{stats:?}");
}

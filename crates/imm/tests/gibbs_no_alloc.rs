//! No heap allocation in a Gibbs sweep once the chain is made (its buffers are allocated by
//! `GibbsChain::new`), counted with `stats_alloc` as in aircraft_no_alloc.rs. One test in
//! this binary, so that no other test thread allocates while the region is measured.

// A test binary: a panic on an unexpected error is the failure report.
#![allow(clippy::unwrap_used, missing_docs)]

use std::alloc::System;

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::Kf;
use argus_imm::smooth::gibbs::{GibbsChain, GibbsProblem};
use argus_imm::{Imm, MarkovMatrix};
use argus_motion_models::{CoordinatedTurn, Cv2D, PlanarModel};
use argus_sensors::CartesianPosition;
use stats_alloc::{INSTRUMENTED_SYSTEM, Region, StatsAlloc};

#[global_allocator]
static GLOBAL: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

#[test]
fn gibbs_sweeps_do_not_allocate() {
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
    let pos = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 2500.0).unwrap();
    let start = Gaussian::new(
        Vector::<4>::new(0.0, 100.0, 0.0, 0.0),
        Matrix::<4, 4>::identity() * 1e4,
    )
    .unwrap();
    // 60 plots every 5 s, a turn in the middle (the positions need not be exact: any
    // plots exercise the same code).
    let times: Vec<f64> = (0..=60).map(|k| 5.0 * f64::from(k)).collect();
    let plots: Vec<_> = times[1..]
        .iter()
        .map(|t| {
            let bend = (t - 150.0).max(0.0);
            (pos, Vector::<2>::new(100.0 * t, 0.2 * bend * bend))
        })
        .collect();
    let problem = GibbsProblem::new(&imm, [1.0 / 3.0; 3], &start, &times, &plots).unwrap();
    let mut chain = GibbsChain::new(&problem, &vec![0; times.len()], 7, 4).unwrap();
    // Every sweep kind once (burn-in and recorded), then the measured sweeps.
    chain.sweep(4, false).unwrap();
    chain.sweep(4, true).unwrap();
    let region = Region::new(GLOBAL);
    for s in 0..20 {
        chain.sweep(4, s % 2 == 0).unwrap();
    }
    let stats = region.change();
    assert_eq!(chain.sweeps(), 11);
    assert_eq!(stats.allocations, 0, "{stats:?}");
    assert_eq!(stats.reallocations, 0, "{stats:?}");
}

//! Seed 001 "maneuver-1d": issue 17 §1 over the detection threshold η, for both
//! compensations — why no default η meets the whole requirement (docs/papers/
//! 001-maneuver-1d.md, "No threshold meets §1").
//!
//! The requirement at the default η, over ≥ 200 seeded runs: mean delay ≤ 0.5 s and 95th
//! percentile ≤ 0.7 s after every switch, and zero detections in the maneuver-free runs.
//! η is the only free parameter (SPEC 001 fixes a, T, R, q, M = 20, N = 5); the delays grow
//! with η and the false detections fall with it. Runs `0..n` of seed 1, as `argus run
//! maneuver-1d` (`--set eta2=… --set default_comp=0|1` prints the same numbers).
//! About 10 s in the dev profile.
#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use argus_adaptive::Compensation;
use argus_scenarios::experiments::maneuver_1d::{CASE2, Maneuver1dConfig, monte_carlo};

/// Delays are multiples of T = 0.05 s: 1e-9 s for their round-off. NaN (nothing detected)
/// counts as exceeding.
fn exceeds(v: f64, bound: f64) -> bool {
    v.is_nan() || v > bound + 1e-9
}

/// Whether every switch of case 2 has mean delay ≤ 0.5 s (issue 17 §1).
fn means_hold(eta: f64, comp: Compensation, runs: u64) -> bool {
    let s = monte_carlo(&Maneuver1dConfig::default(), CASE2, eta, comp, 0..runs).unwrap();
    (0..s.switches.len()).all(|i| !exceeds(s.delay_mean(i), 0.5))
}

/// Maneuver-free detections over runs `0..runs`.
fn false_detections(eta: f64, comp: Compensation, runs: u64) -> usize {
    monte_carlo(&Maneuver1dConfig::default(), &[], eta, comp, 0..runs)
        .unwrap()
        .false_alarms
}

/// How many of the maneuver-free runs `0..runs` have at least one detection.
fn runs_with_detections(eta: f64, comp: Compensation, runs: u64) -> usize {
    let cfg = Maneuver1dConfig::default();
    (0..runs)
        .filter(|&r| {
            monte_carlo(&cfg, &[], eta, comp, r..r + 1)
                .unwrap()
                .false_alarms
                > 0
        })
        .count()
}

#[test]
fn glrt_alone_misses_a_switch_off_p95_at_every_threshold() {
    // GLRT alone (the crate's default compensation): the 95th percentile after case 2's
    // switch-offs (3.8 s, 6.4 s) exceeds 0.7 s at every η from 16 to 22 (measured at 200
    // runs: 3.8 s 0.80–1.00 s or > 5 % missed; the cause is the single-window input
    // estimate's error, σ ≈ 42 m/s², derived in maneuver_1d_later_switches.rs). 1000 runs
    // here so that the statement is not one sample's: the p95 of 1000 runs has a binomial
    // spread of ±1.4 % in rank, ~0.05 s at these tails, below the 0.1–0.3 s excess.
    let cfg = Maneuver1dConfig::default();
    for eta in [16.0, 18.0, 20.0, 22.0] {
        let s = monte_carlo(&cfg, CASE2, eta, Compensation::Glrt, 0..1000).unwrap();
        eprintln!(
            "GLRT eta {eta}: p95 after the switch-offs {:.2} / {:.2} s (missed {} / {})",
            s.delay_p95(1),
            s.delay_p95(3),
            s.missed(1),
            s.missed(3)
        );
        // NaN: more than 5 % of the runs missed the switch (p95 never detected).
        assert!(
            exceeds(s.delay_p95(1), 0.7) || exceeds(s.delay_p95(3), 0.7),
            "eta {eta}"
        );
    }
}

#[test]
fn with_mras_the_mean_delays_and_zero_false_detections_exclude_each_other() {
    // GLRT + MRAS meets every 95th percentile (with_mras_… in maneuver_1d_requirement.rs);
    // its means and the zero-detection requirement cannot both hold at any η of the grid
    // on the requirement's own 200 runs.
    let comp = Compensation::GlrtMras;
    let grid = [15.0, 16.0, 17.0, 18.0, 19.0, 20.0];
    for eta in grid {
        let means = means_hold(eta, comp, 200);
        let free = false_detections(eta, comp, 200);
        eprintln!("MRAS eta {eta}, 200 runs: means hold {means}, false detections {free}");
        assert!(
            !(means && free == 0),
            "eta {eta}: both hold on 200 runs (means ok, 0 false detections)"
        );
    }
    // Not one sample's accident: over 5000 runs (the mean's standard error ~0.001 s),
    // the largest η of the grid whose means all hold has a fraction p of maneuver-free
    // runs with a detection such that (1 − p)^200 < 0.1 — zero detections in 200
    // independent runs would be a < 10 % chance (measured at η = 16: 89 detections in
    // 5000 runs).
    let runs = 5000;
    let best = grid
        .into_iter()
        .rfind(|&eta| means_hold(eta, comp, runs))
        .expect("some eta of the grid meets the means");
    let p = runs_with_detections(best, comp, runs) as f64 / runs as f64;
    let zero_chance = (1.0 - p).powi(200);
    eprintln!(
        "MRAS: largest eta with the means {best}; runs with a detection {p:.4}, P(0 in 200) {zero_chance:.3}"
    );
    assert!(zero_chance < 0.1, "eta {best}: P(0 in 200) = {zero_chance}");
    // And above it the means fail by more than their standard error (η = 20: second
    // onset 0.523 s over 5000 runs).
    assert!(!means_hold(20.0, comp, runs));
}

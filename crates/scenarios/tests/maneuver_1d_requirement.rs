//! Seed 001 "maneuver-1d": the detection requirement of issue 17 §1 (which replaces the
//! blocked one of issue 8), checked at the full count of 200 seeded runs per case
//! (200 runs of an 8-s 1-D KF scenario: ~0.1 s per case in the dev profile).
//! Default detector: GLRT alone (`Compensation::Glrt`, the crate's default), persistent
//! signature, M = 20, N = 5, η = 20; SPEC 001's a = 210 m/s², T = 0.05 s, R = 36 m².
//! Runs 0..200 of seed 1 (`ChaCha8Rng::seed_from_u64(i)`), as `argus run maneuver-1d`.
#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use argus_adaptive::Compensation;
use argus_scenarios::experiments::maneuver_1d::{
    CASE1, CASE2, Maneuver1dConfig, Stats1d, monte_carlo, noise_free_statistic, within_derived,
};

const ETA: f64 = 20.0;
const RUNS: u64 = 200;

/// Whether a delay statistic misses its bound (NaN: nothing detected, a miss). Delays are
/// multiples of T = 0.05 s: 1e-9 s for their round-off.
fn exceeds(v: f64, bound: f64) -> bool {
    v.is_nan() || v > bound + 1e-9
}

/// Fraction of the runs whose switch `i` was detected within 0.5 s.
fn within_switch(s: &Stats1d, i: usize) -> (usize, usize) {
    let v = &s.delays[i];
    let hit = v
        .iter()
        .filter(|d| d.is_some_and(|d| d <= 0.5 + 1e-9))
        .count();
    (hit, v.len())
}

#[test]
fn detection_requirement_of_issue_17_over_200_runs() {
    let cfg = Maneuver1dConfig::default();
    let lambda = noise_free_statistic(&cfg, 2.0, 0.5).unwrap();
    let derived = within_derived(lambda, ETA);
    eprintln!(
        "noise-free lambda(0.5 s) = {lambda:.2}; Phi(sqrt(lambda) - sqrt(eta)) = {derived:.3}"
    );
    // The non-centrality that issue 8's analysis measured: 24.8 (±1 %).
    assert!((lambda - 24.8).abs() < 0.25, "{lambda}");
    let mut failed = Vec::new();
    let mut first_onset = (0, 0);
    for (name, windows) in [("case 1", CASE1), ("case 2", CASE2)] {
        let s = monte_carlo(&cfg, windows, ETA, Compensation::Glrt, 0..RUNS).unwrap();
        let ratio = s.rms_in_ad / s.rms_in_kf;
        eprintln!(
            "{name}: mean {:.3?} p95 {:.3?} missed {:?}; RMS inside {:.2} / {:.2} = {ratio:.3}; within 0.5 s {:.3}, per switch {:?}",
            (0..s.switches.len())
                .map(|i| s.delay_mean(i))
                .collect::<Vec<_>>(),
            (0..s.switches.len())
                .map(|i| s.delay_p95(i))
                .collect::<Vec<_>>(),
            (0..s.switches.len())
                .map(|i| s.missed(i))
                .collect::<Vec<_>>(),
            s.rms_in_ad,
            s.rms_in_kf,
            s.fraction_within(0.5),
            (0..s.switches.len())
                .map(|i| within_switch(&s, i))
                .collect::<Vec<_>>(),
        );
        // Issue 17: adaptive RMS inside the maneuvers ≤ 0.5 × the KF's.
        assert!(ratio <= 0.5, "{name}: ratio {ratio}");
        for i in 0..s.switches.len() {
            // Issue 17: mean delay ≤ 0.5 s and 95th percentile ≤ 0.7 s for every switch.
            if exceeds(s.delay_mean(i), 0.5) {
                failed.push((name, i, "mean"));
            }
            if exceeds(s.delay_p95(i), 0.7) {
                failed.push((name, i, "p95"));
            }
        }
        if windows == CASE1 {
            // Both cases share their runs' data up to 3.8 s: the first onset counts once.
            first_onset = within_switch(&s, 0);
        }
    }
    // What does not hold at the default η, measured (docs/papers/001-maneuver-1d.md):
    // case 2's switch-off at 3.8 s (95th pct 1.00 s: 10 of 200 runs drop the input early
    // and so miss the switch, others are late), its second onset at 5.0 s (mean 0.511 s)
    // and its switch-off at 6.4 s (95th pct 0.80 s, 7 missed). Pinned here so that any
    // change of these results (better or worse) shows and the document is updated. Why:
    // maneuver_1d_later_switches.rs (the noise-free λ after each switch given the filter's
    // state there; with every estimate exact the second onset's derived mean is 0.517 s).
    assert_eq!(
        failed,
        [
            ("case 2", 1, "p95"),
            ("case 2", 2, "mean"),
            ("case 2", 3, "p95")
        ],
        "per-switch requirement failures"
    );
    // The derived chance Φ(√λ − √η) holds for an onset from the plain filter's steady
    // running (the first onset, 200 runs; the same data in both cases): within 3 binomial
    // standard deviations √(p(1 − p)/n) (n = 200: 0.033). Later switches start from a corrected
    // filter (carried-input error, inflated covariance) and are not covered by it.
    let frac = first_onset.0 as f64 / first_onset.1 as f64;
    let sd = (derived * (1.0 - derived) / first_onset.1 as f64).sqrt();
    eprintln!("first onset within 0.5 s: {frac:.3} vs derived {derived:.3} (sd {sd:.3})");
    assert!((frac - derived).abs() <= 3.0 * sd, "{frac} vs {derived}");
    // Issue 17: zero detections over 200 maneuver-free runs at the default η.
    let free = monte_carlo(&cfg, &[], ETA, Compensation::Glrt, 0..RUNS).unwrap();
    assert_eq!(free.false_alarms, 0);
}

#[test]
fn with_mras_the_same_requirement_misses_only_case_2_means() {
    // GLRT + MRAS at the default η, 200 runs: RMS ratio and 95th percentiles hold for every
    // switch; the mean delays of case 2's switch-off at 3.8 s (0.505 s) and second onset
    // (0.526 s) exceed 0.5 s (measured; pinned as above).
    let cfg = Maneuver1dConfig::default();
    let mut failed = Vec::new();
    for (name, windows) in [("case 1", CASE1), ("case 2", CASE2)] {
        let s = monte_carlo(&cfg, windows, ETA, Compensation::GlrtMras, 0..RUNS).unwrap();
        assert!(s.rms_in_ad <= 0.5 * s.rms_in_kf, "{name}");
        for i in 0..s.switches.len() {
            if exceeds(s.delay_mean(i), 0.5) {
                failed.push((name, i, "mean"));
            }
            if exceeds(s.delay_p95(i), 0.7) {
                failed.push((name, i, "p95"));
            }
        }
    }
    assert_eq!(failed, [("case 2", 1, "mean"), ("case 2", 2, "mean")]);
    let free = monte_carlo(&cfg, &[], ETA, Compensation::GlrtMras, 0..RUNS).unwrap();
    assert_eq!(free.false_alarms, 0);
}

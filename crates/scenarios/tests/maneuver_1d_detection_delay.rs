//! Seed 001 "maneuver-1d": the scenario's Monte Carlo (`experiments::maneuver_1d`, used
//! by `argus run maneuver-1d`) against the independent implementation of argus-adaptive's
//! tests, and the per-switch detection-delay distribution (issue 8: "detection within
//! 0.5 s of each switch").
#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

// The independent 1-D simulation and filters of argus-adaptive's GLRT tests (one copy,
// shared rather than written twice).
#[path = "../../adaptive/tests/glrt_common/mod.rs"]
mod glrt_common;

use argus_adaptive::Compensation;
use argus_scenarios::experiments::maneuver_1d::{
    CASE1, CASE2, Maneuver1dConfig, monte_carlo, run_filters, simulate,
};

#[test]
fn library_monte_carlo_matches_the_test_implementation() {
    // Same seeds, same draw order, independent filter code (TestKf<Cv1> vs Kf<Cv1D> with
    // CvNoise::VelocityPerStep): identical errors to round-off.
    let cfg = Maneuver1dConfig::default();
    for seed in 0..5 {
        for windows in [CASE1, CASE2] {
            let lib = run_filters(
                &cfg,
                &simulate(&cfg, windows, seed).unwrap(),
                20.0,
                Compensation::GlrtMras,
            )
            .unwrap();
            let run = glrt_common::simulate(seed, windows, 210.0);
            let t = glrt_common::run_filters(
                &run,
                glrt_common::config(20, 5, 20.0),
                Compensation::GlrtMras,
            );
            assert_eq!(lib.detections, t.detections);
            for (a, b) in lib
                .ad_err
                .iter()
                .zip(&t.ad_err)
                .chain(lib.kf_err.iter().zip(&t.kf_err))
            {
                assert!((a - b).abs() < 1e-9, "{a} vs {b}");
            }
        }
    }
}

#[test]
#[ignore = "exploration, prints only"]
fn explore_delay() {
    let d = Maneuver1dConfig::default();
    for (m, n) in [(20, 5), (20, 3), (20, 2), (20, 1), (10, 2), (40, 5)] {
        for eta in [10.0, 15.0, 20.0] {
            let cfg = Maneuver1dConfig {
                max_age: m,
                min_age: n,
                ..d
            };
            for comp in [Compensation::Glrt, Compensation::GlrtMras] {
                let s1 = monte_carlo(&cfg, CASE1, eta, comp, 0..200).unwrap();
                let s2 = monte_carlo(&cfg, CASE2, eta, comp, 0..200).unwrap();
                let free = monte_carlo(&cfg, &[], eta, comp, 0..200).unwrap();
                let within = (s1.fraction_within(0.5) * 2.0 + s2.fraction_within(0.5) * 4.0) / 6.0;
                eprintln!(
                    "M {m:2} N {n} eta {eta:4.1} {comp:?}: within 0.5 s {:.3}; case1 q50 {:.2} q95 {:.2} max {:.2} missed {:?}; case2 q95 {:.2} max {:.2} missed {:?}; free FA/run {:.3}; rms in c1 {:.1}/{:.1} c2 {:.1}/{:.1}",
                    within,
                    s1.delay_quantile(0.5),
                    s1.delay_quantile(0.95),
                    s1.delay_quantile(1.0),
                    (0..2).map(|i| s1.missed(i)).collect::<Vec<_>>(),
                    s2.delay_quantile(0.95),
                    s2.delay_quantile(1.0),
                    (0..4).map(|i| s2.missed(i)).collect::<Vec<_>>(),
                    free.false_alarms as f64 / 200.0,
                    s1.rms_in_kf,
                    s1.rms_in_ad,
                    s2.rms_in_kf,
                    s2.rms_in_ad,
                );
            }
        }
    }
}

/// The noise-free GLRT statistic `λ(τ)` a time `τ` after the onset (case 1, 210 m/s²):
/// the non-centrality of the statistic, so that the chance of a detection by `τ` at the
/// true onset is `P(|N(√λ, 1)| ≥ √η) ≈ Φ(√λ − √η)`.
fn noise_free_statistic(tau: f64) -> f64 {
    use argus_adaptive::{FailureKind, GlrtConfig, ManeuverState};
    use argus_core_math::{Gaussian, Matrix, Vector};
    use glrt_common::*;
    let ad = adaptive(Compensation::Glrt);
    let meas = Pos1 { r: R };
    let cfg = GlrtConfig::new(40, 0, 1e12, FailureKind::Persistent).unwrap();
    let x0 = Vector::<2>::new(2000.0, 70.0);
    let mut st = ManeuverState::<2, 1, 1>::new(
        Gaussian::new(x0, Matrix::<2, 2>::identity() * 100.0).unwrap(),
        cfg,
    );
    let phi = Matrix::<2, 2>::new(1.0, T, 0.0, 1.0);
    let mut x = x0;
    let mut out = f64::NAN;
    for k in 0..STEPS {
        x = phi * x + gamma() * accel(&[(2.0, 6.0)], 210.0, k);
        let rep = ad.step(&mut st, T, &meas, &Vector::<1>::new(x[0])).unwrap();
        let t = (k + 1) as f64 * T;
        if (t - (2.0 + tau)).abs() < 1e-9 {
            out = rep.max_statistic.unwrap().0;
        }
    }
    out
}

#[test]
fn detection_delay_is_limited_by_the_signal_to_noise_of_the_first_half_second() {
    // Issue 8 asks for a detection within 0.5 s of each switch. Derived bound: the
    // statistic at the true onset is non-central χ²(1) with non-centrality λ(τ); a
    // detection by τ needs it to exceed η, with probability ≈ Φ(√λ(τ) − √η) (the max
    // over the window adds a little). Noise-free λ, measured here: λ(0.25 s) = 1.3,
    // λ(0.4 s) = 9.7, λ(0.5 s) = 24.8, λ(0.6 s) = 52.5. So at η = 20 a switch is
    // detected within 0.5 s with probability ≈ Φ(4.98 − 4.47) ≈ 0.69, and no choice of
    // N (λ(0.25 s) is tiny anyway) or M changes λ; only a lower η does: 95 % needs
    // √η ≤ 4.98 − 1.645, η ≤ 11, where the detector fires ≈ 0.5 times per 8-s
    // maneuver-free run (explore_delay).
    let lam: Vec<f64> = [0.25, 0.4, 0.5, 0.6]
        .iter()
        .map(|&t| noise_free_statistic(t))
        .collect();
    eprintln!("noise-free statistic at 0.25, 0.4, 0.5, 0.6 s after onset: {lam:.2?}");
    assert!(lam.windows(2).all(|w| w[1] > w[0]));
    // λ(0.5 s) must be close to η = 20 for the bound to say "about two in three".
    assert!((20.0..30.0).contains(&lam[2]), "{}", lam[2]);
    // Nominal Monte Carlo (200 runs, GLRT, M = 20, N = 5, η = 20, both cases, 1200
    // switches): the fraction within 0.5 s must sit near that bound, not at 100 %.
    let cfg = Maneuver1dConfig::default();
    let s1 = monte_carlo(&cfg, CASE1, 20.0, Compensation::Glrt, 0..200).unwrap();
    let s2 = monte_carlo(&cfg, CASE2, 20.0, Compensation::Glrt, 0..200).unwrap();
    let within = (s1.fraction_within(0.5) * 2.0 + s2.fraction_within(0.5) * 4.0) / 6.0;
    eprintln!(
        "fraction within 0.5 s: {within:.3}; onset q95 {:.2} s",
        s1.delay_quantile(0.95)
    );
    // Measured 0.64 (200 runs); the bound above with λ(0.5 s) gives ≈ 0.7.
    assert!((0.5..0.8).contains(&within), "{within}");
}

#[test]
fn bad_maneuver_1d_inputs_are_rejected_with_the_field_named() {
    use argus_adaptive::AdaptiveError;
    let d = Maneuver1dConfig::default();
    let cases = [
        ("dt", Maneuver1dConfig { dt: -0.05, ..d }),
        ("r", Maneuver1dConfig { r: 0.0, ..d }),
        ("q", Maneuver1dConfig { q: f64::NAN, ..d }),
        (
            "accel",
            Maneuver1dConfig {
                accel: f64::INFINITY,
                ..d
            },
        ),
        ("steps", Maneuver1dConfig { steps: 0, ..d }),
    ];
    let run = simulate(&d, CASE1, 0).unwrap();
    for (field, cfg) in cases {
        match run_filters(&cfg, &run, 20.0, Compensation::Glrt) {
            Err(AdaptiveError::InvalidParameter { what, .. }) => assert_eq!(what, field),
            other => panic!("{field}: {other:?}"),
        }
    }
    assert!(matches!(
        run_filters(&d, &run, f64::NAN, Compensation::Glrt),
        Err(AdaptiveError::InvalidParameter { .. })
    ));
    let window = Maneuver1dConfig { min_age: 30, ..d };
    assert!(matches!(
        run_filters(&window, &run, 20.0, Compensation::Glrt),
        Err(AdaptiveError::InvalidWindow { .. })
    ));
    // Windows: inverted, overlapping, non-finite.
    for w in [
        &[(3.0, 2.0)][..],
        &[(2.0, 4.0), (3.0, 5.0)][..],
        &[(f64::NAN, 2.0)][..],
    ] {
        assert!(matches!(
            simulate(&d, w, 0),
            Err(AdaptiveError::InvalidParameter { .. })
        ));
    }
}

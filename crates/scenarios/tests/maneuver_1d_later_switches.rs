//! Seed 001 "maneuver-1d", issue 17 §1: why switches after the first are detected later.
//! The noise-free GLRT statistic `λ(τ)` after each switch, given the state the adaptive
//! filter has at that switch (`after_switch::switch_states`), against the simulated
//! delays; and the same for the noise-free run of the scheme itself, where every input
//! estimate is exact and only the covariance increases of eq 3-12 remain
//! (docs/papers/001-maneuver-1d.md, "Later switches").
//! SPEC 001 parameters, default η = 20, M = 20, N = 5; runs 0..200 of seed 1.
#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use argus_adaptive::Compensation;
use argus_core_math::{Gaussian, Matrix, Vector};
use argus_scenarios::experiments::maneuver_1d::after_switch::{
    SwitchState, mismatch_statistic, switch_states,
};
use argus_scenarios::experiments::maneuver_1d::{
    CASE1, CASE2, Maneuver1dConfig, monte_carlo, run_filters, simulate,
};

const ETA: f64 = 20.0;

/// The noise-free run of the scheme: no process noise, plots on the truth, the filter
/// started on the true state with SPEC's P₀.
fn noise_free(
    cfg: &Maneuver1dConfig,
    windows: &[(f64, f64)],
    comp: Compensation,
) -> (Vec<f64>, Vec<SwitchState>) {
    let quiet = Maneuver1dConfig { q: 0.0, ..*cfg };
    let mut run = simulate(&quiet, windows, 0).unwrap();
    run.plots = run.truth.iter().map(|x| x[0]).collect();
    run.initial = Gaussian::new(
        Vector::<2>::new(cfg.x0, cfg.v0),
        Matrix::<2, 2>::identity() * cfg.p0,
    )
    .unwrap();
    let det = run_filters(cfg, &run, ETA, comp)
        .unwrap()
        .detections
        .iter()
        .map(|&k| cfg.time(k))
        .collect();
    (det, switch_states(cfg, windows, &run, ETA, comp).unwrap())
}

#[test]
fn noise_free_scheme_second_onset_starts_from_the_eq_3_12_covariance() {
    let cfg = Maneuver1dConfig::default();
    let (det, ss) = noise_free(&cfg, CASE2, Compensation::Glrt);
    // Deterministic: onset at 2.5 s, removal at 4.3 s, onset at 5.5 s, removal at 6.9 s
    // (plot times are multiples of T = 0.05 s; 1e-9 s for round-off).
    for (a, b) in det.iter().zip([2.5, 4.3, 5.5, 6.9]) {
        assert!((a - b).abs() < 1e-9, "{det:?}");
    }
    assert_eq!(det.len(), 4);
    let first = &ss[0];
    let second = &ss[2];
    // Every input estimate of the noise-free run is exact: the state at the second onset
    // is the truth (1e-6 m, m/s: round-off of the corrections), the input was removed.
    assert!(second.error.norm() < 1e-6, "{:?}", second.error);
    assert_eq!(second.carried, None);
    // ... but its covariance still carries the increase of eq 3-12 applied at the removal
    // 0.7 s before: P₁₁ 6.03 m² against 4.00 m² at the first onset (±0.05 m²).
    assert!((first.cov[(0, 0)] - 4.00).abs() < 0.05, "{:?}", first.cov);
    assert!((second.cov[(0, 0)] - 6.03).abs() < 0.05, "{:?}", second.cov);
    // So the gain is larger and the signature smaller: λ(0.5 s) 20.8 against 24.8
    // (±1 %), and the derived mean delay Σ T·(1 − Φ(√λ − √η)) exceeds 0.5 s.
    let l1 = first.lambda_at(cfg.dt, 0.5);
    let l2 = second.lambda_at(cfg.dt, 0.5);
    assert!((l1 - 24.8).abs() < 0.25, "{l1}");
    assert!((l2 - 20.8).abs() < 0.21, "{l2}");
    let (m1, m2) = (first.mean_delay(&cfg, ETA), second.mean_delay(&cfg, ETA));
    eprintln!(
        "noise-free scheme: lambda(0.5) {l1:.2} / {l2:.2}; derived mean delay {m1:.3} / {m2:.3} s"
    );
    // 0.497 s and 0.517 s (±0.002 s): the first onset is just inside issue 17's 0.5 s,
    // the second is outside it with every estimate exact.
    assert!((m1 - 0.497).abs() < 0.002, "{m1}");
    assert!((m2 - 0.517).abs() < 0.002, "{m2}");
    // The plain filter's own onset at 5.0 s (no correction before it): λ(0.5 s) as the
    // first onset's to 2 %: the difference is the covariance, not the time.
    let plain = mismatch_statistic(&cfg, &[(5.0, 210.0)], 5.5).unwrap();
    let lp = plain[109];
    assert!((lp - l1).abs() < 0.02 * l1, "{lp} vs {l1}");
    // The noise-free λ never breaks the 95th percentile: P(delay ≤ 0.7 s) ≥ 0.999 after
    // every switch (the misses of issue 17 come from the noisy input estimates).
    for s in &ss {
        assert!(s.within(&cfg, ETA, 0.7) >= 0.999, "{}", s.switch);
    }
    // The removal's sensitivity to the carried input ĉ (true 210 m/s², the residual mismatch
    // on since 2.5 s, plain filter): λ(0.5 s) = 5.2 / 25.3 / 74.2 for ĉ = 190 / 210 / 230
    // (±1 %); plot 3.8 s + 0.5 s is index 85.
    for (c, want) in [(190.0, 5.2), (210.0, 25.3), (230.0, 74.2)] {
        let l = mismatch_statistic(&cfg, &[(2.5, 210.0 - c), (3.8, -c)], 4.6).unwrap();
        assert!((l[85] - want).abs() < 0.01 * want + 0.05, "{c}: {}", l[85]);
    }
    // GLRT + MRAS, noise-free: derived means 0.531 s (3.8 s) and 0.535 s (5.0 s): the
    // estimator absorbs part of the change the GLRT has to see (±0.002 s).
    let (_, mr) = noise_free(&cfg, CASE2, Compensation::GlrtMras);
    let (a, b) = (mr[1].mean_delay(&cfg, ETA), mr[2].mean_delay(&cfg, ETA));
    assert!(
        (a - 0.531).abs() < 0.002 && (b - 0.535).abs() < 0.002,
        "{a} {b}"
    );
}

#[test]
fn conditional_lambda_predicts_the_simulated_delays_per_switch() {
    let cfg = Maneuver1dConfig::default();
    let runs = 200;
    for (name, windows) in [("case 1", CASE1), ("case 2", CASE2)] {
        let stats = monte_carlo(&cfg, windows, ETA, Compensation::Glrt, 0..runs).unwrap();
        let n = stats.switches.len();
        let (mut p5, mut p7, mut mean) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        for seed in 0..runs {
            let run = simulate(&cfg, windows, seed).unwrap();
            let ss = switch_states(&cfg, windows, &run, ETA, Compensation::Glrt).unwrap();
            assert_eq!(ss.len(), n);
            for (i, s) in ss.iter().enumerate() {
                p5[i] += s.within(&cfg, ETA, 0.5) / runs as f64;
                p7[i] += s.within(&cfg, ETA, 0.7) / runs as f64;
                mean[i] += s.mean_delay(&cfg, ETA) / runs as f64;
            }
        }
        for i in 0..n {
            let v = &stats.delays[i];
            let obs = |lim: f64| v.within(lim) as f64 / v.runs() as f64;
            let (o5, o7) = (obs(0.5), obs(0.7));
            eprintln!(
                "{name} switch {i}: within 0.5 s derived {:.3} observed {o5:.3}; within 0.7 s {:.3} / {o7:.3}; mean {:.3} / {:.3} s",
                p5[i],
                p7[i],
                mean[i],
                stats.delay_mean(i)
            );
            // Within 3 binomial standard deviations of the derived chance (the spread of
            // a sum of Bernoulli trials with unequal p_i is at most that of equal ones).
            let sd = |p: f64| (p * (1.0 - p) / v.runs() as f64).sqrt();
            assert!(
                (o5 - p5[i]).abs() <= 3.0 * sd(p5[i]),
                "{name} {i}: {o5} vs {}",
                p5[i]
            );
        }
        if windows == CASE2 {
            // The second onset (5.0 s): derived mean 0.516 s against 0.511 s measured, both
            // above issue 17's 0.5 s; the derived within-0.7 s 0.994 against 0.995.
            assert!(mean[2] > 0.5 && stats.delay_mean(2) > 0.5, "{}", mean[2]);
            assert!((mean[2] - stats.delay_mean(2)).abs() < 0.015, "{}", mean[2]);
            // The switch-offs: given the carried input and covariance the scheme has at
            // 3.8 s and 6.4 s, P(delay ≤ 0.7 s) is 0.880 and 0.857 < 0.95; measured
            // 0.920 and 0.930 (later re-onset detections of runs that dropped the input
            // early count as detections of the switch): both below 0.95 (issue 17's p95).
            for i in [1, 3] {
                assert!(p7[i] < 0.95, "{i}: {}", p7[i]);
            }
        }
    }
}

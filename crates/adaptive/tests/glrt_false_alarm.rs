//! Seed 001 "maneuver-1d", issue 17 §2: the false-alarm rate of the windowed-maximum
//! GLRT statistic under no maneuver, derived and simulated.
//!
//! Derivation. With a consistent KF the normalised innovations `e_j = r_j / √S_j` are
//! i.i.d. N(0, 1), so for the onset `θ` the statistic is `l(m;θ) = z²` with
//! `z = Σ_j w_j e_j / ‖w‖`, `w_j = G(j;θ) / √S_j`: χ²(1) exactly (the signature's
//! dimension is 1). One hypothesis exceeds η with `p₁ = P(χ²(1) ≥ η)` (η = 10:
//! 1.565e-3). The per-step maximum over the `n` eligible onsets is bounded by
//! `p₁ ≤ P(max l ≥ η) ≤ n p₁` (Bonferroni) and more tightly by Hunter's bound along the
//! chain of neighbouring onsets, `Σ P(A_a) − Σ P(A_a ∩ A_{a+1})`, whose terms are bivariate
//! normal tails with the correlation `ρ` of the two `z` (computed from the signatures).
//! Summed over the 160 steps of a run that bounds the number of steps with `max l ≥ η`;
//! at N = 0, M = 20, η = 10 the Bonferroni bound alone is ≤ 21 · 160 · p₁ = 5.3 per run.
#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use argus_adaptive::maneuver::maneuver_1d::{Maneuver1dConfig, simulate};
use argus_adaptive::{
    FailureKind, Glrt, GlrtConfig, InputLinearization, ModelInput, StepLinearization,
};
use argus_core_math::{Matrix, Vector, chi2_cdf};
use argus_filters::{GaussianFilter, Kf};
use argus_motion_models::{Cv1D, CvNoise};
use argus_sensors::CartesianPosition;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

/// Counts from one maneuver-free run of the GLRT fed by the plain KF (no correction).
#[derive(Debug, Default, Clone, Copy)]
struct Counts {
    /// Steps whose windowed maximum reaches η (window never emptied).
    exceed_steps: usize,
    /// Detections when the window is emptied after each one (as the adaptive filter does).
    detections_reset: usize,
    /// Normalised innovations: sum of squares and count (consistency check).
    nis: (f64, usize),
}

/// The GLRT alone on the KF's innovations of maneuver-free run `seed` (library code:
/// `Kf<Cv1D>`, `Glrt`); no correction is fed back, so the statistic is the null one.
fn glrt_alone(cfg: &Maneuver1dConfig, seed: u64, min_age: usize, eta: f64) -> Counts {
    let run = simulate(cfg, &[], seed).unwrap();
    let model = Cv1D::new(CvNoise::VelocityPerStep { q: cfg.q }).unwrap();
    let kf = Kf::new(model);
    let lin = ModelInput::new(model, Matrix::<2, 1>::new(0.0, 1.0)).unwrap();
    let meas = CartesianPosition::<2, 1>::new([0], Matrix::<1, 1>::new(cfg.r)).unwrap();
    let gc = GlrtConfig::new(cfg.max_age, min_age, eta, FailureKind::Persistent).unwrap();
    let (mut keep, mut reset) = (Glrt::<2, 1, 1>::new(gc), Glrt::<2, 1, 1>::new(gc));
    let mut est = run.initial;
    let mut c = Counts::default();
    for z in &run.plots {
        let phi = lin.transition(est.mean(), cfg.dt);
        let gamma = lin.input_gain(est.mean(), cfg.dt);
        let pred = kf.predict(&est, cfg.dt).unwrap();
        let mp = kf.predict_measurement(&pred, &meas).unwrap();
        let inn = mp.innovation(&meas, &Vector::<1>::new(*z)).unwrap();
        let h = Matrix::<1, 2>::new(1.0, 0.0);
        let step = StepLinearization {
            phi: &phi,
            gamma: &gamma,
            h: &h,
            gain: mp.gain(),
            s_factor: mp.s_factor(),
            residual: &inn.residual,
        };
        let o = keep.step(&step).unwrap();
        keep.commit();
        if o.max_statistic.is_some_and(|(l, _)| l >= eta) {
            c.exceed_steps += 1;
        }
        if reset.step(&step).unwrap().detection.is_some() {
            c.detections_reset += 1;
            reset.reset();
        } else {
            reset.commit();
        }
        c.nis.0 += mp.s_factor().mahalanobis_sq(&inn.residual);
        c.nis.1 += 1;
        est = mp.update(&pred, &inn.residual).unwrap();
    }
    c
}

/// Steady-state normalised signature `w_a = G(a) / √S`, `a = 0..=max_age`, of the
/// persistent input through `Γ = [T²/2, T]ᵀ` (own scalar recursion, independent of the
/// library): `D₀ = Γ`, `D_{a+1} = Φ D_a + Γ`, `G_a = H (D_a − Φ F_{a−1})`,
/// `F_a = K G_a + Φ F_{a−1}`.
fn steady_weights(cfg: &Maneuver1dConfig) -> Vec<f64> {
    let t = cfg.dt;
    let phi = Matrix::<2, 2>::new(1.0, t, 0.0, 1.0);
    let q = Matrix::<2, 2>::new(0.0, 0.0, 0.0, cfg.q);
    let mut p = Matrix::<2, 2>::identity() * cfg.p0;
    let (mut k, mut s) = (Vector::<2>::zeros(), 0.0);
    for _ in 0..5000 {
        let pm = phi * p * phi.transpose() + q;
        s = pm[(0, 0)] + cfg.r;
        k = Vector::<2>::new(pm[(0, 0)], pm[(1, 0)]) / s;
        let ikh = Matrix::<2, 2>::identity() - k * Matrix::<1, 2>::new(1.0, 0.0);
        p = ikh * pm;
    }
    let gamma = Vector::<2>::new(0.5 * t * t, t);
    let (mut dev, mut f) = (gamma, Vector::<2>::zeros());
    let mut w = Vec::new();
    for _ in 0..=cfg.max_age {
        let phi_f = phi * f;
        let g = dev[0] - phi_f[0];
        f = k * g + phi_f;
        dev = phi * dev + gamma;
        w.push(g / s.sqrt());
    }
    w
}

/// Upper tail of N(0, 1) at `x` (from the χ²(1) CDF).
fn upper(x: f64) -> f64 {
    let two_sided = 1.0 - chi2_cdf(x * x, 1.0).unwrap();
    if x >= 0.0 {
        0.5 * two_sided
    } else {
        1.0 - 0.5 * two_sided
    }
}

/// `P(|X| ≥ c, |Y| ≥ c)` for standard bivariate normal `X, Y` with correlation `ρ`
/// (Simpson's rule over `x ∈ [c, c + 12]`, doubled by symmetry).
fn both_exceed(c: f64, rho: f64) -> f64 {
    let s = (1.0 - rho * rho).max(1e-300).sqrt();
    let f = |x: f64| {
        let phi = (-0.5 * x * x).exp() / (2.0 * std::f64::consts::PI).sqrt();
        phi * (upper((c - rho * x) / s) + upper((c + rho * x) / s))
    };
    let n = 4000;
    let h = 12.0 / n as f64;
    let sum: f64 = (0..=n)
        .map(|i| {
            let wgt = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            wgt * f(c + i as f64 * h)
        })
        .sum();
    2.0 * sum * h / 3.0
}

/// Correlation of the `z` of onset ages `a < b` at the same step (steady state).
fn correlation(w: &[f64], a: usize, b: usize) -> f64 {
    let na: f64 = w[..=a].iter().map(|x| x * x).sum();
    let nb: f64 = w[..=b].iter().map(|x| x * x).sum();
    let cross: f64 = (0..=a).map(|i| w[i] * w[i + b - a]).sum();
    cross / (na * nb).sqrt()
}

/// Derived per-run bounds on the steps with `max l ≥ η` (steady state, the window filling
/// over the first `M` steps): (Σ p₁ lower, Hunter upper, Bonferroni upper).
fn derived_per_run(cfg: &Maneuver1dConfig, min_age: usize, eta: f64) -> (f64, f64, f64) {
    let w = steady_weights(cfg);
    let p1 = 1.0 - chi2_cdf(eta, 1.0).unwrap();
    let c = eta.sqrt();
    let pair: Vec<f64> = (min_age..cfg.max_age)
        .map(|a| both_exceed(c, correlation(&w, a, a + 1)))
        .collect();
    let (mut lo, mut hunter, mut bonf) = (0.0, 0.0, 0.0);
    for m in 0..cfg.steps {
        let oldest = m.min(cfg.max_age);
        if oldest < min_age {
            continue;
        }
        let n = oldest - min_age + 1;
        lo += p1;
        bonf += n as f64 * p1;
        hunter += n as f64 * p1 - pair[..n - 1].iter().sum::<f64>();
    }
    (lo, hunter, bonf)
}

/// The statistic alone from i.i.d. normal innovations through the steady-state weights
/// (independent of the library): steps per run with `max l ≥ η`, and detections when the
/// window restarts empty after each one.
fn gaussian_model(cfg: &Maneuver1dConfig, min_age: usize, eta: f64, runs: u64) -> (f64, f64) {
    let w = steady_weights(cfg);
    let (mut exceed, mut det) = (0usize, 0usize);
    for seed in 0..runs {
        let mut rng = ChaCha8Rng::seed_from_u64(900_000 + seed);
        let e: Vec<f64> = (0..cfg.steps)
            .map(|_| StandardNormal.sample(&mut rng))
            .collect();
        let mut start = 0; // first step the reset window may use
        for m in 0..cfg.steps {
            let stat = |lo: usize| -> f64 {
                let mut best: f64 = 0.0;
                for age in min_age..=m.min(cfg.max_age) {
                    if m - age < lo {
                        break;
                    }
                    let (mut d, mut cc) = (0.0, 0.0);
                    for a in 0..=age {
                        d += w[a] * e[m - age + a];
                        cc += w[a] * w[a];
                    }
                    best = best.max(d * d / cc);
                }
                best
            };
            if stat(0) >= eta {
                exceed += 1;
            }
            if stat(start) >= eta {
                det += 1;
                start = m + 1;
            }
        }
    }
    (exceed as f64 / runs as f64, det as f64 / runs as f64)
}

#[test]
fn the_windowed_maximum_statistic_matches_its_null_distribution() {
    let cfg = Maneuver1dConfig::default();
    let eta = 10.0;
    let runs = 400;
    for min_age in [0, 5] {
        let (lo, hunter, bonf) = derived_per_run(&cfg, min_age, eta);
        let (g_exceed, g_det) = gaussian_model(&cfg, min_age, eta, runs);
        let mut lib = Counts::default();
        for seed in 0..runs {
            let c = glrt_alone(&cfg, 20_000 + seed, min_age, eta);
            lib.exceed_steps += c.exceed_steps;
            lib.detections_reset += c.detections_reset;
            lib.nis.0 += c.nis.0;
            lib.nis.1 += c.nis.1;
        }
        let exceed = lib.exceed_steps as f64 / runs as f64;
        let det = lib.detections_reset as f64 / runs as f64;
        let nis = lib.nis.0 / lib.nis.1 as f64;
        eprintln!(
            "N = {min_age}, eta {eta}: steps above eta per run: derived {lo:.3} <= {hunter:.3} (Hunter) <= {bonf:.3} (Bonferroni); \
             Gaussian model {g_exceed:.3}; library {exceed:.3}. Detections with reset per run: Gaussian model {g_det:.3}, library {det:.3}. NIS {nis:.4}"
        );
        // The KF is consistent: mean NIS 1 within 3 σ of its sampling error
        // (σ = √(2 / n), n = 64 000 plots: 0.0056).
        assert!(
            (nis - 1.0).abs() < 3.0 * (2.0 / lib.nis.1 as f64).sqrt(),
            "{nis}"
        );
        // The library's exceedance count lies inside the derived bounds (Bonferroni is a
        // hard upper bound; the sum of p₁ a hard lower one), with a Poisson allowance of
        // 3 √(count) on the 400-run total.
        let slack = 3.0 * (lib.exceed_steps as f64).sqrt() / runs as f64;
        assert!(exceed <= hunter + slack, "{exceed} vs Hunter {hunter}");
        assert!(exceed >= lo - slack, "{exceed} vs lower {lo}");
        // And it matches the independent Gaussian model of the statistic (same η, same
        // weights in steady state): the two counts differ by less than 3 σ of a Poisson
        // difference plus 10 % for the KF's start-up transient, which the model ignores.
        let diff_sd = ((lib.exceed_steps as f64) + g_exceed * runs as f64).sqrt() / runs as f64;
        assert!(
            (exceed - g_exceed).abs() < 3.0 * diff_sd + 0.1 * g_exceed,
            "{exceed} vs {g_exceed}"
        );
        let diff_sd = ((lib.detections_reset as f64) + g_det * runs as f64).sqrt() / runs as f64;
        assert!(
            (det - g_det).abs() < 3.0 * diff_sd + 0.1 * g_det,
            "{det} vs {g_det}"
        );
        // The number SPEC's re-implementation reports for N = 0 (7.53 per run) is above the
        // Bonferroni bound: no consistent χ²(1) statistic over this window can fire that
        // often, whatever the counting rule (issue 17 §2; docs/papers/001-maneuver-1d.md).
        if min_age == 0 {
            assert!(bonf < 7.53, "{bonf}");
        }
    }
}

/// The full adaptive filter (corrections fed back) on maneuver-free runs at η = 10, and
/// with a filter `q` below the truth's 0.5 (an over-confident KF). Measured (200 runs):
/// N = 0: 1.59 / 1.86 / 2.35 / 2.81 detections per run for q = 0.5 / 0.25 / 0.1 / 0.025;
/// N = 5: 0.65 / 0.90 / 1.25 / 1.77 — none near SPEC's 7.53.
#[test]
#[ignore = "exploration, prints only"]
fn explore_full_filter_false_alarms() {
    use argus_adaptive::Compensation;
    use argus_adaptive::maneuver::maneuver_1d::{CASE1, Stats1d, run_filters};
    let truth = Maneuver1dConfig::default();
    for n in [0, 5] {
        for q_filter in [0.5, 0.25, 0.1, 0.025] {
            let f = Maneuver1dConfig {
                q: q_filter,
                min_age: n,
                ..truth
            };
            let (mut det, mut se, mut cnt) = (0usize, 0.0, 0usize);
            for seed in 0..200 {
                let run = simulate(&truth, &[], 30_000 + seed).unwrap();
                let o = run_filters(&f, &run, 10.0, Compensation::Glrt).unwrap();
                det += o.detections.len();
                se += o.ad_err.iter().map(|e| e * e).sum::<f64>();
                cnt += o.ad_err.len();
            }
            let c1 = {
                let runs: Vec<_> = (0..100)
                    .map(|s| {
                        let r = simulate(&truth, CASE1, s).unwrap();
                        run_filters(&f, &r, 20.0, Compensation::Glrt).unwrap()
                    })
                    .collect();
                Stats1d::from_outcomes(&f, CASE1, &runs)
            };
            eprintln!(
                "N {n} filter q {q_filter}: eta 10 free detections/run {:.2}, free RMS {:.2} m; case 1 eta 20 RMS outside {:.2} inside {:.2}",
                det as f64 / 200.0,
                (se / cnt as f64).sqrt(),
                c1.rms_out_ad,
                c1.rms_in_ad
            );
        }
    }
}

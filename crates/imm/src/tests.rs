//! Crate tests: the IMM against a plain Kalman filter and hand-computed probabilities,
//! log-space robustness, bad input, and Monte Carlo checks on the gimpo scenario.
#![allow(clippy::unwrap_used, clippy::expect_used, non_snake_case)]

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::GaussianFilter;
use argus_motion_models::MotionModel;
use argus_sensors::PolarMeasurement;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use crate::test_support::{Kf, Motion, beam_times, ct, cv, paper_imm, plots, truth_at, two_point};
use crate::*;

fn meas(r: f64) -> PositionMeasurement<4> {
    PositionMeasurement::new(0, 2, Matrix::<2, 2>::identity() * r).unwrap()
}

fn start() -> Gaussian<4> {
    Gaussian::new(
        Vector::<4>::new(100.0, 10.0, -50.0, 5.0),
        Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(400.0, 25.0, 400.0, 25.0)),
    )
    .unwrap()
}

#[test]
fn single_mode_imm_is_the_kalman_filter() {
    // With one mode and Π = [1] the IMM reduces to its filter exactly, and ln Λ is the
    // filter's innovation log-likelihood.
    let f = Kf::new(cv(0.3));
    let imm = Imm::new([f], MarkovMatrix::new([[1.0]]).unwrap()).unwrap();
    let est = ImmEstimate::from_common(start(), [1.0]).unwrap();
    let z = Vector::<2>::new(170.0, -20.0);
    let upd = imm.step(&est, 5.0, &meas(50.0), &z).unwrap();
    let pred = f.predict(&start(), 5.0).unwrap();
    let (post, innov) = f.update(&pred, &meas(50.0), &z).unwrap();
    let c = upd.estimate.combined().unwrap();
    assert!((c.mean() - post.mean()).amax() < 1e-9);
    assert!((c.cov() - post.cov()).amax() < 1e-9);
    assert!((upd.log_likelihood - innov.log_likelihood()).abs() < 1e-12);
}

#[test]
fn mode_probabilities_and_mixing_match_a_hand_computation() {
    // Two modes (CV with different process noise), μ = (0.7, 0.3), Π = [[0.9, 0.1], [0.2, 0.8]].
    // Reference: eqs (1), (2), (6) evaluated directly in linear space.
    let f = [Kf::new(cv(0.1)), Kf::new(cv(3.0))];
    let pi = [[0.9, 0.1], [0.2, 0.8]];
    let imm = Imm::new(f, MarkovMatrix::new(pi).unwrap()).unwrap();
    let g1 = start();
    let g2 = Gaussian::new(
        Vector::<4>::new(120.0, 8.0, -40.0, 7.0),
        Matrix::<4, 4>::identity() * 300.0,
    )
    .unwrap();
    let mu = [0.7, 0.3];
    let est = ImmEstimate::new([g1, g2], mu).unwrap();
    let z = Vector::<2>::new(190.0, -10.0);
    let upd = imm.step(&est, 5.0, &meas(40.0), &z).unwrap();

    let cbar = [0.7 * 0.9 + 0.3 * 0.2, 0.7 * 0.1 + 0.3 * 0.8];
    let g = [g1, g2];
    let mut lik = [0.0; 2];
    for j in 0..2 {
        let w = [pi[0][j] * mu[0] / cbar[j], pi[1][j] * mu[1] / cbar[j]];
        let x0 = g[0].mean() * w[0] + g[1].mean() * w[1];
        let mut P0 = Matrix::<4, 4>::zeros();
        for i in 0..2 {
            let d = g[i].mean() - x0;
            P0 += (g[i].cov() + d * d.transpose()) * w[i];
        }
        let pred = f[j].predict(&Gaussian::new(x0, P0).unwrap(), 5.0).unwrap();
        let (post, innov) = f[j].update(&pred, &meas(40.0), &z).unwrap();
        lik[j] = innov.log_likelihood().exp();
        assert!((upd.estimate.modes()[j].mean() - post.mean()).amax() < 1e-9);
    }
    let total = cbar[0] * lik[0] + cbar[1] * lik[1];
    let mu_new = upd.estimate.mode_probabilities();
    for j in 0..2 {
        assert!((mu_new[j] - cbar[j] * lik[j] / total).abs() < 1e-12);
    }
    assert!((upd.log_likelihood - total.ln()).abs() < 1e-12);
}

#[test]
fn linear_and_log_space_updates_agree() {
    // The same cycle through `step` (linear μ̄) and `predict` + `update` (ln μ̄, eq (6)
    // in log space): the probabilities and ln Λ agree to round-off (1e-12: a few dozen
    // operations on numbers of order one).
    let imm = Imm::new(
        [Kf::new(cv(0.1)), Kf::new(cv(20.0))],
        MarkovMatrix::new([[0.9, 0.1], [0.2, 0.8]]).unwrap(),
    )
    .unwrap();
    let est = ImmEstimate::from_common(start(), [0.7, 0.3]).unwrap();
    let z = Vector::<2>::new(160.0, -20.0);
    let a = imm.step(&est, 5.0, &meas(40.0), &z).unwrap();
    let b = imm
        .update(&imm.predict(&est, 5.0).unwrap(), &meas(40.0), &z)
        .unwrap();
    assert!((a.log_likelihood - b.log_likelihood).abs() < 1e-12);
    let (pa, pb) = (
        a.estimate.mode_probabilities(),
        b.estimate.mode_probabilities(),
    );
    let (la, lb) = (
        a.estimate.log_mode_probabilities(),
        b.estimate.log_mode_probabilities(),
    );
    for j in 0..2 {
        assert!((pa[j] - pb[j]).abs() < 1e-12);
        assert!((la[j] - lb[j]).abs() < 1e-12);
        assert!((la[j] - pa[j].ln()).abs() < 1e-12);
    }
}

#[test]
fn a_mode_below_f64_keeps_its_log_probability_through_cycles() {
    // Mode 0 explains a plot 2 km off with R = 1 m² far worse than mode 1 (μ₀ ≈ e^{-883},
    // below the smallest f64, e^{-745}): μ₀ is 0.0 and lives as ln μ₀ only. With Π = I
    // the next cycle's ln μ̄₀ = ln μ₀ is below f64 too, so the update runs in log space;
    // eq (6) must still hold for the logarithms: ln μ₀' = ln μ₀ + ln Λ₀ − ln Λ (relative
    // 1e-12: round-off of a few additions of numbers up to ~1e3).
    let mix = Imm::new(
        [Kf::new(cv(0.1)), Kf::new(cv(20.0))],
        MarkovMatrix::new([[0.5, 0.5], [0.5, 0.5]]).unwrap(),
    )
    .unwrap();
    let est = ImmEstimate::from_common(start(), [0.5, 0.5]).unwrap();
    let first = mix
        .step(&est, 1.0, &meas(1.0), &Vector::<2>::new(2100.0, -50.0))
        .unwrap()
        .estimate;
    let l0 = first.log_mode_probabilities()[0];
    assert!(first.mode_probabilities()[0] == 0.0 && l0.is_finite() && l0 < -745.0);
    let stay = Imm::new(
        [Kf::new(cv(0.1)), Kf::new(cv(20.0))],
        MarkovMatrix::new([[1.0, 0.0], [0.0, 1.0]]).unwrap(),
    )
    .unwrap();
    let z = Vector::<2>::new(2110.0, -40.0);
    let second = stay.step(&first, 1.0, &meas(100.0), &z).unwrap();
    let l0_new = second.estimate.log_mode_probabilities()[0];
    let expected = l0 + second.mode_log_likelihoods[0] - second.log_likelihood;
    assert!(l0_new.is_finite());
    assert!((l0_new - expected).abs() < 1e-12 * expected.abs());
    let mu = second.estimate.mode_probabilities();
    assert!((mu.iter().sum::<f64>() - 1.0).abs() < 1e-12);
}

#[test]
fn tiny_likelihoods_do_not_underflow() {
    // A plot 2 km off with R = 1 m²: every likelihood is about e^{-2e6/2}, which is 0.0 in
    // f64; linear-space normalisation would give 0/0. In log space the probabilities stay
    // finite and sum to one, and the mode with the larger S is preferred.
    let imm = Imm::new(
        [Kf::new(cv(0.1)), Kf::new(cv(20.0))],
        MarkovMatrix::new([[0.5, 0.5], [0.5, 0.5]]).unwrap(),
    )
    .unwrap();
    let est = ImmEstimate::from_common(start(), [0.5, 0.5]).unwrap();
    let upd = imm
        .step(&est, 1.0, &meas(1.0), &Vector::<2>::new(2100.0, -50.0))
        .unwrap();
    assert!(upd.mode_log_likelihoods[0].exp() == 0.0);
    let mu = upd.estimate.mode_probabilities();
    assert!(mu.iter().all(|p| p.is_finite()));
    assert!((mu.iter().sum::<f64>() - 1.0).abs() < 1e-12);
    assert!(mu[1] > 0.999);
    assert!(upd.estimate.log_mode_probabilities()[0].is_finite());
    // Mixing keeps it: with Π = I, mode 0 is fed only by itself (μ ≈ e^{-1e6}, which the
    // scaled linear mixing cannot represent); the log-space fallback gives ln μ̄₀ = ln μ₀.
    let stay = Imm::new(
        [Kf::new(cv(0.1)), Kf::new(cv(20.0))],
        MarkovMatrix::new([[1.0, 0.0], [0.0, 1.0]]).unwrap(),
    )
    .unwrap();
    let pred = stay.predict(&upd.estimate, 1.0).unwrap();
    let l0 = upd.estimate.log_mode_probabilities()[0];
    assert!((pred.log_predicted_probabilities()[0] - l0).abs() < 1e-9 * l0.abs());
}

#[test]
fn bad_input_is_rejected_and_the_estimate_is_untouched() {
    let imm = paper_imm();
    let est = ImmEstimate::from_common(start(), [1.0 / 3.0; 3]).unwrap();
    let copy = est;
    let z = Vector::<2>::new(150.0, -20.0);
    for dt in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            imm.step(&est, dt, &meas(10.0), &z),
            Err(ImmError::InvalidInterval { .. })
        ));
    }
    assert!(matches!(
        imm.step(&est, 5.0, &meas(10.0), &Vector::<2>::new(f64::NAN, 0.0)),
        Err(ImmError::Filter { mode: 0, .. })
    ));
    assert_eq!(est, copy);
    assert!(matches!(
        ImmEstimate::<4, 3>::from_common(start(), [0.5, 0.5, 0.5]),
        Err(ImmError::InvalidProbabilities { .. })
    ));
    assert!(matches!(
        ImmEstimate::<4, 2>::from_common(start(), [f64::NAN, 1.0]),
        Err(ImmError::InvalidProbabilities { .. })
    ));
    // Imm::<_, _, 0> cannot be built: MarkovMatrix::<0>::new is rejected (markov tests).
    assert!(NoiseGrid::<5>::common(0.6).is_err()); // 1 − 2p < 0
    assert!(NoiseGrid::<5>::independent(0.1).is_err()); // 5 is not a square
    assert!(NoiseGrid::<5>::common(f64::NAN).is_err());
    assert!(NoiseGrid::<2>::custom([[1.0, 0.0], [1.0, 1.0]]).is_err());
    assert!(MultiImm::new(paper_imm(), NoiseGrid::<5>::common(0.1).unwrap(), Some(1.5)).is_err());
    assert!(VariationalNoiseImm::new(paper_imm(), 0.0).is_err());
    assert!(
        VariationalNoiseImm::new(paper_imm(), 0.9)
            .unwrap()
            .with_iterations(0)
            .is_err()
    );
    let var = NoiseVariances::new(1.0, 1.0).unwrap();
    assert!(VariationalEstimate::new(est, var, -1.0).is_err());
    assert!(EvidenceEstimate::new(est, var, 0.0).is_err());
    assert!(EvidenceNoiseImm::new(paper_imm(), 0.0, 1.0, None).is_err());
    assert!(EvidenceNoiseImm::new(paper_imm(), 0.2, 1.5, None).is_err());
    assert!(EvidenceNoiseImm::new(paper_imm(), 0.2, 1.0, Some(1.0)).is_err());
    assert!(EvidenceNoiseImm::new(paper_imm(), f64::NAN, 1.0, None).is_err());
    assert!(Embedded::<Motion, 4, 3>::new(cv(1.0), 0.0).is_err());
    assert!(Embedded::<Motion, 4, 5>::new(cv(1.0), -1.0).is_err());
}

#[test]
fn multi_imm_bad_steps_leave_the_estimate_untouched() {
    let m = MultiImm::new(
        paper_imm(),
        NoiseGrid::<5>::common(0.1).unwrap(),
        Some(0.05),
    )
    .unwrap();
    let var = NoiseVariances::from_sigmas(70.0, 0.08_f64.to_radians()).unwrap();
    let est = MultiImmEstimate::new(
        ImmEstimate::from_common(start(), [1.0 / 3.0; 3]).unwrap(),
        var,
    );
    let copy = est;
    let conv = UnbiasedConversion::<4>::new(0, 2).unwrap();
    let plot = PolarMeasurement::new(150.0, 0.1).unwrap();
    assert!(matches!(
        m.step(&est, -5.0, &plot, &conv),
        Err(ImmError::InvalidInterval { .. })
    ));
    assert_eq!(est, copy);
    assert!(m.step(&est, 5.0, &plot, &conv).is_ok());
}

#[test]
fn embedded_model_moves_the_shared_states_and_holds_the_rest() {
    // CV (4 states) in a 5-state [x, vx, y, vy, ω] common state: F = diag(F_cv, 1),
    // Q = diag(Q_cv, q dt).
    let cv = cv(0.5);
    let e = Embedded::<Motion, 4, 5>::new(cv, 1e-4).unwrap();
    let x = Vector::<5>::new(1.0, 2.0, 3.0, 4.0, 0.05);
    let y = e.propagate(&x, 2.0);
    let ys = cv.propagate(&Vector::<4>::new(1.0, 2.0, 3.0, 4.0), 2.0);
    assert!((y.fixed_rows::<4>(0) - ys).amax() < 1e-12);
    assert!((y[4] - 0.05).abs() < 1e-15);
    let q = e.process_noise(&x, 2.0);
    assert!((q[(4, 4)] - 2e-4).abs() < 1e-15);
    assert!((q.fixed_view::<4, 4>(0, 0) - cv.process_noise(&ys, 2.0)).amax() < 1e-15);
    assert!(q.fixed_view::<4, 1>(0, 4).amax() < 1e-300);
}

// ---------------------------------------------------------------- gimpo Monte Carlo

const SIGMA_R: f64 = 70.0;
fn sigma_t() -> f64 {
    0.08_f64.to_radians()
}
const STARTS: [f64; 5] = [0.2, 0.5, 1.0, 1.5, 2.0];

/// Per run: the final variance ratios (range, azimuth) and the sum of squared position
/// errors and count over t ≥ 25 % of the scenario.
#[derive(Debug, Clone, Copy, Default)]
struct Outcome {
    ratio: [f64; 2],
    sse: f64,
    n: usize,
}

#[derive(Debug, Clone, Copy)]
enum Estimator {
    Fixed,
    Paper {
        p: f64,
        clip: Option<f64>,
    },
    Variational {
        rho: f64,
    },
    Evidence {
        spacing: f64,
        rho: f64,
        clip: Option<f64>,
        settle: Option<usize>,
        observed: bool,
    },
    Difference {
        rho: f64,
    },
}

/// The IMM of the Monte Carlo runs: the paper's, or for exploration only a model set from
/// `EV_MODELS="cv_sv,ct_deg,ct_sv"` (CV σv, CT ±rate in °/s, CT σv; eq (20) Markov matrix).
fn mc_imm() -> Imm<Kf<Motion>, 4, 3> {
    let Ok(spec) = std::env::var("EV_MODELS") else {
        return paper_imm();
    };
    let v: Vec<f64> = spec.split(',').map(|x| x.parse().unwrap()).collect();
    let w = v[1].to_radians();
    Imm::new(
        [
            Kf::new(cv(v[0])),
            Kf::new(ct(w, v[2])),
            Kf::new(ct(-w, v[2])),
        ],
        MarkovMatrix::new([[0.95, 0.025, 0.025], [0.05, 0.95, 0.0], [0.05, 0.0, 0.95]]).unwrap(),
    )
    .unwrap()
}

/// First seed of the Monte Carlo runs (run i uses `base + i`): 1000, or `EV_SEED` when
/// exploring other seed sets.
fn seed_base() -> u64 {
    std::env::var("EV_SEED").map_or(1000, |v| v.parse().unwrap())
}

fn run_one(kind: Estimator, start_factor: f64, times: &[f64], pl: &[PolarMeasurement]) -> Outcome {
    let truth = NoiseVariances::from_sigmas(SIGMA_R, sigma_t()).unwrap();
    let var0 =
        NoiseVariances::new(truth.range() * start_factor, truth.azimuth() * start_factor).unwrap();
    let imm = mc_imm();
    let conv = UnbiasedConversion::<4>::new(0, 2).unwrap();
    let init = two_point(&pl[0], &pl[1], times[1] - times[0], &var0);
    let t_cut = 0.25 * 1019.0;
    let mut out = Outcome::default();
    let score = |t: f64, x: &Vector<4>, out: &mut Outcome| {
        if t >= t_cut {
            let tr = truth_at(t);
            out.sse += (x[0] - tr[0]).powi(2) + (x[2] - tr[2]).powi(2);
            out.n += 1;
        }
    };
    match kind {
        Estimator::Fixed => {
            let mut est = init;
            for k in 2..times.len() {
                let (m, z) = conv.convert(&pl[k], &var0).unwrap();
                est = imm
                    .step(&est, times[k] - times[k - 1], &m, &z)
                    .unwrap()
                    .estimate;
                score(times[k], est.combined().unwrap().mean(), &mut out);
            }
            out.ratio = [start_factor; 2];
        }
        Estimator::Paper { p, clip } => {
            let m = MultiImm::new(imm, NoiseGrid::<5>::common(p).unwrap(), clip).unwrap();
            let mut est = MultiImmEstimate::new(init, var0);
            for k in 2..times.len() {
                est = m
                    .step(&est, times[k] - times[k - 1], &pl[k], &conv)
                    .unwrap()
                    .estimate;
                score(times[k], est.combined().unwrap().mean(), &mut out);
            }
            let r = est.reference();
            out.ratio = [r.range() / truth.range(), r.azimuth() / truth.azimuth()];
        }
        Estimator::Variational { rho } => {
            let v = VariationalNoiseImm::new(imm, rho).unwrap();
            let mut est = VariationalEstimate::new(init, var0, 2.0).unwrap();
            for k in 2..times.len() {
                est = v
                    .step(&est, times[k] - times[k - 1], &pl[k], &conv)
                    .unwrap()
                    .0;
                score(times[k], est.imm().combined().unwrap().mean(), &mut out);
            }
            let r = est.variances().unwrap();
            out.ratio = [r.range() / truth.range(), r.azimuth() / truth.azimuth()];
        }
        Estimator::Evidence {
            spacing,
            rho,
            clip,
            settle,
            observed,
        } => {
            let mut v = EvidenceNoiseImm::new(imm, spacing, rho, clip).unwrap();
            if let Some(k) = settle {
                v = v.with_post_fit(k);
            }
            if observed {
                v = v.with_observed_information();
            }
            let mut est = EvidenceEstimate::new(init, var0, 2.0).unwrap();
            for k in 2..times.len() {
                est = v
                    .step(&est, times[k] - times[k - 1], &pl[k], &conv)
                    .unwrap();
                score(times[k], est.combined().unwrap().mean(), &mut out);
            }
            let r = est.variances();
            out.ratio = [r.range() / truth.range(), r.azimuth() / truth.azimuth()];
        }
        Estimator::Difference { rho } => {
            let v = DifferenceNoiseImm::new(imm, rho).unwrap();
            let mut est = DifferenceEstimate::new(init, var0, 2.0).unwrap();
            for k in 2..times.len() {
                est = v
                    .step(&est, times[k] - times[k - 1], &pl[k], &conv)
                    .unwrap()
                    .0;
                score(times[k], est.imm().combined().unwrap().mean(), &mut out);
            }
            let r = est.variances().unwrap();
            out.ratio = [r.range() / truth.range(), r.azimuth() / truth.azimuth()];
        }
    }
    out
}

/// Mean final ratios, per-run sd of the range ratio, and the RMS position error, over `runs`
/// runs (common random numbers: run i uses seed 1000 + i whatever the estimator).
fn campaign(kind: Estimator, start_factor: f64, runs: u64) -> ([f64; 2], f64, f64) {
    let times = beam_times();
    let (mut s, mut ss, mut sse, mut n) = ([0.0; 2], 0.0, 0.0, 0);
    let base = seed_base();
    for i in 0..runs {
        let mut rng = ChaCha8Rng::seed_from_u64(base + i);
        let pl = plots(&times, SIGMA_R, sigma_t(), &mut rng);
        let o = run_one(kind, start_factor, &times, &pl);
        if std::env::var("EV_VERBOSE").is_ok()
            && (o.ratio[0] - 1.0).abs().max((o.ratio[1] - 1.0).abs()) > 0.4
        {
            println!("  run {i}: {:.3} {:.3}", o.ratio[0], o.ratio[1]);
        }
        s[0] += o.ratio[0];
        s[1] += o.ratio[1];
        ss += o.ratio[0] * o.ratio[0];
        sse += o.sse;
        n += o.n;
    }
    let r = runs as f64;
    let mean = [s[0] / r, s[1] / r];
    let sd = (ss / r - mean[0] * mean[0]).max(0.0).sqrt();
    (mean, sd, (sse / n as f64).sqrt())
}

/// The paper's rule (p = 0.1, ±5 % clip) against the independent re-implementation quoted
/// in issue 4 (100 runs): final ratio ≈ 0.98 / 1.01 / 1.03 / 1.05 / 1.07 from starts
/// 0.2 … 2, per-run scatter ≈ ±11 %. Our 100-run numbers: 0.986 / 1.015 / 1.041 / 1.062 /
/// 1.080, sd 0.10. With `runs` runs the standard error of a mean is ≈ 0.10/√runs; the
/// tolerance is 3 standard errors (0.039 at 60 runs). Common random numbers across starts
/// make the ordering exact.
fn check_paper_rule(runs: u64) {
    let reference = [0.98, 1.01, 1.03, 1.05, 1.07];
    let tol = 3.0 * 0.10 / (runs as f64).sqrt();
    let mut prev = 0.0;
    let true_r = campaign(Estimator::Fixed, 1.0, runs).2;
    for (f, want) in STARTS.iter().zip(reference) {
        let (mean, sd, rms) = campaign(
            Estimator::Paper {
                p: 0.1,
                clip: Some(0.05),
            },
            *f,
            runs,
        );
        println!(
            "paper rule from {f}: ratio {:.3} sd {sd:.3} rms {rms:.2} (true-R rms {true_r:.2})",
            mean[0]
        );
        assert!(
            (mean[0] - want).abs() < tol,
            "start {f}: {} vs {want}",
            mean[0]
        );
        // One common scale: range and azimuth ratios are identical.
        assert!((mean[0] - mean[1]).abs() < 1e-9);
        assert!(mean[0] > prev, "the fixed point moves with the start");
        prev = mean[0];
        assert!((0.06..0.16).contains(&sd), "per-run scatter {sd} vs ≈ 0.11");
        // RMS: ≈ 1.3 % worse than true R from 0.2, within 0.5 % from 1–2 (issue 4);
        // ours (100 runs): +1.65 % from 0.2, −0.3 … 0.0 % from 1–2.
        let rel = rms / true_r - 1.0;
        if *f < 0.3 {
            assert!((0.0..0.03).contains(&rel), "from 0.2: {rel}");
        } else if *f >= 1.0 {
            assert!(rel.abs() < 0.01, "from {f}: {rel}");
        }
    }
    // Fixed R = 0.2 × truth is clearly worse than 2 × truth (paper Fig. 7).
    let low = campaign(Estimator::Fixed, 0.2, runs).2;
    let high = campaign(Estimator::Fixed, 2.0, runs).2;
    assert!(low > 1.1 * high, "{low} vs {high}");
}

#[test]
fn paper_rule_reproduces_the_reference_on_gimpo() {
    check_paper_rule(60);
}

#[test]
#[ignore = "full 100-run count (≈ 10 s in the dev profile)"]
fn paper_rule_reproduces_the_reference_on_gimpo_full() {
    check_paper_rule(100);
}

/// The variational estimator (ρ = 0.97): its fixed point is the truth (at the true R, the
/// post-fit statistic E[ε² + J P Jᵀ]/σ² measured 0.98 for range, 0.995 for azimuth), but on
/// this scenario the final value keeps a trace of the maneuvers (the last turn ends 86 s
/// before the end). Our 100-run numbers: range 0.969 … 0.984, azimuth 0.962 … 1.055 from
/// the five starts. The claim (within 3 % from all five) does NOT hold for the
/// azimuth from starts 1.5 and 2 (1.038, 1.055); we test what holds, within 3 standard
/// errors (per-run sd 0.135): range within 4 %, azimuth within 7 %, and the spread over
/// starts smaller than the paper rule's.
#[test]
fn variational_estimator_ends_near_the_truth() {
    let runs = 40;
    let se3 = 3.0 * 0.135 / (runs as f64).sqrt();
    let mut ends = Vec::new();
    for f in STARTS {
        let (mean, _, _) = campaign(Estimator::Variational { rho: 0.97 }, f, runs);
        assert!(
            (mean[0] - 1.0).abs() < 0.04 + se3,
            "range from {f}: {}",
            mean[0]
        );
        assert!(
            (mean[1] - 1.0).abs() < 0.07 + se3,
            "azimuth from {f}: {}",
            mean[1]
        );
        ends.push(mean);
    }
    // Range: spread over starts 0.015 (ours) vs the paper rule's ≈ 0.09.
    let spread = ends.iter().map(|m| m[0]).fold(f64::NEG_INFINITY, f64::max)
        - ends.iter().map(|m| m[0]).fold(f64::INFINITY, f64::min);
    assert!(spread < 0.05, "{spread}");
}

/// Final (range, azimuth) ratios of `runs` runs (seeds 1000 + i): mean, per-run sd, max.
fn evidence_finals(kind: Estimator, start_factor: f64, runs: u64) -> [[f64; 2]; 3] {
    let times = beam_times();
    let (mut s, mut ss, mut mx) = ([0.0; 2], [0.0; 2], [0.0_f64; 2]);
    let base = seed_base();
    for i in 0..runs {
        let mut rng = ChaCha8Rng::seed_from_u64(base + i);
        let pl = plots(&times, SIGMA_R, sigma_t(), &mut rng);
        let o = run_one(kind, start_factor, &times, &pl);
        for c in 0..2 {
            s[c] += o.ratio[c];
            ss[c] += o.ratio[c] * o.ratio[c];
            mx[c] = mx[c].max(o.ratio[c]);
        }
    }
    let r = runs as f64;
    let mean = [s[0] / r, s[1] / r];
    let sd = [0, 1].map(|c| (ss[c] / r - mean[c] * mean[c]).max(0.0).sqrt());
    [mean, sd, mx]
}

/// The evidence estimator as `argus run gimpo` runs it (expected information, h = ln 1.2,
/// ρ = 1, 5 % anchor clip, post-fit read-out after 15 unclipped steps).
///
/// What holds (100 runs, two seed sets 1000+i / 5000+i, docs/papers/000-gimpo.md): range
/// 1.008 … 1.021 / 0.978 … 0.995 from the five starts; azimuth 1.055 … 1.088 — the goal
/// (within 3 %) holds for the range, NOT for the azimuth, which the unmatched turns
/// inflate (maneuver-free truth: 0.92 … 0.94, the IMM's CT modes then make it
/// conservative). Per-run sd 0.165 … 0.18 (range), 0.19 … 0.25 (azimuth), so a 40-run
/// mean has a standard error of 0.03 … 0.04: the tolerance is the goal plus 2 standard
/// errors for the range; for the azimuth we assert the sign of the bias and a bound.
/// No run diverges (the estimator as first built, with each plot's fitted curvature as its
/// information, had runs at 2–4 × the truth after the first plots in `argus run gimpo`):
/// every final ratio stays below 2.5, and common random numbers make the spread over starts
/// a tight check that the start is forgotten (paper rule: 0.09).
#[test]
fn evidence_estimator_range_within_three_percent_and_no_divergence() {
    let runs = 40;
    let kind = Estimator::Evidence {
        spacing: 0.2,
        rho: 1.0,
        clip: Some(0.05),
        settle: Some(15),
        observed: false,
    };
    let se2 = |sd: f64| 2.0 * sd / (runs as f64).sqrt();
    let mut ends = Vec::new();
    for f in STARTS {
        let [mean, sd, mx] = evidence_finals(kind, f, runs);
        println!(
            "evidence from {f}: range {:.4} (sd {:.3}, max {:.2}) azimuth {:.4} (sd {:.3}, max {:.2})",
            mean[0], sd[0], mx[0], mean[1], sd[1], mx[1]
        );
        assert!(
            (mean[0] - 1.0).abs() < 0.03 + se2(0.18),
            "range from {f}: {}",
            mean[0]
        );
        assert!(
            mean[1] > 1.0 && mean[1] < 1.10 + se2(0.25),
            "azimuth from {f}: {}",
            mean[1]
        );
        assert!(mx[0] < 2.5 && mx[1] < 2.5, "from {f}: max {mx:?}");
        ends.push(mean);
    }
    for c in 0..2 {
        let v: Vec<f64> = ends.iter().map(|m| m[c]).collect();
        let spread = v.iter().copied().fold(f64::NEG_INFINITY, f64::max)
            - v.iter().copied().fold(f64::INFINITY, f64::min);
        assert!(spread < 0.04, "axis {c}: spread {spread} over the starts");
    }
}

/// The difference estimator as `argus run gimpo` runs it (ρ = 1, prior 2 pseudo-differences
/// at the start): issue 4's claim, within 3 % of the true variance (mean over runs) from all
/// five starts, range and azimuth separately.
///
/// Expected value, derived: every run's estimate is `(2 f σ² + Σ q) / (2 + n_q)` with the
/// `n_q = 199` third differences of the plots after the two-point start, so (i) the start
/// enters only through the prior: `ratio(f) − ratio(1) = 2 (f − 1) / 201` exactly, per run
/// (common random numbers; nothing feeds back from the IMM), and (ii) `E[q] = σ² + c`, where
/// `c` is the truth's own third difference (the turns' changes of acceleration), computed
/// here from the noise-free plots: +0.05 % (range), +0.55 % (azimuth) of σ².
/// Tolerance: the per-run sd is 0.13 … 0.17 (100 runs each of seeds 1000+i, 5000+i,
/// 9000+i and these 200, docs/papers/000-gimpo.md); with 200 runs the standard error is
/// ≤ 0.17/√200 = 0.012, and the mean must be within 3 of them of the derived value, and
/// within the claim's 3 % of the truth (the derived value is at most 1.0105, so ≥ 1.6
/// standard errors of room at the worst start).
#[test]
fn difference_estimator_within_three_percent_from_every_start() {
    let runs = 200;
    let kind = Estimator::Difference { rho: 1.0 };
    let times = beam_times();
    let truth = NoiseVariances::from_sigmas(SIGMA_R, sigma_t()).unwrap();
    // The truth's own contribution c/σ² per axis (noise-free plots, the same weights).
    let clean = plots(&times, 0.0, 0.0, &mut ChaCha8Rng::seed_from_u64(0));
    let mut c = [0.0; 2];
    let n_q = times.len() - 2 - 3;
    for k in 5..times.len() {
        let w = crate::difference::third_difference_weights(
            times[k - 2] - times[k - 3],
            times[k - 1] - times[k - 2],
            times[k] - times[k - 1],
        );
        let norm: f64 = w.iter().map(|x| x * x).sum();
        let (mut dr, mut da) = (0.0, 0.0);
        for (j, wj) in w.iter().enumerate() {
            let p = &clean[k - 3 + j];
            dr += wj * (p.range() - clean[k].range());
            da += wj * argus_sensors::wrap_angle(p.azimuth() - clean[k].azimuth());
        }
        c[0] += dr * dr / norm / truth.range() / n_q as f64;
        c[1] += da * da / norm / truth.azimuth() / n_q as f64;
    }
    println!(
        "n_q {n_q}, truth's own share: range {:.4} azimuth {:.4}",
        c[0], c[1]
    );
    assert_eq!(n_q, 199);
    let se3 = 3.0 * 0.17 / (runs as f64).sqrt();
    let prior = |f: f64| 2.0 * (f - 1.0) / (2.0 + n_q as f64);
    let mut ends = Vec::new();
    for f in STARTS {
        let [mean, sd, mx] = evidence_finals(kind, f, runs);
        println!(
            "difference from {f}: range {:.4} (sd {:.3}, max {:.2}) azimuth {:.4} (sd {:.3}, max {:.2})",
            mean[0], sd[0], mx[0], mean[1], sd[1], mx[1]
        );
        for ax in 0..2 {
            assert!(
                (mean[ax] - 1.0).abs() < 0.03,
                "axis {ax} from {f}: {}",
                mean[ax]
            );
            let want = 1.0 + c[ax] + prior(f);
            assert!(
                (mean[ax] - want).abs() < se3,
                "axis {ax} from {f}: {} vs derived {want}",
                mean[ax]
            );
            assert!((0.08..0.22).contains(&sd[ax]), "axis {ax}: sd {}", sd[ax]);
        }
        ends.push(mean);
    }
    for (f, m) in STARTS.iter().zip(&ends) {
        for ax in 0..2 {
            let shift = m[ax] - ends[2][ax];
            assert!(
                (shift - prior(*f)).abs() < 1e-9,
                "axis {ax} from {f}: {shift}"
            );
        }
    }
}

/// Exploration of the evidence estimator's parameters (prints; run with --release).
#[test]
#[ignore = "exploration: prints the 100-run table for a set of parameters"]
fn evidence_explore() {
    let spacing: f64 = std::env::var("EV_SPACING").map_or(0.2, |v| v.parse().unwrap());
    let rho: f64 = std::env::var("EV_RHO").map_or(1.0, |v| v.parse().unwrap());
    let clip: f64 = std::env::var("EV_CLIP").map_or(0.05, |v| v.parse().unwrap());
    let runs: u64 = std::env::var("EV_RUNS").map_or(100, |v| v.parse().unwrap());
    let settle: Option<usize> = std::env::var("EV_POST").ok().map(|v| v.parse().unwrap());
    let clip = (clip > 0.0).then_some(clip);
    let true_r = campaign(Estimator::Fixed, 1.0, runs).2;
    for f in STARTS {
        let kind = Estimator::Evidence {
            spacing,
            rho,
            clip,
            settle,
            observed: std::env::var("EV_OBS").is_ok(),
        };
        let (mean, sd, rms) = campaign(kind, f, runs);
        println!(
            "h {spacing} rho {rho} clip {clip:?} start {f}: range {:.4} az {:.4} sd_r {sd:.3} rms {:+.2} %",
            mean[0],
            mean[1],
            100.0 * (rms / true_r - 1.0)
        );
    }
}

/// Exploration of the difference estimator (prints; run with --release): `EV_RUNS`,
/// `EV_SEED`, `EV_STRAIGHT`, `EV_RHO` as for [`evidence_explore`].
#[test]
#[ignore = "exploration: prints the 100-run table of the difference estimator"]
fn difference_explore() {
    let rho: f64 = std::env::var("EV_RHO").map_or(1.0, |v| v.parse().unwrap());
    let runs: u64 = std::env::var("EV_RUNS").map_or(100, |v| v.parse().unwrap());
    let true_r = campaign(Estimator::Fixed, 1.0, runs).2;
    for f in STARTS {
        let [mean, sd, mx] = evidence_finals(Estimator::Difference { rho }, f, runs);
        let rms = campaign(Estimator::Difference { rho }, f, runs).2;
        println!(
            "difference rho {rho} start {f}: range {:.4} (sd {:.3}, max {:.2}) az {:.4} (sd {:.3}, max {:.2}) rms {:+.2} %",
            mean[0],
            sd[0],
            mx[0],
            mean[1],
            sd[1],
            mx[1],
            100.0 * (rms / true_r - 1.0)
        );
    }
}

/// Consistency of an IMM on the gimpo truth with the true `R` (prints; run with --release):
/// per Table 1 segment, the mean over runs and plots of the polar normalised innovation
/// squares `ν_i² / S_ii` (`S = J P⁻ Jᵀ + R`, range and azimuth), the NEES of the combined
/// posterior over 4 states (consistent: 1 each), and the post-fit moment
/// `(ε_i² + (J P⁺ Jᵀ)_ii) / σ_i²` that the evidence read-out averages (consistent: 1).
/// `EV_MODELS` picks another model set, `EV_STRAIGHT` the maneuver-free truth.
#[test]
#[ignore = "diagnosis: prints the IMM's consistency per segment of the gimpo truth"]
fn imm_consistency_on_gimpo() {
    let runs: u64 = std::env::var("EV_RUNS").map_or(100, |v| v.parse().unwrap());
    let imm = mc_imm();
    let conv = UnbiasedConversion::<4>::new(0, 2).unwrap();
    let truth = NoiseVariances::from_sigmas(SIGMA_R, sigma_t()).unwrap();
    let sig = truth.as_array();
    let times = beam_times();
    // Segment boundaries of Table 1 (s); a plot belongs to the segment its time falls in.
    let ends = [
        330.0, 393.0, 513.0, 570.0, 675.0, 718.0, 840.0, 863.0, 933.0, 1019.1,
    ];
    let seg = |t: f64| ends.iter().position(|e| t < *e).unwrap_or(9);
    // Per segment: count, NIS_r, NIS_θ, NEES/4, post_r, post_θ.
    let mut acc = [[0.0_f64; 6]; 10];
    for i in 0..runs {
        let mut rng = ChaCha8Rng::seed_from_u64(seed_base() + i);
        let pl = plots(&times, SIGMA_R, sigma_t(), &mut rng);
        let mut est = two_point(&pl[0], &pl[1], times[1] - times[0], &truth);
        for k in 2..times.len() {
            let dt = times[k] - times[k - 1];
            let pred = imm.predict(&est, dt).unwrap();
            let pc = pred.into_estimate().combined().unwrap();
            let (m, z) = conv.convert(&pl[k], &truth).unwrap();
            est = imm.update(&pred, &m, &z).unwrap().estimate;
            let c = est.combined().unwrap();
            let polar = |g: &Gaussian<4>| {
                let (x, y) = (g.mean()[0], g.mean()[2]);
                let r = x.hypot(y);
                let J = Matrix::<2, 2>::new(x / r, y / r, -y / (r * r), x / (r * r));
                let P = Matrix::<2, 2>::new(
                    g.cov()[(0, 0)],
                    g.cov()[(0, 2)],
                    g.cov()[(2, 0)],
                    g.cov()[(2, 2)],
                );
                let jpj = J * P * J.transpose();
                let e = [
                    pl[k].range() - r,
                    argus_sensors::wrap_angle(pl[k].azimuth() - y.atan2(x)),
                ];
                (e, [jpj[(0, 0)], jpj[(1, 1)]])
            };
            let (nu, jpj_pred) = polar(&pc);
            let (eps, jpj_post) = polar(&c);
            let err = c.mean() - truth_at(times[k]);
            let nees = (err.transpose() * c.cov().try_inverse().unwrap() * err)[(0, 0)];
            let a = &mut acc[seg(times[k])];
            a[0] += 1.0;
            for ax in 0..2 {
                a[1 + ax] += nu[ax] * nu[ax] / (jpj_pred[ax] + sig[ax]);
                a[4 + ax] += (eps[ax] * eps[ax] + jpj_post[ax]) / sig[ax];
            }
            a[3] += nees / 4.0;
        }
    }
    println!("segment (rate °/s): plots  NIS_r  NIS_θ  NEES/4  post_r  post_θ");
    let rates = [0.0, 1.5, 0.0, -0.25, 0.0, -2.0, 0.0, -2.5, -0.5, 0.0];
    let mut tot = [0.0_f64; 6];
    for (j, a) in acc.iter().enumerate() {
        let n = a[0].max(1.0);
        println!(
            "{j} ({:+.2}): {:5.0} {:6.3} {:6.3} {:6.3} {:6.3} {:6.3}",
            rates[j],
            a[0] / runs as f64,
            a[1] / n,
            a[2] / n,
            a[3] / n,
            a[4] / n,
            a[5] / n
        );
        if j > 0 {
            for (t, v) in tot.iter_mut().zip(a) {
                *t += v;
            }
        }
    }
    let n = tot[0];
    println!(
        "after segment 0: NIS_r {:.3} NIS_θ {:.3} NEES/4 {:.3} post_r {:.3} post_θ {:.3}",
        tot[1] / n,
        tot[2] / n,
        tot[3] / n,
        tot[4] / n,
        tot[5] / n
    );
}

/// A loop of IMM and multi-IMM steps for `valgrind --tool=callgrind` (no assertion: a
/// profiling driver, see docs/papers/000-gimpo.md "Cost").
#[test]
#[ignore = "profiling driver"]
fn profile_steps() {
    let imm = paper_imm();
    let conv = UnbiasedConversion::<4>::new(0, 2).unwrap();
    let times = beam_times();
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let pl = plots(&times, SIGMA_R, sigma_t(), &mut rng);
    let var = NoiseVariances::from_sigmas(SIGMA_R, sigma_t()).unwrap();
    let m = MultiImm::new(
        paper_imm(),
        NoiseGrid::<5>::common(0.1).unwrap(),
        Some(0.05),
    )
    .unwrap();
    let mut n = 0.0;
    for _ in 0..10 {
        let mut est = two_point(&pl[0], &pl[1], times[1] - times[0], &var);
        let mut mest = MultiImmEstimate::new(est, var);
        for k in 2..times.len() {
            let dt = times[k] - times[k - 1];
            let (me, z) = conv.convert(&pl[k], &var).unwrap();
            est = imm.step(&est, dt, &me, &z).unwrap().estimate;
            mest = m.step(&mest, dt, &pl[k], &conv).unwrap().estimate;
            n += est.combined().unwrap().mean()[0] + mest.combined().unwrap().mean()[0];
        }
    }
    println!("{n}");
}

/// Per-step cost of the evidence estimator against the paper's 5 × 3 rule for
/// `valgrind --tool=callgrind` (no assertion: a profiling driver). `EV_PROF=multi`,
/// `evidence` or `difference`, `EV_PASSES` passes over one run's plots; the difference between two pass
/// counts divided by the extra steps is the instruction count per step.
#[test]
#[ignore = "profiling driver"]
fn profile_evidence_steps() {
    let which = std::env::var("EV_PROF").unwrap_or_else(|_| "evidence".into());
    let passes: usize = std::env::var("EV_PASSES").map_or(1, |v| v.parse().unwrap());
    let conv = UnbiasedConversion::<4>::new(0, 2).unwrap();
    let times = beam_times();
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let pl = plots(&times, SIGMA_R, sigma_t(), &mut rng);
    let var = NoiseVariances::from_sigmas(SIGMA_R, sigma_t()).unwrap();
    let init = two_point(&pl[0], &pl[1], times[1] - times[0], &var);
    let m = MultiImm::new(
        paper_imm(),
        NoiseGrid::<5>::common(0.1).unwrap(),
        Some(0.05),
    )
    .unwrap();
    let ev = EvidenceNoiseImm::new(paper_imm(), 0.2, 1.0, Some(0.05))
        .unwrap()
        .with_post_fit(15);
    let df = DifferenceNoiseImm::new(paper_imm(), 1.0).unwrap();
    let (mut n, mut steps) = (0.0, 0);
    for _ in 0..passes {
        let mut mest = MultiImmEstimate::new(init, var);
        let mut eest = EvidenceEstimate::new(init, var, 2.0).unwrap();
        let mut dest = DifferenceEstimate::new(init, var, 2.0).unwrap();
        for k in 2..times.len() {
            let dt = times[k] - times[k - 1];
            if which == "difference" {
                dest = df.step(&dest, dt, &pl[k], &conv).unwrap().0;
                n += dest.variances().unwrap().range();
            } else if which == "multi" {
                mest = m.step(&mest, dt, &pl[k], &conv).unwrap().estimate;
                n += mest.reference().range();
            } else {
                eest = ev.step(&eest, dt, &pl[k], &conv).unwrap();
                n += eest.variances().range();
            }
            steps += 1;
        }
    }
    println!("{which}: {steps} steps, {n}");
}

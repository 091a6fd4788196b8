//! Exactness, reference-value and bad-input tests of the association filters and the
//! off-line performance prediction.

#![allow(clippy::unwrap_used)] // test helpers: a failure here is a test failure

use argus_association::{
    AmplitudeModel, AssociationError, Associator, Candidate, ClutterModel, Gate, LinearSystem,
    NearestNeighbour, Pda, PerformancePredictor, PredictedFilter, Psn, SteadyState,
    StrongestNeighbour, hyca_factors, nn_moments, pda_irf, track_step,
};
use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{Ekf, GaussianFilter, Kf};
use argus_motion_models::Cv2D;
use argus_sensors::{CartesianPosition, Polar2D, RadarNoise};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn prior() -> Gaussian<4> {
    Gaussian::new(
        Vector::<4>::new(1000.0, 10.0, 2000.0, -5.0),
        Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(400.0, 25.0, 400.0, 25.0)),
    )
    .unwrap()
}

fn close(a: &Gaussian<4>, b: &Gaussian<4>, tol: f64) -> bool {
    let dm = (a.mean() - b.mean()).abs().max() / b.mean().abs().max();
    let dc = (a.cov() - b.cov()).abs().max() / b.cov().abs().max();
    dm < tol && dc < tol
}

#[test]
fn all_four_equal_the_kalman_filter_without_clutter() {
    // With no clutter, P_D = 1 and the target's plot in the gate, NN, SN, PSN (λ = 0,
    // β_T = 1) and PDA (λ = 0, b = 0, β₁ = 1) are the Kalman update; round-off only (1e-12).
    let kf = Kf::new(Cv2D::discrete(2.0).unwrap());
    let radar = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 100.0).unwrap();
    let gate = Gate::from_probability(0.999, 2).unwrap();
    let amp = AmplitudeModel::from_detection_probability(13.0, 1.0).unwrap();
    let z = Vector::<2>::new(1015.0, 1990.0);
    let plots = [Candidate::with_amplitude(z, 3.0)];
    let pred = kf.predict(&prior(), 1.0).unwrap();
    let (kf_post, _) = kf.update(&pred, &radar, &z).unwrap();
    let nn = track_step(
        &kf,
        &NearestNeighbour::new(gate),
        &radar,
        &prior(),
        1.0,
        &plots,
    )
    .unwrap();
    let sn = track_step(
        &kf,
        &StrongestNeighbour::new(gate),
        &radar,
        &prior(),
        1.0,
        &plots,
    )
    .unwrap();
    let psn = Psn::new(gate, amp, 0.0).unwrap();
    let psn = track_step(&kf, &psn, &radar, &prior(), 1.0, &plots).unwrap();
    let pda = Pda::new(gate, 1.0, ClutterModel::Poisson { density: 0.0 }).unwrap();
    let pda = track_step(&kf, &pda, &radar, &prior(), 1.0, &plots).unwrap();
    for (name, out) in [("NN", &nn), ("SN", &sn), ("PSN", &psn), ("PDA", &pda)] {
        assert!(
            close(&out.posterior, &kf_post, 1e-12),
            "{name}: {:?}",
            out.posterior
        );
        assert_eq!(out.gated, 1, "{name}");
    }
}

#[test]
fn works_on_an_ekf_with_polar_plots() {
    // Same exactness through the EKF (any GaussianFilter): PDA with λ = 0 = EKF update.
    let ekf = Ekf::new(Cv2D::discrete(2.0).unwrap());
    let radar = Polar2D::<4>::new(
        [0, 2],
        [0.0, 0.0],
        RadarNoise::constant(10.0, 0.002, 0.0).unwrap(),
    )
    .unwrap();
    let gate = Gate::from_probability(0.999, 2).unwrap();
    let pred = ekf.predict(&prior(), 1.0).unwrap();
    let mp = ekf.predict_measurement(&pred, &radar).unwrap();
    let z = mp.z_pred() + Vector::<2>::new(5.0, 0.001);
    let (ekf_post, _) = ekf.update(&pred, &radar, &z).unwrap();
    let pda = Pda::new(gate, 1.0, ClutterModel::Poisson { density: 0.0 }).unwrap();
    let out = pda
        .associate(&pred, &mp, &radar, &[Candidate::new(z)])
        .unwrap();
    assert!(close(&out.posterior, &ekf_post, 1e-12));
}

#[test]
#[allow(non_snake_case)]
fn pda_weights_match_a_hand_computation() {
    // Two gated plots, parametric PDA: βᵢ = eᵢ/(b + e₁ + e₂), b = λ(1 − P_D P_G)/P_D,
    // eᵢ = N(νᵢ; 0, S) — computed here independently from S, and the covariance
    // P = β₀P⁻ + (1−β₀)Pᶜ + K(Σβᵢνᵢνᵢᵀ − ν̄ν̄ᵀ)Kᵀ (Bar-Shalom & Tse 1975).
    let kf = Kf::new(Cv2D::discrete(2.0).unwrap());
    let radar = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 100.0).unwrap();
    let gate = Gate::from_probability(0.99, 2).unwrap();
    let (p_d, lambda) = (0.8, 2e-4);
    let pda = Pda::new(gate, p_d, ClutterModel::Poisson { density: lambda }).unwrap();
    let pred = kf.predict(&prior(), 1.0).unwrap();
    let mp = kf.predict_measurement(&pred, &radar).unwrap();
    let v1 = Vector::<2>::new(12.0, -5.0);
    let v2 = Vector::<2>::new(-20.0, 18.0);
    let plots = [
        Candidate::new(mp.z_pred() + v1),
        Candidate::new(mp.z_pred() + v2),
        Candidate::new(mp.z_pred() + Vector::<2>::new(500.0, 0.0)), // outside
    ];
    let out = pda.associate(&pred, &mp, &radar, &plots).unwrap();
    assert_eq!(out.gated, 2);
    let S = *mp.s();
    let Si = S.try_inverse().unwrap();
    let norm = 1.0 / (2.0 * std::f64::consts::PI * S.determinant().sqrt());
    let e = |v: &Vector<2>| norm * (-0.5 * (v.transpose() * Si * v)[(0, 0)]).exp();
    let b = lambda * (1.0 - p_d * gate.p_gate()) / p_d;
    let d = b + e(&v1) + e(&v2);
    let (b1, b2, b0) = (e(&v1) / d, e(&v2) / d, b / d);
    let nu = v1 * b1 + v2 * b2;
    let K = Matrix::<4, 2>::from(*mp.gain());
    let P = pred.cov();
    let H = Matrix::<2, 4>::new(1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0);
    let Pc = P - K * H * P;
    let spread = v1 * v1.transpose() * b1 + v2 * v2.transpose() * b2 - nu * nu.transpose();
    let cov = P * b0 + Pc * (1.0 - b0) + K * spread * K.transpose();
    let mean = pred.mean() + K * nu;
    let expect = Gaussian::from_symmetrized(mean, &cov).unwrap();
    assert!(close(&out.posterior, &expect, 1e-10));
    assert!((out.miss_probability - b0).abs() < 1e-12);
}

#[test]
fn psn_weight_and_negative_information() {
    // One gated plot: β_T = w_T/(w_T + w_F), w_T = P_D N(ν;0,S) ρ(a),
    // w_F = λ(1 − P_D P_G F̄₁(a)) (our derivation, psn.rs). The posterior variance
    // must be larger than the Kalman one, and when nothing is gated P ≥ P⁻.
    let kf = Kf::new(Cv2D::discrete(2.0).unwrap());
    let radar = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 100.0).unwrap();
    let gate = Gate::from_probability(0.999, 2).unwrap();
    let amp = AmplitudeModel::from_detection_probability(10.0, 0.9).unwrap();
    let lambda = 1e-4;
    let psn = Psn::new(gate, amp, lambda).unwrap();
    let pred = kf.predict(&prior(), 1.0).unwrap();
    let mp = kf.predict_measurement(&pred, &radar).unwrap();
    let nu = Vector::<2>::new(10.0, 10.0);
    let a = amp.threshold() + 1.0;
    let out = psn
        .associate(
            &pred,
            &mp,
            &radar,
            &[Candidate::with_amplitude(mp.z_pred() + nu, a)],
        )
        .unwrap();
    let nis = mp.nis(&nu);
    let w_t = amp.p_d() * mp.log_likelihood_from_nis(nis).exp() * amp.likelihood_ratio(a);
    let w_f = lambda * (1.0 - amp.p_d() * gate.p_gate() * amp.target_tail(a));
    assert!((1.0 - out.miss_probability - w_t / (w_t + w_f)).abs() < 1e-12);
    let kf_cov = mp.posterior_cov(pred.cov());
    assert!(out.posterior.cov()[(0, 0)] > kf_cov[(0, 0)]);
    let none = psn.associate(&pred, &mp, &radar, &[]).unwrap();
    assert!(none.posterior.cov()[(0, 0)] > pred.cov()[(0, 0)]);
    assert_eq!(none.posterior.mean(), pred.mean());
}

#[test]
fn hyca_factors_match_the_two_dimensional_closed_form() {
    // n = 2: c_T = (P_D/4) I(β+½), c_F = (β/2)[(1−P_D) I(β) + P_D I(β+½)],
    // I(a) = ∫₀^γ q e^{−aq} dq = (1 − e^{−aγ}(1 + aγ))/a² (Fig. 2 of seed 002 corrected).
    let gate = Gate::from_threshold(16.0, 2).unwrap();
    let g = gate.gamma();
    let i = |a: f64| (1.0 - (-a * g).exp() * (1.0 + a * g)) / (a * a);
    for (beta, p_d) in [(1e-3, 0.9), (0.05, 0.7), (0.5, 1.0)] {
        let (c_t, c_f) = hyca_factors(&gate, beta, p_d).unwrap();
        let e_t = p_d / 4.0 * i(beta + 0.5);
        let e_f = beta / 2.0 * ((1.0 - p_d) * i(beta) + p_d * i(beta + 0.5));
        assert!((c_t / e_t - 1.0).abs() < 1e-10, "c_T {c_t} vs {e_t}");
        assert!((c_f / e_f - 1.0).abs() < 1e-10, "c_F {c_f} vs {e_f}");
    }
    // β = 0: c_T = P_D P(χ²₄ ≤ γ), c_F = 0 (the gated Kalman filter).
    let (c_t, c_f) = hyca_factors(&gate, 0.0, 1.0).unwrap();
    assert!((c_t - gate.second_moment_factor()).abs() < 1e-12 && c_f.abs() < 1e-15);
    // n = 1 and 3 go through the general chi-square path: β = 0 gives G_{n+2}(γ) too.
    for n in [1, 3] {
        let gate = Gate::from_probability(0.999, n).unwrap();
        let (c_t, _) = hyca_factors(&gate, 0.0, 1.0).unwrap();
        assert!((c_t - gate.second_moment_factor()).abs() < 1e-9, "n = {n}");
    }
}

#[test]
fn nn_moments_reduce_to_hyca_for_a_matched_filter() {
    // Σ = I (the filter's S equals the target's S̄): E[uuᵀ1{M_T}] = c_T I and the clutter
    // moment is c_F, the HYCA factors (1e-10: both are Gauss–Legendre on smooth
    // integrands, the angular rule is exact for these quadratic moments).
    for (n, beta, p_d) in [(2, 0.02, 0.9), (2, 0.3, 0.7), (2, 0.0, 1.0)] {
        let gate = Gate::from_threshold(16.0, n).unwrap();
        let m = nn_moments::<2>(&gate, beta, p_d, &Matrix::<2, 2>::identity(), 1.0).unwrap();
        let (c_t, c_f) = hyca_factors(&gate, beta, p_d).unwrap();
        assert!((m.target - Matrix::<2, 2>::identity() * c_t).abs().max() < 1e-10 * c_t);
        assert!(
            (m.clutter - c_f).abs() <= 1e-10 * c_f.max(1e-300),
            "{} {c_f}",
            m.clutter
        );
        // P(M₀) = (1 − P_D P_G) e^{−β γ}.
        let none = (1.0 - p_d * gate.p_gate()) * (-beta * 16.0).exp();
        assert!((m.none - none).abs() < 1e-10, "{} {none}", m.none);
    }
    for n in [1usize, 3] {
        let gate = Gate::from_threshold(9.0, n).unwrap();
        let (c_t, c_f) = hyca_factors(&gate, 0.05, 0.9).unwrap();
        let (t, c) = if n == 1 {
            let m = nn_moments::<1>(&gate, 0.05, 0.9, &Matrix::<1, 1>::identity(), 1.0).unwrap();
            (m.target[(0, 0)], m.clutter)
        } else {
            let m = nn_moments::<3>(&gate, 0.05, 0.9, &Matrix::<3, 3>::identity(), 1.0).unwrap();
            (m.target[(1, 1)], m.clutter)
        };
        assert!((t / c_t - 1.0).abs() < 1e-8, "n {n}: {t} vs {c_t}");
        assert!((c / c_f - 1.0).abs() < 1e-8, "n {n}: {c} vs {c_f}");
    }
    // Σ = s I: the target's gate probability is P(χ²₂ ≤ γ/s) = 1 − e^{−γ/(2s)}.
    let gate = Gate::from_threshold(16.0, 2).unwrap();
    let s = 1.7;
    let m = nn_moments::<2>(&gate, 0.01, 0.9, &(Matrix::<2, 2>::identity() / s), s).unwrap();
    let expect = -(-8.0 / s).exp_m1();
    assert!(
        (m.target_in_gate - expect).abs() < 1e-12,
        "{}",
        m.target_in_gate
    );
}

#[test]
fn nn_moments_match_sampling_with_a_mismatched_filter() {
    // An anisotropic, correlated Σ (the target's innovation wider than the filter
    // thinks): the moments against 200 000 sampled scans (seed 21). Sampling standard
    // errors are ≈ 0.3 % of each moment; we allow 2 %.
    use rand_distr::{Distribution, Poisson, StandardNormal};
    let gate = Gate::from_threshold(16.0, 2).unwrap();
    let (beta, p_d) = (0.04, 0.9);
    let sigma = Matrix::<2, 2>::new(2.0, 0.5, 0.5, 1.2);
    let chol = sigma.cholesky().unwrap().l();
    let sigma_inv = sigma.try_inverse().unwrap();
    let m = nn_moments::<2>(&gate, beta, p_d, &sigma_inv, sigma.determinant().sqrt()).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(21);
    let pois = Poisson::new(beta * 16.0).unwrap();
    let (mut mt, mut mf, mut none) = (Matrix::<2, 2>::zeros(), Matrix::<2, 2>::zeros(), 0.0);
    let samples = 200_000;
    for _ in 0..samples {
        let mut best: Option<(f64, Vector<2>, bool)> = None;
        if rng.random::<f64>() < p_d {
            let w = Vector::<2>::new(
                StandardNormal.sample(&mut rng),
                StandardNormal.sample(&mut rng),
            );
            let u = chol * w;
            if u.norm_squared() <= 16.0 {
                best = Some((u.norm_squared(), u, true));
            }
        }
        let k: f64 = pois.sample(&mut rng);
        for _ in 0..k as usize {
            let r = (16.0 * rng.random::<f64>()).sqrt();
            let th = std::f64::consts::TAU * rng.random::<f64>();
            let u = Vector::<2>::new(r * th.cos(), r * th.sin());
            if best.is_none_or(|(d, _, _)| u.norm_squared() < d) {
                best = Some((u.norm_squared(), u, false));
            }
        }
        match best {
            Some((_, u, true)) => mt += u * u.transpose(),
            Some((_, u, false)) => mf += u * u.transpose(),
            None => none += 1.0,
        }
    }
    let n = f64::from(samples);
    let (mt, mf, none) = (mt / n, mf / n, none / n);
    for (a, b) in [
        (m.target[(0, 0)], mt[(0, 0)]),
        (m.target[(0, 1)], mt[(0, 1)]),
        (m.target[(1, 1)], mt[(1, 1)]),
        (m.clutter, 0.5 * (mf[(0, 0)] + mf[(1, 1)])),
        (m.none, none),
    ] {
        assert!((a / b - 1.0).abs() < 0.02, "quadrature {a} vs sampled {b}");
    }
    // The clutter moment is isotropic: off-diagonal ≈ 0 (within 5 standard errors).
    assert!(mf[(0, 1)].abs() < 0.05 * m.clutter, "{}", mf[(0, 1)]);
}

#[test]
fn general_gain_recursion_with_the_mse_gain_is_hyca() {
    // With the filter's covariance equal to the MSE, K = W̄, S = S̄ and the general-gain
    // update P̄⁻ − W̄M_TKᵀ − KM_TW̄ᵀ + K(M_T + C_F)Kᵀ is Fig. 2's P̄⁻ − (c_T − c_F)W̄S̄W̄ᵀ
    // (round-off and quadrature only: 1e-9 relative).
    let sys = cv_system(1.0, 1.0, 20.0);
    let gate = Gate::from_threshold(16.0, 2).unwrap();
    let p = Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(300.0, 40.0, 300.0, 40.0));
    for lam in [0.0, 1e-5, 5e-5] {
        let general = PerformancePredictor::new(
            sys,
            gate,
            0.9,
            lam,
            PredictedFilter::NearestNeighbourKalmanGain,
        )
        .unwrap()
        .step_with_filter(&p, &p)
        .unwrap();
        let hyca =
            PerformancePredictor::new(sys, gate, 0.9, lam, PredictedFilter::NearestNeighbour)
                .unwrap()
                .step(&p)
                .unwrap();
        let d = (general.posterior - hyca.posterior).abs().max() / hyca.posterior.abs().max();
        assert!(d < 1e-9, "λ = {lam}: {d}");
        assert!((general.filter_gain - hyca.gain).abs().max() < 1e-12);
    }
    // The plain NN's own covariance stays the (averaged) Kalman one while its MSE grows
    // with clutter: at λ = 2e-5 the predicted MSE exceeds the filter's covariance.
    let pp = PerformancePredictor::new(
        sys,
        gate,
        0.9,
        2e-5,
        PredictedFilter::NearestNeighbourKalmanGain,
    )
    .unwrap();
    match pp.steady_state(&p, 1e-9, 20_000).unwrap() {
        SteadyState::Converged { step, .. } => {
            assert!(step.posterior[(0, 0)] > step.filter_posterior[(0, 0)]);
        }
        SteadyState::Diverged { .. } => panic!("expected convergence at λ = 2e-5"),
    }
}

/// `E‖ν̄‖²/n` of the PDA by direct sampling of scans in whitened coordinates.
fn sampled_q2(gate: &Gate, mu: f64, p_d: f64, samples: usize, seed: u64) -> f64 {
    use rand_distr::{Distribution, Poisson, StandardNormal};
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let g = gate.gamma();
    let b = mu * 2.0 * std::f64::consts::PI * (1.0 - p_d * gate.p_gate())
        / (p_d * std::f64::consts::PI * g);
    let pois = Poisson::new(mu).unwrap();
    let mut acc = 0.0;
    for _ in 0..samples {
        let mut d = b;
        let mut sv = Vector::<2>::zeros();
        if rng.random::<f64>() < p_d {
            let u = Vector::<2>::new(
                StandardNormal.sample(&mut rng),
                StandardNormal.sample(&mut rng),
            );
            if u.norm_squared() <= g {
                let e = (-0.5 * u.norm_squared()).exp();
                d += e;
                sv += u * e;
            }
        }
        let m: f64 = pois.sample(&mut rng);
        for _ in 0..m as usize {
            let r = (g * rng.random::<f64>()).sqrt();
            let th = std::f64::consts::TAU * rng.random::<f64>();
            let u = Vector::<2>::new(r * th.cos(), r * th.sin());
            let e = (-0.5 * u.norm_squared()).exp();
            d += e;
            sv += u * e;
        }
        if d > 0.0 {
            acc += (sv / d).norm_squared();
        }
    }
    acc / samples as f64 / 2.0
}

#[test]
fn pda_information_reduction_factor() {
    let gate = Gate::from_threshold(16.0, 2).unwrap();
    // μ = 0: q₂ = P_D P(χ²₄ ≤ γ) exactly (derived in prediction.rs).
    let q = pda_irf(&gate, 0.0, 0.9).unwrap();
    assert!((q - 0.9 * gate.second_moment_factor()).abs() < 1e-6, "{q}");
    // Against direct sampling of the PDA weights (40 000 scans, seed 7): the sampling
    // error of q₂ is below 1 %; we allow 2 %.
    for (mu, p_d) in [(0.5, 0.9), (2.0, 0.9), (5.0, 0.7)] {
        let q = pda_irf(&gate, mu, p_d).unwrap();
        let s = sampled_q2(&gate, mu, p_d, 40_000, 7);
        assert!(
            (q / s - 1.0).abs() < 0.02,
            "μ = {mu}: quadrature {q} vs sampled {s}"
        );
    }
    // More clutter, less information.
    assert!(pda_irf(&gate, 5.0, 0.9).unwrap() < pda_irf(&gate, 1.0, 0.9).unwrap());
}

#[allow(non_snake_case)]
fn cv_system(T: f64, sigma_a: f64, sigma: f64) -> LinearSystem<4, 2> {
    let f = Matrix::<2, 2>::new(1.0, T, 0.0, 1.0);
    let q = Matrix::<2, 2>::new(T.powi(4) / 4.0, T.powi(3) / 2.0, T.powi(3) / 2.0, T * T)
        * sigma_a
        * sigma_a;
    let mut F = Matrix::<4, 4>::zeros();
    let mut Q = Matrix::<4, 4>::zeros();
    F.fixed_view_mut::<2, 2>(0, 0).copy_from(&f);
    F.fixed_view_mut::<2, 2>(2, 2).copy_from(&f);
    Q.fixed_view_mut::<2, 2>(0, 0).copy_from(&q);
    Q.fixed_view_mut::<2, 2>(2, 2).copy_from(&q);
    let H = Matrix::<2, 4>::new(1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0);
    LinearSystem::new(F, Q, H, Matrix::<2, 2>::identity() * sigma * sigma).unwrap()
}

#[test]
fn steady_states_order_and_divergence() {
    // No clutter, P_D = 1, wide gate: both recursions give (nearly) the KF steady state,
    // which is below every cluttered one; very dense clutter makes NN's diverge.
    let sys = cv_system(1.0, 2.0, 20.0);
    let gate = Gate::from_threshold(25.0, 2).unwrap();
    let p0 = Matrix::<4, 4>::identity() * 400.0;
    let ss = |f, pd, lam| {
        PerformancePredictor::new(sys, gate, pd, lam, f)
            .unwrap()
            .steady_state(&p0, 1e-10, 20_000)
            .unwrap()
    };
    let tr = |s: SteadyState<4, 2>| match s {
        SteadyState::Converged { step, .. } => step.posterior[(0, 0)] + step.posterior[(2, 2)],
        SteadyState::Diverged { .. } => f64::INFINITY,
    };
    let kf_nn = tr(ss(PredictedFilter::NearestNeighbour, 1.0, 0.0));
    let kf_pda = tr(ss(PredictedFilter::Pda, 1.0, 0.0));
    // Both factors are G₄(25) = 1 − e^{−12.5}(1 + 12.5) ≈ 0.99995 at λ = 0: equal to 1e-6.
    assert!((kf_nn / kf_pda - 1.0).abs() < 1e-6, "{kf_nn} {kf_pda}");
    let pda = tr(ss(PredictedFilter::Pda, 0.9, 1e-4));
    let nn = tr(ss(PredictedFilter::NearestNeighbour, 0.9, 1e-4));
    assert!(pda > kf_pda && nn > kf_nn);
    assert!(matches!(
        ss(PredictedFilter::NearestNeighbour, 0.9, 1e-2),
        SteadyState::Diverged { .. }
    ));
}

#[test]
fn bad_input_is_rejected_with_a_named_error() {
    let kf = Kf::new(Cv2D::discrete(2.0).unwrap());
    let radar = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 100.0).unwrap();
    let gate = Gate::from_probability(0.99, 2).unwrap();
    let amp = AmplitudeModel::from_detection_probability(10.0, 0.9).unwrap();
    let prior = prior();
    let before = prior;
    let nan = [Candidate::with_amplitude(
        Vector::<2>::new(f64::NAN, 0.0),
        3.0,
    )];
    let nn = NearestNeighbour::new(gate);
    assert!(matches!(
        track_step(&kf, &nn, &radar, &prior, 1.0, &nan),
        Err(AssociationError::Filter(_))
    ));
    // Time going backwards.
    assert!(matches!(
        track_step(&kf, &nn, &radar, &prior, -1.0, &[]),
        Err(AssociationError::Filter(_))
    ));
    let z = *prior.mean();
    let near = Vector::<2>::new(z[0] + 10.0, z[2]);
    let sn = StrongestNeighbour::new(gate);
    assert!(matches!(
        track_step(&kf, &sn, &radar, &prior, 1.0, &[Candidate::new(near)]),
        Err(AssociationError::MissingAmplitude { index: 0, .. })
    ));
    let psn = Psn::new(gate, amp, 1e-4).unwrap();
    assert!(matches!(
        track_step(
            &kf,
            &psn,
            &radar,
            &prior,
            1.0,
            &[Candidate::with_amplitude(near, 0.1)]
        ),
        Err(AssociationError::InvalidAmplitude { index: 0, .. })
    ));
    assert_eq!(prior, before);
    // Constructors.
    assert!(Pda::new(gate, 1.5, ClutterModel::NonParametric).is_err());
    assert!(Pda::new(gate, 0.9, ClutterModel::Poisson { density: -1.0 }).is_err());
    assert!(Psn::new(gate, amp, f64::NAN).is_err());
    let gate3 = Gate::from_probability(0.99, 3).unwrap();
    assert!(matches!(
        track_step(&kf, &NearestNeighbour::new(gate3), &radar, &prior, 1.0, &[]),
        Err(AssociationError::DimensionMismatch {
            expected: 3,
            got: 2,
            ..
        })
    ));
    assert!(hyca_factors(&gate, -1.0, 0.9).is_err());
    assert!(pda_irf(&gate, f64::NAN, 0.9).is_err());
    let mut bad_r = Matrix::<2, 2>::identity();
    bad_r[(1, 1)] = -1.0;
    assert!(
        LinearSystem::new(
            Matrix::<4, 4>::identity(),
            Matrix::<4, 4>::identity(),
            Matrix::<2, 4>::zeros(),
            bad_r
        )
        .is_err()
    );
    let sys = cv_system(1.0, 1.0, 10.0);
    assert!(PerformancePredictor::new(sys, gate3, 0.9, 1e-4, PredictedFilter::Pda).is_err());
    assert!(PerformancePredictor::new(sys, gate, 0.0, 1e-4, PredictedFilter::Pda).is_err());
    // The general-gain NN moments and step.
    let id2 = Matrix::<2, 2>::identity();
    let gate2 = Gate::from_threshold(16.0, 2).unwrap();
    assert!(nn_moments::<2>(&gate2, -0.1, 0.9, &id2, 1.0).is_err());
    assert!(nn_moments::<2>(&gate2, 0.1, 1.2, &id2, 1.0).is_err());
    assert!(nn_moments::<2>(&gate2, 0.1, 0.9, &(id2 * f64::NAN), 1.0).is_err());
    assert!(nn_moments::<2>(&gate2, 0.1, 0.9, &id2, 0.0).is_err());
    assert!(matches!(
        nn_moments::<2>(&gate3, 0.1, 0.9, &id2, 1.0),
        Err(AssociationError::DimensionMismatch { .. })
    ));
    let gate4 = Gate::from_threshold(16.0, 4).unwrap();
    assert!(matches!(
        nn_moments::<4>(&gate4, 0.1, 0.9, &Matrix::<4, 4>::identity(), 1.0),
        Err(AssociationError::InvalidParameter { .. })
    ));
    let pp = PerformancePredictor::new(
        sys,
        gate2,
        0.9,
        1e-5,
        PredictedFilter::NearestNeighbourKalmanGain,
    )
    .unwrap();
    let p = Matrix::<4, 4>::identity() * 100.0;
    assert!(pp.step_with_filter(&p, &(p * f64::NAN)).is_err());
    assert!(pp.step_with_filter(&p, &(p * -1.0)).is_err());
}

#[test]
fn imm_pda_with_identical_modes_is_the_pda() {
    // An IMM with two identical modes and the PDA as association: both modes give the
    // plain PDA posterior and the mode probabilities stay at the Markov prediction (the
    // likelihoods are equal), to round-off (1e-12).
    use argus_association::imm_associate;
    use argus_imm::{Imm, ImmEstimate, MarkovMatrix};
    let kf = Kf::new(Cv2D::discrete(2.0).unwrap());
    let radar = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 100.0).unwrap();
    let gate = Gate::from_probability(0.999, 2).unwrap();
    let pda = Pda::new(gate, 0.9, ClutterModel::Poisson { density: 1e-4 }).unwrap();
    let imm = Imm::new(
        [kf, kf],
        MarkovMatrix::new([[0.9, 0.1], [0.2, 0.8]]).unwrap(),
    )
    .unwrap();
    let est = ImmEstimate::from_common(prior(), [0.3, 0.7]).unwrap();
    let pred = imm.predict(&est, 1.0).unwrap();
    let z = *pred.modes()[0].mean();
    let plots = [
        Candidate::new(Vector::<2>::new(z[0] + 8.0, z[2] - 4.0)),
        Candidate::new(Vector::<2>::new(z[0] - 20.0, z[2] + 15.0)),
    ];
    let (upd, ll) = imm_associate(imm.filters(), &pda, &radar, &pred, &plots).unwrap();
    let single = track_step(&kf, &pda, &radar, &prior(), 1.0, &plots).unwrap();
    assert!(close(&upd.modes()[0], &single.posterior, 1e-12));
    assert!((ll[0] - single.log_likelihood).abs() < 1e-12);
    let mu_pred = pred.log_predicted_probabilities().map(f64::exp);
    for (a, b) in upd.mode_probabilities().iter().zip(mu_pred) {
        assert!((a - b).abs() < 1e-12);
    }
}

#[test]
fn non_parametric_pda_uses_m_over_v() {
    // The non-parametric PDA is the parametric one with λ = m/V (m gated plots, V the
    // gate volume c₂ γ |S|^{1/2}); equal to round-off (1e-12).
    let kf = Kf::new(Cv2D::discrete(2.0).unwrap());
    let radar = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 100.0).unwrap();
    let gate = Gate::from_probability(0.99, 2).unwrap();
    let pred = kf.predict(&prior(), 1.0).unwrap();
    let mp = kf.predict_measurement(&pred, &radar).unwrap();
    let plots = [
        Candidate::new(mp.z_pred() + Vector::<2>::new(10.0, 3.0)),
        Candidate::new(mp.z_pred() + Vector::<2>::new(-25.0, 12.0)),
        Candidate::new(mp.z_pred() + Vector::<2>::new(5.0, -30.0)),
    ];
    let np = Pda::new(gate, 0.8, ClutterModel::NonParametric).unwrap();
    let out = np.associate(&pred, &mp, &radar, &plots).unwrap();
    let lambda = out.gated as f64 / gate.volume(&mp);
    let par = Pda::new(gate, 0.8, ClutterModel::Poisson { density: lambda }).unwrap();
    let expect = par.associate(&pred, &mp, &radar, &plots).unwrap();
    assert_eq!(out.gated, 3);
    assert!(close(&out.posterior, &expect.posterior, 1e-12));
}

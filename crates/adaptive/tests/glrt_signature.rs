//! Exactness of the GLRT signature, statistic, estimate and correction on
//! noise-free data (seed 001 eqs 3-2 to 3-12; derived: with `r₁ = 0` the innovation
//! is exactly `G(m;θ) u`, so `û = u` and the corrected state is the truth up to
//! round-off), its null distribution, and the MRAS estimator's closed forms.
#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

mod glrt_common;

use argus_adaptive::{
    AdaptiveError, Compensation, FailureKind, Glrt, GlrtConfig, ManeuverState, Mras,
    StepLinearization,
};
use argus_core_math::{Gaussian, Matrix, Vector, chi2_quantile};
use argus_filters::{FilterError, GaussianFilter};
use glrt_common::*;

#[test]
fn persistent_input_is_recovered_exactly_and_correction_restores_truth() {
    // Threshold tiny so the best hypothesis is always reported.
    let model = Cv1 { q: Q };
    let kf = TestKf { model };
    let meas = Pos1 { r: R };
    let phi = Matrix::<2, 2>::new(1.0, T, 0.0, 1.0);
    let g = Matrix::<2, 1>::from_column_slice(gamma().as_slice());
    let h = Matrix::<1, 2>::new(1.0, 0.0);
    let onset = 10;
    let u = 210.0;
    let mut glrt =
        Glrt::<2, 1, 1>::new(GlrtConfig::new(30, 0, 1e-12, FailureKind::Persistent).unwrap());
    let mut x = Vector::<2>::new(2000.0, 70.0);
    let mut est = Gaussian::new(x, Matrix::<2, 2>::identity() * 100.0).unwrap();
    for k in 0..onset + 12 {
        x = phi * x + gamma() * if k >= onset { u } else { 0.0 };
        let pred = kf.predict(&est, T).unwrap();
        let mp = kf.predict_measurement(&pred, &meas).unwrap();
        let innov = mp.innovation(&meas, &Vector::<1>::new(x[0])).unwrap();
        est = mp.update(&pred, &innov.residual).unwrap();
        let out = glrt
            .step(&StepLinearization {
                phi: &phi,
                gamma: &g,
                h: &h,
                gain: mp.gain(),
                s_factor: mp.s_factor(),
                residual: &innov.residual,
            })
            .unwrap();
        glrt.commit();
        if k >= onset {
            let det = out.detection.expect("noise-free maneuver must give l > 0");
            // Derived: the true onset explains the innovations exactly.
            assert_eq!(det.age, k - onset, "onset at step {k}");
            assert!(
                (det.input[0] - u).abs() < 1e-6 * u,
                "u_hat {} at step {k}",
                det.input[0]
            );
            let corrected = est.mean() + det.state_correction();
            assert!(
                (corrected - x).norm() < 1e-6,
                "corrected {corrected:?} truth {x:?}"
            );
        } else {
            // Before the onset every innovation is exactly zero: l = 0 < 1e-12.
            assert!(out.detection.is_none());
        }
    }
}

#[test]
fn jump_is_recovered_exactly() {
    let model = Cv1 { q: Q };
    let kf = TestKf { model };
    let meas = Pos1 { r: R };
    let phi = Matrix::<2, 2>::new(1.0, T, 0.0, 1.0);
    // A jump through the full identity (the paper's D(θ;θ) = I is 2-D; here a jump of
    // the state through Γ = I with a 2-D "input").
    let gi = Matrix::<2, 2>::identity();
    let h = Matrix::<1, 2>::new(1.0, 0.0);
    let jump = Vector::<2>::new(5.0, -4.0);
    let mut glrt = Glrt::<2, 1, 2>::new(GlrtConfig::new(30, 0, 1e-12, FailureKind::Jump).unwrap());
    let mut x = Vector::<2>::new(2000.0, 70.0);
    let mut est = Gaussian::new(x, Matrix::<2, 2>::identity() * 100.0).unwrap();
    let onset = 6;
    let mut checked = 0;
    for k in 0..onset + 10 {
        x = phi * x
            + if k == onset {
                jump
            } else {
                Vector::<2>::zeros()
            };
        let pred = kf.predict(&est, T).unwrap();
        let mp = kf.predict_measurement(&pred, &meas).unwrap();
        let innov = mp.innovation(&meas, &Vector::<1>::new(x[0])).unwrap();
        est = mp.update(&pred, &innov.residual).unwrap();
        let out = glrt
            .step(&StepLinearization {
                phi: &phi,
                gamma: &gi,
                h: &h,
                gain: mp.gain(),
                s_factor: mp.s_factor(),
                residual: &innov.residual,
            })
            .unwrap();
        glrt.commit();
        // A 2-D jump from scalar plots is identifiable after two plots (C rank 2).
        if k > onset {
            let det = out.detection.expect("identifiable");
            assert_eq!(det.age, k - onset);
            assert!(
                (det.input - jump).norm() < 1e-6,
                "jump estimate {:?}",
                det.input
            );
            assert!((est.mean() + det.state_correction() - x).norm() < 1e-6);
            checked += 1;
        }
    }
    assert_eq!(checked, 9);
}

#[test]
fn statistic_for_a_fixed_onset_is_chi_square_one_under_no_maneuver() {
    // With M = N = 10 exactly one onset is tested each step, and under H0 its l is
    // χ²(1) (Willsky & Jones 1976). Per-step exceedance of the 0.99 quantile must be
    // 1 % ± 3 binomial sigmas over 200 runs × 140 tested steps = 28 000 (correlated
    // across steps, so the bound is loose on purpose: ±0.25 %).
    let eta = chi2_quantile(0.99, 1.0).unwrap();
    let cfg = GlrtConfig::new(10, 10, eta, FailureKind::Persistent).unwrap();
    let (mut fires, mut tested, mut sum_l) = (0usize, 0usize, 0.0);
    for seed in 0..200 {
        let run = simulate(1000 + seed, &[], 0.0);
        let kf = TestKf {
            model: Cv1 { q: Q },
        };
        let meas = Pos1 { r: R };
        let phi = Matrix::<2, 2>::new(1.0, T, 0.0, 1.0);
        let g = Matrix::<2, 1>::from_column_slice(gamma().as_slice());
        let h = Matrix::<1, 2>::new(1.0, 0.0);
        let mut glrt = Glrt::<2, 1, 1>::new(cfg);
        let mut est = run.initial;
        for z in &run.plots {
            let pred = kf.predict(&est, T).unwrap();
            let mp = kf.predict_measurement(&pred, &meas).unwrap();
            let innov = mp.innovation(&meas, &Vector::<1>::new(*z)).unwrap();
            est = mp.update(&pred, &innov.residual).unwrap();
            let out = glrt
                .step(&StepLinearization {
                    phi: &phi,
                    gamma: &g,
                    h: &h,
                    gain: mp.gain(),
                    s_factor: mp.s_factor(),
                    residual: &innov.residual,
                })
                .unwrap();
            glrt.commit();
            if let Some((l, age)) = out.max_statistic {
                assert_eq!(age, 10);
                tested += 1;
                sum_l += l;
                fires += usize::from(l >= eta);
            }
        }
    }
    let rate = fires as f64 / tested as f64;
    let mean = sum_l / tested as f64;
    assert!((rate - 0.01).abs() < 0.0025, "false-alarm rate {rate}");
    // E[χ²(1)] = 1; the sample mean of 28 000 correlated values: ±0.05.
    assert!((mean - 1.0).abs() < 0.05, "mean statistic {mean}");
}

#[test]
fn mras_with_infinite_initial_gain_equals_the_glrt_ml_estimate() {
    // Eq 4-6 with L(0) → ∞ is the ML estimate C⁻¹ d: MRAS started at the onset must
    // reproduce the GLRT's û for that onset (same sums), to round-off.
    let run = simulate(7, &[(2.0, 6.0)], 210.0);
    let kf = TestKf {
        model: Cv1 { q: Q },
    };
    let meas = Pos1 { r: R };
    let phi = Matrix::<2, 2>::new(1.0, T, 0.0, 1.0);
    let g = Matrix::<2, 1>::from_column_slice(gamma().as_slice());
    let h = Matrix::<1, 2>::new(1.0, 0.0);
    let onset = 40; // first step with the input on (t = 2.0–2.05 s)
    let mut glrt =
        Glrt::<2, 1, 1>::new(GlrtConfig::new(15, 15, 1e-12, FailureKind::Persistent).unwrap());
    // The same detector with a prior information Λ₀ = 1/4 on the input (L(0) = 4, u(0) = 0).
    let mut glrt_prior =
        Glrt::<2, 1, 1>::new(GlrtConfig::new(15, 15, 1e-12, FailureKind::Persistent).unwrap())
            .with_input_prior(Matrix::<1, 1>::new(0.25))
            .unwrap();
    let mut mras: Mras<2, 1> = Mras::new_ml();
    let prior_l0 = Matrix::<1, 1>::new(4.0);
    let u0 = Vector::<1>::new(100.0);
    let mut mras_prior = Mras::<2, 1>::with_prior(u0, &prior_l0).unwrap();
    let (mut c, mut d) = (0.0, 0.0);
    let mut est = run.initial;
    let mut rls_u = u0[0];
    let mut rls_l = prior_l0[(0, 0)];
    let mut compared = 0;
    let mut dev_f = (Matrix::<2, 1>::zeros(), Matrix::<2, 1>::zeros());
    for (k, z) in run.plots.iter().enumerate() {
        let pred = kf.predict(&est, T).unwrap();
        let mp = kf.predict_measurement(&pred, &meas).unwrap();
        let innov = mp.innovation(&meas, &Vector::<1>::new(*z)).unwrap();
        est = mp.update(&pred, &innov.residual).unwrap();
        let lin = StepLinearization {
            phi: &phi,
            gamma: &g,
            h: &h,
            gain: mp.gain(),
            s_factor: mp.s_factor(),
            residual: &innov.residual,
        };
        let out = glrt.step(&lin).unwrap();
        glrt.commit();
        let out_prior = glrt_prior.step(&lin).unwrap();
        glrt_prior.commit();
        if k >= onset {
            // Independent regressor: D ← Φ D + Γ, G = H (D − Φ F), F ← Φ F + K G (eqs 3-3, 3-4).
            let started = k > onset;
            let dev = if started { phi * dev_f.0 + g } else { g };
            let phi_f = if started {
                phi * dev_f.1
            } else {
                Matrix::<2, 1>::zeros()
            };
            let gk = (h * (dev - phi_f))[(0, 0)];
            dev_f = (dev, phi_f + mp.gain() * gk);
            mras = mras.step(&lin).unwrap();
            mras_prior = mras_prior.step(&lin).unwrap();
            // Textbook scalar RLS (eqs 4-4, 4-5 over one step): L⁻¹ += G²/S, u += L G (r − G u)/S.
            let s = mp.s()[(0, 0)];
            rls_l = 1.0 / (1.0 / rls_l + gk * gk / s);
            rls_u += rls_l * gk * (innov.residual[0] - gk * rls_u) / s;
            c += gk * gk / s;
            d += gk * innov.residual[0] / s;
            let (u_prior, l_prior) = mras_prior.estimate().unwrap();
            // Closed form, eq 4-6/4-7 in discrete form: (L0⁻¹ + C)⁻¹ (L0⁻¹ u0 + d).
            let closed = (u0[0] / prior_l0[(0, 0)] + d) / (1.0 / prior_l0[(0, 0)] + c);
            assert!(
                (u_prior[0] - closed).abs() < 1e-9 * closed.abs().max(1.0),
                "closed form"
            );
            assert!(
                (u_prior[0] - rls_u).abs() < 1e-9 * rls_u.abs().max(1.0),
                "RLS recursion"
            );
            assert!((l_prior[(0, 0)] - rls_l).abs() < 1e-12 * rls_l);
        }
        if k == onset + 15 {
            let det = out.detection.expect("tiny threshold");
            assert_eq!(det.age, 15);
            let (u_ml, l_ml) = mras.estimate().unwrap();
            assert!(
                (u_ml[0] - det.input[0]).abs() < 1e-9 * det.input[0].abs(),
                "MRAS {u_ml:?} vs GLRT {:?}",
                det.input
            );
            assert!((l_ml[(0, 0)] - det.input_cov[(0, 0)]).abs() < 1e-9 * l_ml[(0, 0)]);
            // With the prior: û = (Λ₀ + C)⁻¹ d, covariance (Λ₀ + C)⁻¹ (eq 4-6, finite L(0),
            // u(0) = 0), from the independent sums; the statistic stays dᵀ C⁻¹ d = d²/C.
            let det_p = out_prior.detection.expect("tiny threshold");
            let closed = d / (0.25 + c);
            assert!(
                (det_p.input[0] - closed).abs() < 1e-9 * closed.abs(),
                "prior estimate"
            );
            assert!((det_p.input_cov[(0, 0)] - 1.0 / (0.25 + c)).abs() < 1e-9 / (0.25 + c));
            assert!((det_p.statistic - d * d / c).abs() < 1e-9 * det_p.statistic);
            assert!((det_p.statistic - det.statistic).abs() < 1e-9 * det.statistic);
            compared += 1;
        }
    }
    assert_eq!(compared, 1);
}

#[test]
fn bad_configuration_and_inputs_are_rejected_and_leave_state_unchanged() {
    assert!(matches!(
        GlrtConfig::new(5, 6, 20.0, FailureKind::Persistent),
        Err(AdaptiveError::InvalidWindow {
            max_age: 5,
            min_age: 6,
            ..
        })
    ));
    assert!(matches!(
        GlrtConfig::new(20, 5, f64::NAN, FailureKind::Persistent),
        Err(AdaptiveError::InvalidParameter {
            what: "GLRT threshold eta",
            ..
        })
    ));
    assert!(matches!(
        GlrtConfig::new(20, 5, -1.0, FailureKind::Jump),
        Err(AdaptiveError::InvalidParameter { .. })
    ));
    assert!(
        GlrtConfig::new(
            argus_adaptive::glrt::MAX_WINDOW + 1,
            0,
            1.0,
            FailureKind::Jump
        )
        .is_err()
    );
    assert!(Mras::<2, 1>::with_prior(Vector::<1>::new(0.0), &Matrix::<1, 1>::new(-1.0)).is_err());
    // A GLRT input prior must be finite and positive definite.
    let cfg1 = GlrtConfig::new(20, 5, 20.0, FailureKind::Persistent).unwrap();
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(
            matches!(
                Glrt::<2, 1, 1>::new(cfg1).with_input_prior(Matrix::<1, 1>::new(bad)),
                Err(AdaptiveError::Math(_))
            ),
            "{bad}"
        );
    }
    assert!(
        Mras::<2, 1>::with_prior(Vector::<1>::new(f64::NAN), &Matrix::<1, 1>::new(1.0)).is_err()
    );
    assert!(
        argus_adaptive::ModelInput::<Cv1, 2, 1>::new(
            Cv1 { q: Q },
            Matrix::<2, 1>::new(f64::INFINITY, 1.0)
        )
        .is_err()
    );

    let run = simulate(3, &[(2.0, 6.0)], 210.0);
    let ad = adaptive(Compensation::GlrtMras);
    let meas = Pos1 { r: R };
    let mut st = ManeuverState::<2, 1, 1>::new(run.initial, config(20, 5, 20.0));
    for z in run.plots.iter().take(60) {
        ad.step(&mut st, T, &meas, &Vector::<1>::new(*z)).unwrap();
    }
    let before = st.clone();
    for (dt, z, what) in [
        (-T, 1.0, "negative dt"),
        (0.0, 1.0, "zero dt"),
        (f64::NAN, 1.0, "NaN dt"),
        (T, f64::NAN, "NaN plot"),
        (T, f64::INFINITY, "infinite plot"),
    ] {
        let err = ad
            .step(&mut st, dt, &meas, &Vector::<1>::new(z))
            .unwrap_err();
        match what {
            "NaN plot" | "infinite plot" => {
                assert!(matches!(err, AdaptiveError::Math(_)), "{what}: {err}")
            }
            _ => assert!(
                matches!(
                    err,
                    AdaptiveError::Filter(FilterError::InvalidInterval { .. })
                ),
                "{what}: {err}"
            ),
        }
        assert_eq!(st.estimate(), before.estimate(), "{what}");
        assert_eq!(st.steps(), before.steps());
        assert_eq!(st.glrt().len(), before.glrt().len());
        assert_eq!(st.input_estimate(), before.input_estimate());
    }
    // Non-finite step quantities are rejected by the bare detector too.
    let mut glrt = Glrt::<2, 1, 1>::new(config(20, 5, 20.0));
    let s = argus_core_math::SpdFactor::new(&Matrix::<1, 1>::new(36.0), "S").unwrap();
    let bad_phi = Matrix::<2, 2>::new(1.0, f64::NAN, 0.0, 1.0);
    let err = glrt
        .step(&StepLinearization {
            phi: &bad_phi,
            gamma: &Matrix::<2, 1>::new(0.0, 1.0),
            h: &Matrix::<1, 2>::new(1.0, 0.0),
            gain: &Matrix::<2, 1>::new(0.5, 0.1),
            s_factor: &s,
            residual: &Vector::<1>::new(0.0),
        })
        .unwrap_err();
    assert!(matches!(
        err,
        AdaptiveError::Math(argus_core_math::MathError::NonFinite {
            what: "transition Phi"
        })
    ));
    assert!(glrt.is_empty());
}

#[test]
fn with_threshold_keeps_the_window_and_only_changes_the_decision() {
    let model = Cv1 { q: Q };
    let kf = TestKf { model };
    let meas = Pos1 { r: R };
    let phi = Matrix::<2, 2>::new(1.0, T, 0.0, 1.0);
    let g = Matrix::<2, 1>::from_column_slice(gamma().as_slice());
    let h = Matrix::<1, 2>::new(1.0, 0.0);
    let mut glrt =
        Glrt::<2, 1, 1>::new(GlrtConfig::new(20, 0, 1e-12, FailureKind::Persistent).unwrap());
    assert!(glrt.clone().with_threshold(f64::NAN).is_err());
    assert!(glrt.clone().with_threshold(0.0).is_err());
    let mut x = Vector::<2>::new(2000.0, 70.0);
    let mut est = Gaussian::new(x, Matrix::<2, 2>::identity() * 100.0).unwrap();
    let mut copy = None;
    for k in 0..16 {
        x = phi * x + gamma() * if k >= 8 { 210.0 } else { 0.0 };
        let pred = kf.predict(&est, T).unwrap();
        let mp = kf.predict_measurement(&pred, &meas).unwrap();
        let innov = mp.innovation(&meas, &Vector::<1>::new(x[0])).unwrap();
        est = mp.update(&pred, &innov.residual).unwrap();
        let lin = StepLinearization {
            phi: &phi,
            gamma: &g,
            h: &h,
            gain: mp.gain(),
            s_factor: mp.s_factor(),
            residual: &innov.residual,
        };
        if k == 10 {
            let c: Glrt<2, 1, 1> = glrt.clone().with_threshold(f64::MAX).unwrap();
            assert_eq!(c.len(), glrt.len());
            assert!(c.config().threshold() >= f64::MAX);
            copy = Some(c);
        }
        let out = glrt.step(&lin).unwrap();
        glrt.commit();
        if let Some(c) = copy.as_mut() {
            let o = c.step(&lin).unwrap();
            c.commit();
            // Same window, same statistic (bit for bit); only the decision differs.
            assert_eq!(o.max_statistic, out.max_statistic, "step {k}");
            assert!(o.detection.is_none() && out.detection.is_some(), "step {k}");
        }
    }
}

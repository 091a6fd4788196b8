//! Tests of the aircraft IMM: typed errors with the estimate untouched, the mixing rule,
//! and a steady turn's rate found.

use argus_core_math::Vector;
use argus_filters::GaussianFilter;
use argus_motion_models::{CoordinatedTurnRate, MotionModel};
use argus_sensors::RadarNoise;

use super::*;
use crate::ImmError;

fn radar() -> AircraftRadar {
    AircraftRadar::new(
        [0.0, 0.0],
        RadarNoise::constant(70.0, 0.08_f64.to_radians(), 0.0).unwrap(),
    )
    .unwrap()
}

/// Noise-free plots of a `[x, vx, y, vy, ω]` truth every 5 s.
fn turn_plots(omega_deg: f64, n: usize) -> Vec<Vector<2>> {
    let truth_model = CoordinatedTurnRate::new(0.0, 0.0).unwrap();
    let mut x = Vector::<5>::new(60e3, -150.0, 20e3, 80.0, omega_deg.to_radians());
    let r = radar();
    (0..n)
        .map(|_| {
            let z = r.predict(&x.fixed_rows::<4>(0).into_owned());
            x = truth_model.propagate(&x, 5.0);
            z
        })
        .collect()
}

#[test]
fn bad_steps_are_typed_errors_and_leave_the_estimate_untouched() {
    let tuning = AircraftTuning::<2, 3>::default();
    let imm = tuning.build().unwrap();
    let z = turn_plots(0.0, 3);
    let est = tuning.start(&radar(), &z[0], &z[1], 5.0).unwrap();
    let before = est;
    for dt in [0.0, -5.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            imm.step(&est, dt, &radar(), &z[2]),
            Err(ImmError::InvalidInterval { .. })
        ));
    }
    for (bad, what) in [
        (Vector::<2>::new(f64::NAN, 0.3), "plot range"),
        (Vector::<2>::new(0.0, 0.3), "plot range"),
        (Vector::<2>::new(5e4, f64::INFINITY), "plot azimuth"),
    ] {
        match imm.step(&est, 5.0, &radar(), &bad) {
            Err(ImmError::InvalidParameter { what: w, .. }) => assert_eq!(w, what),
            other => panic!("{other:?}"),
        }
        let pred = imm.predict(&est, 5.0).unwrap();
        assert!(imm.update(&pred, &radar(), &bad).is_err());
    }
    assert_eq!(est, before);
    // A good step still works from the untouched estimate.
    let up = imm.step(&est, 5.0, &radar(), &z[2]).unwrap();
    let total: f64 = up.estimate.mode_probabilities().iter().sum();
    // Tolerance: round-off of three exponentials of normalised logarithms.
    assert!((total - 1.0).abs() < 1e-12);
    assert!(up.log_likelihood.is_finite());
}

#[test]
fn bad_tuning_and_starts_are_typed_errors() {
    let good = AircraftTuning::<2, 3>::default();
    let mut t = good;
    t.markov[1] = [0.5, 0.4, 0.05];
    assert!(matches!(t.build(), Err(ImmError::RowSum { row: 1, .. })));
    t.markov[1] = [1.2, -0.2, 0.0];
    assert!(matches!(
        t.build(),
        Err(ImmError::InvalidTransition { row: 1, col: 0, .. })
    ));
    let mut t = good;
    t.cv_sigma_a[0] = -0.3;
    assert!(matches!(
        t.build(),
        Err(ImmError::InvalidParameter {
            what: "CV sigma_a",
            ..
        })
    ));
    let mut t = good;
    t.ct_sigma_omega = f64::NAN;
    assert!(matches!(t.build(), Err(ImmError::InvalidParameter { .. })));
    let mut t = good;
    t.start_mu = [0.5, 0.5, 0.5];
    assert!(matches!(
        t.build(),
        Err(ImmError::InvalidProbabilities { .. })
    ));
    let mut t = good;
    t.augmentation = Augmentation::Fixed { sigma: -1.0 };
    assert!(matches!(t.build(), Err(ImmError::InvalidParameter { .. })));
    let z = turn_plots(0.0, 2);
    assert!(matches!(
        good.start(&radar(), &z[0], &z[1], 0.0),
        Err(ImmError::InvalidInterval { .. })
    ));
    assert!(matches!(
        good.start(&radar(), &Vector::<2>::new(f64::NAN, 0.0), &z[1], 5.0),
        Err(ImmError::InvalidParameter { .. })
    ));
    assert!(matches!(
        two_point_start::<2, 3>(&radar(), &z[0], &z[1], 5.0, 0.0, good.start_mu),
        Err(ImmError::InvalidParameter { .. })
    ));
    assert!(
        AircraftRadar::new(
            [f64::NAN, 0.0],
            RadarNoise::constant(1.0, 0.1, 0.0).unwrap()
        )
        .is_err()
    );
}

#[test]
fn start_gives_the_ct_mode_its_turn_rate_prior() {
    let tuning = AircraftTuning::<2, 3>::default();
    let z = turn_plots(0.0, 2);
    let est = tuning.start(&radar(), &z[0], &z[1], 5.0).unwrap();
    let (w, s) = est.turn_rate();
    assert!(w.abs() < 1e-300);
    // Exactly the documented prior σ_ω = 2 °/s (a square root of its square: round-off).
    assert!((s - 2.0_f64.to_radians()).abs() < 1e-15);
    // The CT mode's kinematic part is the CV modes' start, uncorrelated with ω.
    let ct = est.ct_mode();
    assert_eq!(
        ct.cov().fixed_view::<4, 4>(0, 0).into_owned(),
        *est.cv_modes()[0].cov()
    );
    assert!(ct.cov().row(4).iter().take(4).all(|v| *v == 0.0));
    let mu = est.mode_probabilities();
    assert!((mu[0] - 0.6).abs() < 1e-12 && (mu[2] - 0.2).abs() < 1e-12);
}

#[test]
fn unbiased_mixing_keeps_the_ct_turn_rate_and_a_fixed_extension_pulls_it_to_zero() {
    // Granström et al. (2015). The CT prediction keeps ω (ω' = ω), so the predicted CT
    // turn rate is the mixed one: under the unbiased rule exactly the CT mode's own ω̂;
    // under a fixed ω = 0 extension μ_CT|CT ω̂ = π_CC μ_C / μ̄_C ω̂.
    let tuning = AircraftTuning::<2, 3>::default();
    let imm = tuning.build().unwrap();
    let z = turn_plots(2.0, 12);
    let mut est = tuning.start(&radar(), &z[0], &z[1], 5.0).unwrap();
    for zk in &z[2..] {
        est = imm.step(&est, 5.0, &radar(), zk).unwrap().estimate;
    }
    let (w, _) = est.turn_rate();
    assert!(w.abs() > 0.5_f64.to_radians(), "a turn rate to keep: {w}");
    let pred = imm.predict(&est, 5.0).unwrap();
    // Tolerance: round-off of a weighted sum of equal values (weights sum to one).
    assert!((pred.modes().turn_rate().0 - w).abs() < 1e-15);

    let mut zero = tuning;
    zero.augmentation = Augmentation::Fixed { sigma: 1e-5 };
    let pz = zero.build().unwrap().predict(&est, 5.0).unwrap();
    let mu = est.mode_probabilities();
    let pi = tuning.markov;
    let cbar: f64 = (0..3).map(|i| pi[i][2] * mu[i]).sum();
    let expect = pi[2][2] * mu[2] / cbar * w;
    assert!((pz.modes().turn_rate().0 - expect).abs() < 1e-12 * w.abs());
    // The predicted probabilities are μ̄ in both.
    assert!((pred.modes().mode_probabilities()[2] - cbar).abs() < 1e-12);
}

#[test]
fn finds_the_rate_of_a_steady_turn() {
    // Noise-free plots of a 2 °/s turn at 60 km: after 40 revisits (200 s) the CT mode
    // dominates (measured μ_CT = 0.88) and its rate is within 0.05 °/s of the truth
    // (measured 0.016 °/s, the lag the CV modes' mixing leaves; the bound is ~3× that).
    let tuning = AircraftTuning::<2, 3>::default();
    let imm = tuning.build().unwrap();
    let z = turn_plots(2.0, 42);
    let mut est = tuning.start(&radar(), &z[0], &z[1], 5.0).unwrap();
    for zk in &z[2..] {
        est = imm.step(&est, 5.0, &radar(), zk).unwrap().estimate;
    }
    let (w, s) = est.turn_rate();
    assert!(
        (w.to_degrees() - 2.0).abs() < 0.05,
        "ω = {} °/s",
        w.to_degrees()
    );
    // The posterior σ_ω settles near 0.84 °/s (measured): the random walk adds 0.5 °/s
    // per revisit against ~100–200 m of position noise. It must be below the 2 °/s prior.
    assert!(s.to_degrees() < 1.0, "σ_ω = {} °/s", s.to_degrees());
    assert!(
        est.mode_probabilities()[2] > 0.8,
        "{:?}",
        est.mode_probabilities()
    );
    // Coasting through a miss keeps μ̄ and the predicted modes.
    let pred = imm.predict(&est, 5.0).unwrap();
    let coast = pred.into_estimate();
    assert_eq!(coast, *pred.modes());
    assert!(coast.combined().is_ok());
}

#[test]
fn a_plot_at_the_same_instant_updates_the_modes_as_they_are() {
    // `into_prediction` is the estimate itself as a prediction (μ̄ = μ, no mixing, no
    // motion): the round trip is exact, and updating it is the update of each mode's own
    // estimate (checked on the CT mode against its filter alone; tolerance: round-off).
    let tuning = AircraftTuning::<2, 3>::default();
    let imm = tuning.build().unwrap();
    let z = turn_plots(2.0, 4);
    let r = radar();
    let mut est = tuning.start(&r, &z[0], &z[1], 5.0).unwrap();
    est = imm.step(&est, 5.0, &r, &z[2]).unwrap().estimate;
    assert_eq!(est.into_prediction().into_estimate(), est);
    let up = imm.update(&est.into_prediction(), &r, &z[3]).unwrap();
    let (ct, _) = imm
        .ct_filter()
        .update(est.ct_mode(), r.ct(), &z[3])
        .unwrap();
    let d = (up.estimate.ct_mode().mean() - ct.mean()).norm();
    assert!(d < 1e-9 * ct.mean().norm(), "{d}");
    // The start from a CV estimate made elsewhere is `two_point_start`'s own.
    let (p1, r1) = r.convert(&z[0]).unwrap();
    let (p2, r2) = r.convert(&z[1]).unwrap();
    let cv = argus_filters::two_point_cv2(&p1, &r1, &p2, &r2, 5.0).unwrap();
    assert_eq!(
        tuning.start_from_cv(&cv).unwrap(),
        tuning.start(&r, &z[0], &z[1], 5.0).unwrap()
    );
}

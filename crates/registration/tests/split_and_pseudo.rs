//! Structural identities of seed 004: the split `X̂ᵇ = X̂ + G β` (eqs (9), (13), (16), (20)),
//! exactness of the pseudo-measurements on noise-free data, and bad-input handling.

#![allow(clippy::unwrap_used)] // test code: a failure should panic with its message

use argus_core_math::faer::Mat;
use argus_core_math::{Gaussian, Matrix, Vector};
use argus_registration::{
    BiasEstimator, BiasedLocalFilter, BiasedTrack, ConvertedPlot, Initiation, Linearization,
    PolarSensor, Registrar, RegistrarConfig, RegistrationError, exx_pseudo_measurement,
    position_matrix, pseudo_measurement,
};
use argus_sensors::{PolarBias, PolarMeasurement};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

/// `B C` and `R` of `sensor` at the global position `p` (the noise-free plot of `p`).
fn linearised_at(sensor: &PolarSensor, p: &Vector<2>) -> (Matrix<2, 4>, Matrix<2, 2>) {
    let c = sensor
        .convert(0.0, &sensor.polar_of(p).unwrap(), None)
        .unwrap();
    (*c.bias_jacobian(), *c.noise())
}

fn truth(t: f64) -> Vector<4> {
    Vector::<4>::new(3_000.0 + 20.0 * t, 20.0, 15_000.0 + 20.0 * t, 20.0)
}

/// Runs a filter on linearised plots `z = H X + B C β + w` with a fixed per-step `B C`, `R`
/// (independent of β), returning the final track.
fn run_linearised(beta: &Vector<4>, two_point: bool) -> BiasedTrack {
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let sensor = PolarSensor::new(Vector::<2>::zeros(), 10.0, 1e-3).unwrap();
    let f = BiasedLocalFilter::new(6.0).unwrap();
    let h = position_matrix();
    let mut plots = Vec::new();
    for k in 0..40 {
        let t = f64::from(k);
        let x = truth(t);
        let (bc, r) = linearised_at(&sensor, &(h * x));
        let w = r.cholesky().unwrap().l()
            * Vector::<2>::new(
                StandardNormal.sample(&mut rng),
                StandardNormal.sample(&mut rng),
            );
        plots.push(ConvertedPlot::new(t, h * x + bc * beta + w, r, bc).unwrap());
    }
    let mut track = if two_point {
        BiasedTrack::two_point(&plots[0], &plots[1]).unwrap()
    } else {
        let start = Gaussian::new(
            truth(1.0),
            Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(100.0, 25.0, 100.0, 25.0)),
        )
        .unwrap();
        BiasedTrack::bias_free(start, 1.0).unwrap()
    };
    for p in &plots[2..] {
        track = f.update(&track, p).unwrap();
    }
    track
}

#[test]
fn split_is_exact_on_linearised_plots() {
    // Same plots with and without a known bias: X̂ᵇ − G β must equal X̂ (linear algebra,
    // so to round-off: 1e-6 m on ~20 km states).
    let beta = Vector::<4>::new(20.0, 2e-3, 3e-5, 2e-4);
    for two_point in [false, true] {
        let biased = run_linearised(&beta, two_point);
        let clean = run_linearised(&Vector::<4>::zeros(), two_point);
        let split = biased.estimate().mean() - biased.g() * beta;
        let diff = (split - clean.estimate().mean()).amax();
        assert!(diff < 1e-6, "two_point={two_point}: |X̂ᵇ − Gβ − X̂| = {diff}");
        // G is the same in both runs (it does not depend on the plots' values) and P too.
        assert!((biased.g() - clean.g()).amax() < 1e-12);
        assert!((biased.estimate().cov() - clean.estimate().cov()).amax() < 1e-9);
        // And the bias really moved the track: |G β| is metres, not round-off.
        assert!((biased.g() * beta).amax() > 10.0);
    }
}

#[test]
fn split_holds_to_second_order_on_polar_plots() {
    // Real polar plots (eq (1)), linearised at the plot: the split is exact only to
    // second order in the bias. With r ≈ 20 km, δθ ≈ 2.2 mrad: r δθ²/2 ≈ 0.05 m, δr·δθ ≈
    // 0.05 m; allow 0.5 m (against |G β| ≈ 60 m).
    let sensor = PolarSensor::new(Vector::<2>::zeros(), 10.0, 1e-3).unwrap();
    let bias = PolarBias::new(20.0, 2e-3, 3e-5, 2e-4).unwrap();
    let f = BiasedLocalFilter::new(6.0).unwrap();
    let h = position_matrix();
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let start = Gaussian::new(
        truth(0.0),
        Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(100.0, 25.0, 100.0, 25.0)),
    )
    .unwrap();
    let mut tb = BiasedTrack::bias_free(start, 0.0).unwrap();
    let mut tc = tb;
    for k in 1..120 {
        let t = f64::from(k);
        let p = h * truth(t);
        let (a, b): (f64, f64) = (
            StandardNormal.sample(&mut rng),
            StandardNormal.sample(&mut rng),
        );
        let pb = sensor.biased_plot(&p, &bias, a, b).unwrap();
        let pc = sensor.biased_plot(&p, &PolarBias::zero(), a, b).unwrap();
        // Evaluate R, B C at the clean plot for both so the gains coincide.
        let at = *sensor.convert(t, &pc, None).unwrap().z();
        tb = f
            .update(&tb, &sensor.convert(t, &pb, Some(&at)).unwrap())
            .unwrap();
        tc = f
            .update(&tc, &sensor.convert(t, &pc, Some(&at)).unwrap())
            .unwrap();
    }
    let split = tb.estimate().mean() - tb.g() * bias.as_vector();
    let d = split - tc.estimate().mean();
    assert!(
        d[0].hypot(d[2]) < 0.5,
        "position split error {}",
        d[0].hypot(d[2])
    );
    assert!((tb.g() * bias.as_vector()).amax() > 30.0);
}

#[test]
fn pseudo_measurements_are_exact_without_noise() {
    // Three sensors; tracks equal to truth + G_j β_j with P small, noise-free plot:
    // z_b − H_b b = H Φ X̂_j-error = 0 exactly (eq (22)). Stacked R_b has R_i off the diagonal (eq (32)).
    let f = BiasedLocalFilter::new(6.0).unwrap();
    let h = position_matrix();
    let betas = [
        Vector::<4>::new(20.0, 2e-3, 3e-5, 2e-4),
        Vector::<4>::new(-10.0, 1e-3, -2e-5, 1e-4),
        Vector::<4>::new(5.0, -3e-3, 1e-5, -2e-4),
    ];
    let sensors = [
        PolarSensor::new(Vector::<2>::new(0.0, 0.0), 10.0, 1e-3).unwrap(),
        PolarSensor::new(Vector::<2>::new(10_000.0, 0.0), 10.0, 1e-3).unwrap(),
        PolarSensor::new(Vector::<2>::new(20_000.0, 0.0), 10.0, 1e-3).unwrap(),
    ];
    let g1 = Matrix::<4, 4>::from_fn(|i, j| 0.1 * (i + 2 * j) as f64);
    let g2 = Matrix::<4, 4>::from_fn(|i, j| -0.05 * (3 * i + j) as f64 + 1.0);
    let cov = Matrix::<4, 4>::identity();
    let mk = |g: Matrix<4, 4>, beta: &Vector<4>, t0: f64| {
        BiasedTrack::new(Gaussian::new(truth(t0) + g * beta, cov).unwrap(), g, t0).unwrap()
    };
    let tr1 = mk(g1, &betas[1], 9.5);
    let tr2 = mk(g2, &betas[2], 9.25);
    let t = 10.0;
    let (bc, r0) = linearised_at(&sensors[0], &(h * truth(t)));
    let plot = ConvertedPlot::new(t, h * truth(t) + bc * betas[0], r0, bc).unwrap();
    let pm = pseudo_measurement(&f, 3, 0, &plot, &[(1, &tr1), (2, &tr2)]).unwrap();
    let b = Mat::from_fn(12, 1, |i, _| betas[i / 4][i % 4]);
    let resid = pm.z() - pm.h() * &b;
    for i in 0..4 {
        // Round-off on ~20 km positions: 1e-7 m.
        assert!(resid[(i, 0)].abs() < 1e-7, "row {i}: {}", resid[(i, 0)]);
    }
    for a in 0..2 {
        for c in 0..2 {
            assert!((pm.r()[(a, 2 + c)] - r0[(a, c)]).abs() < 1e-9);
        }
    }
    // Bad input: j == i, unknown j, no other tracks; a track later than the plot.
    assert!(pseudo_measurement(&f, 3, 0, &plot, &[(0, &tr1)]).is_err());
    assert!(pseudo_measurement(&f, 3, 0, &plot, &[(3, &tr1)]).is_err());
    assert!(pseudo_measurement(&f, 3, 0, &plot, &[(1, &tr1), (1, &tr2)]).is_err());
    assert!(matches!(
        pseudo_measurement(&f, 3, 0, &plot, &[]),
        Err(RegistrationError::Empty { .. })
    ));
    let late = mk(g1, &betas[1], 11.0);
    assert!(matches!(
        pseudo_measurement(&f, 3, 0, &plot, &[(1, &late)]),
        Err(RegistrationError::TimeNotIncreasing { .. })
    ));
}

#[test]
fn exx_cancels_a_constant_velocity_state() {
    // Noise-free linearised plots of a CV target at t = 0, 0.5, 1 from two sensors:
    // Σ a_k z_k = H_ex b exactly (SPEC §004: weights ∝ (t₂−t₃, t₃−t₁, t₁−t₂)).
    let h = position_matrix();
    let betas = [
        Vector::<4>::new(20.0, 2e-3, 3e-5, 2e-4),
        Vector::<4>::new(-7.0, 1e-3, 1e-5, -1e-4),
    ];
    let sensors = [
        PolarSensor::new(Vector::<2>::new(0.0, 0.0), 10.0, 1e-3).unwrap(),
        PolarSensor::new(Vector::<2>::new(10_000.0, 0.0), 10.0, 1e-3).unwrap(),
    ];
    let mk = |s: usize, t: f64| {
        let p = h * truth(t);
        let (bc, r) = linearised_at(&sensors[s], &p);
        (s, ConvertedPlot::new(t, p + bc * betas[s], r, bc).unwrap())
    };
    let triple = [mk(0, 0.0), mk(1, 0.5), mk(0, 1.0)];
    let pm = exx_pseudo_measurement(2, &triple).unwrap();
    let b = Mat::from_fn(8, 1, |i, _| betas[i / 4][i % 4]);
    let resid = pm.z() - pm.h() * &b;
    assert!(resid[(0, 0)].abs() < 1e-7 && resid[(1, 0)].abs() < 1e-7);
    let same = [mk(0, 1.0), mk(1, 1.0), mk(0, 1.0)];
    assert!(exx_pseudo_measurement(2, &same).is_err());
    assert!(exx_pseudo_measurement(1, &triple).is_err());
}

#[test]
fn registrar_rejects_bad_input_and_keeps_state() {
    let sensors = vec![
        PolarSensor::new(Vector::<2>::new(0.0, 0.0), 10.0, 1e-3).unwrap(),
        PolarSensor::new(Vector::<2>::new(10_000.0, 0.0), 10.0, 1e-3).unwrap(),
    ];
    let prior = Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(1e4, 0.04, 1e-4, 1e-2));
    let cfg = RegistrarConfig {
        sensors: sensors.clone(),
        targets: 1,
        q_tilde: 6.0,
        prior_cov: prior,
        linearization: Linearization::AtPrediction,
        initiation: Initiation::TwoPoint,
        run_exx: true,
    };
    assert!(
        Registrar::new(RegistrarConfig {
            sensors: vec![],
            ..cfg.clone()
        })
        .is_err()
    );
    assert!(
        Registrar::new(RegistrarConfig {
            targets: 0,
            ..cfg.clone()
        })
        .is_err()
    );
    assert!(
        Registrar::new(RegistrarConfig {
            q_tilde: f64::NAN,
            ..cfg.clone()
        })
        .is_err()
    );
    assert!(
        Registrar::new(RegistrarConfig {
            prior_cov: -prior,
            ..cfg.clone()
        })
        .is_err()
    );
    let mut reg = Registrar::new(cfg).unwrap();
    let plot = |t: f64, s: usize| {
        sensors[s]
            .polar_of(&(position_matrix() * truth(t)))
            .unwrap()
    };
    for k in 0..4 {
        let t = f64::from(k);
        reg.process(0, 0, t, &plot(t, 0)).unwrap();
        reg.process(1, 0, t + 0.5, &plot(t + 0.5, 1)).unwrap();
    }
    assert!(reg.proposed().updates() > 0);
    assert!(reg.exx().is_some_and(|e| e.updates() > 0));
    let before_track = *reg.track(0, 0).unwrap();
    let before_b = reg.proposed().stacked().to_owned();
    assert!(matches!(
        reg.process(2, 0, 5.0, &plot(5.0, 0)),
        Err(RegistrationError::UnknownSensor { .. })
    ));
    assert!(reg.process(0, 1, 5.0, &plot(5.0, 0)).is_err());
    assert!(matches!(
        reg.process(0, 0, 1.0, &plot(1.0, 0)),
        Err(RegistrationError::TimeNotIncreasing { .. })
    ));
    assert!(
        reg.process(0, 0, 5.0, &PolarMeasurement::new(0.0, 0.0).unwrap())
            .is_err()
    );
    assert!(reg.process(0, 0, f64::INFINITY, &plot(5.0, 0)).is_err());
    assert_eq!(*reg.track(0, 0).unwrap(), before_track);
    assert_eq!(reg.proposed().stacked().to_owned(), before_b);
    let _ = BiasEstimator::new(2, &prior).unwrap();
}

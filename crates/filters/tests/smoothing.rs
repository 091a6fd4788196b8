//! Fixed-interval and fixed-lag smoothing: the RTS smoother against the batch
//! least-squares solution, the unscented RTS smoother against the RTS, covariance
//! ordering, smoothed NEES on a cv-polar-like Monte Carlo, and the errors of bad sequences.

// A test binary: a panic on an unexpected error is the failure report.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use argus_core_math::{Gaussian, Matrix, Vector, anees_interval};
use argus_filters::{
    Ekf, FixedLagSmoother, GaussianFilter, Kf, Lag, RtsStep, RtsTrack, SmoothError,
    SmoothingFilter, Ukf, UtParams, rts_smooth, rts_smooth_into, two_point_cv2,
};
use argus_motion_models::{CoordinatedTurnRate, Cv2D, LinearMotionModel, MotionModel};
use argus_sensors::{
    CartesianPosition, ConversionMethod, Measurement, Polar2D, RadarNoise, convert_polar,
};
use argus_sim::{
    KinematicState, Schedule, Segment, SensorId, SensorKind, SensorSpec, Trajectory, Truth,
    generate_plots, run_rng,
};
use nalgebra::{DMatrix, DVector};
use rand::RngExt;
use rand_distr::StandardNormal;

/// The linear-Gaussian test problem: 2-D CV with continuous white acceleration (full-rank
/// `Q`), position plots with a correlated `R`, irregular intervals.
struct Linear {
    kf: Kf<Cv2D>,
    meas: CartesianPosition<4, 2>,
    r: Matrix<2, 2>,
    prior: Gaussian<4>,
    times: Vec<f64>,
    plots: Vec<Vector<2>>,
}

fn linear_problem(n: usize, seed: u64) -> Linear {
    let model = Cv2D::continuous(0.3).unwrap();
    let r = Matrix::<2, 2>::new(400.0, 120.0, 120.0, 250.0);
    let prior = Gaussian::new(
        Vector::<4>::new(1000.0, -20.0, -500.0, 10.0),
        Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(2500.0, 100.0, 2500.0, 100.0)),
    )
    .unwrap();
    let mut rng = run_rng(seed, 0);
    let mut gauss = |s: f64| -> f64 { s * rng.sample::<f64, _>(StandardNormal) };
    let lr = r.cholesky().unwrap().l();
    let mut x = prior.mean() + Vector::<4>::new(gauss(50.0), gauss(10.0), gauss(50.0), gauss(10.0));
    let (mut t, mut times, mut plots) = (0.0, vec![0.0], Vec::new());
    for k in 0..n {
        // Irregular sampling: 0.5 … 3.5 s.
        let dt = 0.5 + 3.0 * ((k * 7 + 3) % 11) as f64 / 10.0;
        t += dt;
        let lq = model.process_noise(&x, dt).cholesky().unwrap().l();
        x = model.transition(dt) * x
            + lq * Vector::<4>::new(gauss(1.0), gauss(1.0), gauss(1.0), gauss(1.0));
        plots.push(Vector::<2>::new(x[0], x[2]) + lr * Vector::<2>::new(gauss(1.0), gauss(1.0)));
        times.push(t);
    }
    Linear {
        kf: Kf::new(model),
        meas: CartesianPosition::<4, 2>::cv(r).unwrap(),
        r,
        prior,
        times,
        plots,
    }
}

fn record<F: SmoothingFilter<4>>(p: &Linear, f: &F) -> RtsTrack<4> {
    let mut track = RtsTrack::with_capacity(0.0, p.prior, p.times.len()).unwrap();
    for (t, z) in p.times[1..].iter().zip(&p.plots) {
        track.step(f, *t, &p.meas, z).unwrap();
    }
    track
}

/// The batch least-squares (information-form) solution over the whole sequence: the
/// minimiser of `‖x₀ − m₀‖²_{P₀⁻¹} + Σ‖xₖ₊₁ − Fₖxₖ‖²_{Qₖ⁻¹} + Σ‖zₖ − Hxₖ‖²_{R⁻¹}`; its
/// Hessian `J` is the joint information matrix, so `J⁻¹`'s diagonal blocks are the
/// smoothed covariances (Bar-Shalom, Li & Kirubarajan 2001 §8.6; Särkkä 2013 §8.1).
fn batch(p: &Linear) -> (Vec<Vector<4>>, Vec<Matrix<4, 4>>) {
    let n = p.times.len();
    let dim = 4 * n;
    let mut j = DMatrix::<f64>::zeros(dim, dim);
    let mut b = DVector::<f64>::zeros(dim);
    let add = |j: &mut DMatrix<f64>, r: usize, c: usize, m: &Matrix<4, 4>| {
        let mut v = j.view_mut((4 * r, 4 * c), (4, 4));
        v += m;
    };
    let p0i = p.prior.cov().try_inverse().unwrap();
    add(&mut j, 0, 0, &p0i);
    b.rows_mut(0, 4).copy_from(&(p0i * p.prior.mean()));
    let model = p.kf.model();
    let h = Matrix::<2, 4>::new(1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0);
    let ri = p.r.try_inverse().unwrap();
    for k in 0..n - 1 {
        let dt = p.times[k + 1] - p.times[k];
        let f = model.transition(dt);
        let qi = model
            .process_noise(&Vector::<4>::zeros(), dt)
            .try_inverse()
            .unwrap();
        add(&mut j, k, k, &(f.transpose() * qi * f));
        add(&mut j, k, k + 1, &(-f.transpose() * qi));
        add(&mut j, k + 1, k, &(-qi * f));
        add(&mut j, k + 1, k + 1, &qi);
        add(&mut j, k + 1, k + 1, &(h.transpose() * ri * h));
        let mut bv = b.rows_mut(4 * (k + 1), 4);
        bv += h.transpose() * ri * p.plots[k];
    }
    let chol = j.cholesky().unwrap();
    let x = chol.solve(&b);
    let cov = chol.inverse();
    let means = (0..n)
        .map(|k| Vector::<4>::from_iterator(x.rows(4 * k, 4).iter().copied()))
        .collect();
    let covs = (0..n)
        .map(|k| Matrix::<4, 4>::from_iterator(cov.view((4 * k, 4 * k), (4, 4)).iter().copied()))
        .collect();
    (means, covs)
}

#[test]
fn rts_equals_the_batch_least_squares_solution() {
    // Exact identity for a linear-Gaussian model (RTS 1965): the smoothed moments are the
    // batch solution's. Tolerance 1e-9 relative to each quantity's scale (states of order
    // 1e3, covariances of order 1e2): round-off of a 60-step recursion and a 244-unknown
    // Cholesky solve.
    let p = linear_problem(60, 11);
    let smoothed = record(&p, &p.kf).smooth().unwrap();
    let (means, covs) = batch(&p);
    for (k, (s, (m, c))) in smoothed.iter().zip(means.iter().zip(&covs)).enumerate() {
        let em = (s.mean() - m).amax() / m.amax().max(1.0);
        let ec = (s.cov() - c).amax() / c.amax();
        assert!(em < 1e-9, "step {k}: mean differs by {em:e} (relative)");
        assert!(
            ec < 1e-9,
            "step {k}: covariance differs by {ec:e} (relative)"
        );
    }
}

#[test]
fn urts_equals_rts_on_a_linear_model() {
    // The unscented transform of a linear map is exact, so the sigma-point cross
    // covariance is P Fᵀ and the URTS is the RTS (Särkkä 2008 §IV); for any valid UT
    // parameters. Tolerance: round-off, 1e-9 relative.
    let p = linear_problem(40, 12);
    let rts = record(&p, &p.kf).smooth().unwrap();
    for params in [
        UtParams::default(),
        UtParams {
            alpha: 0.5,
            beta: 2.0,
            kappa: 1.0,
        },
    ] {
        let ukf = Ukf::new(*p.kf.model(), params).unwrap();
        let urts = record(&p, &ukf).smooth().unwrap();
        for (k, (a, b)) in rts.iter().zip(&urts).enumerate() {
            assert!(
                (a.mean() - b.mean()).amax() < 1e-9 * a.mean().amax(),
                "{params:?} step {k}"
            );
            assert!(
                (a.cov() - b.cov()).amax() < 1e-9 * a.cov().amax(),
                "{params:?} step {k}"
            );
        }
    }
}

/// The smallest eigenvalue of `filtered − smoothed`, relative to the filtered covariance's
/// largest entry.
fn min_gap(filtered: &Matrix<4, 4>, smoothed: &Matrix<4, 4>) -> f64 {
    let d = filtered - smoothed;
    d.symmetric_eigenvalues().min() / filtered.amax()
}

#[test]
fn smoothed_covariance_is_below_the_filtered_one() {
    // Pₖ|ₙ = Pₖ|ₖ + G (Pₖ₊₁|ₙ − Pₖ₊₁⁻) Gᵀ with Pₖ₊₁|ₙ ≤ Pₖ₊₁|ₖ₊₁ ≤ Pₖ₊₁⁻: the difference
    // Pₖ|ₖ − Pₖ|ₙ is positive semidefinite at every step (its smallest eigenvalue ≥ 0 up to
    // round-off, −1e-12 relative); for the KF, the EKF on polar plots and the URTS.
    let p = linear_problem(50, 13);
    let ukf = Ukf::with_defaults(*p.kf.model()).unwrap();
    for track in [record(&p, &p.kf), record(&p, &ukf)] {
        let smoothed = track.smooth().unwrap();
        for (k, (s, st)) in smoothed.iter().zip(track.steps()).enumerate() {
            let gap = min_gap(st.filtered().cov(), s.cov());
            assert!(gap > -1e-12, "step {k}: smallest eigenvalue {gap:e}");
        }
    }
    // EKF on polar plots of the same trajectory's positions.
    let polar = Polar2D::cv([0.0, 0.0], RadarNoise::constant(20.0, 0.01, 0.0).unwrap()).unwrap();
    let ekf = Ekf::new(*p.kf.model());
    let mut track = RtsTrack::new(0.0, p.prior).unwrap();
    for (t, z) in p.times[1..].iter().zip(&p.plots) {
        let zp = Vector::<2>::new(z[0].hypot(z[1]), z[1].atan2(z[0]));
        track.step(&ekf, *t, &polar, &zp).unwrap();
    }
    let smoothed = track.smooth().unwrap();
    for (k, (s, st)) in smoothed.iter().zip(track.steps()).enumerate() {
        let gap = min_gap(st.filtered().cov(), s.cov());
        assert!(gap > -1e-12, "EKF step {k}: smallest eigenvalue {gap:e}");
    }
}

#[test]
fn nonlinear_motion_smooths_with_ekf_and_ukf() {
    // A coordinated turn with the rate in the state (the workspace's nonlinear motion
    // model): the EKF's RTS and the URTS both smooth a 3 deg/s turn; the smoothed
    // position error summed over the track is below the filtered one (it could fail if a
    // cross covariance were wrong), and the smoothed covariance is below the filtered one.
    let model = CoordinatedTurnRate::new(0.5, 0.002).unwrap();
    let meas = CartesianPosition::<5, 2>::new([0, 2], Matrix::<2, 2>::identity() * 900.0).unwrap();
    let omega = 3.0_f64.to_radians();
    let mut rng = run_rng(14, 0);
    let mut truth = Vector::<5>::new(0.0, 150.0, 0.0, 0.0, omega);
    let prior = Gaussian::new(
        truth,
        Matrix::<5, 5>::from_diagonal(&Vector::<5>::new(900.0, 100.0, 900.0, 100.0, 1e-4)),
    )
    .unwrap();
    let mut states = vec![truth];
    let mut plots = Vec::new();
    for _ in 0..60 {
        truth = model.propagate(&truth, 2.0);
        states.push(truth);
        let e = Vector::<2>::new(rng.sample(StandardNormal), rng.sample(StandardNormal)) * 30.0;
        plots.push(Vector::<2>::new(truth[0], truth[2]) + e);
    }
    let ekf = Ekf::new(model);
    let ukf = Ukf::with_defaults(model).unwrap();
    let run = |f: &dyn Fn(&mut RtsTrack<5>, f64, &Vector<2>)| {
        let mut track = RtsTrack::new(0.0, prior).unwrap();
        for (k, z) in plots.iter().enumerate() {
            f(&mut track, 2.0 * (k + 1) as f64, z);
        }
        let smoothed = track.smooth().unwrap();
        let err = |g: &Gaussian<5>, x: &Vector<5>| (g.mean()[0] - x[0]).hypot(g.mean()[2] - x[2]);
        let (mut ef, mut es) = (0.0, 0.0);
        for ((s, st), x) in smoothed.iter().zip(track.steps()).zip(&states) {
            ef += err(st.filtered(), x);
            es += err(s, x);
            let d = st.filtered().cov() - s.cov();
            assert!(d.symmetric_eigenvalues().min() > -1e-9 * st.filtered().cov().amax());
        }
        (ef, es)
    };
    let (ef, es) = run(&|t, time, z| {
        t.step(&ekf, time, &meas, z).unwrap();
    });
    assert!(es < 0.8 * ef, "EKF: smoothed {es} vs filtered {ef}");
    let (uf, us) = run(&|t, time, z| {
        t.step(&ukf, time, &meas, z).unwrap();
    });
    assert!(us < 0.8 * uf, "UKF: smoothed {us} vs filtered {uf}");
}

#[test]
fn smoothed_nees_of_a_cv_polar_campaign_is_in_its_band() {
    // cv-polar's scene (crates/cli/src/scenarios/cv_polar.rs defaults): CV target from
    // (40 km, 10 km) at (−150, 100) m/s for 200 s, polar radar at the origin every 2 s,
    // σr = 50 m, σθ = 0.1°, KF with no process noise on unbiased converted plots,
    // two-point start. 60 seeded runs; per step, 60 · ANEES ~ χ²(4 · 60) for a consistent
    // smoother: every step's ANEES must lie in the two-sided 99.9 % interval (the steps
    // are strongly correlated — with Q = 0 the smoothed errors are one error propagated —
    // so this is close to a single 99.9 % test).
    let runs = 60;
    let (sigma_r, sigma_th) = (50.0, 0.1_f64.to_radians());
    let mut truth = Truth::new();
    let traj = Trajectory::new(
        0.0,
        KinematicState::planar(40_000.0, 10_000.0, -150.0, 100.0),
        vec![Segment::ConstantVelocity { duration: 200.0 }],
    )
    .unwrap();
    truth.add(traj.clone());
    let radar = SensorSpec::new(
        SensorId(1),
        Vector::<3>::zeros(),
        SensorKind::Polar {
            sigma_range: sigma_r,
            sigma_azimuth: sigma_th,
        },
        Schedule::Periodic {
            period: 2.0,
            offset: 0.0,
        },
    )
    .unwrap();
    let kf = Kf::new(Cv2D::discrete(0.0).unwrap());
    let mut sums: Vec<(f64, f64)> = Vec::new();
    for run in 0..runs {
        let mut rng = run_rng(19, run);
        let plots = generate_plots(&truth, std::slice::from_ref(&radar), &mut rng).unwrap();
        let conv: Vec<(f64, Vector<2>, Matrix<2, 2>)> = plots
            .iter()
            .filter_map(|pl| match pl.plot.measurement() {
                Measurement::Polar(m) => {
                    let (range, azimuth) = (m.range(), m.azimuth());

                    let c = convert_polar(
                        range,
                        azimuth,
                        sigma_r,
                        sigma_th,
                        ConversionMethod::Unbiased,
                    )
                    .unwrap();
                    Some((pl.plot.time(), c.position, c.covariance))
                }
                _ => None,
            })
            .collect();
        let ((t1, z1, r1), (t2, z2, r2)) = (conv[0], conv[1]);
        let start = two_point_cv2(&z1, &r1, &z2, &r2, t2 - t1).unwrap();
        let mut track = RtsTrack::new(t2, start).unwrap();
        for (t, z, r) in &conv[2..] {
            track
                .step(&kf, *t, &CartesianPosition::<4, 2>::cv(*r).unwrap(), z)
                .unwrap();
        }
        let smoothed = track.smooth().unwrap();
        sums.resize(smoothed.len(), (0.0, 0.0));
        for ((s, st), acc) in smoothed.iter().zip(track.steps()).zip(sums.iter_mut()) {
            let x = traj.state_at(st.time()).unwrap().state_2d();
            acc.0 += s.mahalanobis_sq(&x);
            acc.1 += st.filtered().mahalanobis_sq(&x);
        }
    }
    let band = anees_interval(4, runs as usize, 0.999).unwrap();
    let mut mean = 0.0;
    for (k, (s, f)) in sums.iter().enumerate() {
        let (s, f) = (s / runs as f64, f / runs as f64);
        mean += s / sums.len() as f64;
        assert!(
            band.contains(s),
            "step {k}: smoothed ANEES {s} outside [{}, {}] (filtered {f})",
            band.lower,
            band.upper
        );
    }
    eprintln!(
        "cv-polar smoothed ANEES, mean over steps: {mean:.3} (band {:.3}–{:.3})",
        band.lower, band.upper
    );
}

#[test]
fn fixed_lag_equals_fixed_interval_of_the_track_so_far() {
    // The backward pass from the latest filtered estimate gives x̂ⱼ|ₖ for every j ≤ k:
    // the lag-L estimate of step j is the fixed-interval smoother of the first j + L
    // steps, at j (the same arithmetic: tolerance 1e-12 relative).
    let p = linear_problem(30, 15);
    let full = record(&p, &p.kf);
    for lag in [Lag::Steps(0), Lag::Steps(3), Lag::Seconds(5.0)] {
        let mut fl = FixedLagSmoother::new(lag, 0.0, p.prior).unwrap();
        let mut got = Vec::new();
        for (t, z) in p.times[1..].iter().zip(&p.plots) {
            fl.step(&p.kf, *t, &p.meas, z).unwrap();
            while let Some(l) = fl.pop() {
                got.push(l);
            }
        }
        let during = got.len();
        fl.flush().unwrap();
        while let Some(l) = fl.pop() {
            got.push(l);
        }
        assert_eq!(
            got.len(),
            p.times.len(),
            "{lag:?}: every step handed out once"
        );
        for (j, l) in got.iter().enumerate() {
            assert_eq!(l.step, j);
            let expect = rts_smooth(&full.steps()[..=l.given]).unwrap()[j];
            assert!((l.estimate.mean() - expect.mean()).amax() < 1e-12 * expect.mean().amax());
            assert!((l.estimate.cov() - expect.cov()).amax() < 1e-12 * expect.cov().amax());
            match lag {
                Lag::Steps(n) if j < during => assert_eq!(l.given, j + n),
                Lag::Seconds(s) if j < during => {
                    assert!(p.times[l.given] - p.times[j] >= s);
                    assert!(p.times[l.given - 1] - p.times[j] < s);
                }
                _ => {}
            }
        }
    }
    assert!(matches!(
        FixedLagSmoother::new(Lag::Seconds(-1.0), 0.0, p.prior),
        Err(SmoothError::InvalidLag { .. })
    ));
}

#[test]
fn bad_sequences_get_errors_naming_the_step() {
    let p = linear_problem(10, 16);
    // A failed forward step (a NaN plot at step 4): recorded, and the track refuses to be
    // smoothed (the three good steps can be, explicitly).
    let mut track = RtsTrack::new(0.0, p.prior).unwrap();
    for (t, z) in p.times[1..4].iter().zip(&p.plots) {
        track.step(&p.kf, *t, &p.meas, z).unwrap();
    }
    let err = track
        .step(&p.kf, p.times[4], &p.meas, &Vector::<2>::new(f64::NAN, 0.0))
        .unwrap_err();
    assert!(
        matches!(err, SmoothError::ForwardFailed { step: 4, .. }),
        "{err}"
    );
    assert_eq!(track.smooth().unwrap_err(), err);
    assert_eq!(
        track
            .step(&p.kf, p.times[5], &p.meas, &p.plots[4])
            .unwrap_err(),
        err
    );
    assert_eq!(rts_smooth(track.steps()).unwrap().len(), 4);

    // Time going backwards at step 3.
    let mut track = RtsTrack::new(0.0, p.prior).unwrap();
    track.step(&p.kf, 1.0, &p.meas, &p.plots[0]).unwrap();
    track.step(&p.kf, 2.0, &p.meas, &p.plots[1]).unwrap();
    let err = track.predict(&p.kf, 1.5).unwrap_err();
    assert_eq!(
        err,
        SmoothError::TimeNotIncreasing {
            step: 3,
            prev: 2.0,
            now: 1.5
        }
    );
    assert_eq!(track.smooth().unwrap_err(), err);
    assert!(err.to_string().contains("step 3"), "{err}");

    // A sequence built by hand: time going backwards, a step without a transition,
    // an output of the wrong length.
    let good = record(&p, &p.kf);
    let mut steps = good.steps().to_vec();
    steps.swap(5, 6);
    assert!(matches!(
        rts_smooth(&steps),
        Err(SmoothError::TimeNotIncreasing { step: 6, .. })
    ));
    let mut steps = good.steps().to_vec();
    steps[7] = RtsStep::first(steps[7].time(), *steps[7].filtered());
    assert_eq!(
        rts_smooth(&steps).unwrap_err(),
        SmoothError::MissingTransition { step: 7 }
    );
    let mut out = vec![p.prior; 3];
    assert_eq!(
        rts_smooth_into(good.steps(), &mut out).unwrap_err(),
        SmoothError::LengthMismatch {
            what: "smoothed output",
            expected: 11,
            found: 3
        }
    );
    assert_eq!(
        good.smooth_into(&mut out).unwrap_err(),
        rts_smooth_into(good.steps(), &mut out).unwrap_err()
    );
    assert_eq!(rts_smooth::<4>(&[]).unwrap_err(), SmoothError::Empty);

    // Out of order: an update without a prediction, smoothing with a prediction pending.
    let mut track = RtsTrack::new(0.0, p.prior).unwrap();
    assert!(matches!(
        track.coast(),
        Err(SmoothError::OutOfOrder { step: 1, .. })
    ));
    track.predict(&p.kf, 1.0).unwrap();
    assert!(matches!(
        track.smooth(),
        Err(SmoothError::OutOfOrder { step: 1, .. })
    ));
    assert!(matches!(
        track.predict(&p.kf, 2.0),
        Err(SmoothError::OutOfOrder { step: 1, .. })
    ));
    track.coast().unwrap();
    assert_eq!(track.smooth().unwrap().len(), 2);
}

#[test]
fn predict_with_cross_matches_predict() {
    // The smoothing prediction is the filter's prediction (to round-off, 1e-12 relative),
    // and its cross covariance is P Fᵀ for the KF and the EKF.
    let p = linear_problem(1, 17);
    let model = *p.kf.model();
    let f = model.transition(2.5);
    let ekf = Ekf::new(model);
    let ukf = Ukf::with_defaults(model).unwrap();
    let a = p.kf.predict(&p.prior, 2.5).unwrap();
    for tr in [
        p.kf.predict_with_cross(&p.prior, 2.5).unwrap(),
        ekf.predict_with_cross(&p.prior, 2.5).unwrap(),
        ukf.predict_with_cross(&p.prior, 2.5).unwrap(),
    ] {
        assert!((tr.predicted().mean() - a.mean()).amax() < 1e-12 * a.mean().amax());
        assert!((tr.predicted().cov() - a.cov()).amax() < 1e-12 * a.cov().amax());
        let c = p.prior.cov() * f.transpose();
        assert!((tr.cross() - c).amax() < 1e-12 * c.amax());
    }
}

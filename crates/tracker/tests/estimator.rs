//! The per-track estimator chosen by configuration: KF or a two-mode CV IMM.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use argus_core_math::{Matrix, Vector};
use argus_sim::{ChaCha8Rng, TargetId, TrackScan, TrackStatistics, run_rng};
use argus_tracker::{EstimatorConfig, Plot, SensorId, TrackStatus, Tracker, TrackerConfig};
use rand_distr::{Distribution, StandardNormal};

const S0: SensorId = SensorId(0);
const T: f64 = 5.0;
const SIGMA: f64 = 50.0;

fn plot(rng: &mut ChaCha8Rng, t: f64, p: Vector<2>) -> Plot {
    let nx: f64 = StandardNormal.sample(rng);
    let ny: f64 = StandardNormal.sample(rng);
    Plot::cartesian(
        t,
        S0,
        p + Vector::<2>::new(SIGMA * nx, SIGMA * ny),
        Matrix::<2, 2>::identity() * (SIGMA * SIGMA),
    )
    .unwrap()
}

#[test]
fn imm_of_identical_modes_equals_the_kalman_filter() {
    // An IMM whose modes are the same filter mixes identical Gaussians (no spread of
    // means), so every mode, and the combination, is the KF estimate (Bar-Shalom, Li &
    // Kirubarajan 2001 §11.6.6). Two targets and some clutter-like extra plots.
    let kf_cfg = TrackerConfig::new(vec![S0]);
    let mut imm_cfg = kf_cfg.clone();
    imm_cfg.estimator = EstimatorConfig::ImmCv2 {
        sigma_a_low: kf_cfg.sigma_a,
        sigma_a_high: kf_cfg.sigma_a,
        p_stay: 0.9,
    };
    let mut kf = Tracker::new(kf_cfg).unwrap();
    let mut imm = Tracker::new(imm_cfg).unwrap();
    let mut rng = run_rng(21, 0);
    for k in 0..15 {
        let t = T * f64::from(k);
        let plots = vec![
            plot(&mut rng, t, Vector::<2>::new(200.0 * t, 0.0)),
            plot(&mut rng, t, Vector::<2>::new(-150.0 * t, 30_000.0)),
            plot(
                &mut rng,
                t,
                Vector::<2>::new(5_000.0 * f64::from(k % 3), -40_000.0),
            ),
        ];
        kf.process_scan(t, S0, &plots).unwrap();
        imm.process_scan(t, S0, &plots).unwrap();
        assert_eq!(kf.tracks().len(), imm.tracks().len());
        for (a, b) in kf.tracks().iter().zip(imm.tracks()) {
            assert_eq!((a.id(), a.status()), (b.id(), b.status()));
            let dm = (a.estimate().mean() - b.estimate().mean()).norm();
            let dp = (a.estimate().cov() - b.estimate().cov()).norm();
            assert!(
                dm < 1e-6 && dp < 1e-6 * a.estimate().cov().norm(),
                "scan {k}: {dm} {dp}"
            );
            assert!(b.state().mode_probabilities().is_some());
        }
    }
}

/// A target at 250 m/s along +x that turns left at `accel` m/s² for 30 s from t = 40 s,
/// then flies straight; plots every 5 s (P_D = 1) for 120 s.
fn turning_truth(t: f64, accel: f64) -> Vector<2> {
    let v = 250.0;
    let w = accel / v;
    let (t0, t1) = (40.0, 70.0);
    if t <= t0 {
        return Vector::<2>::new(v * t, 0.0);
    }
    let tau = t.min(t1) - t0;
    let th = w * tau;
    let p = Vector::<2>::new(v * t0 + v / w * th.sin(), v / w * (1.0 - th.cos()));
    if t <= t1 {
        return p;
    }
    p + Vector::<2>::new(th.cos(), th.sin()) * v * (t - t1)
}

fn run_turn(estimator: EstimatorConfig, seed: u64, accel: f64) -> TrackStatistics {
    let mut cfg = TrackerConfig::new(vec![S0]);
    cfg.estimator = estimator;
    let mut tracker = Tracker::new(cfg).unwrap();
    let mut rng = run_rng(22, seed);
    let mut scans = Vec::new();
    for k in 0..=24 {
        let t = T * f64::from(k);
        let truth = turning_truth(t, accel);
        tracker
            .process_scan(t, S0, &[plot(&mut rng, t, truth)])
            .unwrap();
        let tracks: Vec<(u64, Vector<2>)> = tracker
            .tracks()
            .iter()
            .filter(|tr| tr.status() == TrackStatus::Confirmed)
            .map(|tr| {
                (
                    tr.id().0,
                    Vector::<2>::new(tr.estimate().mean()[0], tr.estimate().mean()[2]),
                )
            })
            .collect();
        scans.push(TrackScan::assign(t, &[(TargetId(0), truth)], &tracks, 1000.0).unwrap());
    }
    TrackStatistics::from_scans(&scans).unwrap()
}

#[test]
fn imm_holds_a_1g_turn_that_breaks_the_quiet_kalman_filter() {
    // A 10 m/s² (≈ 1 g) turn for 30 s at 250 m/s: over one 5 s scan it moves the target
    // ½ a T² = 125 m off the CV prediction and bends the velocity by 50 m/s per scan,
    // far more than the quiet model (σ_a = 2 m/s²) allows. The IMM with a manoeuvre mode
    // of σ_a = 30 m/s² keeps one track through it (no break, no new id, no false track);
    // the KF with σ_a = 2 alone loses it in every seed.
    // Harder turns, 1.5 g, 2 g and 3 g: the IMM tracks are gated per mode (a plot in the
    // manoeuvre mode's gate is taken), and the same IMM holds them in every seed; when it
    // was gated on its moment-matched prediction it broke 1 of these 5 seeds at each.
    let imm = EstimatorConfig::ImmCv2 {
        sigma_a_low: 2.0,
        sigma_a_high: 30.0,
        p_stay: 0.9,
    };
    for seed in 0..5 {
        for accel in [10.0, 15.0, 20.0, 30.0] {
            let st = run_turn(imm, seed, accel);
            assert_eq!(
                (st.breaks, st.id_swaps, st.tracks_seen),
                (0, 0, 1),
                "seed {seed}, {accel} m/s²: {st:?}"
            );
            assert_eq!(st.false_track_scans, 0, "seed {seed}, {accel} m/s²");
        }
        let kf = run_turn(EstimatorConfig::Kf, seed, 10.0);
        assert!(kf.breaks >= 1, "seed {seed}: KF kept the turn: {kf:?}");
    }
}

#[test]
fn bad_estimator_config_names_the_field() {
    let mut cfg = TrackerConfig::new(vec![S0]);
    cfg.estimator = EstimatorConfig::ImmCv2 {
        sigma_a_low: 1.0,
        sigma_a_high: 30.0,
        p_stay: 1.0,
    };
    assert!(matches!(
        Tracker::new(cfg),
        Err(argus_tracker::TrackerError::InvalidConfig {
            field: argus_tracker::ConfigField::Estimator(argus_tracker::EstimatorField::PStay),
            ..
        })
    ));
}

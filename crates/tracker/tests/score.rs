//! Track-score (SPRT) confirmation and deletion.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use argus_core_math::{Matrix, Vector};
use argus_filters::{GaussianFilter, Kf, two_point_cv2};
use argus_motion_models::Cv2D;
use argus_sensors::CartesianPosition;
use argus_sim::run_rng;
use argus_tracker::{
    DeletionReason, Plot, ScoreConfig, SensorId, TrackStatus, Tracker, TrackerConfig,
};
use rand::RngExt;
use rand_distr::{Distribution, Poisson};

const S0: SensorId = SensorId(0);
const T: f64 = 5.0;
const SIGMA: f64 = 50.0;
const LAMBDA: f64 = 2.5e-8; // 10 clutter plots per scan over 20 km × 20 km

fn r() -> Matrix<2, 2> {
    Matrix::<2, 2>::identity() * (SIGMA * SIGMA)
}

fn config(alpha: f64) -> TrackerConfig {
    let mut cfg = TrackerConfig::new(vec![S0]);
    cfg.max_speed = 300.0;
    cfg.max_misses = 10;
    cfg.score = Some(ScoreConfig {
        p_detection: 0.9,
        clutter_density: LAMBDA,
        new_target_density: 1e-9,
        false_confirm: alpha,
        missed_confirm: 0.1,
        delete_drop: 5.0,
    });
    cfg
}

#[test]
fn score_follows_the_llr_recursion_and_drives_confirmation_and_deletion() {
    // A noise-free CV target (so every innovation is 0) at 200 m/s, plots at scans
    // 0..=9, none after. The expected score is rebuilt here from the filters' API:
    // L₀ = ln(β_NT/λ) + ln(P_D/(λ π r²)), r = v_max T + 3 √(tr R₁ + tr R₂) (Blackman &
    // Popoli eq. 6.11–6.13), then + ln(P_D/λ) + ln N(0; 0, S_k) per hit and
    // + ln(1 − P_D P_G) per miss.
    let cfg = config(1e-3);
    let sc = cfg.score.unwrap();
    let mut tracker = Tracker::new(cfg.clone()).unwrap();
    let p_g = tracker.gate().p_gate();
    let kf = Kf::new(Cv2D::discrete(cfg.sigma_a).unwrap());
    let model = CartesianPosition::<4, 2>::cv(r()).unwrap();
    let pos = |t: f64| Vector::<2>::new(200.0 * t, 500.0);
    let rad = 300.0 * T + 3.0 * (4.0 * SIGMA * SIGMA).sqrt();
    let mut expected =
        (1e-9 / LAMBDA).ln() + (0.9 / (LAMBDA * std::f64::consts::PI * rad * rad)).ln();
    let mut est = two_point_cv2(&pos(0.0), &r(), &pos(T), &r(), T).unwrap();
    let mut confirm_scan = None;
    let mut expected_confirm = None;
    let mut delete_scan = None;
    let mut peak = expected;
    let mut expected_delete = None;
    for k in 0..20 {
        let t = T * f64::from(k);
        let plots = if k <= 9 {
            vec![Plot::cartesian(t, S0, pos(t), r()).unwrap()]
        } else {
            vec![]
        };
        let rep = tracker.process_scan(t, S0, &plots).unwrap();
        if k >= 2 {
            let pred = kf.predict(&est, T).unwrap();
            if k <= 9 {
                let mp = kf.predict_measurement(&pred, &model).unwrap();
                expected += (0.9 / LAMBDA).ln() + mp.log_likelihood_from_nis(0.0);
                est = mp.update(&pred, &Vector::<2>::zeros()).unwrap();
            } else {
                expected += (1.0 - 0.9 * p_g).ln();
                est = pred;
            }
            peak = peak.max(expected);
        }
        if k >= 1 && expected_confirm.is_none() && expected >= sc.confirm_threshold() {
            expected_confirm = Some(k);
        }
        if expected_delete.is_none() && peak - expected >= sc.delete_drop {
            expected_delete = Some(k);
        }
        if let Some(tr) = tracker.tracks().first() {
            assert!(
                (tr.score() - expected).abs() < 1e-6,
                "scan {k}: {} vs {expected}",
                tr.score()
            );
        }
        if !rep.confirmed.is_empty() {
            confirm_scan = Some(k);
        }
        if !rep.deleted.is_empty() {
            delete_scan = Some(k);
        }
    }
    assert!(expected_confirm.is_some() && expected_delete.is_some());
    assert_eq!(confirm_scan, expected_confirm);
    assert_eq!(delete_scan, expected_delete);
    // −2.22 per miss, drop 5: deleted at the third miss (scan 12), by score.
    assert_eq!(delete_scan, Some(12));
    assert_eq!(tracker.deleted()[0].deletion(), Some(DeletionReason::Score));
}

#[test]
fn false_confirmations_stay_under_villes_bound() {
    // Clutter only (Poisson, λ = 2.5e-8 /m², 200 scans), α = 0.2 so that some clutter
    // tracks do confirm. For a false track exp(L − L₀) is a supermartingale with mean
    // ≤ 1 (ScoreConfig docs), so P(confirm) ≤ exp(L₀ − ln((1 − β)/α)) and the expected
    // number of false confirmations is at most the sum of that over the tentative
    // tracks started.
    let cfg = config(0.2);
    let threshold = cfg.score.unwrap().confirm_threshold();
    let mut tracker = Tracker::new(cfg).unwrap();
    let side = 20_000.0;
    let poisson = Poisson::new(LAMBDA * side * side).unwrap();
    let mut rng = run_rng(13, 0);
    let (mut bound, mut confirmations, mut started) = (0.0, 0usize, 0usize);
    for k in 0..200 {
        let t = T * f64::from(k);
        let n: f64 = poisson.sample(&mut rng);
        let plots: Vec<Plot> = (0..n as usize)
            .map(|_| {
                Plot::cartesian(
                    t,
                    S0,
                    Vector::<2>::new(side * rng.random::<f64>(), side * rng.random::<f64>()),
                    r(),
                )
                .unwrap()
            })
            .collect();
        let rep = tracker.process_scan(t, S0, &plots).unwrap();
        for id in &rep.initiated {
            let tr = tracker.tracks().iter().find(|tr| tr.id() == *id).unwrap();
            bound += (tr.score() - threshold).exp();
            started += 1;
            if tr.status() == TrackStatus::Confirmed {
                confirmations += 1;
            }
        }
        confirmations += rep
            .confirmed
            .iter()
            .filter(|id| !rep.initiated.contains(id))
            .count();
        tracker.take_deleted();
    }
    println!(
        "score, clutter only: {started} started, {confirmations} confirmed, Ville bound {bound:.2}"
    );
    assert!(started > 100);
    assert!(confirmations as f64 <= bound, "{confirmations} > {bound}");
}

#[test]
fn bad_score_config_names_the_field() {
    let mut cfg = config(0.2);
    if let Some(sc) = cfg.score.as_mut() {
        sc.false_confirm = 0.7;
    }
    assert!(matches!(
        Tracker::new(cfg),
        Err(argus_tracker::TrackerError::InvalidConfig {
            field: argus_tracker::ConfigField::Score(argus_tracker::ScoreField::FalseConfirm),
            ..
        })
    ));
}

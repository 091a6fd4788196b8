//! `argus_tracker::smooth::TrackSmoother`, the one smoother of the tracker's tracks: a
//! track's rows (time, filtered estimate, estimator state) smoothed from the rows alone
//! equal the smoother of the same forward pass run by the filter itself.

#![allow(clippy::unwrap_used)]

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{Kf, RtsTrack};
use argus_imm::{ImmEstimate, ImmTrack};
use argus_motion_models::Cv2D;
use argus_sensors::CartesianPosition;
use argus_tracker::smooth::{FilteredRow, Smoothing, TrackSmoother};
use argus_tracker::{EstimatorConfig, EstimatorState, SensorId, TrackerConfig};

/// A deterministic zero-mean jitter in [−a, a] (no RNG needed).
fn jitter(k: usize, a: f64) -> f64 {
    a * ((k as f64 * 12.9898).sin() * 43_758.545_3)
        .rem_euclid(1.0)
        .mul_add(2.0, -1.0)
}

fn start() -> Gaussian<4> {
    Gaussian::new(
        Vector::<4>::new(0.0, 100.0, 0.0, 0.0),
        Matrix::<4, 4>::identity() * 1e4,
    )
    .unwrap()
}

fn meas() -> CartesianPosition<4, 2> {
    CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 900.0).unwrap()
}

fn rows<'a>(
    times: &[f64],
    est: &'a [Gaussian<4>],
    states: &'a [EstimatorState],
) -> Vec<FilteredRow<'a>> {
    times
        .iter()
        .zip(est.iter().zip(states))
        .map(|(&time, (estimate, state))| FilteredRow {
            time,
            estimate,
            state,
        })
        .collect()
}

/// Relative agreement of two means (1e-9 of the largest component: round-off of the dense
/// `F P Fᵀ` against the CV model's block form, positions ~1e4 m).
fn close(a: &Vector<4>, b: &Vector<4>) -> bool {
    (a - b).iter().all(|v| v.abs() < 1e-9 * b.amax())
}

#[test]
fn kf_rows_smooth_as_the_rts_smoother_of_their_filter() {
    // Updates, one coasted row, and a repeated last row (a deleted track's) that takes
    // the last step's value.
    let sigma_a = 2.0;
    let kf = Kf::new(Cv2D::discrete(sigma_a).unwrap());
    let mut config = TrackerConfig::new([SensorId(1)]);
    config.sigma_a = sigma_a;
    let smoother = TrackSmoother::new(&config).unwrap();
    assert_eq!(smoother.mode_count(), 0);
    let mut rt = RtsTrack::new(0.0, start()).unwrap();
    let (mut times, mut est) = (vec![0.0], vec![start()]);
    for k in 1..30 {
        let t = 5.0 * k as f64 + jitter(k, 0.5);
        if k == 12 {
            rt.predict(&kf, t).unwrap();
            rt.coast().unwrap();
        } else {
            let z = Vector::<2>::new(100.0 * t + jitter(k, 40.0), jitter(k + 99, 40.0));
            rt.step(&kf, t, &meas(), &z).unwrap();
        }
        times.push(t);
        est.push(*rt.latest());
    }
    times.push(*times.last().unwrap());
    est.push(*est.last().unwrap());
    let states = vec![EstimatorState::Plain; est.len()];
    let s = smoother
        .smooth(&rows(&times, &est, &states), Smoothing::Interval)
        .unwrap();
    let want = rt.smooth().unwrap();
    assert_eq!(s.len(), times.len());
    let mut moved = 0.0_f64;
    for (k, (r, w)) in s
        .iter()
        .zip(want.iter().chain([want.last().unwrap()]))
        .enumerate()
    {
        assert!(close(r.estimate.mean(), w.mean()), "row {k}");
        assert!(r.modes.is_none());
        moved = moved.max((r.estimate.mean()[2] - est[k].mean()[2]).abs());
    }
    // The smoother is not the filter (the test can fail).
    assert!(moved > 1.0, "smoothing moved y by at most {moved} m");
}

#[test]
fn imm_rows_smooth_as_the_imm_smoother_of_their_forward_pass() {
    // A two-mode IMM track (a turn from step 15 on, one coasted row, a repeated last
    // row) smoothed from its recorded mode states equals ImmTrack's smoother of the same
    // forward pass (ImmTrack::step), 1e-9 relative.
    let (low, high, p) = (0.5, 10.0, 0.95);
    let imm = argus_tracker::two_mode_imm(low, high, p).unwrap();
    let mut config = TrackerConfig::new([SensorId(1)]);
    config.estimator = EstimatorConfig::ImmCv2 {
        sigma_a_low: low,
        sigma_a_high: high,
        p_stay: p,
    };
    let smoother = TrackSmoother::new(&config).unwrap();
    assert_eq!(smoother.mode_count(), 2);
    let e0 = ImmEstimate::from_common(start(), [0.5, 0.5]).unwrap();
    let mut it = ImmTrack::new(*imm.markov(), 0.0, e0).unwrap();
    let (mut times, mut est, mut states) =
        (vec![0.0], vec![start()], vec![EstimatorState::Imm(e0)]);
    let mut t = 0.0;
    for k in 1..30 {
        let tn = 5.0 * k as f64 + jitter(k, 0.5);
        if k == 12 {
            let pr = imm.predict(it.latest(), tn - t).unwrap();
            it.push(&imm, tn, pr.into_estimate()).unwrap();
        } else {
            let y = if k > 15 {
                30.0 * (k - 15).pow(2) as f64
            } else {
                0.0
            };
            let z = Vector::<2>::new(100.0 * tn + jitter(k, 40.0), y + jitter(k + 99, 40.0));
            it.step(&imm, tn, &meas(), &z).unwrap();
        }
        t = tn;
        times.push(t);
        est.push(it.latest().combined().unwrap());
        states.push(EstimatorState::Imm(*it.latest()));
    }
    times.push(t);
    est.push(*est.last().unwrap());
    states.push(states.last().unwrap().clone());
    let s = smoother
        .smooth(&rows(&times, &est, &states), Smoothing::Interval)
        .unwrap();
    let want = it.smooth().unwrap();
    let mut moved = 0.0_f64;
    for (k, (r, w)) in s
        .iter()
        .zip(want.iter().chain([want.last().unwrap()]))
        .enumerate()
    {
        assert!(close(r.estimate.mean(), w.combined.mean()), "row {k}");
        let mu = r.modes.as_deref().unwrap();
        assert!((mu[0] - w.mode_probabilities[0]).abs() < 1e-9, "row {k}");
        moved = moved.max((r.estimate.mean()[2] - est[k].mean()[2]).abs());
    }
    assert!(moved > 1.0, "smoothing moved y by at most {moved} m");
    // A row without an IMM state is a typed failure at its step, not a half-smoothed
    // track.
    let mut bad = states.clone();
    bad[7] = EstimatorState::Plain;
    let f = smoother
        .smooth(&rows(&times, &est, &bad), Smoothing::Interval)
        .unwrap_err();
    assert_eq!((f.step(), f.message()), (7, "the row has no IMM state"));
    assert!((f.time() - times[7]).abs() < 1e-12);
}

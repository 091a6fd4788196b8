//! Smoothing on `real-traffic` (issues 19 and 18): the confirmed Kalman-filter tracks
//! smoothed over their own lives, scored like the filtered ones (`smooth_rms_ratio`), and
//! the NEES of every configuration's `[x, vx, y, vy]` against an RTS-smoothed ADS-B truth.
//!
//! **Tracks.** The tracker keeps per track only its filtered estimate. For its CV Kalman
//! filter (`gnn_kf`, `jpda_kf`) that is enough and exact: it predicts a track from its
//! last posterior by `Cv2D::discrete(sigma_a)`, so the same prediction from the row before
//! is the tracker's own to round-off, and the RTS pass over the rows is the fixed-interval
//! smoother of the recorded forward pass (with JPDA: of the PDA posteriors' moments), as
//! `argus track --smooth` does. The two-mode IMM tracks (`gnn_imm`, `jpda_imm`) are
//! smoothed by `argus_imm`'s IMM smoother over their recorded mode-conditioned states
//! ([`argus_tracker::EstimatorState::Imm`] per row): the forward record (every mode's
//! estimate predicted through every model with its cross covariance, `ln μ̄`) is
//! recomputed from the row before's mode estimates over the rows' time difference by an
//! IMM built as the tracker builds its own, so with GNN it is the IMM's own forward pass
//! and with JPDA the smoother of the recorded per-mode PDA moments — as `argus track
//! --smooth` does (`crates/cli/src/track/multi_smooth.rs`). This holds because a track
//! is recorded after every sector and a rotating radar updates it at most once per
//! revolution (a sector is one revolution's eighth), so no forward step falls between two
//! rows. The aircraft-IMM tracks (`*_aircraft`) are smoothed the same way by `argus_imm`'s
//! aircraft-IMM smoother over their recorded states
//! ([`argus_tracker::EstimatorState::Aircraft`] per row; the record recomputed from the
//! row before's modes by the IMM of the tuning, `AircraftTuning::build`, as the tracker
//! builds it), as `argus track --smooth` does.
//!
//! **Smoothed truth.** The ADS-B positions jitter (docs/real-traffic.md: a 1-s sample's
//! distance from the midpoint of its neighbours has median 11.5 m, 90th percentile 52 m;
//! for independent per-axis noise σ that distance is Rayleigh of scale σ·√1.5, so the
//! 90th percentile reads σ ≈ 20 m). Each covered path, split at gaps over 10 s, is
//! smoothed by an RTS smoother of a CV model with σa = [`TRUTH_SIGMA_A`] on its positions
//! with σ = [`TRUTH_SIGMA`] per axis, started from its first sample (ADS-B velocity, σ 5
//! m/s). A track row is compared with the nearest smoothed-truth path present at its time
//! (interpolated linearly between the two samples around it), within the scorer's cutoff.

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{GaussianFilter, Kf, RtsStep, SmoothingFilter, rts_smooth};
use argus_imm::{AircraftEkf, AircraftEstimate, AircraftTrack, ImmEstimate, ImmTrack};
use argus_motion_models::Cv2D;
use argus_score::{TrackHistory, TrackRow, TruthPath};
use argus_sensors::CartesianPosition;
use argus_tracker::TwoModeImm;

use crate::error::ScenarioError;

mod modes;

/// The smoothed truth's assumed ADS-B position noise per axis (m), module docs.
pub(crate) const TRUTH_SIGMA: f64 = 20.0;
/// The smoothed truth's CV process noise (m/s²): a standard-rate turn at 200 m/s is
/// 10 m/s² of centripetal acceleration, brief; 3 m/s² keeps the lag in such a turn at
/// 1-s samples below the noise (module docs).
pub(crate) const TRUTH_SIGMA_A: f64 = 3.0;
/// The scorer does not interpolate the truth across gaps longer than this (s).
const MAX_GAP: f64 = 10.0;

/// One stretch of a truth path without gaps, smoothed: times and `[x, vx, y, vy]`.
#[derive(Debug, Clone)]
pub(crate) struct SmoothedTruth {
    times: Vec<f64>,
    states: Vec<Vector<4>>,
}

impl SmoothedTruth {
    /// The smoothed state at `t` (linear between the samples around it), if `t` is inside.
    fn at(&self, t: f64) -> Option<Vector<4>> {
        let (first, last) = (*self.times.first()?, *self.times.last()?);
        if t < first || t > last {
            return None;
        }
        let i = self.times.partition_point(|&s| s <= t);
        if i == 0 || i >= self.times.len() {
            return self.states.last().copied();
        }
        let (t0, t1) = (self.times[i - 1], self.times[i]);
        let w = (t - t0) / (t1 - t0);
        Some(self.states[i - 1] * (1.0 - w) + self.states[i] * w)
    }
}

fn smoothing_error(what: &str, e: impl std::fmt::Display) -> ScenarioError {
    ScenarioError::Degenerate {
        scenario: "real-traffic",
        message: format!("smoothing {what}: {e}"),
    }
}

/// Every covered truth path smoothed (module docs), split at gaps over 10 s.
///
/// # Errors
/// [`ScenarioError::Degenerate`] naming the path if its smoothing fails.
pub(crate) fn smoothed_truth(truth: &[TruthPath]) -> Result<Vec<SmoothedTruth>, ScenarioError> {
    let kf = Kf::new(Cv2D::discrete(TRUTH_SIGMA_A).map_err(|e| smoothing_error("the truth", e))?);
    let meas = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * TRUTH_SIGMA.powi(2))
        .map_err(|e| smoothing_error("the truth", e))?;
    let mut out = Vec::new();
    for path in truth {
        let fail =
            |e: &dyn std::fmt::Display| smoothing_error(&format!("truth {}", path.name()), e);
        let samples = path.samples();
        let mut start = 0;
        while start < samples.len() {
            let mut end = start + 1;
            while end < samples.len() && samples[end].t - samples[end - 1].t <= MAX_GAP {
                end += 1;
            }
            let seg = &samples[start..end];
            let s0 = seg[0];
            let cov = Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(
                TRUTH_SIGMA.powi(2),
                25.0,
                TRUTH_SIGMA.powi(2),
                25.0,
            ));
            let mut g = Gaussian::new(Vector::<4>::new(s0.x, s0.vx, s0.y, s0.vy), cov)
                .map_err(|e| fail(&e))?;
            let mut steps = vec![RtsStep::first(s0.t, g)];
            for (prev, s) in seg.iter().zip(&seg[1..]) {
                if s.t <= prev.t {
                    continue;
                }
                let tr = kf
                    .predict_with_cross(&g, s.t - prev.t)
                    .map_err(|e| fail(&e))?;
                let (post, _) = kf
                    .update(tr.predicted(), &meas, &Vector::<2>::new(s.x, s.y))
                    .map_err(|e| fail(&e))?;
                steps.push(RtsStep::new(s.t, tr, post));
                g = post;
            }
            let smoothed = rts_smooth(&steps).map_err(|e| fail(&e))?;
            out.push(SmoothedTruth {
                times: steps.iter().map(RtsStep::time).collect(),
                states: smoothed.iter().map(|g| *g.mean()).collect(),
            });
            start = end;
        }
    }
    Ok(out)
}

/// A track's rows smoothed by the RTS smoother of the tracker's CV Kalman filter `kf`
/// (module docs): a history with the same rows and flags and the smoothed states. Rows at
/// the time of the row before (a deleted track's last row) take that row's smoothed state.
///
/// # Errors
/// [`ScenarioError::Degenerate`] naming the track if a step fails.
pub(crate) fn smoothed_track(
    kf: &Kf<Cv2D>,
    history: &TrackHistory,
    estimates: &[Gaussian<4>],
) -> Result<TrackHistory, ScenarioError> {
    let fail = |e: &dyn std::fmt::Display| smoothing_error(&format!("track {}", history.name()), e);
    let rows = history.rows();
    let mut steps: Vec<RtsStep<4>> = Vec::with_capacity(rows.len());
    // Per row, the step it belongs to.
    let mut step_of = Vec::with_capacity(rows.len());
    for (r, g) in rows.iter().zip(estimates) {
        match steps.last() {
            None => steps.push(RtsStep::first(r.t, *g)),
            Some(last) if r.t > last.time() => {
                let tr = kf
                    .predict_with_cross(last.filtered(), r.t - last.time())
                    .map_err(|e| fail(&e))?;
                steps.push(RtsStep::new(r.t, tr, *g));
            }
            Some(_) => {}
        }
        step_of.push(steps.len() - 1);
    }
    let smoothed = rts_smooth(&steps).map_err(|e| fail(&e))?;
    with_smoothed_states(history, &step_of, |k| smoothed[k].mean())
}

/// `history` with each row's state replaced by its step's smoothed mean: row `i` takes
/// `mean(step_of[i])`, its flags and time kept.
///
/// # Errors
/// [`ScenarioError`] if the history cannot be rebuilt (it was valid, so it can).
fn with_smoothed_states<'a>(
    history: &TrackHistory,
    step_of: &[usize],
    mean: impl Fn(usize) -> &'a Vector<4>,
) -> Result<TrackHistory, ScenarioError> {
    let rows = history
        .rows()
        .iter()
        .zip(step_of)
        .map(|(r, &k)| {
            let m = mean(k);
            TrackRow {
                x: m[0],
                vx: m[1],
                y: m[2],
                vy: m[3],
                ..*r
            }
        })
        .collect();
    TrackHistory::new(history.name(), rows).map_err(ScenarioError::from)
}

/// A two-mode IMM track's rows smoothed by `argus_imm`'s IMM smoother over its recorded
/// mode-conditioned states `states` (module docs): a history with the same rows and flags
/// and the smoothed combined states. Rows at the time of the row before (a deleted
/// track's last row) take that row's smoothed state, as in [`smoothed_track`].
///
/// # Errors
/// [`ScenarioError::Degenerate`] naming the track if a row has no IMM state or a step
/// fails.
pub(crate) fn smoothed_imm_track(
    imm: &TwoModeImm,
    history: &TrackHistory,
    states: &[Option<ImmEstimate<4, 2>>],
) -> Result<TrackHistory, ScenarioError> {
    modes::smoothed_mode_track::<ImmTrack<4, 2>, _, _>(imm, history, states, "IMM", |s| *s)
}

/// An aircraft-IMM track's rows smoothed by `argus_imm`'s aircraft-IMM smoother over its
/// recorded states `states` (module docs), as [`smoothed_imm_track`] does for the
/// two-mode IMM.
///
/// # Errors
/// [`ScenarioError::Degenerate`] naming the track if a row has no aircraft-IMM state or a
/// step fails.
pub(crate) fn smoothed_aircraft_track(
    imm: &AircraftEkf<2, 3>,
    history: &TrackHistory,
    states: &[Option<Box<AircraftEstimate<2, 3>>>],
) -> Result<TrackHistory, ScenarioError> {
    modes::smoothed_mode_track::<AircraftTrack<2, 3>, _, _>(
        imm,
        history,
        states,
        "aircraft-IMM",
        |s| s.as_deref().copied(),
    )
}

/// `Σ NEES` and the number of confirmed rows compared: each confirmed row's
/// `(x̂ − x)ᵀ P⁻¹ (x̂ − x)` against the nearest smoothed-truth state present at its time
/// within `cutoff` metres (module docs).
pub(crate) fn nees_against(
    histories: &[TrackHistory],
    estimates: &[Vec<Gaussian<4>>],
    truth: &[SmoothedTruth],
    cutoff: f64,
) -> (f64, usize) {
    let (mut sum, mut count) = (0.0, 0);
    for (h, est) in histories.iter().zip(estimates) {
        for (r, g) in h.rows().iter().zip(est) {
            if !r.confirmed {
                continue;
            }
            let nearest = truth
                .iter()
                .filter_map(|s| s.at(r.t))
                .map(|x| ((x[0] - r.x).hypot(x[2] - r.y), x))
                .min_by(|a, b| a.0.total_cmp(&b.0));
            if let Some((d, x)) = nearest
                && d <= cutoff
            {
                let nees = g.mahalanobis_sq(&x);
                if nees.is_finite() {
                    sum += nees;
                    count += 1;
                }
            }
        }
    }
    (sum, count)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;
    use argus_filters::RtsTrack;
    use argus_score::TruthSample;

    /// A deterministic zero-mean jitter in [−a, a] (no RNG needed for a unit test).
    fn jitter(k: usize, a: f64) -> f64 {
        a * ((k as f64 * 12.9898).sin() * 43_758.545_3)
            .rem_euclid(1.0)
            .mul_add(2.0, -1.0)
    }

    #[test]
    fn a_track_smooths_as_the_rts_smoother_of_its_filter() {
        // Rows of a KF track (updates, one coasted row, a repeated last row) smoothed from
        // the rows alone equal RtsTrack's smoother of the same forward pass to round-off
        // (1e-9 relative); the repeated row takes the last step's value.
        let kf = Kf::new(Cv2D::discrete(2.0).unwrap());
        let meas = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 900.0).unwrap();
        let g0 = Gaussian::new(
            Vector::<4>::new(0.0, 100.0, 0.0, 0.0),
            Matrix::<4, 4>::identity() * 1e4,
        )
        .unwrap();
        let mut rt = RtsTrack::new(0.0, g0).unwrap();
        let (mut rows, mut est) = (vec![], vec![g0]);
        rows.push(TrackRow {
            t: 0.0,
            confirmed: false,
            x: 0.0,
            vx: 100.0,
            y: 0.0,
            vy: 0.0,
        });
        for k in 1..30 {
            let t = 5.0 * k as f64 + jitter(k, 0.5);
            if k == 12 {
                rt.predict(&kf, t).unwrap();
                rt.coast().unwrap();
            } else {
                let z = Vector::<2>::new(100.0 * t + jitter(k, 40.0), jitter(k + 99, 40.0));
                rt.step(&kf, t, &meas, &z).unwrap();
            }
            let g = *rt.latest();
            rows.push(TrackRow {
                t,
                confirmed: true,
                x: g.mean()[0],
                vx: g.mean()[1],
                y: g.mean()[2],
                vy: g.mean()[3],
            });
            est.push(g);
        }
        let last = *rows.last().unwrap();
        rows.push(TrackRow {
            confirmed: false,
            ..last
        });
        est.push(*est.last().unwrap());
        let h = TrackHistory::new("1", rows).unwrap();
        let s = smoothed_track(&kf, &h, &est).unwrap();
        let want = rt.smooth().unwrap();
        for (k, (r, w)) in s
            .rows()
            .iter()
            .zip(want.iter().chain([want.last().unwrap()]))
            .enumerate()
        {
            let m = w.mean();
            let d = [r.x - m[0], r.vx - m[1], r.y - m[2], r.vy - m[3]];
            assert!(
                d.iter().all(|v| v.abs() < 1e-9 * m.amax()),
                "row {k}: {d:?}"
            );
        }
    }

    #[test]
    fn the_smoothed_truth_removes_most_of_the_jitter() {
        // A straight 1-s path at 200 m/s with uniform jitter of ±35 m per axis (σ ≈ 20 m,
        // the module's TRUTH_SIGMA) and a 30-s gap: two stretches; away from the ends the
        // smoothed position error is under half the jitter's σ (a CV smoother over ~10
        // effective samples reduces it about threefold).
        let samples: Vec<TruthSample> = (0..200)
            .filter(|k| !(100..130).contains(k))
            .map(|k| {
                let t = k as f64;
                TruthSample {
                    t,
                    x: 200.0 * t + jitter(k, 35.0),
                    vx: 200.0,
                    y: 1000.0 + jitter(k + 7, 35.0),
                    vy: 0.0,
                }
            })
            .collect();
        let path = TruthPath::new("a", samples).unwrap();
        let s = smoothed_truth(std::slice::from_ref(&path)).unwrap();
        assert_eq!(s.len(), 2);
        let (mut se, mut n) = (0.0, 0.0);
        for t in (10..90).chain(140..190) {
            let t = t as f64 + 0.5;
            let x = s.iter().find_map(|p| p.at(t)).unwrap();
            se += (x[0] - 200.0 * t).powi(2) + (x[2] - 1000.0).powi(2);
            n += 2.0;
        }
        let rms = (se / n).sqrt();
        assert!(rms < 0.5 * TRUTH_SIGMA, "smoothed truth RMS error {rms} m");
        assert!(
            s.iter().all(|p| p.at(115.0).is_none()),
            "the gap is not bridged"
        );
    }
    #[test]
    fn an_imm_track_smooths_as_the_imm_smoother_of_its_forward_pass() {
        // Rows of a two-mode IMM track (updates, one coasted row, a repeated last row)
        // smoothed from the recorded mode states alone equal ImmTrack's smoother of the
        // same forward pass (ImmTrack::step) to round-off (1e-9 relative).
        let imm = argus_tracker::two_mode_imm(0.5, 10.0, 0.95).unwrap();
        let meas = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 900.0).unwrap();
        let g0 = Gaussian::new(
            Vector::<4>::new(0.0, 100.0, 0.0, 0.0),
            Matrix::<4, 4>::identity() * 1e4,
        )
        .unwrap();
        let e0 = ImmEstimate::from_common(g0, [0.5, 0.5]).unwrap();
        let mut it = ImmTrack::new(*imm.markov(), 0.0, e0).unwrap();
        let row = |t: f64, g: &Gaussian<4>| TrackRow {
            t,
            confirmed: true,
            x: g.mean()[0],
            vx: g.mean()[1],
            y: g.mean()[2],
            vy: g.mean()[3],
        };
        let (mut rows, mut states) = (vec![row(0.0, &g0)], vec![Some(e0)]);
        let mut t = 0.0;
        for k in 1..30 {
            let tn = 5.0 * k as f64 + jitter(k, 0.5);
            if k == 12 {
                let p = imm.predict(it.latest(), tn - t).unwrap();
                it.push(&imm, tn, p.into_estimate()).unwrap();
            } else {
                // A turn from step 15 on.
                let y = if k > 15 {
                    30.0 * (k - 15).pow(2) as f64
                } else {
                    0.0
                };
                let z = Vector::<2>::new(100.0 * tn + jitter(k, 40.0), y + jitter(k + 99, 40.0));
                it.step(&imm, tn, &meas, &z).unwrap();
            }
            t = tn;
            rows.push(row(t, &it.latest().combined().unwrap()));
            states.push(Some(*it.latest()));
        }
        let last = *rows.last().unwrap();
        rows.push(TrackRow {
            confirmed: false,
            ..last
        });
        states.push(*states.last().unwrap());
        let h = TrackHistory::new("1", rows).unwrap();
        let s = smoothed_imm_track(&imm, &h, &states).unwrap();
        let want = it.smooth().unwrap();
        let mut moved = 0.0_f64;
        for (k, (r, w)) in s
            .rows()
            .iter()
            .zip(want.iter().chain([want.last().unwrap()]))
            .enumerate()
        {
            let m = w.combined.mean();
            let d = [r.x - m[0], r.vx - m[1], r.y - m[2], r.vy - m[3]];
            assert!(
                d.iter().all(|v| v.abs() < 1e-9 * m.amax()),
                "row {k}: {d:?}"
            );
            moved = moved.max((r.y - h.rows()[k].y).abs());
        }
        // The smoother is not the filter (the test can fail).
        assert!(moved > 1.0, "smoothing moved y by at most {moved} m");
        // A row without an IMM state is a typed error, not a half-smoothed track.
        let mut bad = states.clone();
        bad[7] = None;
        let e = smoothed_imm_track(&imm, &h, &bad).unwrap_err().to_string();
        assert!(e.contains("row 7 has no IMM state"), "{e}");
        let e = smoothed_imm_track(&imm, &h, &states[1..])
            .unwrap_err()
            .to_string();
        assert!(e.contains("rows against"), "{e}");
    }
}

//! Smoothing on `real-traffic` (issues 19 and 18): the confirmed Kalman-filter tracks
//! smoothed over their own lives, scored like the filtered ones (`smooth_rms_ratio`), and
//! the NEES of every configuration's `[x, vx, y, vy]` against an RTS-smoothed ADS-B truth.
//!
//! **Tracks.** Every configuration's tracks are smoothed over their own lives by the
//! tracker's one smoother of its tracks ([`argus_tracker::smooth::TrackSmoother`], as
//! `argus track --smooth` does; its docs say what is smoothed for each estimator and why
//! it is exact) from the rows recorded after every sector. This holds because a rotating
//! radar updates a track at most once per revolution (a sector is one revolution's
//! eighth), so no forward step falls between two rows. Rows at the time of the row
//! before (a deleted track's last row) take that row's smoothed state.
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
use argus_motion_models::Cv2D;
use argus_score::{TrackHistory, TrackRow, TruthPath};
use argus_sensors::CartesianPosition;
use argus_tracker::EstimatorState;
use argus_tracker::smooth::{FilteredRow, Smoothing, TrackSmoother};

use crate::error::ScenarioError;

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

/// A track's rows smoothed by `smoother` over their recorded estimates and estimator
/// states (module docs): a history with the same rows and flags and the smoothed states.
///
/// # Errors
/// [`ScenarioError::Degenerate`] naming the track if the rows, estimates and states
/// differ in number, or a step fails.
pub(crate) fn smoothed_history(
    smoother: &TrackSmoother,
    history: &TrackHistory,
    estimates: &[Gaussian<4>],
    states: &[EstimatorState],
) -> Result<TrackHistory, ScenarioError> {
    let fail = |e: &dyn std::fmt::Display| smoothing_error(&format!("track {}", history.name()), e);
    let rows = history.rows();
    if estimates.len() != rows.len() || states.len() != rows.len() {
        return Err(fail(&format!(
            "{} rows against {} estimates and {} states",
            rows.len(),
            estimates.len(),
            states.len()
        )));
    }
    let filtered: Vec<FilteredRow<'_>> = rows
        .iter()
        .zip(estimates.iter().zip(states))
        .map(|(r, (estimate, state))| FilteredRow {
            time: r.t,
            estimate,
            state,
        })
        .collect();
    let smoothed = smoother
        .smooth(&filtered, Smoothing::Interval)
        .map_err(|f| {
            fail(&format!(
                "step {} (t = {} s): {}",
                f.step(),
                f.time(),
                f.message()
            ))
        })?;
    let rows = rows
        .iter()
        .zip(&smoothed)
        .map(|(r, s)| {
            let m = s.estimate.mean();
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
    use argus_score::TruthSample;

    /// A deterministic zero-mean jitter in [−a, a] (no RNG needed for a unit test).
    fn jitter(k: usize, a: f64) -> f64 {
        a * ((k as f64 * 12.9898).sin() * 43_758.545_3)
            .rem_euclid(1.0)
            .mul_add(2.0, -1.0)
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
}

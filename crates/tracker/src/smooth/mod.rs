//! Smoothing a recorded track (`argus track --smooth`, `--smooth-lag N`,
//! `--smooth-lag-seconds S`, the single-target engine's [`crate::single`] and the
//! command's smoothing of the tracker's tracks): a track's filtered estimates, one per
//! row, smoothed by the RTS smoother of `argus_filters` (KF, EKF) or the IMM smoothers of
//! `argus_imm` ([`ModeRecorder`]); the tracker's tracks by their one smoother,
//! [`TrackSmoother`].
//!
//! # What is smoothed, and why it is exact
//! Rows of one time (plots of one instant applied in turn, scans of two sensors at one
//! time) are one step: its filtered estimate is the last row's, and every row of that
//! time gets the step's smoothed estimate (the state at one instant has one smoothed
//! value). The transition into step `k` — `x̂ₖ⁻, Pₖ⁻` and `Cₖ = Pₖ₋₁ Fᵀ` — is the
//! estimator's own prediction of step `k − 1`'s filtered estimate over `tₖ − tₖ₋₁`
//! ([`SmoothingFilter::predict_with_cross`]): the prediction the forward filter made
//! (to round-off: the dense `F P Fᵀ` against the CV model's block form), since the KF
//! and EKF on the CV model predict by the same linear model from the same posterior.
//! The IMM is recorded during its forward pass ([`argus_imm::ImmTrack`]).
//!
//! # Fixed lag
//! Step `j`'s fixed-lag estimate is `x̂ⱼ|ₖ`, the fixed-interval smoother of steps
//! `0 … k` at `j`, with `k = j + N` (`--smooth-lag N`) or the first step with
//! `tₖ − tⱼ ≥ S` (`--smooth-lag-seconds S`), or the last step when the track ends first:
//! the definition of `argus_filters::FixedLagSmoother` ([`Lag`]). The RTS backward pass
//! from `k` to `j` needs only steps `j … k`, so each is the backward pass over that
//! window (`N` backward steps per step).
//!
//! # Failures
//! A track is smoothed whole or not at all: a failed step is a [`Failure`] naming the
//! step (0 is the track's first estimate) and its time.

mod record;
mod track;

pub use record::{AircraftRecorder, ImmRecorder, ModeRecorder};
pub use track::{FilteredRow, SmoothedRow, TrackSmoother};

use argus_core_math::Gaussian;
use argus_filters::{Lag, RtsStep, SmoothError, SmoothingFilter, rts_smooth};
use argus_imm::ImmSmoothError;

/// How a track is smoothed (`argus track`'s command-line flags).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Smoothing {
    /// `--smooth`: fixed-interval, over the whole track.
    Interval,
    /// `--smooth-lag N` ([`Lag::Steps`], `N ≥ 1`) or `--smooth-lag-seconds S`
    /// ([`Lag::Seconds`], `S > 0`).
    Lag(Lag),
}

impl Smoothing {
    /// The description `argus track`'s summary gives: `fixed-interval`, `fixed-lag 3
    /// steps`, `fixed-lag 10 s`.
    #[must_use]
    pub fn describe(self) -> String {
        match self {
            Self::Interval => "fixed-interval".to_owned(),
            Self::Lag(Lag::Steps(n)) => format!("fixed-lag {n} steps"),
            Self::Lag(Lag::Seconds(s)) => format!("fixed-lag {s} s"),
        }
    }
}

/// A track that could not be smoothed: the step and its time, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct Failure {
    step: usize,
    time: f64,
    message: String,
}

impl Failure {
    /// A failure at step `step` (time `time`).
    #[must_use]
    pub fn new(step: usize, time: f64, message: String) -> Self {
        Self {
            step,
            time,
            message,
        }
    }

    /// The step that failed (0 is the track's first estimate; rows of one time are one
    /// step).
    #[must_use]
    pub fn step(&self) -> usize {
        self.step
    }

    /// The step's time (s).
    #[must_use]
    pub fn time(&self) -> f64 {
        self.time
    }

    /// What failed.
    #[must_use]
    pub fn message(&self) -> &str {
        &self.message
    }
}

/// The steps of a track's rows: `row_step[i]` is row `i`'s step, `last_row[k]` the last
/// row of step `k` (rows of one time are one step).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Steps {
    /// Row `i`'s step.
    pub row_step: Vec<usize>,
    /// Step `k`'s last row.
    pub last_row: Vec<usize>,
}

/// Groups rows of equal times (in row order) into steps.
#[must_use]
pub fn steps(times: &[f64]) -> Steps {
    let mut row_step = Vec::with_capacity(times.len());
    let mut last_row: Vec<usize> = Vec::with_capacity(times.len());
    for (i, t) in times.iter().enumerate() {
        let same = i > 0 && times[i - 1].total_cmp(t).is_eq();
        match last_row.last_mut() {
            Some(last) if same => *last = i,
            _ => last_row.push(i),
        }
        row_step.push(last_row.len() - 1);
    }
    Steps { row_step, last_row }
}

/// The last step of step `j`'s window (module docs, fixed lag).
fn window_end(times: &[f64], j: usize, how: Smoothing) -> usize {
    let last = times.len().saturating_sub(1);
    match how {
        Smoothing::Interval => last,
        Smoothing::Lag(Lag::Steps(n)) => j.saturating_add(n).min(last),
        Smoothing::Lag(Lag::Seconds(s)) => (j..times.len())
            .find(|&k| times[k] - times[j] >= s)
            .unwrap_or(last),
    }
}

/// Per step, the smoothed value: `smooth(j, k)` smooths the window of steps `j … k` and
/// returns one value per step of it (fixed interval: the one window of every step;
/// fixed lag: each step's window, module docs).
///
/// # Errors
/// `smooth`'s [`Failure`]; a window that gives no value.
pub fn by_windows<T: Copy>(
    times: &[f64],
    how: Smoothing,
    smooth: impl Fn(usize, usize) -> Result<Vec<T>, Failure>,
) -> Result<Vec<T>, Failure> {
    if times.is_empty() {
        return Ok(Vec::new());
    }
    if how == Smoothing::Interval {
        return smooth(0, times.len() - 1);
    }
    (0..times.len())
        .map(|j| {
            let k = window_end(times, j, how);
            smooth(j, k)?.first().copied().ok_or_else(|| Failure {
                step: j,
                time: times[j],
                message: "empty smoothing window".to_owned(),
            })
        })
        .collect()
}

/// A sequence error of the window starting at step `base`, at its absolute step.
fn sequence_failure(e: &SmoothError, base: usize, times: &[f64]) -> Failure {
    let (step, message) = match e {
        SmoothError::Backward { step, source } => (base + step, format!("backward pass: {source}")),
        SmoothError::TimeNotIncreasing { step, prev, now } => (
            base + step,
            format!("time {now} s does not follow the previous step's {prev} s"),
        ),
        SmoothError::MissingTransition { step } => {
            (base + step, "no transition from the step before".to_owned())
        }
        other => (base, other.to_string()),
    };
    Failure {
        step,
        time: times.get(step).copied().unwrap_or(f64::NAN),
        message,
    }
}

/// RTS smoothing (KF, EKF) of a track's rows `(time, filtered estimate)` in time order:
/// one smoothed estimate per row.
///
/// # Errors
/// [`Failure`] at the step whose prediction or backward step fails, or whose time goes
/// backwards.
pub fn rts_rows<const N: usize, F: SmoothingFilter<N>>(
    filter: &F,
    rows: &[(f64, Gaussian<N>)],
    how: Smoothing,
) -> Result<Vec<Gaussian<N>>, Failure> {
    let times: Vec<f64> = rows.iter().map(|r| r.0).collect();
    let s = steps(&times);
    let step_times: Vec<f64> = s.last_row.iter().map(|&i| times[i]).collect();
    let mut seq: Vec<RtsStep<N>> = Vec::with_capacity(s.last_row.len());
    for (k, &i) in s.last_row.iter().enumerate() {
        let (t, g) = rows[i];
        let step = match seq.last() {
            None => RtsStep::first(t, g),
            Some(prev) => {
                let dt = t - prev.time();
                if dt.is_nan() || dt <= 0.0 {
                    return Err(sequence_failure(
                        &SmoothError::TimeNotIncreasing {
                            step: k,
                            prev: prev.time(),
                            now: t,
                        },
                        0,
                        &step_times,
                    ));
                }
                let tr = filter
                    .predict_with_cross(prev.filtered(), dt)
                    .map_err(|e| Failure {
                        step: k,
                        time: t,
                        message: format!("predicting the step before to this one: {e}"),
                    })?;
                RtsStep::new(t, tr, g)
            }
        };
        seq.push(step);
    }
    let smoothed = by_windows(&step_times, how, |j, k| {
        rts_smooth(&seq[j..=k]).map_err(|e| sequence_failure(&e, j, &step_times))
    })?;
    Ok(s.row_step.iter().map(|&k| smoothed[k]).collect())
}

/// An IMM error of the window starting at step `base`, at its absolute step.
pub(crate) fn imm_failure(e: &ImmSmoothError, base: usize, times: &[f64]) -> Failure {
    let (step, message) = match e {
        ImmSmoothError::Sequence(s) => return sequence_failure(s, base, times),
        ImmSmoothError::ForwardFailed { step, source } => {
            (base + step, format!("IMM prediction: {source}"))
        }
        ImmSmoothError::Backward { step, mode, source } => (
            base + step,
            format!(
                "IMM backward pass{}: {source}",
                mode.map_or(String::new(), |m| format!(", mode {}", m + 1))
            ),
        ),
        other => (base, other.to_string()),
    };
    Failure {
        step,
        time: times.get(step).copied().unwrap_or(f64::NAN),
        message,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use argus_core_math::{Matrix, Vector};
    use argus_filters::Kf;
    use argus_motion_models::Cv2D;
    use argus_sensors::CartesianPosition;

    /// A KF over position plots of a CV target, with two plots at t = 8 s (one step):
    /// the rows `(t, filtered)`.
    fn forward() -> (Kf<Cv2D>, Vec<(f64, Gaussian<4>)>) {
        let kf = Kf::new(Cv2D::discrete(0.5).unwrap());
        let pos = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 400.0).unwrap();
        let mut x = Gaussian::new(
            Vector::<4>::new(0.0, 10.0, 0.0, -5.0),
            Matrix::<4, 4>::identity() * 1e4,
        )
        .unwrap();
        let mut t = 0.0;
        let mut rows = vec![(t, x)];
        // Deterministic plot offsets (±20 m), irregular intervals, a repeated time.
        for (k, dt) in [2.0, 3.0, 3.0, 0.0, 1.5, 4.0, 2.0, 2.0, 5.0, 1.0]
            .iter()
            .enumerate()
        {
            let tn = t + dt;
            let off = if k % 2 == 0 { 20.0 } else { -20.0 };
            let z = Vector::<2>::new(10.0 * tn + off, -5.0 * tn - off);
            let pred = if *dt > 0.0 {
                kf.predict(&x, *dt).unwrap()
            } else {
                x
            };
            x = kf.update(&pred, &pos, &z).unwrap().0;
            t = tn;
            rows.push((t, x));
        }
        (kf, rows)
    }

    use argus_filters::GaussianFilter as _;

    #[test]
    fn rows_of_one_time_share_a_step_and_every_covariance_shrinks() {
        let (kf, rows) = forward();
        let s = steps(&rows.iter().map(|r| r.0).collect::<Vec<_>>());
        // 11 rows, rows 3 and 4 at t = 8 s: 10 steps, the step's estimate is row 4's.
        assert_eq!(s.last_row.len(), 10);
        assert_eq!(s.row_step[3], s.row_step[4]);
        assert_eq!(s.last_row[s.row_step[4]], 4);
        let sm = rts_rows(&kf, &rows, Smoothing::Interval).unwrap();
        assert_eq!(sm[3], sm[4]);
        // The last row is the filter's.
        assert_eq!(sm[10], rows[10].1);
        for ((_, f), g) in rows.iter().zip(&sm) {
            // P − Pˢ ⪰ 0: smallest eigenvalue ≥ −1e-9 of P's largest entry (round-off).
            let d = f.cov() - g.cov();
            let min = d.symmetric_eigen().eigenvalues.min();
            assert!(min >= -1e-9 * f.cov().amax(), "eigenvalue {min}");
        }
        // The repeated time's first row is not a step of its own: its smoothed
        // covariance is also ≤ its own (larger) filtered one, checked above.
    }

    #[test]
    fn lags_window_the_same_backward_pass() {
        let (kf, rows) = forward();
        let interval = rts_rows(&kf, &rows, Smoothing::Interval).unwrap();
        // A lag as long as the track is the fixed-interval smoother, to the bit (the
        // window of step 0 is the whole track, and each step's window ends at the end).
        for lag in [Lag::Steps(9), Lag::Steps(50), Lag::Seconds(1e3)] {
            assert_eq!(rts_rows(&kf, &rows, Smoothing::Lag(lag)).unwrap(), interval);
        }
        // A lag of 2 steps: step j is x̂ⱼ|ⱼ₊₂, the fixed-interval smoother of the rows
        // up to step j + 2, at j.
        let lag2 = rts_rows(&kf, &rows, Smoothing::Lag(Lag::Steps(2))).unwrap();
        let upto = rts_rows(&kf, &rows[..=2], Smoothing::Interval).unwrap();
        assert_eq!(lag2[0], upto[0]);
        // A lag of 5 s: step 0 (t = 0) waits for t = 5 (row 2).
        let lag5 = rts_rows(&kf, &rows, Smoothing::Lag(Lag::Seconds(5.0))).unwrap();
        assert_eq!(lag5[0], upto[0]);
    }

    #[test]
    fn time_going_backwards_names_the_step() {
        let (kf, mut rows) = forward();
        rows[6].0 = 1.0;
        let e = rts_rows(&kf, &rows, Smoothing::Interval).unwrap_err();
        // Row 6 is step 5 (rows 3 and 4 are one step).
        assert_eq!((e.step, e.time), (5, 1.0));
        assert!(e.message.contains("does not follow"), "{}", e.message);
    }
}

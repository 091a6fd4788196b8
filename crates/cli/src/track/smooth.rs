//! `argus track --smooth` (fixed interval), `--smooth-lag N` and `--smooth-lag-seconds S`
//! (fixed lag): a track's filtered estimates, one per row, smoothed by the RTS smoother of
//! `argus_filters` (KF, EKF) or the IMM smoother of `argus_imm`.
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
//! The IMM is recorded during its forward pass ([`ImmTrack`]).
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
//! step (0 is the track's first estimate) and its time, and the command stops with
//! [`CliError::Smooth`] naming the track; nothing is written.

use argus_core_math::Gaussian;
use argus_filters::{Lag, RtsStep, SmoothError, SmoothingFilter, rts_smooth};
use argus_imm::{Imm, ImmEstimate, ImmSmoothError, ImmSmoothed, ImmTrack, MarkovMatrix};

use crate::error::CliError;

/// How `argus track` smooths (the command-line flags).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Smoothing {
    /// `--smooth`: fixed-interval, over the whole track.
    Interval,
    /// `--smooth-lag N` ([`Lag::Steps`], `N ≥ 1`) or `--smooth-lag-seconds S`
    /// ([`Lag::Seconds`], `S > 0`).
    Lag(Lag),
}

impl Smoothing {
    /// The summary's description: `fixed-interval`, `fixed-lag 3 steps`, `fixed-lag 10 s`.
    pub(super) fn describe(self) -> String {
        match self {
            Self::Interval => "fixed-interval".to_owned(),
            Self::Lag(Lag::Steps(n)) => format!("fixed-lag {n} steps"),
            Self::Lag(Lag::Seconds(s)) => format!("fixed-lag {s} s"),
        }
    }
}

/// A track that could not be smoothed: the step and its time, and why.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Failure {
    step: usize,
    time: f64,
    message: String,
}

impl Failure {
    /// The command's error for track `track`.
    pub(super) fn into_cli(self, track: u64) -> CliError {
        CliError::Smooth {
            track,
            step: self.step,
            time: self.time,
            message: self.message,
        }
    }
}

/// The steps of a track's rows: `row_step[i]` is row `i`'s step, `last_row[k]` the last
/// row of step `k` (rows of one time are one step).
pub(super) struct Steps {
    pub(super) row_step: Vec<usize>,
    pub(super) last_row: Vec<usize>,
}

/// Groups rows of equal times (in row order) into steps.
pub(super) fn steps(times: &[f64]) -> Steps {
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
/// returns one value per step of it.
fn by_windows<T: Copy>(
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
pub(super) fn rts_rows<const N: usize, F: SmoothingFilter<N>>(
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
                if !(dt > 0.0) {
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
fn imm_failure(e: &ImmSmoothError, base: usize, times: &[f64]) -> Failure {
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

/// An IMM forward pass being recorded for smoothing, one step per time: the posterior of
/// a time is recorded when the next time comes (plots of one instant are applied in
/// turn), so that the transitions start from the last posterior of each time.
pub(super) struct ImmRecorder<const R: usize> {
    markov: MarkovMatrix<R>,
    track: Option<ImmTrack<4, R>>,
    pending: Option<(f64, ImmEstimate<4, R>)>,
    times: Vec<f64>,
}

impl<const R: usize> ImmRecorder<R> {
    /// An empty record of an IMM with `markov`.
    pub(super) fn new(markov: MarkovMatrix<R>) -> Self {
        Self {
            markov,
            track: None,
            pending: None,
            times: Vec::new(),
        }
    }

    /// Records the posterior `est` at `time` (the row's).
    ///
    /// # Errors
    /// [`Failure`] when the transitions from the previous time cannot be formed.
    pub(super) fn record<F: SmoothingFilter<4>>(
        &mut self,
        imm: &Imm<F, 4, R>,
        time: f64,
        est: ImmEstimate<4, R>,
    ) -> Result<(), Failure> {
        if let Some((t, _)) = &self.pending
            && t.total_cmp(&time).is_eq()
        {
            self.pending = Some((time, est));
            return Ok(());
        }
        self.flush(imm)?;
        self.pending = Some((time, est));
        Ok(())
    }

    fn flush<F: SmoothingFilter<4>>(&mut self, imm: &Imm<F, 4, R>) -> Result<(), Failure> {
        let Some((t, est)) = self.pending.take() else {
            return Ok(());
        };
        self.times.push(t);
        let res = match &mut self.track {
            None => ImmTrack::new(self.markov, t, est).map(|tr| self.track = Some(tr)),
            Some(tr) => tr.push(imm, t, est),
        };
        res.map_err(|e| imm_failure(&e, 0, &self.times))
    }

    /// Smooths the record: one smoothed IMM estimate per step (rows of one time share it).
    ///
    /// # Errors
    /// [`Failure`] at the failed step.
    pub(super) fn smooth<F: SmoothingFilter<4>>(
        mut self,
        imm: &Imm<F, 4, R>,
        how: Smoothing,
    ) -> Result<Vec<ImmSmoothed<4, R>>, Failure> {
        self.flush(imm)?;
        let Some(track) = &self.track else {
            return Ok(Vec::new());
        };
        let times = &self.times;
        let steps = track.steps();
        by_windows(times, how, |j, k| {
            argus_imm::imm_smooth(
                track.markov(),
                argus_imm::PairWeights::default(),
                &steps[j..=k],
            )
            .map_err(|e| imm_failure(&e, j, times))
        })
    }
}

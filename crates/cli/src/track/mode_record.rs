//! The forward-pass record of a mode-switching estimator (the IMM, the aircraft IMM),
//! kept for smoothing one step per time: the posterior of a time is recorded when the
//! next time comes (plots of one instant are applied in turn), so that the transitions
//! start from the last posterior of each time. [`ModeTrack`] is what the record needs
//! of `argus_imm`'s track of one estimator ([`super::smooth_imm`],
//! [`super::smooth_aircraft`]).

use argus_core_math::Gaussian;
use argus_imm::ImmSmoothError;

use super::smooth::{Failure, Smoothing, by_windows, imm_failure};

/// A recorded forward pass of the estimator `M` (`argus_imm`'s `ImmTrack`,
/// `AircraftTrack`) and its smoother.
pub(super) trait ModeTrack<M>: Sized {
    /// The estimator's posterior at one time.
    type Estimate;
    /// The smoother's estimate at one step.
    type Smoothed: Copy;

    /// A record whose first step is `est` at `time`, with `imm`'s Markov matrix.
    ///
    /// # Errors
    /// [`ImmSmoothError`] for a time the record refuses.
    fn start(imm: &M, time: f64, est: Self::Estimate) -> Result<Self, ImmSmoothError>;

    /// Records `est` at `time`, its transition from the latest step recomputed by `imm`.
    ///
    /// # Errors
    /// [`ImmSmoothError`] when the transition cannot be formed.
    fn push(&mut self, imm: &M, time: f64, est: Self::Estimate) -> Result<(), ImmSmoothError>;

    /// The smoother over the recorded steps `j ..= k`: one estimate per step.
    ///
    /// # Errors
    /// [`ImmSmoothError`] at the failed step (relative to `j`).
    fn smooth_steps(&self, j: usize, k: usize) -> Result<Vec<Self::Smoothed>, ImmSmoothError>;

    /// A smoothed step as the tracker's row has it: the combined estimate and the mode
    /// probabilities.
    fn row(s: &Self::Smoothed) -> (Gaussian<4>, Vec<f64>);
}

/// A forward pass being recorded for smoothing (module docs): the track `T` and the
/// posterior `E` of the latest time, held until the next time comes.
pub(super) struct ModeRecorder<T, E> {
    track: Option<T>,
    pending: Option<(f64, E)>,
    times: Vec<f64>,
}

impl<T, E> ModeRecorder<T, E> {
    /// An empty record.
    pub(super) fn new() -> Self {
        Self {
            track: None,
            pending: None,
            times: Vec::new(),
        }
    }

    /// Records the posterior `est` at `time` (the row's).
    ///
    /// # Errors
    /// [`Failure`] when the transitions from the previous time cannot be formed.
    pub(super) fn record<M>(&mut self, imm: &M, time: f64, est: E) -> Result<(), Failure>
    where
        T: ModeTrack<M, Estimate = E>,
    {
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

    fn flush<M>(&mut self, imm: &M) -> Result<(), Failure>
    where
        T: ModeTrack<M, Estimate = E>,
    {
        let Some((t, est)) = self.pending.take() else {
            return Ok(());
        };
        self.times.push(t);
        let res = match &mut self.track {
            None => T::start(imm, t, est).map(|tr| self.track = Some(tr)),
            Some(tr) => tr.push(imm, t, est),
        };
        res.map_err(|e| imm_failure(&e, 0, &self.times))
    }

    /// Smooths the record: one smoothed estimate per step (rows of one time share it).
    ///
    /// # Errors
    /// [`Failure`] at the failed step.
    pub(super) fn smooth<M>(mut self, imm: &M, how: Smoothing) -> Result<Vec<T::Smoothed>, Failure>
    where
        T: ModeTrack<M, Estimate = E>,
    {
        self.flush(imm)?;
        let Some(track) = &self.track else {
            return Ok(Vec::new());
        };
        let times = &self.times;
        by_windows(times, how, |j, k| {
            track
                .smooth_steps(j, k)
                .map_err(|e| imm_failure(&e, j, times))
        })
    }
}

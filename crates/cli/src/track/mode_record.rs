//! The forward-pass record of a mode-switching estimator (the IMM, the aircraft IMM),
//! kept for smoothing one step per time: the posterior of a time is recorded when the
//! next time comes (plots of one instant are applied in turn), so that the transitions
//! start from the last posterior of each time, into `argus_imm`'s track of one estimator
//! ([`ForwardRecord`]: [`super::smooth_imm`], [`super::smooth_aircraft`]).

use argus_imm::ForwardRecord;

use super::smooth::{Failure, Smoothing, by_windows, imm_failure};

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
        T: ForwardRecord<M, 4, Estimate = E>,
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
        T: ForwardRecord<M, 4, Estimate = E>,
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
        T: ForwardRecord<M, 4, Estimate = E>,
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

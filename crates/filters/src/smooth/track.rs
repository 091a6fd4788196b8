//! The record of a forward pass: per step the time, the transition into it and the
//! filtered estimate.

use argus_core_math::{Gaussian, Vector};
use argus_sensors::MeasurementModel;

use super::rts::{backward, validate};
use super::{RtsStep, SmoothError, SmoothingFilter, Transition};
use crate::Innovation;

/// A forward pass recorded for smoothing.
///
/// Each step is [`RtsTrack::predict`] to the next time, then one of [`RtsTrack::update`]
/// (a plot through the filter), [`RtsTrack::record_update`] (a posterior computed
/// elsewhere, e.g. by a PDA) or [`RtsTrack::coast`] (no plot); [`RtsTrack::step`] does
/// predict + update. If the filter fails, or time does not move forward, the track
/// records the failure: every later call and [`RtsTrack::smooth`] return
/// [`SmoothError::ForwardFailed`] (or the time error) naming the step. The steps before
/// it stay readable ([`RtsTrack::steps`]) and can be smoothed, explicitly, with
/// [`super::rts_smooth`].
#[derive(Debug, Clone, PartialEq)]
pub struct RtsTrack<const N: usize> {
    steps: Vec<RtsStep<N>>,
    /// The number of the first step held (the fixed-lag smoother drops old steps).
    base: usize,
    /// A prediction waiting for its update: `(time, transition)`.
    pending: Option<(f64, Transition<N>)>,
    failure: Option<SmoothError>,
}

impl<const N: usize> RtsTrack<N> {
    /// A track starting at `time` with the estimate `initial` (step 0).
    ///
    /// # Errors
    /// [`SmoothError::TimeNotIncreasing`] when `time` is not finite.
    pub fn new(time: f64, initial: Gaussian<N>) -> Result<Self, SmoothError> {
        Self::with_capacity(time, initial, 0)
    }

    /// As [`RtsTrack::new`], with room for `steps` steps (no reallocation while recording).
    ///
    /// # Errors
    /// As [`RtsTrack::new`].
    pub fn with_capacity(
        time: f64,
        initial: Gaussian<N>,
        steps: usize,
    ) -> Result<Self, SmoothError> {
        if !time.is_finite() {
            return Err(SmoothError::TimeNotIncreasing {
                step: 0,
                prev: f64::NEG_INFINITY,
                now: time,
            });
        }
        let mut v = Vec::with_capacity(steps.max(1));
        v.push(RtsStep::first(time, initial));
        Ok(Self {
            steps: v,
            base: 0,
            pending: None,
            failure: None,
        })
    }

    /// The recorded steps (those still held, for a fixed-lag window).
    #[must_use]
    pub fn steps(&self) -> &[RtsStep<N>] {
        &self.steps
    }

    /// The number of steps held.
    #[must_use]
    pub fn len(&self) -> usize {
        self.steps.len()
    }

    /// Always `false`: a track holds at least its first step.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.steps.is_empty()
    }

    /// The number of the first step held (0 unless a fixed-lag window dropped steps).
    #[must_use]
    pub fn first_step(&self) -> usize {
        self.base
    }

    /// The latest filtered estimate.
    #[must_use]
    pub fn latest(&self) -> &Gaussian<N> {
        // Never empty: `new` pushes the first step and `drop_oldest` keeps the last one.
        self.steps[self.steps.len() - 1].filtered()
    }

    /// The time of the latest step.
    #[must_use]
    pub fn latest_time(&self) -> f64 {
        self.steps[self.steps.len() - 1].time()
    }

    /// The failure recorded, if any.
    #[must_use]
    pub fn failure(&self) -> Option<&SmoothError> {
        self.failure.as_ref()
    }

    /// The number the next step will have.
    fn next_step(&self) -> usize {
        self.base + self.steps.len()
    }

    fn check_usable(&self) -> Result<(), SmoothError> {
        self.failure.clone().map_or(Ok(()), Err)
    }

    fn fail(&mut self, e: SmoothError) -> SmoothError {
        self.failure = Some(e.clone());
        e
    }

    /// Predicts the latest estimate to `time` and keeps the prediction and its cross
    /// covariance; returns the prediction (for gating and the update).
    ///
    /// # Errors
    /// [`SmoothError::OutOfOrder`] when a prediction is already pending (nothing changes);
    /// [`SmoothError::TimeNotIncreasing`] when `time` is not after the latest step and
    /// [`SmoothError::ForwardFailed`] when the filter fails (both recorded: the track
    /// cannot be smoothed past them); a failure recorded earlier.
    pub fn predict<F: SmoothingFilter<N>>(
        &mut self,
        filter: &F,
        time: f64,
    ) -> Result<&Gaussian<N>, SmoothError> {
        self.check_usable()?;
        let step = self.next_step();
        if self.pending.is_some() {
            return Err(SmoothError::OutOfOrder {
                step,
                what: "predict called while a prediction is pending",
            });
        }
        let prev = self.latest_time();
        if !(time > prev && time.is_finite()) {
            return Err(self.fail(SmoothError::TimeNotIncreasing {
                step,
                prev,
                now: time,
            }));
        }
        match filter.predict_with_cross(self.latest(), time - prev) {
            Ok(tr) => Ok(self.pending.insert((time, tr)).1.predicted()),
            Err(source) => Err(self.fail(SmoothError::ForwardFailed { step, source })),
        }
    }

    /// Takes the pending prediction.
    fn take_pending(&mut self) -> Result<(f64, Transition<N>), SmoothError> {
        self.check_usable()?;
        self.pending.take().ok_or(SmoothError::OutOfOrder {
            step: self.next_step(),
            what: "no prediction to update (call predict first)",
        })
    }

    /// Updates the pending prediction with plot `z` through `filter` and records the step;
    /// returns the innovation.
    ///
    /// # Errors
    /// [`SmoothError::OutOfOrder`] without a pending prediction;
    /// [`SmoothError::ForwardFailed`] when the update fails (recorded).
    pub fn update<const M: usize, F: SmoothingFilter<N>, Me: MeasurementModel<N, M>>(
        &mut self,
        filter: &F,
        meas: &Me,
        z: &Vector<M>,
    ) -> Result<Innovation<M>, SmoothError> {
        let (time, tr) = self.take_pending()?;
        match filter.update(tr.predicted(), meas, z) {
            Ok((post, innov)) => {
                self.steps.push(RtsStep::new(time, tr, post));
                Ok(innov)
            }
            Err(source) => {
                let step = self.next_step();
                Err(self.fail(SmoothError::ForwardFailed { step, source }))
            }
        }
    }

    /// Records `posterior` as the filtered estimate of the pending prediction (an update
    /// computed elsewhere, from this prediction).
    ///
    /// # Errors
    /// [`SmoothError::OutOfOrder`] without a pending prediction.
    pub fn record_update(&mut self, posterior: Gaussian<N>) -> Result<(), SmoothError> {
        let (time, tr) = self.take_pending()?;
        self.steps.push(RtsStep::new(time, tr, posterior));
        Ok(())
    }

    /// Records the pending prediction as the estimate (no plot at this time).
    ///
    /// # Errors
    /// [`SmoothError::OutOfOrder`] without a pending prediction.
    pub fn coast(&mut self) -> Result<(), SmoothError> {
        let (time, tr) = self.take_pending()?;
        let pred = *tr.predicted();
        self.steps.push(RtsStep::new(time, tr, pred));
        Ok(())
    }

    /// [`RtsTrack::predict`] to `time`, then [`RtsTrack::update`] with `z`.
    ///
    /// # Errors
    /// As the two calls.
    pub fn step<const M: usize, F: SmoothingFilter<N>, Me: MeasurementModel<N, M>>(
        &mut self,
        filter: &F,
        time: f64,
        meas: &Me,
        z: &Vector<M>,
    ) -> Result<Innovation<M>, SmoothError> {
        self.predict(filter, time)?;
        self.update(filter, meas, z)
    }

    /// Fixed-interval smoothing of the whole track: one estimate per step held.
    ///
    /// # Errors
    /// A recorded failure ([`SmoothError::ForwardFailed`], [`SmoothError::TimeNotIncreasing`]);
    /// [`SmoothError::OutOfOrder`] while a prediction is pending (the last step is not
    /// complete); [`SmoothError::Backward`] for a numerical failure.
    pub fn smooth(&self) -> Result<Vec<Gaussian<N>>, SmoothError> {
        let mut out: Vec<Gaussian<N>> = self.steps.iter().map(|s| *s.filtered()).collect();
        self.smooth_into(&mut out)?;
        Ok(out)
    }

    /// [`RtsTrack::smooth`] into `out` (one entry per step held), allocating nothing.
    ///
    /// # Errors
    /// As [`RtsTrack::smooth`], and [`SmoothError::LengthMismatch`] for an `out` of
    /// another length.
    pub fn smooth_into(&self, out: &mut [Gaussian<N>]) -> Result<(), SmoothError> {
        self.check_usable()?;
        if self.pending.is_some() {
            return Err(SmoothError::OutOfOrder {
                step: self.next_step(),
                what: "smooth called while a prediction waits for its update",
            });
        }
        if out.len() != self.steps.len() {
            return Err(SmoothError::LengthMismatch {
                what: "smoothed output",
                expected: self.steps.len(),
                found: out.len(),
            });
        }
        // Recorded through predict/update the sequence is valid by construction; checked
        // anyway (cheap) so that the backward pass never sees a bad one.
        validate(&self.steps, self.base)?;
        backward(&self.steps, self.base, out)
    }

    /// Drops the `n` oldest steps (the fixed-lag window), keeping at least the latest.
    pub(crate) fn drop_oldest(&mut self, n: usize) {
        let n = n.min(self.steps.len().saturating_sub(1));
        self.steps.drain(..n);
        self.base += n;
    }
}

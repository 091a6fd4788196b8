//! Fixed-lag smoothing: the RTS backward pass over a sliding window of the latest steps.

use std::collections::VecDeque;

use argus_core_math::{Gaussian, Vector};
use argus_sensors::MeasurementModel;

use super::rts::backward;
use super::{RtsTrack, SmoothError, SmoothingFilter};
use crate::Innovation;

/// How far behind the latest step a fixed-lag estimate is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Lag {
    /// Step `j` is handed out once `L` steps follow it (`k − j = L`); `Steps(0)` is the filter.
    Steps(usize),
    /// Step `j` is handed out once the latest step is `T` seconds later (`tₖ − tⱼ ≥ T`);
    /// with irregular sampling several steps, or none, may come out per step.
    Seconds(f64),
}

/// A fixed-lag smoothed estimate: `x̂ⱼ|ₖ` of step `j` given the plots up to step `k`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lagged<const N: usize> {
    /// The step `j` (0 is the first estimate of the track).
    pub step: usize,
    /// Its time (s).
    pub time: f64,
    /// The latest step `k` whose plots it uses.
    pub given: usize,
    /// The smoothed estimate.
    pub estimate: Gaussian<N>,
}

/// A fixed-lag RTS smoother: a forward pass like [`RtsTrack`] (the same recording calls)
/// that holds only the window of steps not yet handed out and, after each step, hands out
/// the steps whose lag is reached ([`FixedLagSmoother::pop`]).
///
/// Each handed-out estimate is exactly the fixed-interval RTS smoother of the track so far
/// at that step (the backward pass started from the latest filtered estimate gives
/// `x̂ⱼ|ₖ` for every `j ≤ k`). Cost per step: one backward step per step in the window;
/// after the window has filled, nothing is allocated.
///
/// # References
/// Bar-Shalom, Li & Kirubarajan (2001) §8.6; Särkkä (2013) §8.2 (fixed-lag smoothing as
/// the RTS pass over the last `L` steps).
#[derive(Debug, Clone, PartialEq)]
pub struct FixedLagSmoother<const N: usize> {
    lag: Lag,
    track: RtsTrack<N>,
    /// The number of the oldest step not yet handed out.
    next_out: usize,
    buffer: Vec<Gaussian<N>>,
    ready: VecDeque<Lagged<N>>,
}

impl<const N: usize> FixedLagSmoother<N> {
    /// A fixed-lag smoother with `lag`, starting at `time` with `initial` (step 0).
    ///
    /// # Errors
    /// [`SmoothError::InvalidLag`] for a negative or non-finite lag in seconds;
    /// [`SmoothError::TimeNotIncreasing`] for a non-finite `time`.
    pub fn new(lag: Lag, time: f64, initial: Gaussian<N>) -> Result<Self, SmoothError> {
        let room = match lag {
            Lag::Steps(l) => l.saturating_add(2),
            Lag::Seconds(t) if t.is_finite() && t >= 0.0 => 2,
            Lag::Seconds(seconds) => return Err(SmoothError::InvalidLag { seconds }),
        };
        let mut s = Self {
            lag,
            track: RtsTrack::with_capacity(time, initial, room)?,
            next_out: 0,
            buffer: Vec::with_capacity(room),
            ready: VecDeque::with_capacity(room),
        };
        s.advance()?;
        Ok(s)
    }

    /// The lag.
    #[must_use]
    pub fn lag(&self) -> Lag {
        self.lag
    }

    /// The window (the forward steps held).
    #[must_use]
    pub fn window(&self) -> &RtsTrack<N> {
        &self.track
    }

    /// The oldest smoothed estimate handed out and not yet taken.
    pub fn pop(&mut self) -> Option<Lagged<N>> {
        self.ready.pop_front()
    }

    /// As [`RtsTrack::predict`].
    ///
    /// # Errors
    /// As [`RtsTrack::predict`].
    pub fn predict<F: SmoothingFilter<N>>(
        &mut self,
        filter: &F,
        time: f64,
    ) -> Result<&Gaussian<N>, SmoothError> {
        self.track.predict(filter, time)
    }

    /// As [`RtsTrack::update`]; then hands out the steps whose lag is reached.
    ///
    /// # Errors
    /// As [`RtsTrack::update`], and [`SmoothError::Backward`] for a numerical failure.
    pub fn update<const M: usize, F: SmoothingFilter<N>, Me: MeasurementModel<N, M>>(
        &mut self,
        filter: &F,
        meas: &Me,
        z: &Vector<M>,
    ) -> Result<Innovation<M>, SmoothError> {
        let innov = self.track.update(filter, meas, z)?;
        self.advance()?;
        Ok(innov)
    }

    /// As [`RtsTrack::record_update`]; then hands out the steps whose lag is reached.
    ///
    /// # Errors
    /// As [`RtsTrack::record_update`], and [`SmoothError::Backward`].
    pub fn record_update(&mut self, posterior: Gaussian<N>) -> Result<(), SmoothError> {
        self.track.record_update(posterior)?;
        self.advance()
    }

    /// As [`RtsTrack::coast`]; then hands out the steps whose lag is reached.
    ///
    /// # Errors
    /// As [`RtsTrack::coast`], and [`SmoothError::Backward`].
    pub fn coast(&mut self) -> Result<(), SmoothError> {
        self.track.coast()?;
        self.advance()
    }

    /// As [`RtsTrack::step`]; then hands out the steps whose lag is reached.
    ///
    /// # Errors
    /// As [`RtsTrack::step`], and [`SmoothError::Backward`].
    pub fn step<const M: usize, F: SmoothingFilter<N>, Me: MeasurementModel<N, M>>(
        &mut self,
        filter: &F,
        time: f64,
        meas: &Me,
        z: &Vector<M>,
    ) -> Result<Innovation<M>, SmoothError> {
        self.track.predict(filter, time)?;
        self.update(filter, meas, z)
    }

    /// The end of the track: hands out every step not yet handed out, smoothed over the
    /// whole window (as the fixed-interval smoother's last steps).
    ///
    /// # Errors
    /// A recorded failure, a pending prediction, or [`SmoothError::Backward`].
    pub fn flush(&mut self) -> Result<(), SmoothError> {
        let n = self.track.len();
        self.emit(n, true)
    }

    /// Hands out the steps whose lag is reached, then drops them from the window.
    fn advance(&mut self) -> Result<(), SmoothError> {
        let steps = self.track.steps();
        let newest = steps.len() - 1;
        let t_new = steps[newest].time();
        let base = self.track.first_step();
        // Steps are in time order: count the leading ones whose lag is reached.
        let due = steps
            .iter()
            .enumerate()
            .take_while(|(i, s)| match self.lag {
                Lag::Steps(l) => newest - i >= l,
                Lag::Seconds(t) => t_new - s.time() >= t,
            })
            .count();
        // Those before `next_out` were handed out already (the newest is kept as the anchor).
        let already = self.next_out - base;
        if due > already {
            self.emit(due, false)?;
        }
        Ok(())
    }

    /// Smooths the window and hands out its steps `next_out .. base + count`.
    fn emit(&mut self, count: usize, all: bool) -> Result<(), SmoothError> {
        let base = self.track.first_step();
        let already = self.next_out - base;
        let len = self.track.len();
        if count <= already {
            return Ok(());
        }
        if all {
            // `smooth_into` also refuses a recorded failure or a pending prediction.
            self.buffer.resize(len, *self.track.latest());
            self.track.smooth_into(&mut self.buffer)?;
        } else {
            self.buffer.resize(len, *self.track.latest());
            backward(self.track.steps(), base, &mut self.buffer)?;
        }
        let given = base + len - 1;
        for (i, (s, g)) in self
            .track
            .steps()
            .iter()
            .zip(&self.buffer)
            .enumerate()
            .take(count)
            .skip(already)
        {
            self.ready.push_back(Lagged {
                step: base + i,
                time: s.time(),
                given,
                estimate: *g,
            });
        }
        self.next_out = base + count;
        self.track.drop_oldest(count);
        Ok(())
    }
}

//! The record of an IMM forward pass for smoothing.

use argus_core_math::{Matrix, Vector};
use argus_filters::{SmoothingFilter, Transition};
use argus_sensors::MeasurementModel;

use super::ImmSmoothError;
use super::backward::{ImmSmoothed, PairWeights, imm_smooth};
use super::record::Record;
use super::step::{ImmStep, ImmTransition};
use crate::markov::log_sum_exp;
use crate::{Imm, ImmError, ImmEstimate, ImmUpdate, MarkovMatrix};

/// An IMM forward pass recorded for smoothing ([`crate::smooth`] for the equations).
///
/// [`ImmTrack::step`] runs one IMM cycle and records it; [`ImmTrack::push`] records a
/// posterior the caller computed with the same IMM (several plots of one scan, coasting
/// via [`crate::ImmPrediction::into_estimate`]). A failed step is recorded: every later
/// call and [`ImmTrack::smooth`] return [`ImmSmoothError::ForwardFailed`] naming it.
#[derive(Debug, Clone, PartialEq)]
pub struct ImmTrack<const N: usize, const R: usize> {
    markov: MarkovMatrix<R>,
    record: Record<ImmStep<N, R>>,
}

impl<const N: usize, const R: usize> ImmTrack<N, R> {
    /// A track of an IMM with transition matrix `markov`, starting at `time` with
    /// `initial` (step 0).
    ///
    /// # Errors
    /// [`argus_filters::SmoothError::TimeNotIncreasing`] for a non-finite `time`.
    pub fn new(
        markov: MarkovMatrix<R>,
        time: f64,
        initial: ImmEstimate<N, R>,
    ) -> Result<Self, ImmSmoothError> {
        Ok(Self {
            markov,
            record: Record::new(ImmStep {
                time,
                transition: None,
                filtered: initial,
            })?,
        })
    }

    /// Room for `additional` more steps (no reallocation while recording them).
    pub fn reserve(&mut self, additional: usize) {
        self.record.reserve(additional);
    }

    /// The transition matrix.
    #[must_use]
    pub fn markov(&self) -> &MarkovMatrix<R> {
        &self.markov
    }

    /// The recorded steps.
    #[must_use]
    pub fn steps(&self) -> &[ImmStep<N, R>] {
        self.record.steps()
    }

    /// The latest posterior.
    #[must_use]
    pub fn latest(&self) -> &ImmEstimate<N, R> {
        &self.record.latest().filtered
    }

    /// The failure recorded, if any.
    #[must_use]
    pub fn failure(&self) -> Option<&ImmSmoothError> {
        self.record.failure()
    }

    /// Records `estimate`, the posterior at `time` of `imm` run from the latest step:
    /// computes every latest filtered mode estimate's prediction through every model with
    /// its cross covariance (`R²` predictions), and `ln μ̄`.
    ///
    /// # Errors
    /// [`argus_filters::SmoothError::TimeNotIncreasing`] (inside
    /// [`ImmSmoothError::Sequence`]) or [`ImmSmoothError::ForwardFailed`] when a mode's
    /// prediction fails; both recorded.
    pub fn push<F: SmoothingFilter<N>>(
        &mut self,
        imm: &Imm<F, N, R>,
        time: f64,
        estimate: ImmEstimate<N, R>,
    ) -> Result<(), ImmSmoothError> {
        let (step, dt) = self.record.next_interval(time)?;
        self.append(imm, step, dt, time, estimate)
    }

    /// Appends `estimate` at `time` as step `step`, `dt` after the latest, with the
    /// transition from the latest posterior.
    fn append<F: SmoothingFilter<N>>(
        &mut self,
        imm: &Imm<F, N, R>,
        step: usize,
        dt: f64,
        time: f64,
        estimate: ImmEstimate<N, R>,
    ) -> Result<(), ImmSmoothError> {
        let transition = self.transition(imm, step, dt)?;
        self.record.push(ImmStep {
            time,
            transition: Some(transition),
            filtered: estimate,
        });
        Ok(())
    }

    fn transition<F: SmoothingFilter<N>>(
        &mut self,
        imm: &Imm<F, N, R>,
        step: usize,
        dt: f64,
    ) -> Result<ImmTransition<N, R>, ImmSmoothError> {
        let prev = *self.latest();
        let placeholder =
            Transition::new(prev.modes()[0], Matrix::<N, N>::zeros()).map_err(|source| {
                ImmSmoothError::Backward {
                    step,
                    mode: None,
                    source,
                }
            })?;
        let mut pairs = [[placeholder; R]; R];
        for (g, row) in prev.modes().iter().zip(pairs.iter_mut()) {
            for (mode, (f, out)) in imm.filters().iter().zip(row.iter_mut()).enumerate() {
                let tr = f
                    .predict_with_cross(g, dt)
                    .map_err(|source| ImmError::Filter { mode, source });
                *out = self.record.forward(step, tr)?;
            }
        }
        // ln μ̄ⱼ = ln Σᵢ πᵢⱼ μᵢ (log-sum-exp over the kept logarithms).
        let log_pi = self.markov.log_matrix();
        let log_mu = prev.log_mode_probabilities();
        let log_cbar = core::array::from_fn(|j| {
            let terms: [f64; R] = core::array::from_fn(|i| log_pi[(i, j)] + log_mu[i]);
            log_sum_exp(&terms)
        });
        Ok(ImmTransition { pairs, log_cbar })
    }

    /// One IMM cycle ([`Imm::step`]) from the latest step to `time` with plot `z`,
    /// recorded; returns the IMM's update.
    ///
    /// # Errors
    /// As [`ImmTrack::push`]; [`ImmSmoothError::ForwardFailed`] when the IMM step fails
    /// (recorded).
    pub fn step<const M: usize, F: SmoothingFilter<N>, Me: MeasurementModel<N, M>>(
        &mut self,
        imm: &Imm<F, N, R>,
        time: f64,
        meas: &Me,
        z: &Vector<M>,
    ) -> Result<ImmUpdate<N, R>, ImmSmoothError> {
        let (step, dt) = self.record.next_interval(time)?;
        let upd = imm.step(self.latest(), dt, meas, z);
        let upd = self.record.forward(step, upd)?;
        self.append(imm, step, dt, time, upd.estimate)?;
        Ok(upd)
    }

    /// Fixed-interval smoothing of the whole track: per step the smoothed mode estimates,
    /// mode probabilities and combined estimate.
    ///
    /// # Errors
    /// A recorded failure; [`ImmSmoothError::Backward`] for a numerical failure.
    pub fn smooth(&self) -> Result<Vec<ImmSmoothed<N, R>>, ImmSmoothError> {
        self.smooth_with(PairWeights::default())
    }

    /// [`ImmTrack::smooth`] with the chosen pair weights.
    ///
    /// # Errors
    /// As [`ImmTrack::smooth`].
    pub fn smooth_with(
        &self,
        weights: PairWeights,
    ) -> Result<Vec<ImmSmoothed<N, R>>, ImmSmoothError> {
        imm_smooth(&self.markov, weights, self.record.to_smooth()?)
    }

    /// [`ImmTrack::smooth`] over steps `first ..= last` alone (a fixed-lag smoother's
    /// window: the later plots ignored, `last`'s estimate the filter's).
    ///
    /// # Errors
    /// As [`ImmTrack::smooth`]; [`argus_filters::SmoothError::LengthMismatch`] for a
    /// window that is empty or reaches past the latest step.
    pub fn smooth_window(
        &self,
        first: usize,
        last: usize,
    ) -> Result<Vec<ImmSmoothed<N, R>>, ImmSmoothError> {
        imm_smooth(
            &self.markov,
            PairWeights::default(),
            self.record.window(first, last)?,
        )
    }
}

//! The record of an IMM forward pass for smoothing.

use argus_core_math::{Matrix, Vector};
use argus_filters::{SmoothError, SmoothingFilter, Transition};
use argus_sensors::MeasurementModel;

use super::ImmSmoothError;
use super::backward::{ImmSmoothed, PairWeights, imm_smooth};
use crate::markov::log_sum_exp;
use crate::{Imm, ImmError, ImmEstimate, ImmUpdate, MarkovMatrix};

/// What the backward pass needs of the transition into a step: every mode's filtered
/// estimate predicted through every model, with the cross covariance, and `ln μ̄ⱼ`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImmTransition<const N: usize, const R: usize> {
    /// `pairs[i][j]`: mode `i`'s filtered estimate through model `j`.
    pairs: [[Transition<N>; R]; R],
    log_cbar: [f64; R],
}

impl<const N: usize, const R: usize> ImmTransition<N, R> {
    /// The transitions `x̂ⁱʲₖ₊₁|ₖ, Pⁱʲₖ₊₁|ₖ, Cⁱʲₖ₊₁`: entry `[i][j]` is mode `i`'s filtered
    /// estimate predicted through model `j`.
    #[must_use]
    pub fn pairs(&self) -> &[[Transition<N>; R]; R] {
        &self.pairs
    }

    /// The predicted mode probabilities `ln μ̄ⱼₖ₊₁ = ln Σᵢ πᵢⱼ μᵢₖ`.
    #[must_use]
    pub fn log_predicted_probabilities(&self) -> &[f64; R] {
        &self.log_cbar
    }
}

/// One step of an IMM forward pass: time, transition from the step before (none for the
/// first), the IMM's posterior.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImmStep<const N: usize, const R: usize> {
    time: f64,
    transition: Option<ImmTransition<N, R>>,
    filtered: ImmEstimate<N, R>,
}

impl<const N: usize, const R: usize> ImmStep<N, R> {
    /// The time (s).
    #[must_use]
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The transition from the step before.
    #[must_use]
    pub fn transition(&self) -> Option<&ImmTransition<N, R>> {
        self.transition.as_ref()
    }

    /// The IMM's posterior at this step.
    #[must_use]
    pub fn filtered(&self) -> &ImmEstimate<N, R> {
        &self.filtered
    }
}

/// An IMM forward pass recorded for smoothing ([`crate::smooth`] for the equations).
///
/// [`ImmTrack::step`] runs one IMM cycle and records it; [`ImmTrack::push`] records a
/// posterior the caller computed with the same IMM (several plots of one scan, coasting
/// via [`crate::ImmPrediction::into_estimate`]). A failed step is recorded: every later
/// call and [`ImmTrack::smooth`] return [`ImmSmoothError::ForwardFailed`] naming it.
#[derive(Debug, Clone, PartialEq)]
pub struct ImmTrack<const N: usize, const R: usize> {
    markov: MarkovMatrix<R>,
    steps: Vec<ImmStep<N, R>>,
    failure: Option<ImmSmoothError>,
}

impl<const N: usize, const R: usize> ImmTrack<N, R> {
    /// A track of an IMM with transition matrix `markov`, starting at `time` with
    /// `initial` (step 0).
    ///
    /// # Errors
    /// [`SmoothError::TimeNotIncreasing`] for a non-finite `time`.
    pub fn new(
        markov: MarkovMatrix<R>,
        time: f64,
        initial: ImmEstimate<N, R>,
    ) -> Result<Self, ImmSmoothError> {
        if !time.is_finite() {
            return Err(SmoothError::TimeNotIncreasing {
                step: 0,
                prev: f64::NEG_INFINITY,
                now: time,
            }
            .into());
        }
        Ok(Self {
            markov,
            steps: vec![ImmStep {
                time,
                transition: None,
                filtered: initial,
            }],
            failure: None,
        })
    }

    /// Room for `additional` more steps (no reallocation while recording them).
    pub fn reserve(&mut self, additional: usize) {
        self.steps.reserve(additional);
    }

    /// The transition matrix.
    #[must_use]
    pub fn markov(&self) -> &MarkovMatrix<R> {
        &self.markov
    }

    /// The recorded steps.
    #[must_use]
    pub fn steps(&self) -> &[ImmStep<N, R>] {
        &self.steps
    }

    /// The latest posterior.
    #[must_use]
    pub fn latest(&self) -> &ImmEstimate<N, R> {
        // Never empty: `new` pushes the first step and nothing removes one.
        &self.steps[self.steps.len() - 1].filtered
    }

    /// The failure recorded, if any.
    #[must_use]
    pub fn failure(&self) -> Option<&ImmSmoothError> {
        self.failure.as_ref()
    }

    fn fail(&mut self, e: ImmSmoothError) -> ImmSmoothError {
        self.failure = Some(e.clone());
        e
    }

    /// Checks `time` against the latest step; returns `(step, dt)`.
    fn next_interval(&mut self, time: f64) -> Result<(usize, f64), ImmSmoothError> {
        if let Some(e) = &self.failure {
            return Err(e.clone());
        }
        let step = self.steps.len();
        let prev = self.steps[step - 1].time;
        if !(time > prev && time.is_finite()) {
            return Err(self.fail(
                SmoothError::TimeNotIncreasing {
                    step,
                    prev,
                    now: time,
                }
                .into(),
            ));
        }
        Ok((step, time - prev))
    }

    /// Records `estimate`, the posterior at `time` of `imm` run from the latest step:
    /// computes every latest filtered mode estimate's prediction through every model with
    /// its cross covariance (`R²` predictions), and `ln μ̄`.
    ///
    /// # Errors
    /// [`SmoothError::TimeNotIncreasing`] (inside [`ImmSmoothError::Sequence`]) or
    /// [`ImmSmoothError::ForwardFailed`] when a mode's prediction fails; both recorded.
    pub fn push<F: SmoothingFilter<N>>(
        &mut self,
        imm: &Imm<F, N, R>,
        time: f64,
        estimate: ImmEstimate<N, R>,
    ) -> Result<(), ImmSmoothError> {
        let (step, dt) = self.next_interval(time)?;
        let transition = self.transition(imm, step, dt)?;
        self.steps.push(ImmStep {
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
                match f.predict_with_cross(g, dt) {
                    Ok(tr) => *out = tr,
                    Err(source) => {
                        return Err(self.fail(ImmSmoothError::ForwardFailed {
                            step,
                            source: ImmError::Filter { mode, source },
                        }));
                    }
                }
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
        let (step, dt) = self.next_interval(time)?;
        let upd = match imm.step(self.latest(), dt, meas, z) {
            Ok(u) => u,
            Err(source) => return Err(self.fail(ImmSmoothError::ForwardFailed { step, source })),
        };
        let transition = self.transition(imm, step, dt)?;
        self.steps.push(ImmStep {
            time,
            transition: Some(transition),
            filtered: upd.estimate,
        });
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
        if let Some(e) = &self.failure {
            return Err(e.clone());
        }
        imm_smooth(&self.markov, weights, &self.steps)
    }
}

//! One step of an IMM forward pass as recorded for smoothing, and the transition into it:
//! what the record ([`super::ImmTrack`]) keeps and the backward pass
//! ([`super::imm_smooth`]) reads.

use argus_filters::Transition;

use super::record::RecordedStep;
use crate::ImmEstimate;

/// What the backward pass needs of the transition into a step: every mode's filtered
/// estimate predicted through every model, with the cross covariance, and `ln μ̄ⱼ`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImmTransition<const N: usize, const R: usize> {
    /// `pairs[i][j]`: mode `i`'s filtered estimate through model `j`.
    pub(super) pairs: [[Transition<N>; R]; R],
    pub(super) log_cbar: [f64; R],
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
    pub(super) time: f64,
    pub(super) transition: Option<ImmTransition<N, R>>,
    pub(super) filtered: ImmEstimate<N, R>,
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

impl<const N: usize, const R: usize> RecordedStep for ImmStep<N, R> {
    fn time(&self) -> f64 {
        self.time
    }

    fn has_transition(&self) -> bool {
        self.transition.is_some()
    }
}

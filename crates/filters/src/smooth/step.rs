//! One step of a forward pass as recorded for smoothing: what the record
//! ([`super::RtsTrack`]) keeps and the backward pass ([`super::rts_smooth`]) reads.

use argus_core_math::Gaussian;

use super::Transition;

/// One step of a forward pass: its time, the [`Transition`] from the step before (none
/// for the first) and the filtered estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RtsStep<const N: usize> {
    time: f64,
    transition: Option<Transition<N>>,
    filtered: Gaussian<N>,
}

impl<const N: usize> RtsStep<N> {
    /// The first step of a sequence (no transition into it).
    #[must_use]
    pub fn first(time: f64, filtered: Gaussian<N>) -> Self {
        Self {
            time,
            transition: None,
            filtered,
        }
    }

    /// A later step: the transition from the step before, and the filtered estimate.
    #[must_use]
    pub fn new(time: f64, transition: Transition<N>, filtered: Gaussian<N>) -> Self {
        Self {
            time,
            transition: Some(transition),
            filtered,
        }
    }

    /// The time (s).
    #[must_use]
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The transition from the step before (none for the first step).
    #[must_use]
    pub fn transition(&self) -> Option<&Transition<N>> {
        self.transition.as_ref()
    }

    /// The filtered estimate `x̂ₖ|ₖ, Pₖ|ₖ`.
    #[must_use]
    pub fn filtered(&self) -> &Gaussian<N> {
        &self.filtered
    }
}

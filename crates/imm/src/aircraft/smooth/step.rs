//! One step of an aircraft-IMM forward pass as recorded for smoothing, and the transition
//! into it: what the record ([`super::track`]) keeps and the backward pass
//! ([`super::backward`]) reads.

use super::pair::PairTransition;
use crate::aircraft::AircraftEstimate;
use crate::smooth::RecordedStep;

/// The transition into a step (module docs, forward record): every mode's filtered
/// estimate of the step before brought into every mode's state and predicted through its
/// model, with the cross covariance, and `ln μ̄ⱼ`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AircraftTransition<const C: usize, const R: usize> {
    /// `[i][j]`: CV mode `i` through CV model `j` (identity map).
    pub(super) cv_cv: [[PairTransition<4, 4>; C]; C],
    /// `[i]`: CV mode `i` augmented with `(ω̂ᵃ, σᵃ²)` through the CT model.
    pub(super) cv_ct: [PairTransition<4, 5>; C],
    /// `[j]`: the CT mode's kinematic marginal through CV model `j`.
    pub(super) ct_cv: [PairTransition<5, 4>; C],
    /// The CT mode through the CT model.
    pub(super) ct_ct: PairTransition<5, 5>,
    pub(super) log_cbar: [f64; R],
}

impl<const C: usize, const R: usize> AircraftTransition<C, R> {
    /// CV mode `i` through CV model `j`.
    #[must_use]
    pub fn cv_cv(&self, i: usize, j: usize) -> Option<&PairTransition<4, 4>> {
        self.cv_cv.get(i).and_then(|r| r.get(j))
    }

    /// CV mode `i`, augmented, through the CT model.
    #[must_use]
    pub fn cv_ct(&self, i: usize) -> Option<&PairTransition<4, 5>> {
        self.cv_ct.get(i)
    }

    /// The CT mode's marginal through CV model `j`.
    #[must_use]
    pub fn ct_cv(&self, j: usize) -> Option<&PairTransition<5, 4>> {
        self.ct_cv.get(j)
    }

    /// The CT mode through the CT model.
    #[must_use]
    pub fn ct_ct(&self) -> &PairTransition<5, 5> {
        &self.ct_ct
    }

    /// `ln μ̄ⱼ = ln Σᵢ πᵢⱼ μᵢ`.
    #[must_use]
    pub fn log_predicted_probabilities(&self) -> &[f64; R] {
        &self.log_cbar
    }
}

/// One step of an aircraft-IMM forward pass: time, the transition from the step before
/// (none for the first), the IMM's posterior.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AircraftStep<const C: usize, const R: usize> {
    pub(super) time: f64,
    pub(super) transition: Option<AircraftTransition<C, R>>,
    pub(super) filtered: AircraftEstimate<C, R>,
}

impl<const C: usize, const R: usize> AircraftStep<C, R> {
    /// The time (s).
    #[must_use]
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The transition from the step before.
    #[must_use]
    pub fn transition(&self) -> Option<&AircraftTransition<C, R>> {
        self.transition.as_ref()
    }

    /// The IMM's posterior at this step.
    #[must_use]
    pub fn filtered(&self) -> &AircraftEstimate<C, R> {
        &self.filtered
    }
}

impl<const C: usize, const R: usize> RecordedStep for AircraftStep<C, R> {
    fn time(&self) -> f64 {
        self.time
    }

    fn has_transition(&self) -> bool {
        self.transition.is_some()
    }
}

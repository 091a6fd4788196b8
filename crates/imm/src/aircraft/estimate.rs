//! The state of the aircraft IMM: `C` CV estimates on `[x, vx, y, vy]`, one CT estimate
//! on `[x, vx, y, vy, ω]`, and the `R = C + 1` mode probabilities; and the same state as
//! one cycle's prediction ([`AircraftPrediction`]).

use argus_core_math::Gaussian;

use super::mixing::kinematic_marginal;
use crate::{ImmError, log_probabilities};

/// Mode probabilities, kept as logarithms (a mode whose likelihood underflows keeps a
/// usable, tiny probability).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AircraftEstimate<const C: usize, const R: usize> {
    pub(super) cv: [Gaussian<4>; C],
    pub(super) ct: Gaussian<5>,
    pub(super) log_mu: [f64; R],
}

impl<const C: usize, const R: usize> AircraftEstimate<C, R> {
    /// Checked at compile time: `R` modes are the `C` CV modes and the CT mode.
    pub(super) const MODES: () = assert!(R == C + 1, "R must be C + 1 (C CV modes + 1 CT)");

    /// An estimate from the CV modes' Gaussians (modes `0..C`), the CT mode's (mode `C`)
    /// and the mode probabilities `μ` in that order.
    ///
    /// # Errors
    /// [`ImmError::InvalidProbabilities`] when `μ` has a negative or non-finite entry or
    /// does not sum to one (within 1e-9). Covariances are valid by construction
    /// ([`Gaussian::new`] rejects non-positive-definite ones).
    pub fn new(cv: [Gaussian<4>; C], ct: Gaussian<5>, mu: [f64; R]) -> Result<Self, ImmError> {
        let () = Self::MODES;
        let log_mu = log_probabilities(&mu, "initial mode probabilities")?;
        let ln_sum = mu.iter().sum::<f64>().ln();
        Ok(Self {
            cv,
            ct,
            log_mu: log_mu.map(|l| l - ln_sum),
        })
    }

    /// The estimate as its own prediction, with no mixing and no motion: for a plot at
    /// the same instant as the estimate (`dt = 0`), which [`super::AircraftImm::update`]
    /// then applies to the modes as they are (`μ̄ = μ`). The inverse of
    /// [`AircraftPrediction::into_estimate`].
    #[must_use]
    pub fn into_prediction(self) -> AircraftPrediction<C, R> {
        AircraftPrediction { predicted: self }
    }

    /// The CV modes' estimates `x̂ⱼ, Pⱼ` (`[x, vx, y, vy]`).
    #[must_use]
    pub fn cv_modes(&self) -> &[Gaussian<4>; C] {
        &self.cv
    }

    /// The CT mode's estimate (`[x, vx, y, vy, ω]`).
    #[must_use]
    pub fn ct_mode(&self) -> &Gaussian<5> {
        &self.ct
    }

    /// The mode probabilities `μⱼ` (CV modes, then CT).
    #[must_use]
    pub fn mode_probabilities(&self) -> [f64; R] {
        self.log_mu.map(f64::exp)
    }

    /// `ln μⱼ`.
    #[must_use]
    pub fn log_mode_probabilities(&self) -> &[f64; R] {
        &self.log_mu
    }

    /// The CT mode's turn rate and its standard deviation, rad/s (conditional on the CT
    /// mode).
    #[must_use]
    pub fn turn_rate(&self) -> (f64, f64) {
        (self.ct.mean()[4], self.ct.cov()[(4, 4)].sqrt())
    }

    /// The combined kinematic estimate `[x, vx, y, vy]`: the moment-matched mixture of the
    /// CV estimates and the CT estimate's kinematic marginal, `x = Σ μⱼ x̂ⱼ`,
    /// `P = Σ μⱼ [Pⱼ + (x̂ⱼ − x)(x̂ⱼ − x)ᵀ]`.
    ///
    /// # Errors
    /// [`ImmError::Math`] if the result is not finite (cannot happen for valid inputs).
    pub fn combined(&self) -> Result<Gaussian<4>, ImmError> {
        let mu = self.mode_probabilities();
        let parts = self.kinematic_parts()?;
        Ok(Gaussian::mixture(&mu, &parts)?)
    }

    /// Every mode on the kinematic part: the CV modes and the CT marginal.
    pub(super) fn kinematic_parts(&self) -> Result<[Gaussian<4>; R], ImmError> {
        let ct4 = kinematic_marginal(&self.ct)?;
        Ok(core::array::from_fn(
            |j| {
                if j < C { self.cv[j] } else { ct4 }
            },
        ))
    }
}

/// The mode-matched predictions of one cycle, before the plot is used.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AircraftPrediction<const C: usize, const R: usize> {
    pub(super) predicted: AircraftEstimate<C, R>,
}

impl<const C: usize, const R: usize> AircraftPrediction<C, R> {
    /// The predicted modes, with the predicted mode probabilities `μ̄ⱼ = Σᵢ πᵢⱼ μᵢ` in
    /// place of `μ` (so that [`AircraftEstimate::combined`] is the combined prediction).
    #[must_use]
    pub fn modes(&self) -> &AircraftEstimate<C, R> {
        &self.predicted
    }

    /// Coasts through a missing plot: the predictions become the estimate, `μ = μ̄`.
    #[must_use]
    pub fn into_estimate(self) -> AircraftEstimate<C, R> {
        self.predicted
    }
}

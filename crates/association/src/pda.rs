//! The probabilistic data association (PDA) filter.

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::MeasurementPrediction;
use argus_sensors::MeasurementModel;

use crate::associator::{Associator, Candidate, Outcome, for_each_gated, gaussian_checked};
use crate::error::{AssociationError, check_non_negative, check_prob_open_closed};
use crate::gate::Gate;

/// How the PDA filter models the number of clutter plots in the gate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ClutterModel {
    /// Poisson clutter of known spatial density `λ` (plots per unit measurement volume):
    /// the parametric PDA.
    Poisson {
        /// Clutter density `λ ≥ 0`.
        density: f64,
    },
    /// Diffuse prior on the clutter count: `λ` is replaced by `m/V` (plots gated over
    /// the gate volume), the non-parametric PDA.
    NonParametric,
}

/// The PDA filter (Bar-Shalom & Tse 1975): every gated plot `i` updates the track with
/// the weight
///
/// ```text
/// βᵢ = eᵢ / (b + Σⱼ eⱼ),  β₀ = b / (b + Σⱼ eⱼ),
/// eᵢ = N(νᵢ; 0, S),       b = λ (1 − P_D P_G) / P_D   (λ = m/V non-parametric)
/// ```
///
/// and `x = x⁻ + K ν̄`, `ν̄ = Σ βᵢ νᵢ`,
/// `P = β₀ P⁻ + (1 − β₀) Pᶜ + K (Σ βᵢ νᵢ νᵢᵀ − ν̄ ν̄ᵀ) Kᵀ` (the last term is the spread
/// of the innovations), `Pᶜ` the Kalman posterior covariance of the filter.
///
/// With `λ = 0`, `P_D = 1` and one plot in the gate it is the Kalman filter exactly.
///
/// # References
/// Bar-Shalom, Y. & Tse, E. (1975), "Tracking in a cluttered environment with
/// probabilistic data association", Automatica 11(5) (the update and the spread of
/// the innovations); seed 002 §2.3. The non-parametric variant replaces `λ` by `m/V`
/// (diffuse prior on the clutter count), as in the same line of work.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pda {
    gate: Gate,
    p_d: f64,
    clutter: ClutterModel,
}

impl Pda {
    /// The PDA filter with gate `gate`, detection probability `p_d` and clutter model
    /// `clutter`.
    ///
    /// # Errors
    /// [`AssociationError::InvalidParameter`] when `p_d ∉ (0, 1]` or the density is
    /// negative or non-finite.
    pub fn new(gate: Gate, p_d: f64, clutter: ClutterModel) -> Result<Self, AssociationError> {
        check_prob_open_closed(p_d, "detection probability")?;
        if let ClutterModel::Poisson { density } = clutter {
            check_non_negative(density, "clutter density")?;
        }
        Ok(Self { gate, p_d, clutter })
    }

    /// Detection probability.
    #[must_use]
    pub fn p_d(&self) -> f64 {
        self.p_d
    }

    /// The clutter model.
    #[must_use]
    pub fn clutter(&self) -> ClutterModel {
        self.clutter
    }
}

impl Associator for Pda {
    fn gate(&self) -> &Gate {
        &self.gate
    }

    /// `log_likelihood` is `ln[λ(1 − P_D P_G) + P_D Σ eᵢ]` (the parametric PDA's
    /// likelihood of the scan times `λ^{1−m}`-type factors common to all models;
    /// non-parametric: `λ = m/V` of this model).
    #[allow(non_snake_case)]
    fn associate<const N: usize, const M: usize, Me: MeasurementModel<N, M>>(
        &self,
        predicted: &Gaussian<N>,
        mp: &MeasurementPrediction<N, M>,
        meas: &Me,
        plots: &[Candidate<M>],
    ) -> Result<Outcome<N>, AssociationError> {
        // Unnormalised sums with εᵢ = exp(−dᵢ²/2) = eᵢ (2π)^{M/2} |S|^{1/2}: one pass.
        let mut sum_e = 0.0;
        let mut sum_v = Vector::<M>::zeros();
        let mut sum_vv = Matrix::<M, M>::zeros();
        let gated = for_each_gated(&self.gate, mp, meas, plots, |_, innov, _| {
            let e = (-0.5 * innov.nis).exp();
            sum_e += e;
            sum_v += innov.residual * e;
            sum_vv += innov.residual * innov.residual.transpose() * e;
            Ok(())
        })?;
        // ln of the Gaussian normaliser 1/((2π)^{M/2}|S|^{1/2}).
        let ln_norm = mp.log_likelihood_from_nis(0.0);
        let lambda = match self.clutter {
            ClutterModel::Poisson { density } => density,
            ClutterModel::NonParametric => {
                if gated == 0 {
                    0.0
                } else {
                    gated as f64 / self.gate.volume(mp)
                }
            }
        };
        let miss = 1.0 - self.p_d * self.gate.p_gate();
        // b in ε units.
        let b = lambda * miss / self.p_d * (-ln_norm).exp();
        let log_likelihood = (lambda * miss + self.p_d * sum_e * ln_norm.exp()).ln();
        if gated == 0 {
            return Ok(Outcome {
                posterior: *predicted,
                gated,
                used: None,
                miss_probability: 1.0,
                log_likelihood,
            });
        }
        let d = b + sum_e;
        let beta0 = b / d;
        let nu = sum_v / d;
        let spread = sum_vv / d - nu * nu.transpose();
        let K = mp.gain();
        let P_minus = predicted.cov();
        let P_c = mp.posterior_cov(P_minus);
        let cov = P_minus * beta0 + P_c * (1.0 - beta0) + K * spread * K.transpose();
        let mean = predicted.mean() + K * nu;
        Ok(Outcome {
            posterior: gaussian_checked(mean, &cov)?,
            gated,
            used: None,
            miss_probability: beta0,
            log_likelihood,
        })
    }
}

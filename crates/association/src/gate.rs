//! The validation gate on the normalised innovation squared.

use argus_core_math::{chi2_cdf, gate_threshold, unit_ball_volume};
use argus_filters::MeasurementPrediction;

use crate::error::AssociationError;

/// An ellipsoidal validation gate `νᵀ S⁻¹ ν ≤ γ` for `dim`-dimensional plots.
///
/// `γ` is the chi-square quantile of the gate probability `P_G` with `dim` degrees
/// of freedom; the gate volume is `V = c_n γ^{n/2} |S|^{1/2}`. The gate also keeps
/// `G_{n+2}(γ) = P(χ²_{n+2} ≤ γ)`, the second-moment factor of a truncated Gaussian:
/// `E[ννᵀ 1{νᵀS⁻¹ν ≤ γ}] = G_{n+2}(γ) S`.
///
/// # References
/// Seed 002 §2.1 (validation gate on the normalised distance); Bar-Shalom, Li &
/// Kirubarajan (2001), §6.4 (gate probability and volume).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gate {
    dim: usize,
    gamma: f64,
    p_gate: f64,
    second_moment: f64,
}

impl Gate {
    /// The gate of probability `p_gate` for `dim`-dimensional plots.
    ///
    /// # Errors
    /// [`AssociationError::InvalidParameter`] when `p_gate ∉ (0, 1)` or `dim = 0`.
    pub fn from_probability(p_gate: f64, dim: usize) -> Result<Self, AssociationError> {
        if !(p_gate.is_finite() && p_gate > 0.0 && p_gate < 1.0) {
            return Err(AssociationError::InvalidParameter {
                what: "gate probability",
                value: p_gate,
                reason: "must lie in (0, 1)",
            });
        }
        check_dim(dim)?;
        let gamma = gate_threshold(p_gate, dim)?;
        Self::build(dim, gamma)
    }

    /// The gate with threshold `γ` for `dim`-dimensional plots.
    ///
    /// # Errors
    /// [`AssociationError::InvalidParameter`] when `γ` is not finite and positive or
    /// `dim = 0`.
    pub fn from_threshold(gamma: f64, dim: usize) -> Result<Self, AssociationError> {
        if !(gamma.is_finite() && gamma > 0.0) {
            return Err(AssociationError::InvalidParameter {
                what: "gate threshold",
                value: gamma,
                reason: "must be finite and positive",
            });
        }
        check_dim(dim)?;
        Self::build(dim, gamma)
    }

    fn build(dim: usize, gamma: f64) -> Result<Self, AssociationError> {
        let n = dim as f64;
        let p_gate = chi2_cdf(gamma, n)?;
        let second_moment = chi2_cdf(gamma, n + 2.0)?;
        if p_gate >= 1.0 {
            return Err(AssociationError::InvalidParameter {
                what: "gate threshold",
                value: gamma,
                reason: "gate probability rounds to 1; use a smaller threshold",
            });
        }
        Ok(Self {
            dim,
            gamma,
            p_gate,
            second_moment,
        })
    }

    /// Measurement dimension.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Threshold `γ` on `νᵀS⁻¹ν`.
    #[must_use]
    pub fn gamma(&self) -> f64 {
        self.gamma
    }

    /// Gate probability `P_G = P(χ²_n ≤ γ)`.
    #[must_use]
    pub fn p_gate(&self) -> f64 {
        self.p_gate
    }

    /// `G_{n+2}(γ) = P(χ²_{n+2} ≤ γ)`, so that `E[ννᵀ; in gate] = G_{n+2}(γ) S`.
    #[must_use]
    pub fn second_moment_factor(&self) -> f64 {
        self.second_moment
    }

    /// Whether a plot at normalised distance `nis` lies in the gate.
    #[must_use]
    pub fn contains(&self, nis: f64) -> bool {
        nis <= self.gamma
    }

    /// Gate volume `c_n γ^{n/2} |S|^{1/2}` for the prediction `mp`.
    #[must_use]
    pub fn volume<const N: usize, const M: usize>(&self, mp: &MeasurementPrediction<N, M>) -> f64 {
        mp.gate_volume(self.gamma)
    }

    /// Gate volume from `|S|^{1/2}` directly.
    #[must_use]
    pub fn volume_from_sqrt_det(&self, sqrt_det_s: f64) -> f64 {
        unit_ball_volume(self.dim) * self.gamma.powf(self.dim as f64 / 2.0) * sqrt_det_s
    }

    /// Checks that this gate is for `M`-dimensional plots.
    ///
    /// # Errors
    /// [`AssociationError::DimensionMismatch`].
    pub fn check_dim<const M: usize>(&self) -> Result<(), AssociationError> {
        if self.dim == M {
            Ok(())
        } else {
            Err(AssociationError::DimensionMismatch {
                what: "gate dimension vs measurement dimension",
                expected: self.dim,
                got: M,
            })
        }
    }
}

fn check_dim(dim: usize) -> Result<(), AssociationError> {
    if dim == 0 {
        Err(AssociationError::InvalidParameter {
            what: "measurement dimension",
            value: 0.0,
            reason: "must be at least 1",
        })
    } else {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_dimensional_gate_closed_form() {
        // For n = 2, P(χ²₂ ≤ γ) = 1 − e^{−γ/2} and P(χ²₄ ≤ γ) = 1 − e^{−γ/2}(1 + γ/2).
        let g = Gate::from_threshold(16.0, 2).unwrap();
        assert!((g.p_gate() - (1.0 - (-8.0f64).exp())).abs() < 1e-12);
        assert!((g.second_moment_factor() - (1.0 - 9.0 * (-8.0f64).exp())).abs() < 1e-12);
        let g = Gate::from_probability(0.99, 2).unwrap();
        // γ = −2 ln(0.01) = 9.2103 (chi-square table, 2 dof, 0.99).
        assert!((g.gamma() - 9.210_340_371_976_18).abs() < 1e-8);
        // V = π γ |S|^{1/2}.
        assert!(
            (g.volume_from_sqrt_det(3.0) - std::f64::consts::PI * g.gamma() * 3.0).abs() < 1e-9
        );
    }

    #[test]
    fn rejects_bad_input() {
        assert!(Gate::from_probability(1.0, 2).is_err());
        assert!(Gate::from_probability(0.0, 2).is_err());
        assert!(Gate::from_probability(f64::NAN, 2).is_err());
        assert!(Gate::from_probability(0.99, 0).is_err());
        assert!(Gate::from_threshold(-1.0, 2).is_err());
        assert!(Gate::from_threshold(1e4, 2).is_err());
        let g = Gate::from_threshold(9.0, 2).unwrap();
        assert!(matches!(
            g.check_dim::<3>(),
            Err(AssociationError::DimensionMismatch {
                expected: 2,
                got: 3,
                ..
            })
        ));
    }
}

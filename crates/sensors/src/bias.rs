//! Polar sensor bias: offset and scale errors in range and azimuth (seed 004).

use argus_core_math::{Matrix, Vector};

use crate::angle::wrap_angle;
use crate::conversion::polar_jacobian;
use crate::error::{SensorError, finite};

/// The bias sensitivity `C = [[1, 0, r, 0], [0, 1, 0, θ]]` at `(r, θ)`, so that
/// `C β = [b_r + ε_r r, b_θ + ε_θ θ]` is the polar bias to first order.
///
/// # References
/// Seed 004 (Kim et al. 2011), eq (3).
#[must_use]
pub fn bias_sensitivity(range: f64, azimuth: f64) -> Matrix<2, 4> {
    Matrix::<2, 4>::new(1.0, 0.0, range, 0.0, 0.0, 1.0, 0.0, azimuth)
}

/// The Cartesian bias regressor `B C` at `(r, θ)` (seed 004 eq (2)).
#[must_use]
pub fn bias_regressor(range: f64, azimuth: f64) -> Matrix<2, 4> {
    polar_jacobian(range, azimuth) * bias_sensitivity(range, azimuth)
}

/// Offset and scale biases of a polar sensor, `β = [b_r, b_θ, ε_r, ε_θ]`:
///
/// `r = (1 + ε_r) r_true + b_r`, `θ = (1 + ε_θ) θ_true + b_θ`.
///
/// The scale bias in azimuth multiplies the azimuth value as given (Argus'
/// counter-clockwise-from-+x angle in `(−π, π]`), so it is discontinuous where
/// that angle wraps; the paper's model has the same property.
///
/// # References
/// Seed 004 (Kim et al. 2011), eqs (1)–(6).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PolarBias {
    beta: Vector<4>,
}

impl PolarBias {
    /// Biases from range offset `b_r` (m), azimuth offset `b_θ` (rad), range scale
    /// `ε_r` and azimuth scale `ε_θ` (dimensionless).
    ///
    /// # Errors
    /// [`SensorError::NonFinite`] for a non-finite value.
    pub fn new(
        range_offset: f64,
        azimuth_offset: f64,
        range_scale: f64,
        azimuth_scale: f64,
    ) -> Result<Self, SensorError> {
        Ok(Self {
            beta: Vector::<4>::new(
                finite(range_offset, "range offset bias")?,
                finite(azimuth_offset, "azimuth offset bias")?,
                finite(range_scale, "range scale bias")?,
                finite(azimuth_scale, "azimuth scale bias")?,
            ),
        })
    }

    /// Biases from the vector `β = [b_r, b_θ, ε_r, ε_θ]`.
    ///
    /// # Errors
    /// As [`PolarBias::new`].
    pub fn from_vector(beta: &Vector<4>) -> Result<Self, SensorError> {
        Self::new(beta[0], beta[1], beta[2], beta[3])
    }

    /// No bias.
    #[must_use]
    pub fn zero() -> Self {
        Self {
            beta: Vector::<4>::zeros(),
        }
    }

    /// The vector `β = [b_r, b_θ, ε_r, ε_θ]`.
    #[must_use]
    pub fn as_vector(&self) -> &Vector<4> {
        &self.beta
    }

    /// The biased plot of a true `(r, θ)` (seed 004 eq (1) without noise):
    /// `((1 + ε_r) r + b_r, wrap((1 + ε_θ) θ + b_θ))`.
    ///
    /// # Errors
    /// [`SensorError::NonFinite`] for a non-finite input.
    pub fn apply(&self, range: f64, azimuth: f64) -> Result<(f64, f64), SensorError> {
        let r = finite(range, "range")?;
        let t = finite(azimuth, "azimuth")?;
        let b = &self.beta;
        Ok(((1.0 + b[2]) * r + b[0], wrap_angle((1.0 + b[3]) * t + b[1])))
    }

    /// The linearised Cartesian bias `B C β` at `(r, θ)` (seed 004 eq (2)): the
    /// first-order shift of the converted plot caused by the bias.
    #[must_use]
    pub fn cartesian_offset(&self, range: f64, azimuth: f64) -> Vector<2> {
        bias_regressor(range, azimuth) * self.beta
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn apply_matches_eq_1() {
        // Seed 004 scenario biases: β = [20 m, 2 mrad, 3e−5, 2e−4] at r = 10 km, θ = 0.5 rad:
        // r' = 1.00003·10000 + 20 = 10020.3 m; θ' = 1.0002·0.5 + 0.002 = 0.5021 rad.
        let b = PolarBias::new(20.0, 2e-3, 3e-5, 2e-4).unwrap();
        let (r, t) = b.apply(10_000.0, 0.5).unwrap();
        assert!((r - 10_020.3).abs() < 1e-9);
        assert!((t - 0.5021).abs() < 1e-12);
        assert!(b.apply(f64::NAN, 0.0).is_err());
    }
}

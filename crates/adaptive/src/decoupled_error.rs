//! The error type of `argus-adaptive`.

use argus_core_math::MathError;
use argus_filters::FilterError;

/// What went wrong in an adaptive-filter constructor or step. A failed step
/// never modifies the estimate passed in (estimates are borrowed, never mutated).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum AdaptiveError {
    /// A filter-level failure (time step, non-PD `S`, non-finite value).
    #[error(transparent)]
    Filter(#[from] FilterError),
    /// A numerical check failed in the core algebra.
    #[error(transparent)]
    Math(#[from] MathError),
    /// A value that must be finite is NaN or infinite.
    #[error("{what} is not finite (got {value})")]
    NonFinite {
        /// The quantity.
        what: &'static str,
        /// Its (first offending) value.
        value: f64,
    },
    /// A parameter or input lies outside its domain.
    #[error("{what} = {value} is invalid: {reason}")]
    InvalidParameter {
        /// The parameter.
        what: &'static str,
        /// Its value.
        value: f64,
        /// Why it is rejected.
        reason: &'static str,
    },
    /// A covariance that must be positive definite is not.
    #[error("{what} is not positive definite (at {stage})")]
    NotPositiveDefinite {
        /// The covariance.
        what: &'static str,
        /// The step stage where it was found.
        stage: &'static str,
    },
    /// A frame matrix that must be a rotation is not orthonormal.
    #[error("{what} is not orthonormal (max |DᵀD − I| = {deviation:.3e})")]
    NotOrthonormal {
        /// The matrix.
        what: &'static str,
        /// The largest deviation of `DᵀD` from the identity.
        deviation: f64,
    },
}

/// Checks that `value` is finite.
pub(crate) fn finite(value: f64, what: &'static str) -> Result<f64, AdaptiveError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(AdaptiveError::NonFinite { what, value })
    }
}

/// Checks that `value` is finite and strictly positive.
pub(crate) fn positive(value: f64, what: &'static str) -> Result<f64, AdaptiveError> {
    finite(value, what)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(AdaptiveError::InvalidParameter {
            what,
            value,
            reason: "must be positive",
        })
    }
}

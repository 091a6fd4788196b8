//! The one error type of `argus-adaptive`: the adaptive-R decoupled filter
//! (seed 003) and the GLRT maneuver detection and input estimation (seed 001).

use argus_core_math::MathError;
use argus_filters::FilterError;
use argus_motion_models::MotionError;
use argus_sensors::SensorError;

/// What went wrong in a constructor or step of this crate: the decoupled and
/// adaptive-`R` filters, the GLRT detector, the MRAS estimator, the maneuver
/// filter and the experiments. A failed call never modifies the estimate, the
/// detector or the estimator passed in (they are borrowed, never mutated).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum AdaptiveError {
    /// A filter-level failure (time step, non-PD `S`, non-finite value).
    #[error(transparent)]
    Filter(#[from] FilterError),
    /// A numerical check failed in the core algebra.
    #[error(transparent)]
    Math(#[from] MathError),
    /// A motion model of an experiment could not be built.
    #[error(transparent)]
    Motion(#[from] MotionError),
    /// A sensor model could not be built or rejected a value.
    #[error(transparent)]
    Sensor(#[from] SensorError),
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
    /// The GLRT onset window is empty or inverted (`N > M`), or too long.
    #[error("onset window M = {max_age}, N = {min_age} is invalid: {reason}")]
    InvalidWindow {
        /// The longest onset age `M` considered.
        max_age: usize,
        /// The shortest onset age `N` considered.
        min_age: usize,
        /// Why it is rejected.
        reason: &'static str,
    },
    /// The filter has no measurement Jacobian for the GLRT signature and none was given.
    #[error("the measurement prediction has no Jacobian H, which the GLRT signature needs")]
    MissingJacobian,
}

/// Checks that `value` is finite.
///
/// # Errors
/// [`AdaptiveError::NonFinite`] naming `what`.
pub fn finite(value: f64, what: &'static str) -> Result<f64, AdaptiveError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(AdaptiveError::NonFinite { what, value })
    }
}

/// Checks that `value` is finite and strictly positive.
///
/// # Errors
/// [`AdaptiveError::NonFinite`] or [`AdaptiveError::InvalidParameter`] naming `what`.
pub fn positive(value: f64, what: &'static str) -> Result<f64, AdaptiveError> {
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

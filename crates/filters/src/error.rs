//! The error type of `argus-filters`.

use argus_core_math::MathError;

/// What went wrong in a filter step. The estimate passed in is never modified.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum FilterError {
    /// A numerical check failed (non-finite value, non-PD covariance, singular `S`).
    #[error(transparent)]
    Math(#[from] MathError),
    /// The time step is not finite and positive (time going backwards or standing still).
    #[error("time step dt = {dt} s is not finite and positive")]
    InvalidInterval {
        /// The step given.
        dt: f64,
    },
    /// A second-order filter needs Hessians the model does not provide.
    #[error("{what} provides no Hessians, which the second-order filter needs")]
    HessiansUnavailable {
        /// Which model.
        what: &'static str,
    },
    /// A filter parameter is outside its domain.
    #[error("parameter {what} = {value} is invalid: {reason}")]
    InvalidParameter {
        /// The parameter.
        what: &'static str,
        /// Its value.
        value: f64,
        /// Why it is rejected.
        reason: &'static str,
    },
}

/// Checks a time step: finite and strictly positive.
///
/// # Errors
/// [`FilterError::InvalidInterval`].
pub fn check_dt(dt: f64) -> Result<(), FilterError> {
    if dt > 0.0 && dt < f64::INFINITY {
        Ok(())
    } else {
        Err(FilterError::InvalidInterval { dt })
    }
}

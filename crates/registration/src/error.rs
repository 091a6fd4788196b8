//! The error type of `argus-registration`.

use argus_core_math::MathError;
use argus_sensors::SensorError;

/// What went wrong in a registration step. A failed step leaves every estimate it was
/// given unchanged.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum RegistrationError {
    /// A numerical check failed (non-finite value, covariance not positive definite).
    #[error(transparent)]
    Math(#[from] MathError),
    /// The local Kalman filter refused a step (non-positive-definite `S` or posterior).
    #[error(transparent)]
    Filter(#[from] argus_filters::FilterError),
    /// A sensor-model check failed (non-finite plot, range not positive).
    #[error(transparent)]
    Sensor(#[from] SensorError),
    /// A value that must be finite is NaN or infinite.
    #[error("{what} is not finite: {value}")]
    NonFinite {
        /// The quantity checked.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// A scalar parameter is outside its domain.
    #[error("{what} = {value} is invalid: {reason}")]
    InvalidParameter {
        /// The parameter.
        what: &'static str,
        /// Its value.
        value: f64,
        /// Why it is rejected.
        reason: &'static str,
    },
    /// Time went backwards for a track or a plot stream.
    #[error("{what}: time went backwards from {prev} s to {now} s")]
    TimeNotIncreasing {
        /// Which track or stream.
        what: &'static str,
        /// The time already reached.
        prev: f64,
        /// The time asked for.
        now: f64,
    },
    /// Two sizes that must agree do not.
    #[error("{what}: expected {expected}, got {got}")]
    DimensionMismatch {
        /// The quantity checked.
        what: &'static str,
        /// The size required.
        expected: usize,
        /// The size given.
        got: usize,
    },
    /// A sensor index is out of range.
    #[error("sensor index {sensor} is out of range (the system has {sensors} sensors)")]
    UnknownSensor {
        /// The index given.
        sensor: usize,
        /// How many sensors there are.
        sensors: usize,
    },
    /// A set that must not be empty is empty.
    #[error("{what} is empty")]
    Empty {
        /// The set.
        what: &'static str,
    },
    /// An update produced a covariance that is not positive definite (the estimate is kept).
    #[error("{what} lost positive definiteness in the update")]
    Degenerate {
        /// The quantity.
        what: &'static str,
    },
}

/// Checks a scalar is finite.
///
/// # Errors
/// [`RegistrationError::NonFinite`] naming `what`.
pub fn finite(what: &'static str, value: f64) -> Result<f64, RegistrationError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(RegistrationError::NonFinite { what, value })
    }
}

/// Checks a scalar is finite and strictly positive.
///
/// # Errors
/// [`RegistrationError::NonFinite`] or [`RegistrationError::InvalidParameter`] naming `what`.
pub fn positive(what: &'static str, value: f64) -> Result<f64, RegistrationError> {
    finite(what, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(RegistrationError::InvalidParameter {
            what,
            value,
            reason: "must be positive",
        })
    }
}

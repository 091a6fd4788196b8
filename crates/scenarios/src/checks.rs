//! Scalar checks of the experiments' configurations, with the errors of the library
//! crate whose types they configure (so that a bad field is named as before the move).

use argus_adaptive::AdaptiveError;
use argus_registration::RegistrationError;

/// `value` if finite ([`AdaptiveError::NonFinite`] naming `what` otherwise).
pub(crate) fn adaptive_finite(value: f64, what: &'static str) -> Result<f64, AdaptiveError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(AdaptiveError::NonFinite { what, value })
    }
}

/// `value` if finite and strictly positive.
pub(crate) fn adaptive_positive(value: f64, what: &'static str) -> Result<f64, AdaptiveError> {
    adaptive_finite(value, what)?;
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

/// `value` if finite ([`RegistrationError::NonFinite`] naming `what` otherwise).
pub(crate) fn registration_finite(
    what: &'static str,
    value: f64,
) -> Result<f64, RegistrationError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(RegistrationError::NonFinite { what, value })
    }
}

/// `value` if finite and strictly positive.
pub(crate) fn registration_positive(
    what: &'static str,
    value: f64,
) -> Result<f64, RegistrationError> {
    registration_finite(what, value)?;
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

//! The error type of `argus-motion-models`.

/// Why a motion model could not be built. Models validate their parameters once,
/// in the constructor; a built model's methods are infallible.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MotionError {
    /// A parameter that must be finite is NaN or infinite.
    #[error("{what} = {value} is not finite")]
    NonFinite {
        /// The parameter that was checked.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// A parameter that must be non-negative (a noise intensity) is negative.
    #[error("{what} = {value} is negative")]
    Negative {
        /// The parameter that was checked.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// A parameter that must be strictly positive (a step length, a count) is not.
    #[error("{what} = {value} must be strictly positive")]
    NotPositive {
        /// The parameter that was checked.
        what: &'static str,
        /// The value given.
        value: f64,
    },
}

/// Checks that `value` is finite and `>= 0`.
pub(crate) fn check_non_negative(what: &'static str, value: f64) -> Result<f64, MotionError> {
    if !value.is_finite() {
        return Err(MotionError::NonFinite { what, value });
    }
    if value < 0.0 {
        return Err(MotionError::Negative { what, value });
    }
    Ok(value)
}

/// Checks that `value` is finite and `> 0`.
pub(crate) fn check_positive(what: &'static str, value: f64) -> Result<f64, MotionError> {
    if !value.is_finite() {
        return Err(MotionError::NonFinite { what, value });
    }
    if value <= 0.0 {
        return Err(MotionError::NotPositive { what, value });
    }
    Ok(value)
}

/// Checks that `value` is finite (any sign).
pub(crate) fn check_finite(what: &'static str, value: f64) -> Result<f64, MotionError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(MotionError::NonFinite { what, value })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validation_rejects_bad_values() {
        assert_eq!(check_non_negative("s", 0.0), Ok(0.0));
        assert!(matches!(
            check_non_negative("s", -1.0),
            Err(MotionError::Negative { what: "s", .. })
        ));
        assert!(matches!(
            check_non_negative("s", f64::NAN),
            Err(MotionError::NonFinite { .. })
        ));
        assert!(matches!(
            check_positive("h", 0.0),
            Err(MotionError::NotPositive { .. })
        ));
        assert!(matches!(
            check_finite("w", f64::INFINITY),
            Err(MotionError::NonFinite { .. })
        ));
    }
}

//! The error type of `argus-sensors`.

use argus_core_math::MathError;

/// What went wrong when building a sensor model or converting a plot. Every
/// variant names the offending quantity and carries the value given.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SensorError {
    /// A value that must be finite is NaN or infinite.
    #[error("{what} = {value} is not finite")]
    NonFinite {
        /// The quantity that was checked.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// A value that must be `≥ 0` (a noise standard deviation) is negative.
    #[error("{what} = {value} is negative")]
    Negative {
        /// The quantity that was checked.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// A value that must be `> 0` (a range, a beamwidth, an SNR) is not.
    #[error("{what} = {value} is not strictly positive")]
    NotPositive {
        /// The quantity that was checked.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// A state index given for a position component is not below the state dimension.
    #[error("position index {index} is out of range for a state of dimension {dim}")]
    IndexOutOfRange {
        /// The index given.
        index: usize,
        /// The state dimension `N`.
        dim: usize,
    },
    /// Two position components were given the same state index.
    #[error("position index {index} is used for more than one component")]
    DuplicateIndex {
        /// The repeated index.
        index: usize,
    },
    /// A covariance (or another matrix) failed a numerical check.
    #[error(transparent)]
    Math(#[from] MathError),
}

/// `Ok(value)` when `value` is finite.
pub(crate) fn finite(value: f64, what: &'static str) -> Result<f64, SensorError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(SensorError::NonFinite { what, value })
    }
}

/// `Ok(value)` when `value` is finite and `≥ 0`.
pub(crate) fn non_negative(value: f64, what: &'static str) -> Result<f64, SensorError> {
    finite(value, what)?;
    if value >= 0.0 {
        Ok(value)
    } else {
        Err(SensorError::Negative { what, value })
    }
}

/// `Ok(value)` when `value` is finite and `> 0`.
pub(crate) fn positive(value: f64, what: &'static str) -> Result<f64, SensorError> {
    finite(value, what)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(SensorError::NotPositive { what, value })
    }
}

/// Checks that every index is `< n` and that no index repeats.
pub(crate) fn check_indices<const K: usize>(
    indices: [usize; K],
    n: usize,
) -> Result<[usize; K], SensorError> {
    for (k, &index) in indices.iter().enumerate() {
        if index >= n {
            return Err(SensorError::IndexOutOfRange { index, dim: n });
        }
        if indices.iter().take(k).any(|&other| other == index) {
            return Err(SensorError::DuplicateIndex { index });
        }
    }
    Ok(indices)
}

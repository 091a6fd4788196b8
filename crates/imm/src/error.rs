//! The error type of `argus-imm`.

use argus_core_math::MathError;
use argus_filters::FilterError;
use argus_sensors::SensorError;

/// What went wrong in an IMM or multi-IMM step. The estimate passed in is never modified.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ImmError {
    /// A mode-matched filter failed.
    #[error("mode {mode}: {source}")]
    Filter {
        /// The index of the mode (model) whose filter failed.
        mode: usize,
        /// The filter's error.
        source: FilterError,
    },
    /// A numerical check failed outside a mode filter (mixing, combination, conversion).
    #[error(transparent)]
    Math(#[from] MathError),
    /// The polar conversion rejected a plot (zero range, non-finite value).
    #[error(transparent)]
    Sensor(#[from] SensorError),
    /// A set that must not be empty is empty (no modes, no noise hypotheses).
    #[error("{what} is empty")]
    Empty {
        /// The set.
        what: &'static str,
    },
    /// An entry of a Markov transition matrix is negative, larger than one or not finite.
    #[error("Markov matrix entry ({row}, {col}) = {value} is not a probability")]
    InvalidTransition {
        /// The row (mode switched from).
        row: usize,
        /// The column (mode switched to).
        col: usize,
        /// The value given.
        value: f64,
    },
    /// A row of the Markov matrix does not sum to one.
    #[error("Markov matrix row {row} sums to {sum}, not 1")]
    RowSum {
        /// The row.
        row: usize,
        /// Its sum.
        sum: f64,
    },
    /// Probabilities (initial mode probabilities) that are negative, non-finite or do not sum to one.
    #[error("{what}: probabilities must be finite, non-negative and sum to 1 (sum = {sum})")]
    InvalidProbabilities {
        /// Which probabilities.
        what: &'static str,
        /// Their sum.
        sum: f64,
    },
    /// A parameter is outside its domain.
    #[error("parameter {what} = {value} is invalid: {reason}")]
    InvalidParameter {
        /// The parameter.
        what: &'static str,
        /// Its value.
        value: f64,
        /// Why it is rejected.
        reason: &'static str,
    },
    /// Time went backwards or stood still (or the interval is not finite).
    #[error("time step dt = {dt} s is not finite and positive")]
    InvalidInterval {
        /// The step given.
        dt: f64,
    },
    /// Every mode (or noise hypothesis) gave a zero or non-finite likelihood for the plot.
    #[error("{what}: every hypothesis gave a zero or non-finite likelihood")]
    NoLikelihood {
        /// Which set of hypotheses.
        what: &'static str,
    },
}

/// Checks that `value` is finite and positive.
///
/// # Errors
/// [`ImmError::InvalidParameter`] naming `what`.
pub(crate) fn check_positive(what: &'static str, value: f64) -> Result<(), ImmError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(ImmError::InvalidParameter {
            what,
            value,
            reason: "must be finite and positive",
        })
    }
}

/// Checks a forgetting factor: in `(0, 1]`.
///
/// # Errors
/// [`ImmError::InvalidParameter`] naming the forgetting factor.
pub(crate) fn check_forgetting(value: f64) -> Result<(), ImmError> {
    if value.is_finite() && value > 0.0 && value <= 1.0 {
        Ok(())
    } else {
        Err(ImmError::InvalidParameter {
            what: "forgetting factor",
            value,
            reason: "must be in (0, 1]",
        })
    }
}

/// Checks an optional per-step clip: when given, in `(0, 1)`.
///
/// # Errors
/// [`ImmError::InvalidParameter`] naming `what`.
pub(crate) fn check_clip(what: &'static str, clip: Option<f64>) -> Result<(), ImmError> {
    match clip {
        Some(c) if !(c.is_finite() && c > 0.0 && c < 1.0) => Err(ImmError::InvalidParameter {
            what,
            value: c,
            reason: "must be in (0, 1)",
        }),
        _ => Ok(()),
    }
}

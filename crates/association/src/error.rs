//! The error type of `argus-association`.

use argus_core_math::MathError;
use argus_filters::FilterError;

/// What went wrong in an association step or a performance prediction. The estimate
/// passed in is never modified.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum AssociationError {
    /// The underlying filter failed (non-PD `S`, non-finite plot, bad `dt`).
    #[error(transparent)]
    Filter(#[from] FilterError),
    /// The IMM failed (mixing, prediction, mode probabilities).
    #[error(transparent)]
    Imm(#[from] argus_imm::ImmError),
    /// No IMM mode can explain the scan (every mode's likelihood is zero).
    #[error("no IMM mode can explain the scan (all mode likelihoods are zero)")]
    NoLikelihood,
    /// A numerical check failed.
    #[error(transparent)]
    Math(#[from] MathError),
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
    /// Two sizes that must agree do not (gate built for another measurement dimension).
    #[error("{what}: expected dimension {expected}, got {got}")]
    DimensionMismatch {
        /// What was checked.
        what: &'static str,
        /// The size required.
        expected: usize,
        /// The size given.
        got: usize,
    },
    /// An amplitude-based filter got a plot without an amplitude.
    #[error("plot {index} has no amplitude, which {filter} needs")]
    MissingAmplitude {
        /// Index of the plot in the slice given.
        index: usize,
        /// The filter that needs it.
        filter: &'static str,
    },
    /// A plot's amplitude is non-finite or below the detection threshold.
    #[error(
        "plot {index} has amplitude {value}, not a finite value at or above the threshold {threshold}"
    )]
    InvalidAmplitude {
        /// Index of the plot in the slice given.
        index: usize,
        /// The amplitude given.
        value: f64,
        /// The detection threshold.
        threshold: f64,
    },
}

/// Checks that `p` is a finite probability in `(0, 1]`.
pub(crate) fn check_prob_open_closed(p: f64, what: &'static str) -> Result<(), AssociationError> {
    if p.is_finite() && p > 0.0 && p <= 1.0 {
        Ok(())
    } else {
        Err(AssociationError::InvalidParameter {
            what,
            value: p,
            reason: "must be a probability in (0, 1]",
        })
    }
}

/// Checks that `x` is finite and `≥ 0`.
pub(crate) fn check_non_negative(x: f64, what: &'static str) -> Result<(), AssociationError> {
    if x.is_finite() && x >= 0.0 {
        Ok(())
    } else {
        Err(AssociationError::InvalidParameter {
            what,
            value: x,
            reason: "must be finite and non-negative",
        })
    }
}

//! The error type of `argus-core-math`.

/// What went wrong in a core-math operation. Every variant names the offending
/// quantity so the message can be traced back to user input.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MathError {
    /// A value that must be finite is NaN or infinite.
    #[error("{what} contains a non-finite value (NaN or infinity)")]
    NonFinite {
        /// The quantity that was checked.
        what: &'static str,
    },
    /// A matrix that must be symmetric is not (within a relative tolerance).
    #[error("{what} is not symmetric (largest relative asymmetry {asymmetry:.3e})")]
    NotSymmetric {
        /// The quantity that was checked.
        what: &'static str,
        /// `max |A - Aᵀ| / max |A|`.
        asymmetry: f64,
    },
    /// A matrix that must be positive definite is not (its Cholesky factorisation failed).
    #[error("{what} is not positive definite")]
    NotPositiveDefinite {
        /// The quantity that was checked.
        what: &'static str,
    },
    /// Two run-time sizes that must agree do not.
    #[error("{what}: expected dimension {expected}, got {got}")]
    DimensionMismatch {
        /// The quantity that was checked.
        what: &'static str,
        /// The size required.
        expected: usize,
        /// The size given.
        got: usize,
    },
    /// A scalar argument lies outside its domain.
    #[error("{what} = {value} is outside its domain {domain}")]
    OutOfDomain {
        /// The argument.
        what: &'static str,
        /// The value given.
        value: f64,
        /// The allowed domain, in words.
        domain: &'static str,
    },
}

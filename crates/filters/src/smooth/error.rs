//! The error type of the smoothers.

use argus_core_math::MathError;

use crate::FilterError;

/// What went wrong in recording a forward pass or in smoothing it. Every variant names
/// the step (`0` is the first estimate of the sequence); a sequence that fails is never
/// returned half-smoothed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SmoothError {
    /// There is nothing to smooth.
    #[error("the sequence to smooth is empty")]
    Empty,
    /// Two sequences that must have one entry per step do not.
    #[error("{what}: expected {expected} entries (one per step), got {found}")]
    LengthMismatch {
        /// Which sequence.
        what: &'static str,
        /// The number of steps.
        expected: usize,
        /// The length given.
        found: usize,
    },
    /// The time of a step is not after the time of the one before (or not finite).
    #[error("step {step}: time {now} s does not follow the previous step's {prev} s")]
    TimeNotIncreasing {
        /// The step.
        step: usize,
        /// The previous step's time.
        prev: f64,
        /// This step's time.
        now: f64,
    },
    /// A step after the first carries no transition (predicted moments and cross
    /// covariance) from the step before.
    #[error("step {step} has no transition from step {prev}", prev = step.saturating_sub(1))]
    MissingTransition {
        /// The step.
        step: usize,
    },
    /// The forward filter failed at this step: the track cannot be smoothed past it
    /// (the steps before it can be, explicitly, as a shorter sequence).
    #[error("the forward pass failed at step {step}: {source}")]
    ForwardFailed {
        /// The step.
        step: usize,
        /// The filter's error.
        source: FilterError,
    },
    /// A recording call out of order: an update without a prediction, or a prediction
    /// while one is pending.
    #[error("step {step}: {what}")]
    OutOfOrder {
        /// The step.
        step: usize,
        /// What was called out of order.
        what: &'static str,
    },
    /// The backward pass failed numerically at this step (a predicted covariance that
    /// cannot be factored, a smoothed covariance that is not positive definite, a
    /// non-finite cross covariance).
    #[error("backward pass at step {step}: {source}")]
    Backward {
        /// The step.
        step: usize,
        /// The numerical failure.
        source: MathError,
    },
    /// A fixed lag that is not a finite, non-negative number of seconds.
    #[error("fixed lag of {seconds} s is not finite and non-negative")]
    InvalidLag {
        /// The lag given.
        seconds: f64,
    },
}

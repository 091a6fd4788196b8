//! The error type of the IMM smoother.

use argus_core_math::MathError;
use argus_filters::SmoothError;

use crate::ImmError;

/// What went wrong in recording an IMM forward pass or in smoothing it; every variant
/// names the step (0 is the first estimate). A track is smoothed whole or not at all.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ImmSmoothError {
    /// A bad sequence or call order (empty, time not increasing, a missing transition, an
    /// output of the wrong length, an update without a prediction).
    #[error(transparent)]
    Sequence(#[from] SmoothError),
    /// The forward IMM failed at this step: the track cannot be smoothed past it.
    #[error("the IMM forward pass failed at step {step}: {source}")]
    ForwardFailed {
        /// The step.
        step: usize,
        /// The IMM's error.
        source: ImmError,
    },
    /// The backward pass failed numerically at this step, in this mode (or in the
    /// combination, `mode = None`).
    #[error("IMM backward pass at step {step}{}: {source}", mode.map_or(String::new(), |m| format!(", mode {m}")))]
    Backward {
        /// The step.
        step: usize,
        /// The mode.
        mode: Option<usize>,
        /// The numerical failure.
        source: MathError,
    },
}

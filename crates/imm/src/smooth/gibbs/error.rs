//! The error type of the Gibbs smoother.

use argus_core_math::MathError;

/// What went wrong in setting up or running the Gibbs smoother; every variant about the
/// data names the step (0 is the start, `k ≥ 1` the plot at `times[k]`). Nothing panics: a
/// problem is smoothed whole or not at all.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum GibbsError {
    /// Two lengths that must agree do not (plots against times, a mode sequence against
    /// the steps), or a list that must not be empty is.
    #[error("{what}: expected length {expected}, got {got}")]
    LengthMismatch {
        /// The quantity checked.
        what: &'static str,
        /// The length required.
        expected: usize,
        /// The length given.
        got: usize,
    },
    /// Time does not increase at this step.
    #[error("time does not increase at step {step}: {prev} then {now}")]
    TimeNotIncreasing {
        /// The step.
        step: usize,
        /// The time of the step before.
        prev: f64,
        /// This step's time.
        now: f64,
    },
    /// A value of this step (a time, a plot, a model matrix) is NaN or infinite.
    #[error("step {step}: {what} is not finite")]
    NonFinite {
        /// The step.
        step: usize,
        /// The quantity.
        what: &'static str,
    },
    /// A covariance of this step that must be positive definite is not (the measurement
    /// noise `R`, or an innovation or predicted covariance met while sampling).
    #[error("step {step}: {what} is not positive definite")]
    NotPositiveDefinite {
        /// The step.
        step: usize,
        /// The quantity.
        what: &'static str,
    },
    /// The prior of the first mode is not a probability vector.
    #[error("the mode prior μ₀ is not a probability vector (entries ≥ 0 summing to 1)")]
    InvalidPrior,
    /// A configuration value outside its domain.
    #[error("Gibbs configuration: {what} = {value} is outside {domain}")]
    InvalidConfig {
        /// The setting.
        what: &'static str,
        /// The value given.
        value: usize,
        /// The allowed domain, in words.
        domain: &'static str,
    },
    /// A start mode sequence with a mode out of range or a transition of zero prior
    /// probability at this step.
    #[error(
        "start mode sequence: step {step} has mode {mode}, out of range or of zero prior probability after the step before"
    )]
    InvalidSequence {
        /// The step.
        step: usize,
        /// The mode given there.
        mode: usize,
    },
    /// Sampling failed numerically at this step (no block path of positive finite weight,
    /// a singular backward information step).
    #[error("Gibbs sweep failed at step {step}: {what}")]
    StepFailed {
        /// The step.
        step: usize,
        /// What failed.
        what: &'static str,
    },
    /// The averaged moments of this step do not form a Gaussian (no recorded sweep, or a
    /// covariance that is not positive definite).
    #[error("Gibbs estimate at step {step}: {source}")]
    Estimate {
        /// The step.
        step: usize,
        /// The failure.
        source: MathError,
    },
}

//! The error type of `argus-sim`.

/// What went wrong while building a scenario, generating plots or reducing
/// Monte Carlo results. Every variant names the offending quantity.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SimError {
    /// A parameter is outside its domain (non-finite, negative variance, probability ∉ [0, 1] …).
    #[error("{what} = {value} is invalid: {reason}")]
    InvalidParameter {
        /// The parameter.
        what: &'static str,
        /// Its value.
        value: f64,
        /// Why it is rejected.
        reason: &'static str,
    },
    /// A time lies outside a trajectory's span.
    #[error("time {t} s is outside the trajectory span [{start}, {end}] s")]
    TimeOutOfSpan {
        /// The time asked for.
        t: f64,
        /// Start of the span.
        start: f64,
        /// End of the span.
        end: f64,
    },
    /// Monte Carlo runs to be reduced together do not share one time grid.
    #[error("run {run} has {got} time steps where run {first} has {expected}")]
    RaggedRuns {
        /// Index (in the slice given) of the first run.
        first: usize,
        /// Index of the run that differs.
        run: usize,
        /// Steps in the first run.
        expected: usize,
        /// Steps in the differing run.
        got: usize,
    },
    /// Nothing to reduce: no run, or no run that kept its track.
    #[error("no {what} to compute metrics from")]
    Empty {
        /// What was missing.
        what: &'static str,
    },
    /// A run range is empty or reversed.
    #[error("run range {start}..{end} is empty")]
    EmptyRunRange {
        /// First run index.
        start: u64,
        /// One past the last run index.
        end: u64,
    },
    /// A sensor model or a plot was rejected by `argus-sensors` (a non-finite value).
    #[error(transparent)]
    Sensor(#[from] argus_sensors::SensorError),
    /// A core-math operation failed (chi-square quantile domain …).
    #[error(transparent)]
    Math(#[from] argus_core_math::MathError),
}

/// Checks that `value` is finite.
pub(crate) fn finite(what: &'static str, value: f64) -> Result<f64, SimError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(SimError::InvalidParameter {
            what,
            value,
            reason: "must be finite",
        })
    }
}

/// Checks that `value` is finite and `>= 0`.
pub(crate) fn non_negative(what: &'static str, value: f64) -> Result<f64, SimError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(SimError::InvalidParameter {
            what,
            value,
            reason: "must be finite and non-negative",
        })
    }
}

/// Checks that `value` is finite and `> 0`.
pub(crate) fn positive(what: &'static str, value: f64) -> Result<f64, SimError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(SimError::InvalidParameter {
            what,
            value,
            reason: "must be finite and positive",
        })
    }
}

/// Checks that `value` is a probability in `[0, 1]`.
pub(crate) fn probability(what: &'static str, value: f64) -> Result<f64, SimError> {
    if (0.0..=1.0).contains(&value) {
        Ok(value)
    } else {
        Err(SimError::InvalidParameter {
            what,
            value,
            reason: "must be a probability in [0, 1]",
        })
    }
}

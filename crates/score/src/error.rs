//! The error type of `argus-score`.

use std::path::PathBuf;

/// What went wrong when reading or scoring tracks and truth.
///
/// Input errors name the file, the line (1-based, the header is line 1) and the field,
/// so that a user can fix the file from the message alone.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ScoreError {
    /// The file could not be opened or read.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// A required column is missing from the header.
    #[error("{file}:1: missing column '{column}'")]
    MissingColumn {
        /// The file (as given by the caller).
        file: String,
        /// The column's name.
        column: &'static str,
    },
    /// A field of a row is malformed or out of its domain.
    #[error("{file}:{line}: field '{field}': {message}")]
    Field {
        /// The file.
        file: String,
        /// The line (1-based).
        line: u64,
        /// The column's name.
        field: &'static str,
        /// What is wrong with it.
        message: String,
    },
    /// The file is not well-formed CSV (e.g. a row with the wrong number of fields).
    #[error("{file}:{line}: {message}")]
    Syntax {
        /// The file.
        file: String,
        /// The line (1-based; 1 when unknown).
        line: u64,
        /// The parser's message.
        message: String,
    },
    /// The truth file has no sample.
    #[error("{file}: no truth sample")]
    NoTruth {
        /// The file.
        file: String,
    },
    /// Tracks or truth built in code are not valid (the readers report these with a line).
    #[error("{what} '{name}': {reason}")]
    InvalidInput {
        /// Which kind of input (`truth path`, `track`).
        what: &'static str,
        /// The truth's or track's name.
        name: String,
        /// What is wrong.
        reason: &'static str,
    },
    /// A scoring parameter is out of its domain.
    #[error("scoring parameter {what} = {value}: {domain}")]
    Parameter {
        /// The parameter.
        what: &'static str,
        /// The value given.
        value: f64,
        /// The allowed domain.
        domain: &'static str,
    },
    /// The grid would be too long (more steps than `max`), almost surely a unit mistake.
    #[error("time grid of {steps} steps (span {span} s at step {step} s) exceeds {max}")]
    GridTooLong {
        /// Steps the grid would have.
        steps: f64,
        /// Time span of the truth (s).
        span: f64,
        /// The grid step (s).
        step: f64,
        /// The largest allowed number of steps.
        max: usize,
    },
    /// An error of the metric code in `argus-sim` (OSPA/GOSPA, track statistics).
    #[error(transparent)]
    Sim(#[from] argus_sim::SimError),
}

pub(crate) fn positive(what: &'static str, value: f64) -> Result<f64, ScoreError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(ScoreError::Parameter {
            what,
            value,
            domain: "must be finite and positive",
        })
    }
}

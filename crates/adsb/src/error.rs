//! The error type of `argus-adsb`.

use std::path::PathBuf;

/// Where in the input a record came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Location {
    /// A CSV line (1-based, the header is line 1).
    Line(u64),
    /// A JSON record (0-based index in the array, or line of a JSON Lines file).
    Record(usize),
}

impl std::fmt::Display for Location {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Line(n) => write!(f, "line {n}"),
            Self::Record(n) => write!(f, "record {n}"),
        }
    }
}

/// What went wrong when reading ADS-B state vectors.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum AdsbError {
    /// The file could not be opened or read.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// A required column is missing from the CSV header.
    #[error("CSV header: missing column '{column}'")]
    MissingColumn {
        /// The column's name.
        column: &'static str,
    },
    /// A field could not be read.
    #[error("{at}: field '{field}': {message}")]
    Field {
        /// The record or line.
        at: Location,
        /// The field's name.
        field: &'static str,
        /// What is wrong with it.
        message: String,
    },
    /// The input is not well-formed CSV or JSON.
    #[error("{at}: {message}")]
    Syntax {
        /// The record or line (the start of the input when unknown).
        at: Location,
        /// The parser's message.
        message: String,
    },
    /// A record's position is not a valid coordinate.
    #[error("record {index}: {source}")]
    Record {
        /// The record's index in the input.
        index: usize,
        /// What is wrong.
        source: argus_geo::GeoError,
    },
    /// A cleaning parameter is out of its domain.
    #[error("cleaning parameter {what} = {value}: {domain}")]
    Parameter {
        /// The parameter.
        what: &'static str,
        /// The value given.
        value: f64,
        /// The allowed domain.
        domain: &'static str,
    },
}

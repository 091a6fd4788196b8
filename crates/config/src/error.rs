//! The error type of the configuration: [`ConfigError`], and [`Location`], where a bad
//! value sits in an input file.

use std::path::{Path, PathBuf};

/// Where a bad value sits in an input file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The file.
    pub file: PathBuf,
    /// 1-based line number, when known.
    pub line: Option<u64>,
    /// The field (CSV column or TOML key), when known.
    pub field: Option<String>,
}

impl Location {
    /// The place `file:line`, field `field` (either may be unknown).
    #[must_use]
    pub fn new(file: &Path, line: Option<u64>, field: Option<&str>) -> Self {
        Self {
            file: file.to_path_buf(),
            line,
            field: field.map(str::to_owned),
        }
    }
}

impl std::fmt::Display for Location {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.file.display())?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
        }
        if let Some(field) = &self.field {
            write!(f, ": field '{field}'")?;
        }
        Ok(())
    }
}

/// What is wrong with a configuration file.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ConfigError {
    /// A value in the file is bad (or a key missing).
    #[error("{at}: {message}")]
    Input {
        /// Where.
        at: Location,
        /// What is wrong.
        message: String,
    },
    /// Reading the file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A motion model rejected a value.
    #[error("motion model: {0}")]
    Motion(#[from] argus_motion_models::MotionError),
}

impl ConfigError {
    /// An input error at `file:line`, field `field`.
    pub(crate) fn input(
        file: &Path,
        line: Option<u64>,
        field: Option<&str>,
        message: impl Into<String>,
    ) -> Self {
        Self::Input {
            at: Location::new(file, line, field),
            message: message.into(),
        }
    }
}

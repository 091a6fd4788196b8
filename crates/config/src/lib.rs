//! The `argus track` configuration file (TOML, `docs/FORMATS.md`) turned into a checked
//! specification: [`load`] reads the file once ([`schema`] keeps every value's line),
//! checks its `[[sensor]]` and `[estimator]` tables once with every default filled in
//! ([`Sensor`], [`Estimator`]), its optional `[reference]` point ([`Reference`], sensors
//! given by latitude and longitude around it) and, with a `[tracker]` table, maps it
//! onto the tracker's configuration ([`MultiTarget`], whose validation errors are mapped
//! back to the file's keys). The result is a [`Job`]: one estimator over a plot file, or
//! the multi-target tracker.
//!
//! Every bad value is a [`ConfigError::Input`] naming the file, the line and the key
//! ([`Location`]); nothing a user writes panics.

mod errors;
mod geo;
mod job;
mod schema;
mod spec;
#[cfg(test)]
mod tests;
mod tracker_config;

use std::path::{Path, PathBuf};

pub use crate::geo::{Reference, to_reference};
pub use crate::job::{Job, Loaded, load};
pub use crate::spec::{Estimator, ImmSpec, MAX_MODELS, MultiSpec, Sensor, turned};
pub use crate::tracker_config::{DEFAULT_MAX_EXACT_EVENTS, MultiTarget};

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
            at: Location {
                file: file.to_path_buf(),
                line,
                field: field.map(str::to_owned),
            },
            message: message.into(),
        }
    }
}

//! The error type of the `argus` command.

use std::path::PathBuf;

use argus_config::{ConfigError, Location};
use argus_io::IoError;
use argus_scenarios::{ParamProblem, ScenarioError};

/// What went wrong in a command. Printed once, without a backtrace; the process exits
/// with code 2.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CliError {
    /// A value in an input file is bad.
    #[error("{at}: {message}")]
    Input {
        /// Where.
        at: Location,
        /// What is wrong.
        message: String,
    },
    /// A command-line argument is bad.
    #[error("{0}")]
    Usage(String),
    /// Reading or writing a file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The simulation rejected a parameter.
    #[error("simulation: {0}")]
    Sim(#[from] argus_sim::SimError),
    /// A scenario failed (a bad `--set` value is printed the way the command spells it).
    #[error("{}", scenario_message(.0))]
    Scenario(ScenarioError),
    /// Scoring tracks against a truth failed (a malformed file names file:line:field).
    #[error("score: {0}")]
    Score(#[from] argus_score::ScoreError),
    /// A merged campaign is not whole (a shard or runs missing or given twice).
    #[error("{0}")]
    Merge(#[from] crate::merge_error::MergeError),
    /// A configuration error other than a bad value or an unreadable file, printed as
    /// `argus_config` prints it.
    #[error(transparent)]
    Config(ConfigError),
    /// An `argus track` file error (`argus_io`'s: a plot or capture that cannot be read,
    /// a record of an unknown radar, a track that cannot be smoothed, …), printed as
    /// `argus_io` prints it.
    #[error(transparent)]
    File(IoError),
    /// Drawing a figure failed.
    #[error("figure {file}: {message}")]
    Plot {
        /// The figure file.
        file: PathBuf,
        /// What went wrong.
        message: String,
    },
}

impl From<ScenarioError> for CliError {
    /// A record that does not parse is an input error at its file and line; every other
    /// scenario error is kept as it is.
    fn from(e: ScenarioError) -> Self {
        match e {
            ScenarioError::Record {
                file,
                line,
                message,
            } => Self::input(
                &file,
                Some(line),
                Some("record"),
                format!("not a record of this scenario: {message}"),
            ),
            e => Self::Scenario(e),
        }
    }
}

impl From<ConfigError> for CliError {
    /// Each configuration error as the variant it is printed by (the same text).
    fn from(e: ConfigError) -> Self {
        match e {
            ConfigError::Input { at, message } => Self::Input { at, message },
            ConfigError::Io { path, source } => Self::Io { path, source },
            e => Self::Config(e),
        }
    }
}

impl From<IoError> for CliError {
    /// A file error as the command's: a value at a file line and key as
    /// [`CliError::Input`] (the same text, for one match over every bad input), the
    /// configuration's own errors as [`From<ConfigError>`] maps them, every other error
    /// as it is ([`CliError::File`]).
    fn from(e: IoError) -> Self {
        match e {
            IoError::Input { at, message } => Self::Input { at, message },
            IoError::Io { path, source } => Self::Io { path, source },
            IoError::Config(e) => Self::from(e),
            e => Self::File(e),
        }
    }
}

/// A scenario error as the command prints it: parameter errors name the `--set` setting.
fn scenario_message(e: &ScenarioError) -> String {
    let ScenarioError::Param { key: k, problem } = e else {
        return e.to_string();
    };
    match problem {
        ParamProblem::Syntax => format!("--set {k}: expected key=value"),
        ParamProblem::Unknown { known } => {
            format!("--set {k}: unknown parameter (known: {})", known.join(", "))
        }
        ParamProblem::NotANumber { value, item } => {
            format!("--set {k}={value}: {item:?} is not a number")
        }
        ParamProblem::OutOfRange {
            value,
            item,
            min,
            max,
            help,
        } => format!("--set {k}={value}: {item} must lie in [{min}, {max}] ({help})"),
        ParamProblem::List { len } => {
            format!("--set {k}: takes one value here, got a list of {len}")
        }
        ParamProblem::Conflict { value, reason } => format!("--set {k}={value} {reason}"),
        ParamProblem::Rejected { reason } => format!("--set {k}: {reason}"),
        ParamProblem::Undeclared => format!("parameter {k} is not declared"),
        _ => e.to_string(),
    }
}

impl CliError {
    /// An input error at `file:line`, field `field`.
    pub(crate) fn input(
        file: &std::path::Path,
        line: Option<u64>,
        field: Option<&str>,
        message: impl Into<String>,
    ) -> Self {
        Self::Input {
            at: Location::new(file, line, field),
            message: message.into(),
        }
    }

    /// An I/O error on `path`.
    pub(crate) fn io(path: &std::path::Path, source: std::io::Error) -> Self {
        Self::Io {
            path: path.to_path_buf(),
            source,
        }
    }
}

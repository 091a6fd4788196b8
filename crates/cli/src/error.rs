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
    /// A filter step failed.
    #[error("filter: {0}")]
    Filter(#[from] argus_filters::FilterError),
    /// A measurement model rejected a value.
    #[error("sensor: {0}")]
    Sensor(#[from] argus_sensors::SensorError),
    /// A motion model rejected a value.
    #[error("motion model: {0}")]
    Motion(#[from] argus_motion_models::MotionError),
    /// A numerical check failed.
    #[error("math: {0}")]
    Math(#[from] argus_core_math::MathError),
    /// An IMM or multi-IMM rejected a value.
    #[error("imm: {0}")]
    Imm(#[from] argus_imm::ImmError),
    /// The multi-target tracker rejected a configuration or a plot.
    #[error("tracker: {0}")]
    Tracker(#[from] argus_tracker::TrackerError),
    /// A scenario failed (a bad `--set` value is printed the way the command spells it).
    #[error("{}", scenario_message(.0))]
    Scenario(ScenarioError),
    /// Scoring tracks against a truth failed (a malformed file names file:line:field).
    #[error("score: {0}")]
    Score(#[from] argus_score::ScoreError),
    /// A merged campaign is not whole (a shard or runs missing or given twice).
    #[error("{0}")]
    Merge(#[from] crate::merge_error::MergeError),
    /// Smoothing a track failed (`argus track --smooth`): nothing is written.
    #[error("smoothing track {track}: step {step} (t = {time} s): {message}")]
    Smooth {
        /// The track (1 for the single-target job).
        track: u64,
        /// The step (0 is the track's first estimate; rows of one time are one step).
        step: usize,
        /// The step's time (s).
        time: f64,
        /// What failed.
        message: String,
    },
    /// A packet capture that cannot be read at all (its header, its link type).
    #[error("{file}: {source}")]
    Capture {
        /// The capture.
        file: PathBuf,
        /// Why.
        source: argus_capture::CaptureError,
    },
    /// An ASTERIX plot of a radar (SAC/SIC) that the configuration does not have.
    #[error(
        "{file}: ASTERIX record {record}: I048/010 SAC {sac} SIC {sic} is no [[sensor]] of {config} (known SAC/SIC: {known})"
    )]
    UnknownSource {
        /// The capture or block file.
        file: PathBuf,
        /// 1-based number of the record among the file's decoded records.
        record: u64,
        /// System area code.
        sac: u8,
        /// System identification code.
        sic: u8,
        /// The configuration.
        config: PathBuf,
        /// The configuration's sensors as `SAC/SIC`.
        known: String,
    },
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
            ConfigError::Motion(e) => Self::Motion(e),
            // `ConfigError` is `#[non_exhaustive]`: a variant added later keeps its text.
            e => Self::Usage(e.to_string()),
        }
    }
}

impl From<IoError> for CliError {
    /// Each file error as the variant it is printed by (the same text).
    fn from(e: IoError) -> Self {
        match e {
            IoError::Input { at, message } => Self::Input { at, message },
            IoError::Io { path, source } => Self::Io { path, source },
            IoError::Capture { file, source } => Self::Capture { file, source },
            IoError::UnknownSource {
                file,
                record,
                sac,
                sic,
                config,
                known,
            } => Self::UnknownSource {
                file,
                record,
                sac,
                sic,
                config,
                known,
            },
            IoError::Encode(message) => Self::Usage(message),
            IoError::Score(e) => Self::Score(e),
            IoError::Config(e) => Self::from(e),
            IoError::Usage(message) => Self::Usage(message),
            IoError::Filter(e) => Self::Filter(e),
            IoError::Sensor(e) => Self::Sensor(e),
            IoError::Motion(e) => Self::Motion(e),
            IoError::Math(e) => Self::Math(e),
            IoError::Imm(e) => Self::Imm(e),
            IoError::Tracker(e) => Self::Tracker(e),
            IoError::Smooth {
                track,
                step,
                time,
                message,
            } => Self::Smooth {
                track,
                step,
                time,
                message,
            },
            // `IoError` is `#[non_exhaustive]`: a variant added later keeps its text.
            e => Self::Usage(e.to_string()),
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
            at: Location {
                file: file.to_path_buf(),
                line,
                field: field.map(str::to_owned),
            },
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

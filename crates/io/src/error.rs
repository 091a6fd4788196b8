//! The error type of the readers and writers: [`IoError`].

use std::path::{Path, PathBuf};

use argus_config::Location;

/// What went wrong reading or writing a file.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum IoError {
    /// A value in an input file is bad.
    #[error("{at}: {message}")]
    Input {
        /// Where.
        at: Location,
        /// What is wrong.
        message: String,
    },
    /// Reading or writing a file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A packet capture that cannot be read at all (its header, its link type), or a
    /// datagram a pcap file cannot hold.
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
    /// A plot or track the ASTERIX encoders cannot write (a value out of its item's
    /// range, a plot that is not 2-D polar, a track name that is not a number).
    #[error("{0}")]
    Encode(String),
    /// A tracks CSV that cannot be read (as `argus score` reads it).
    #[error("score: {0}")]
    Score(#[from] argus_score::ScoreError),
    /// The configuration cannot be read or is bad ([`argus_config::load`]), as it prints.
    #[error(transparent)]
    Config(#[from] argus_config::ConfigError),
    /// A request the job cannot do (an estimator not built for the plots' size).
    #[error("{0}")]
    Usage(String),
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
}

impl IoError {
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

    /// An I/O error on `path`.
    pub(crate) fn io(path: &Path, source: std::io::Error) -> Self {
        Self::Io {
            path: path.to_path_buf(),
            source,
        }
    }
}

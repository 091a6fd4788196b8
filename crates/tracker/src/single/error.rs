//! What can go wrong in a single-target run: each error names the tag of the plot it is
//! about (the caller's, e.g. the plot file's line) or the sensor whose configuration is
//! incomplete, and what is wrong.

use argus_filters::FilterError;
use argus_imm::ImmError;
use argus_motion_models::MotionError;
use argus_sensors::SensorError;

use crate::smooth::Failure;

/// The estimators that track one polar radar's plots (the multi-IMM, the aircraft IMM).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum OneRadar {
    /// Seed 000's multi-IMM (it estimates one polar radar's noise).
    MultiImm,
    /// The aircraft IMM (it tracks one 2-D radar's polar plots).
    Aircraft,
}

/// A single-target run that failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SingleError {
    /// A plot of a sensor that is not among the engine's sensors.
    #[error("plot {tag}: unknown sensor {sensor}")]
    UnknownSensor {
        /// The plot's tag.
        tag: u64,
        /// Its sensor.
        sensor: u32,
    },
    /// A sensor with polar or spherical plots but no range / azimuth σ.
    #[error("sensor {sensor} reports polar/spherical plots but has no range / azimuth sigma")]
    NoPolarSigma {
        /// The sensor.
        sensor: u32,
    },
    /// A sensor with spherical plots but no elevation σ.
    #[error("sensor {sensor} reports spherical plots but has no elevation sigma")]
    NoElevationSigma {
        /// The sensor.
        sensor: u32,
    },
    /// A sensor's σ that the radar model refuses (e.g. zero).
    #[error("sensor {sensor}: {message}")]
    SensorNoise {
        /// The sensor.
        sensor: u32,
        /// The model's error.
        message: String,
    },
    /// A plot of another dimension than the first plot's.
    #[error("plot {tag}: plot of another dimension than the first plot")]
    WrongDimension {
        /// The plot's tag.
        tag: u64,
    },
    /// An IMM estimator over 3-D plots (the IMMs are 2-D).
    #[error("the IMM estimators track 2-D plots ([x, vx, y, vy]); the plots are 3-D")]
    ImmNot2D,
    /// An IMM of a mode count that is not built (1 … [`super::MAX_MODELS`] are).
    #[error("{count} IMM models: at most {}", super::MAX_MODELS)]
    ModeCount {
        /// The number of models.
        count: usize,
    },
    /// A multi-IMM grid size that is not built.
    #[error("multi-IMM with n = {n} is not built")]
    MultiSize {
        /// Hypotheses per axis.
        n: usize,
    },
    /// Fewer than two plots.
    #[error("at least two plots are needed to start a track")]
    TooFewPlots,
    /// The two-point start failed at the second plot (e.g. the same time twice).
    #[error("plot {tag}: two-point initialisation: {source}")]
    Start {
        /// The second plot's tag.
        tag: u64,
        /// The initialisation's error.
        source: FilterError,
    },
    /// The aircraft IMM's two-point start failed at the second plot.
    #[error("plot {tag}: two-point initialisation: {source}")]
    AircraftStart {
        /// The second plot's tag.
        tag: u64,
        /// The start's error.
        source: ImmError,
    },
    /// A polar plot's unbiased conversion failed (e.g. a non-positive range).
    #[error("plot {tag}: {source}")]
    PolarConversion {
        /// The plot's tag.
        tag: u64,
        /// The conversion's error.
        source: SensorError,
    },
    /// A spherical plot's unbiased conversion failed.
    #[error("plot {tag}: {source}")]
    SphericalConversion {
        /// The plot's tag.
        tag: u64,
        /// The conversion's error.
        source: SensorError,
    },
    /// A plot the one-radar estimators cannot take: of another sensor than the first
    /// plot's.
    #[error("plot {tag}: plot of sensor {sensor} after sensor {first}")]
    OtherSensor {
        /// The plot's tag.
        tag: u64,
        /// The estimator.
        estimator: OneRadar,
        /// Its sensor.
        sensor: u32,
        /// The first plot's sensor.
        first: u32,
    },
    /// A plot the one-radar estimators cannot take: not a (range, azimuth) plot.
    #[error("plot {tag}: not a (range, azimuth) plot")]
    NotPolar {
        /// The plot's tag.
        tag: u64,
        /// The estimator.
        estimator: OneRadar,
    },
    /// A KF / EKF step failed at a plot.
    #[error("plot {tag}: filter update failed: {source}")]
    FilterStep {
        /// The plot's tag.
        tag: u64,
        /// The filter's error.
        source: FilterError,
    },
    /// An IMM step (or its combination) failed at a plot.
    #[error("plot {tag}: IMM update failed: {source}")]
    ImmStep {
        /// The plot's tag.
        tag: u64,
        /// The IMM's error.
        source: ImmError,
    },
    /// The track could not be smoothed (the step and its time are the failure's).
    #[error("smoothing: step {} (t = {} s): {}", .0.step(), .0.time(), .0.message())]
    Smoothing(Failure),
    /// A motion model refused its parameters (building the estimator).
    #[error(transparent)]
    Motion(#[from] MotionError),
    /// A measurement model refused its parameters (building the estimator or a
    /// measurement).
    #[error(transparent)]
    Sensor(#[from] SensorError),
    /// The IMM refused its parameters (building it, its start), or a combination outside
    /// a plot's step failed.
    #[error(transparent)]
    Imm(#[from] ImmError),
}

//! The error type of `argus-tracker`.

use argus_association::AssociationError;
use argus_filters::FilterError;
use argus_motion_models::MotionError;
use argus_sensors::SensorError;

use crate::SensorId;
use crate::field::ConfigField;

/// What went wrong. Input errors name the plot (its index in the slice given, its
/// time and sensor) or the configuration field; they are detected before any track
/// is touched, so a rejected call leaves the tracker exactly as it was.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum TrackerError {
    /// A configuration value is outside its domain.
    #[error("tracker config {field} = {value} is invalid: {reason}")]
    InvalidConfig {
        /// The field.
        field: ConfigField,
        /// Its value.
        value: f64,
        /// Why it is rejected.
        reason: &'static str,
    },
    /// A plot is earlier than the tracker's current time or than the plot before it.
    #[error("plot {index} at t = {time} s is earlier than t = {previous} s already processed")]
    TimeOrder {
        /// Index of the plot in the slice given.
        index: usize,
        /// Its time (s).
        time: f64,
        /// The time it should not precede (s).
        previous: f64,
    },
    /// A plot comes from a sensor the configuration does not list.
    #[error("plot {index} at t = {time} s comes from unknown sensor {sensor:?}")]
    UnknownSensor {
        /// Index of the plot in the slice given.
        index: usize,
        /// Its time (s).
        time: f64,
        /// The sensor named.
        sensor: SensorId,
    },
    /// A plot's time, position, covariance, range or azimuth is NaN or infinite.
    #[error("plot {index} from sensor {sensor:?} has a non-finite {what}")]
    NonFinite {
        /// Index of the plot in the slice given.
        index: usize,
        /// Its sensor.
        sensor: SensorId,
        /// Which field.
        what: &'static str,
    },
    /// A plot's covariance is not symmetric positive definite.
    #[error("plot {index} at t = {time} s from sensor {sensor:?}: bad covariance: {source}")]
    PlotCovariance {
        /// Index of the plot in the slice given.
        index: usize,
        /// Its time (s).
        time: f64,
        /// Its sensor.
        sensor: SensorId,
        /// What the check found.
        source: SensorError,
    },
    /// [`crate::Tracker::advance_to`] was given a NaN or infinite time.
    #[error("advance_to: time {time} is not finite")]
    NonFiniteTime {
        /// The time given.
        time: f64,
    },
    /// A polar plot's range is zero or negative.
    #[error("plot {index} at t = {time} s from sensor {sensor:?}: range {range} m is not positive")]
    NonPositiveRange {
        /// Index of the plot in the slice given.
        index: usize,
        /// Its time (s).
        time: f64,
        /// Its sensor.
        sensor: SensorId,
        /// The range (m).
        range: f64,
    },
    /// A polar plot comes from a sensor configured without polar noise.
    #[error("plot {index} at t = {time} s is polar but sensor {sensor:?} has no polar noise")]
    NoPolarNoise {
        /// Index of the plot in the slice given.
        index: usize,
        /// Its time (s).
        time: f64,
        /// Its sensor.
        sensor: SensorId,
    },
    /// A Cartesian plot given to a tracker whose estimator needs polar plots (the
    /// multi-IMM, the aircraft IMM).
    #[error(
        "plot {index} at t = {time} s from sensor {sensor:?} is Cartesian; the {estimator} needs polar plots"
    )]
    NotPolar {
        /// Index of the plot in the slice given.
        index: usize,
        /// Its time (s).
        time: f64,
        /// Its sensor.
        sensor: SensorId,
        /// The estimator that needs them (`"multi-IMM"`, `"aircraft IMM"`).
        estimator: &'static str,
    },
    /// A plot is 3-D (spherical or a 3-D position); the tracker takes 2-D plots.
    #[error(
        "plot {index} at t = {time} s from sensor {sensor:?} is 3-D; the tracker takes 2-D polar or Cartesian plots"
    )]
    NotPlanar {
        /// Index of the plot in the slice given.
        index: usize,
        /// Its time (s).
        time: f64,
        /// Its sensor.
        sensor: SensorId,
    },
    /// A polar plot could not be converted to a Cartesian position.
    #[error("plot {index} at t = {time} s from sensor {sensor:?}: conversion failed: {source}")]
    Conversion {
        /// Index of the plot in the slice given.
        index: usize,
        /// Its time (s).
        time: f64,
        /// Its sensor.
        sensor: SensorId,
        /// What the conversion found.
        source: SensorError,
    },
    /// The plots given to one scan do not share one time and one sensor.
    #[error("plot {index} does not share the scan's time {time} s and sensor {sensor:?}")]
    MixedScan {
        /// Index of the plot in the slice given.
        index: usize,
        /// The scan's time (s).
        time: f64,
        /// The scan's sensor.
        sensor: SensorId,
    },
    /// [`crate::Tracker::process_scan`] was given a rotating sensor's plots (they go
    /// through [`crate::Tracker::process`], by sectors), or a synchronous scan at a time
    /// a rotating sensor's sector ends before (call [`crate::Tracker::advance_to`] first).
    #[error("process_scan at t = {time} s for sensor {sensor:?}: {reason}")]
    RotatingScan {
        /// The scan's time (s).
        time: f64,
        /// The scan's sensor.
        sensor: SensorId,
        /// What to do instead.
        reason: &'static str,
    },
    /// A rotation given for a sensor after its first plot (or for a sensor the
    /// configuration does not list); see [`crate::Session`].
    #[error("rotation of sensor {sensor:?} refused: {reason}")]
    LateRotation {
        /// The sensor.
        sensor: SensorId,
        /// Why it is refused.
        reason: &'static str,
    },
    /// The motion model rejected its parameters.
    #[error(transparent)]
    Motion(#[from] MotionError),
    /// The IMM or multi-IMM rejected its parameters.
    #[error(transparent)]
    Imm(#[from] argus_imm::ImmError),
    /// The gate rejected its parameters.
    #[error(transparent)]
    Association(#[from] AssociationError),
    /// A filter step failed where no single track could absorb it.
    #[error(transparent)]
    Filter(#[from] FilterError),
}

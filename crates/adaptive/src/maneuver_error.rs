//! The error type of the maneuver detection and input estimation modules (seed 001).

use argus_core_math::MathError;
use argus_filters::FilterError;
use argus_motion_models::MotionError;
use argus_sensors::SensorError;

/// What went wrong in a GLRT, MRAS or adaptive-filter call. The detector, the
/// estimator and the estimate passed in are never modified by a failed call.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ManeuverError {
    /// The inner filter failed (bad time step, non-PD `S`, non-finite value).
    #[error(transparent)]
    Filter(#[from] FilterError),
    /// A numerical check failed on a quantity handed to the detector.
    #[error(transparent)]
    Math(#[from] MathError),
    /// A motion model of an experiment could not be built.
    #[error(transparent)]
    Motion(#[from] MotionError),
    /// A sensor model of an experiment could not be built.
    #[error(transparent)]
    Sensor(#[from] SensorError),
    /// A configuration parameter is outside its domain.
    #[error("parameter {what} = {value} is invalid: {reason}")]
    InvalidParameter {
        /// The parameter.
        what: &'static str,
        /// Its value.
        value: f64,
        /// Why it is rejected.
        reason: &'static str,
    },
    /// The onset window is empty or inverted (`N > M`), or too long.
    #[error("onset window M = {max_age}, N = {min_age} is invalid: {reason}")]
    InvalidWindow {
        /// The longest onset age `M` considered.
        max_age: usize,
        /// The shortest onset age `N` considered.
        min_age: usize,
        /// Why it is rejected.
        reason: &'static str,
    },
    /// The filter has no measurement Jacobian for the GLRT signature and none was given.
    #[error("the measurement prediction has no Jacobian H, which the GLRT signature needs")]
    MissingJacobian,
}

//! The pieces of a one-target scene seen by one polar radar that `cv-polar` and `gimpo`
//! share: the radar built from the scenario's noise and period parameters, and the
//! scene's one trajectory.

use argus_core_math::Vector;
use argus_sim::{Schedule, SensorId, SensorKind, SensorSpec, Trajectory, Truth};

use crate::error::ScenarioError;
use crate::params::Params;

/// Radar 1 at the origin, measuring range and azimuth with the noise σ of the parameters
/// `sigma_r` (m) and `sigma_az_deg` (deg), on the schedule `schedule(period)` of the
/// parameter `period` (s).
///
/// # Errors
/// A parameter that is not declared, or a value the sensor refuses.
pub(crate) fn polar_radar(
    p: &Params,
    schedule: impl FnOnce(f64) -> Schedule,
) -> Result<SensorSpec, ScenarioError> {
    Ok(SensorSpec::new(
        SensorId(1),
        Vector::<3>::zeros(),
        SensorKind::Polar {
            sigma_range: p.get("sigma_r")?,
            sigma_azimuth: p.get("sigma_az_deg")?.to_radians(),
        },
        schedule(p.get("period")?),
    )?)
}

/// The scene's first (and only) trajectory.
///
/// # Errors
/// [`ScenarioError::Degenerate`] of `scenario` for a scene without a target.
pub(crate) fn first_trajectory(
    truth: &Truth,
    scenario: &'static str,
) -> Result<Trajectory, ScenarioError> {
    truth
        .targets()
        .first()
        .map(|(_, t)| t.clone())
        .ok_or_else(|| ScenarioError::Degenerate {
            scenario,
            message: "no target".into(),
        })
}

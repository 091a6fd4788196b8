//! The registered scenarios. To add one: write `<name>.rs` implementing
//! [`Scenario`] and add one line to [`all`].

use crate::error::ScenarioError;
use crate::scenario::Scenario;
use crate::{
    bias_32, clutter, cv_polar, drag_bearing, gimpo, launch, maneuver_1d, rbs_landing,
    real_traffic, surveillance,
};

/// Every scenario, in listing order.
#[must_use]
pub fn all() -> Vec<Box<dyn Scenario>> {
    vec![
        Box::new(cv_polar::CvPolar),
        Box::new(gimpo::Gimpo),
        Box::new(rbs_landing::RbsLanding),
        Box::new(bias_32::Bias32),
        Box::new(clutter::Clutter),
        Box::new(launch::Launch),
        Box::new(maneuver_1d::Maneuver1d),
        Box::new(drag_bearing::DragBearing),
        Box::new(surveillance::Surveillance),
        Box::new(real_traffic::RealTraffic),
        // One line per scenario, e.g. `Box::new(gimpo::Gimpo),`
    ]
}

/// The scenario called `name`.
///
/// # Errors
/// [`ScenarioError::UnknownScenario`], with the known names.
pub fn find(name: &str) -> Result<Box<dyn Scenario>, ScenarioError> {
    let mut all = all();
    match all.iter().position(|s| s.name() == name) {
        Some(i) => Ok(all.swap_remove(i)),
        None => Err(ScenarioError::UnknownScenario {
            name: name.to_owned(),
            known: all.iter().map(|s| s.name()).collect(),
        }),
    }
}

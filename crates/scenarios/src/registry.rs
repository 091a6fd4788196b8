//! The registered scenarios. To add one: write `scenarios/<name>.rs` implementing
//! [`Scenario`](crate::scenario::Scenario) and add one line to [`all`].

mod bias_32;
mod clutter;
mod cv_polar;
mod drag_bearing;
mod gimpo;
mod launch;
mod maneuver_1d;
mod rbs_landing;
mod surveillance;

use crate::scenario::Scenario;

/// Every scenario, in `argus scenarios` order.
pub(crate) fn all() -> Vec<Box<dyn Scenario>> {
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
        // One line per scenario, e.g. `Box::new(gimpo::Gimpo),`
    ]
}

/// The scenario called `name`.
pub(crate) fn find(name: &str) -> Option<Box<dyn Scenario>> {
    all().into_iter().find(|s| s.name() == name)
}

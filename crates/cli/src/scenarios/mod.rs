//! The registered scenarios. To add one: write `scenarios/<name>.rs` implementing
//! [`Scenario`](crate::scenario::Scenario) and add one line to [`all`].

mod clutter;
mod cv_polar;

use crate::scenario::Scenario;

/// Every scenario, in `argus scenarios` order.
pub(crate) fn all() -> Vec<Box<dyn Scenario>> {
    vec![
        Box::new(cv_polar::CvPolar),
        Box::new(clutter::Clutter),
        // One line per scenario, e.g. `Box::new(gimpo::Gimpo),`
    ]
}

/// The scenario called `name`.
pub(crate) fn find(name: &str) -> Option<Box<dyn Scenario>> {
    all().into_iter().find(|s| s.name() == name)
}

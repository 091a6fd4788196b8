//! The seed papers' experiments (and the framework's own `cv-polar`) as a library: each
//! scenario's simulation, estimator wiring, statistics and figure series behind one small
//! API, called by the `argus` command (which adds argument parsing, files, the table
//! text, figure drawing and a progress bar) and later by the Python bindings.
//!
//! - [`list`] (or [`all`]): every scenario's name, description, default run count and
//!   parameter specs; [`find`] one by name.
//! - [`run`]: one scenario over a run range with a seed, validated [`Params`] and an
//!   optional [`Progress`]; it returns the [`Report`] as data (rows with
//!   key/quantity/paper/ours/unit/note, series, [`Figure`]s, notes) and, for a splittable
//!   campaign, the per-run records; [`merge`] reduces records of split runs.
//! - One error type, [`ScenarioError`]; a bad parameter is [`ScenarioError::Param`]
//!   with its key and a [`ParamProblem`].
//!
//! The experiments with an API of their own beside their scenario are in [`experiments`]:
//! `rbs_landing` (seed 003), `maneuver_1d` and `drag_bearing` (seed 001), `bias_32`
//! (seed 004); the algorithms they run stay in the library crates.
//!
//! # Example
//! ```
//! use argus_scenarios::{NoProgress, Params, find};
//!
//! let sc = find("cv-polar")?;
//! let params = Params::from_settings(&sc.params(), &["duration=20".to_owned()])?;
//! let out = argus_scenarios::run(sc.as_ref(), 0..4, 1, params, &NoProgress)?;
//! assert!(out.report.rows.iter().any(|r| r.key == "anees"));
//! assert_eq!(out.records.map(|r| r.len()), Some(4));
//! # Ok::<(), argus_scenarios::ScenarioError>(())
//! ```

mod api;
pub mod campaign;
mod context;
mod error;
pub mod estimator;
mod params;
mod polar_scene;
mod registry;
mod report;
mod scenario;
mod tracker_params;

mod bias_32;
mod clutter;
mod cv_polar;
mod drag_bearing;
mod gimpo;
mod launch;
mod maneuver_1d;
mod rbs_landing;
mod real_traffic;
mod surveillance;

/// The experiments' own APIs (configuration, one run, statistics) under the scenarios
/// that report them, for the tests and for exploration.
pub mod experiments {
    pub use crate::bias_32::experiment as bias_32;
    /// Seed 001's drag-bearing Monte Carlo: configuration, one run, statistics.
    pub mod drag_bearing {
        pub use crate::drag_bearing::experiment::*;
        pub use crate::drag_bearing::statistics::{McSummary, McSums};
    }
    pub use crate::maneuver_1d::experiment as maneuver_1d;
    /// The rbs-landing experiment and its Monte Carlo statistics.
    pub mod rbs_landing {
        pub use crate::rbs_landing::experiment::*;
        pub use crate::rbs_landing::summary::{McSummary, McSums, run_monte_carlo};
    }
    /// The real-traffic scenario's tracker configurations, by name.
    pub mod real_traffic {
        pub use crate::real_traffic::trackers;
    }
}

pub use api::{RunOutput, ScenarioInfo, list, merge, run};
pub use campaign::{Campaign, Footprint, RecordText, Retained, Splittable, in_process, run_whole};
pub use context::{NoProgress, Progress, RunContext};
pub use error::{ParamProblem, ScenarioError};
pub use params::{ParamSpec, Params};
pub use registry::{all, find};
pub use report::{Figure, Line, LineStyle, Report, Row, Series};
pub use scenario::{Scenario, Simulated, TruthRow};

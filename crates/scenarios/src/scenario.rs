//! The scenario framework: a paper experiment implements [`Scenario`] in its own file
//! and is registered with one line in [`crate::all`].

use std::ops::Range;

use argus_sim::{SensorSpec, Truth};

use crate::campaign::Splittable;
use crate::error::ScenarioError;
use crate::params::{ParamSpec, Params};
use crate::report::Report;

/// Progress of a campaign, ticked once per run (from rayon's threads, hence `Sync`).
/// The command draws a bar with it; [`NoProgress`] ignores it.
pub trait Progress: Sync {
    /// One step done.
    fn tick(&self);
    /// The campaign is done (called once, after the last tick).
    fn finish(&self) {}
}

/// A [`Progress`] that does nothing.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoProgress;

impl Progress for NoProgress {
    fn tick(&self) {}
}

/// What a scenario run gets.
#[derive(Clone)]
pub struct RunContext<'a> {
    /// Run indices to compute (`0..N`, or a sub-range of a split campaign).
    pub runs: Range<u64>,
    /// Base seed.
    pub seed: u64,
    /// Validated parameters.
    pub params: Params,
    /// Progress handle: ticked once per run.
    pub progress: &'a dyn Progress,
}

impl std::fmt::Debug for RunContext<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RunContext")
            .field("runs", &self.runs)
            .field("seed", &self.seed)
            .field("params", &self.params)
            .finish_non_exhaustive()
    }
}

/// A paper experiment (or the framework's own `cv-polar`).
pub trait Scenario: Sync {
    /// Name on the command line (`kebab-case`).
    fn name(&self) -> &'static str;
    /// One line for a listing.
    fn description(&self) -> &'static str;
    /// Monte Carlo runs when none are asked for (the paper's count).
    fn default_runs(&self) -> u64;
    /// The parameters it accepts.
    fn params(&self) -> Vec<ParamSpec>;
    /// The truth and sensors of one run (for exporting a run's plots).
    ///
    /// # Errors
    /// [`ScenarioError::NoScene`] for a scenario without a fixed scene, else whatever
    /// building the scene reports.
    fn scene(&self, params: &Params) -> Result<(Truth, Vec<SensorSpec>), ScenarioError>;
    /// Runs the Monte Carlo campaign.
    ///
    /// # Errors
    /// Whatever the simulation or the filters report.
    fn run(&self, ctx: &RunContext<'_>) -> Result<Report, ScenarioError>;
    /// The campaign as per-run records and a reduce step, when the scenario provides
    /// one ([`crate::campaign::Campaign`]): the command then also writes the records,
    /// and split campaigns can be merged. `None` (the default): the scenario runs
    /// whole only.
    fn splittable(&self) -> Option<&dyn Splittable> {
        None
    }
}

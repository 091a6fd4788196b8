//! The scenario framework: a paper experiment implements [`Scenario`] in its own file
//! and is registered with one line in [`crate::all`].

use argus_sim::{LabelledPlot, SensorSpec, Truth};

use crate::campaign::Splittable;
use crate::context::RunContext;
use crate::error::ScenarioError;
use crate::params::{ParamSpec, Params};
use crate::report::Report;

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
    /// One run's plots and truth made by the scenario itself, for a scenario whose
    /// plots do not come from a [`Truth`] scene through `argus_sim::generate_plots`
    /// (e.g. recorded traffic seen by a rotating radar). `None` (the default): use
    /// [`Scenario::scene`].
    fn simulated(
        &self,
        _params: &Params,
        _seed: u64,
        _run: u64,
    ) -> Option<Result<Simulated, ScenarioError>> {
        None
    }
}

/// One run's plots and truth, as [`Scenario::simulated`] makes them.
#[derive(Debug, Clone, PartialEq)]
pub struct Simulated {
    /// The plots, in time order.
    pub plots: Vec<LabelledPlot>,
    /// The truth samples, per target in time order.
    pub truth: Vec<TruthRow>,
}

/// One truth sample of [`Simulated`]: time (s), target name, position (m) and velocity
/// (m/s) in the local plane.
#[derive(Debug, Clone, PartialEq)]
pub struct TruthRow {
    /// Time, s.
    pub t: f64,
    /// The target's name.
    pub target: String,
    /// x (east), m.
    pub x: f64,
    /// x velocity, m/s.
    pub vx: f64,
    /// y (north), m.
    pub y: f64,
    /// y velocity, m/s.
    pub vy: f64,
}

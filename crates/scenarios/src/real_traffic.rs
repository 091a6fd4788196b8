//! `real-traffic`: the multi-target tracker on real air traffic (issue 18). The truth is
//! the committed busiest hour of the `traffic` 2.13 package's `collections/quickstart`
//! sample (OpenSky ADS-B around Paris, 123 aircraft; `data/real-traffic/README.md`),
//! cleaned by `argus-adsb`'s documented rules and placed in the East-North plane of a
//! radar at Paris CDG (`argus-geo`, WGS-84). A 2-D rotating surveillance radar at the
//! origin (seed 000's: 5-s revolution, clockwise, north at t = 0, σr 70 m, σθ 0.08°,
//! P_D 0.9, 10 clutter plots per revolution out to 150 km) takes each aircraft's plot at
//! the instant its beam crosses it ([`argus_sim::beam_crossings_along`]); the plots keep
//! their own times and go to the tracker as they are (a rotating sensor, processed by
//! sectors). Every configuration's confirmed tracks are scored against the ADS-B truth
//! inside the coverage by `argus-score` (completeness, breaks per aircraft-hour, identity
//! swaps, spurious track time, RMSE, GOSPA: `docs/scoring.md`).
//!
//! Every parameter is settable with `--set`; `argus simulate real-traffic` writes the
//! plot file (`t,sensor,range,azimuth`) and the truth (`t,target,x,vx,y,vy`) so that any
//! tracker can be run on them (`docs/examples/real-traffic.toml` is Argus's).
//!
//! # Random draws
//! Run `i` draws from `run_rng(seed, i)`: per flight segment in order, per beam crossing
//! inside the coverage one uniform (detection) and, if detected, two normals (range,
//! azimuth); then per revolution the clutter count and per clutter plot its radius and
//! azimuth. The truth is the same in every run.

mod params;
mod radar;
mod report;
mod setup;
mod smooth;
mod truth;

pub(crate) use setup::Setup;

/// The tracker configurations `argus run real-traffic` compares, by name (`gnn_kf`, …,
/// `gnn_aircraft`), for the parameters given.
///
/// # Errors
/// [`ScenarioError::Param`] for a bad parameter, [`ScenarioError::Tracker`] for a
/// configuration the tracker refuses.
pub fn trackers(
    params: &Params,
) -> Result<Vec<(&'static str, argus_tracker::TrackerConfig)>, ScenarioError> {
    Ok(Setup::new(params)?
        .trackers
        .into_iter()
        .map(|n| (n.name, n.config))
        .collect())
}

use argus_sim::{ChaCha8Rng, SensorSpec, Truth};

use crate::campaign::{Campaign, Splittable, run_whole};
use crate::context::RunContext;
use crate::error::ScenarioError;
use crate::params::{ParamSpec, Params};
use crate::report::Report;
use crate::scenario::{Scenario, Simulated};
use setup::RealRun;

/// The `real-traffic` scenario.
pub(crate) struct RealTraffic;

impl Scenario for RealTraffic {
    fn name(&self) -> &'static str {
        "real-traffic"
    }

    fn description(&self) -> &'static str {
        "issue 18: one real hour of ADS-B traffic around Paris seen by a simulated 5-s rotating radar at CDG; tracker scored against the ADS-B truth"
    }

    fn default_runs(&self) -> u64 {
        1
    }

    fn params(&self) -> Vec<ParamSpec> {
        params::params()
    }

    fn scene(&self, _params: &Params) -> Result<(Truth, Vec<SensorSpec>), ScenarioError> {
        Err(ScenarioError::NoScene {
            scenario: "real-traffic",
            reason: "its truth is recorded traffic, not a simulated scene: `argus simulate real-traffic` writes its plots and truth",
        })
    }

    fn simulated(
        &self,
        params: &Params,
        seed: u64,
        run: u64,
    ) -> Option<Result<Simulated, ScenarioError>> {
        Some(Setup::new(params).and_then(|s| s.simulated(seed, run)))
    }

    fn run(&self, ctx: &RunContext<'_>) -> Result<Report, ScenarioError> {
        run_whole(self, ctx)
    }

    fn splittable(&self) -> Option<&dyn Splittable> {
        Some(self)
    }
}

impl Campaign for RealTraffic {
    type Setup = Setup;
    type Run = RealRun;

    fn setup(&self, params: &Params) -> Result<Setup, ScenarioError> {
        Setup::new(params)
    }

    fn one_run(
        &self,
        s: &Setup,
        _seed: u64,
        run: u64,
        rng: &mut ChaCha8Rng,
    ) -> Result<RealRun, ScenarioError> {
        s.one_run(run, rng)
    }

    fn reduce(&self, s: &Setup, runs: &[RealRun]) -> Result<Report, ScenarioError> {
        report::reduce(s, runs)
    }
}

//! The small API the command and the bindings call: list the scenarios, run one, merge
//! the records of split runs.

use std::ops::Range;

use crate::campaign::{RecordText, in_process};
use crate::context::{Progress, RunContext};
use crate::error::ScenarioError;
use crate::params::{ParamSpec, Params};
use crate::registry::all;
use crate::report::Report;
use crate::scenario::Scenario;

/// What a listing shows of a scenario.
#[derive(Debug, Clone, PartialEq)]
pub struct ScenarioInfo {
    /// Name (`kebab-case`).
    pub name: &'static str,
    /// One line.
    pub description: &'static str,
    /// The paper's Monte Carlo run count.
    pub default_runs: u64,
    /// The parameters it accepts.
    pub params: Vec<ParamSpec>,
}

/// Every scenario, in listing order.
#[must_use]
pub fn list() -> Vec<ScenarioInfo> {
    all()
        .iter()
        .map(|s| ScenarioInfo {
            name: s.name(),
            description: s.description(),
            default_runs: s.default_runs(),
            params: s.params(),
        })
        .collect()
}

/// The result of [`run`].
#[derive(Debug, Clone, PartialEq)]
pub struct RunOutput {
    /// The report.
    pub report: Report,
    /// For a splittable campaign, one JSON record per run (`records[i]` is run
    /// `runs.start + i`): what [`merge`] reduces. `None` for a scenario that runs whole.
    pub records: Option<Vec<String>>,
}

/// Runs `scenario` over `runs` (run `r` draws from `argus_sim::run_rng(seed, r)`) with
/// `params`, ticking `progress` once per run. A splittable campaign is reduced from its
/// records as JSON text, exactly as [`merge`] would reduce them.
///
/// # Errors
/// [`ScenarioError::Param`] for a parameter the scenario refuses, else whatever the
/// simulation, the filters or the statistics report.
pub fn run(
    scenario: &dyn Scenario,
    runs: Range<u64>,
    seed: u64,
    params: Params,
    progress: &dyn Progress,
) -> Result<RunOutput, ScenarioError> {
    let ctx = RunContext {
        runs,
        seed,
        params,
        progress,
    };
    match scenario.splittable() {
        Some(sp) => {
            let records = sp.records(&ctx)?;
            let count = ctx.runs.end - ctx.runs.start;
            let report =
                sp.reduce_records(&ctx.params, count, &mut in_process(&records, &ctx.runs))?;
            Ok(RunOutput {
                report,
                records: Some(records),
            })
        }
        None => Ok(RunOutput {
            report: scenario.run(&ctx)?,
            records: None,
        }),
    }
}

/// The report of the `count` records of split runs, streamed in run order (as
/// `RunOutput::records` gave them, with where each was read from): the records are
/// parsed one at a time.
///
/// # Errors
/// [`ScenarioError::NotSplittable`], [`ScenarioError::Record`] for a record that does not
/// parse, then the reduce step's error.
pub fn merge(
    scenario: &dyn Scenario,
    params: &Params,
    count: u64,
    records: &mut dyn Iterator<Item = Result<RecordText, ScenarioError>>,
) -> Result<Report, ScenarioError> {
    let sp = scenario
        .splittable()
        .ok_or_else(|| ScenarioError::NotSplittable {
            scenario: scenario.name(),
        })?;
    sp.reduce_records(params, count, records)
}

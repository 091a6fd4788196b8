//! Splittable campaigns: a scenario that computes one serialisable record per run and
//! reduces the records into its [`Report`] can be run in pieces (runs `A..B` on several
//! machines, or the shards of a cluster job array) and merged, with the numbers of one
//! whole run. Every registered scenario is splittable.
//!
//! # Adopting it in a new scenario
//! 1. Split the campaign in three: what every run shares (built from the parameters
//!    alone: scene, filters, configurations) → [`Campaign::Setup`]; one run →
//!    [`Campaign::one_run`], returning a record ([`Campaign::Run`], `Serialize +
//!    Deserialize`) that holds **everything the reduce step reads of that run** — per-step
//!    squared errors for RMS curves, detection indices for delays and their percentiles,
//!    the trajectory when run 0 feeds a figure; and [`Campaign::reduce`] (or the streaming
//!    [`Campaign::reduce_stream`]), the report from the records in run order.
//! 2. A run draws only from `run_rng(seed, run)` (the `rng` given) or from streams derived
//!    from `seed` and `run` alone, never from state shared between runs, so that a run's
//!    record does not depend on which other runs are computed with it.
//! 3. In `impl Scenario`: `fn run(&self, ctx) { run_whole(self, ctx) }` and
//!    `fn splittable(&self) -> Option<&dyn Splittable> { Some(self) }`.
//! 4. Add a case to `tests/split_merge.rs` (2–3 shards merged == the whole run, exactly).
//!
//! Types without serde (nalgebra vectors) go into the record as arrays (see
//! `drag_bearing::DragRecord`). JSON has no NaN: use `Option<f64>` for a missing value
//! (a NaN would be written as `null` and refused when read back).
//!
//! The records are JSON text; the command stores them as `runs/<A>-<B>.jsonl` beside the
//! report (format in `docs/FORMATS.md`) and streams them back, one at a time, for
//! `argus merge`. Even a whole campaign is reduced from the records as read back from
//! their JSON text, in run order, so a report from one whole run and one from merged
//! pieces of the same runs come from the same bytes through the same floating-point
//! operations (serde_json's `float_roundtrip` makes the text exact).

use std::ops::Range;
use std::path::PathBuf;

use argus_sim::{ChaCha8Rng, monte_carlo};
use serde::Serialize;
use serde::de::DeserializeOwned;

use crate::context::RunContext;
use crate::error::ScenarioError;
use crate::params::Params;
use crate::report::Report;

/// A Monte Carlo campaign split into independent runs and a reduce step.
pub trait Campaign: Sync {
    /// Read-only data shared by the runs and the reduce step (scene, filters …), built
    /// once from the parameters.
    type Setup: Sync;
    /// What one run leaves for the reduce step. Stored as one JSON line per run; use
    /// `Option<f64>` for a missing value (JSON has no NaN: a NaN would be written as
    /// `null` and rejected when read back).
    type Run: Serialize + DeserializeOwned + Send;

    /// Builds the shared data.
    ///
    /// # Errors
    /// Whatever building the scene or filters reports.
    fn setup(&self, params: &Params) -> Result<Self::Setup, ScenarioError>;

    /// Run `run` of the campaign with base seed `seed`, with its own generator
    /// ([`argus_sim::run_rng`]`(seed, run)`). A scenario that draws from other streams
    /// (one per configuration, say) derives them from `seed` and `run` alone, so that a
    /// run's record never depends on which other runs are computed with it.
    ///
    /// # Errors
    /// Whatever the simulation or the filters report.
    fn one_run(
        &self,
        setup: &Self::Setup,
        seed: u64,
        run: u64,
        rng: &mut ChaCha8Rng,
    ) -> Result<Self::Run, ScenarioError>;

    /// The report of the runs given, in run order.
    ///
    /// # Errors
    /// Whatever the metrics report (e.g. every run lost).
    fn reduce(&self, setup: &Self::Setup, runs: &[Self::Run]) -> Result<Report, ScenarioError>;

    /// The report of the `count` runs of a stream, in run order: what
    /// [`Splittable::reduce_records`] calls. The default collects the parsed runs and calls
    /// [`Campaign::reduce`] (memory grows with the parsed records, never with the files'
    /// text); a scenario whose reduction is a fold over the runs overrides it to keep only
    /// its running sums (gimpo does).
    ///
    /// # Errors
    /// The stream's first error (a record that does not parse), then the reduce step's.
    fn reduce_stream(
        &self,
        setup: &Self::Setup,
        count: u64,
        runs: &mut dyn Iterator<Item = Result<Self::Run, ScenarioError>>,
    ) -> Result<Report, ScenarioError> {
        let _ = count;
        let runs = runs.collect::<Result<Vec<_>, _>>()?;
        self.reduce(setup, &runs)
    }
}

/// The object-safe face of a [`Campaign`], used by the command.
pub trait Splittable: Sync {
    /// Computes the runs of `ctx` in parallel and returns their records as JSON text,
    /// in run order.
    ///
    /// # Errors
    /// The first failing run's error (in run order).
    fn records(&self, ctx: &RunContext<'_>) -> Result<Vec<String>, ScenarioError>;

    /// Parses the `count` records (JSON text, in run order, one at a time as the stream
    /// yields them) and reduces them.
    ///
    /// # Errors
    /// The stream's first error, [`ScenarioError::Record`] for a record that does not
    /// parse (with its file and line), then the reduce step's error.
    fn reduce_records(
        &self,
        params: &Params,
        count: u64,
        records: &mut dyn Iterator<Item = Result<RecordText, ScenarioError>>,
    ) -> Result<Report, ScenarioError>;
}

/// One run's record as text, with where it came from (for error messages).
#[derive(Debug, Clone)]
pub struct RecordText {
    /// The JSON text of the record.
    pub json: String,
    /// File it was read from (empty when computed in this process).
    pub file: PathBuf,
    /// 1-based line in that file.
    pub line: u64,
}

impl<C: Campaign> Splittable for C {
    fn records(&self, ctx: &RunContext<'_>) -> Result<Vec<String>, ScenarioError> {
        let setup = self.setup(&ctx.params)?;
        let progress = &ctx.progress;
        let runs = monte_carlo(
            ctx.seed,
            ctx.runs.clone(),
            |run, rng| -> Result<String, ScenarioError> {
                let r = self.one_run(&setup, ctx.seed, run, rng)?;
                serde_json::to_string(&r).map_err(|e| ScenarioError::Serialize {
                    run,
                    message: e.to_string(),
                })
            },
            || progress.tick(),
        );
        progress.finish();
        runs
    }

    fn reduce_records(
        &self,
        params: &Params,
        count: u64,
        records: &mut dyn Iterator<Item = Result<RecordText, ScenarioError>>,
    ) -> Result<Report, ScenarioError> {
        let setup = self.setup(params)?;
        let mut runs = records.map(|r| {
            let r = r?;
            serde_json::from_str::<C::Run>(&r.json).map_err(|e| ScenarioError::Record {
                file: r.file.clone(),
                line: r.line,
                message: e.to_string(),
            })
        });
        self.reduce_stream(&setup, count, &mut runs)
    }
}

/// In-process records as a stream of [`RecordText`] (no file), for
/// [`Splittable::reduce_records`].
pub fn in_process<'a>(
    records: &'a [String],
    runs: &Range<u64>,
) -> impl Iterator<Item = Result<RecordText, ScenarioError>> + 'a {
    records.iter().zip(runs.clone()).map(|(json, run)| {
        Ok(RecordText {
            json: json.clone(),
            file: PathBuf::from(format!("<run {run}>")),
            line: 1,
        })
    })
}

/// The whole campaign of `ctx` through its records: computes them and reduces them as
/// read back from their JSON text, exactly as a merge of split runs would. What a
/// splittable scenario's [`Scenario::run`](crate::scenario::Scenario::run) returns.
///
/// # Errors
/// As [`Splittable::records`], then [`Splittable::reduce_records`].
pub fn run_whole(sp: &dyn Splittable, ctx: &RunContext<'_>) -> Result<Report, ScenarioError> {
    let records = sp.records(ctx)?;
    sp.reduce_records(
        &ctx.params,
        ctx.runs.end - ctx.runs.start,
        &mut in_process(&records, &ctx.runs),
    )
}

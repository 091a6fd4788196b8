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
//!    the trajectory when run 0 feeds a figure; and the reduce step in three:
//!    [`Campaign::start`] (the empty running state, [`Campaign::Sums`]),
//!    [`Campaign::add`] (one run's record into it, in run order) and
//!    [`Campaign::finish`] (the report). The state keeps sums, never the records: a
//!    merge of any number of runs holds the same few per-step sums (see [`Footprint`]).
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
    /// The reduce step's running state: what it keeps of the runs added so far.
    type Sums: Retained;

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

    /// The empty running state of the reduce step for a stream of `count` runs.
    ///
    /// # Errors
    /// Whatever the reduce step refuses before any run (a bad parameter).
    fn start(&self, setup: &Self::Setup, count: u64) -> Result<Self::Sums, ScenarioError>;

    /// Adds the next run (in run order) to the running state. The state keeps what the
    /// report needs of the run — sums over the runs, per step or pooled — and drops the
    /// record, so that its size does not grow with the number of runs.
    ///
    /// # Errors
    /// A record the reduce step cannot use (of another length than the first, say).
    fn add(
        &self,
        setup: &Self::Setup,
        sums: &mut Self::Sums,
        run: Self::Run,
    ) -> Result<(), ScenarioError>;

    /// The report from the running state once every run is added.
    ///
    /// # Errors
    /// Whatever the metrics report (e.g. every run lost).
    fn finish(&self, setup: &Self::Setup, sums: Self::Sums) -> Result<Report, ScenarioError>;

    /// The report of the `count` runs of a stream, in run order, in one pass:
    /// [`Campaign::start`], [`Campaign::add`] for each run, [`Campaign::finish`]. What
    /// [`Splittable::reduce_records`] calls, for a whole run and a merge alike.
    ///
    /// # Errors
    /// The stream's first error (a record that does not parse), then the reduce step's.
    fn reduce_stream(
        &self,
        setup: &Self::Setup,
        count: u64,
        runs: &mut dyn Iterator<Item = Result<Self::Run, ScenarioError>>,
    ) -> Result<Report, ScenarioError> {
        let sums = self.fold(setup, count, runs)?;
        self.finish(setup, sums)
    }

    /// The running state after every run of the stream.
    ///
    /// # Errors
    /// As [`Campaign::reduce_stream`].
    fn fold(
        &self,
        setup: &Self::Setup,
        count: u64,
        runs: &mut dyn Iterator<Item = Result<Self::Run, ScenarioError>>,
    ) -> Result<Self::Sums, ScenarioError> {
        let mut sums = self.start(setup, count)?;
        for r in runs {
            self.add(setup, &mut sums, r?)?;
        }
        Ok(sums)
    }
}

/// How much a reduce step's running state holds, in numbers (an `f64`, a count, an
/// index: one each), split by how it grows.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Footprint {
    /// Numbers whose count does not depend on the number of runs: per-step sums, pooled
    /// sums, the first run's trajectory for a figure.
    pub fixed: usize,
    /// Numbers kept one per run (or a few per run) because an exact statistic needs every
    /// run's value: gimpo's final ratios (their mean and standard deviation, in two passes
    /// over the values as the report always computed them). Never a run's per-step series.
    /// (Percentiles of values on a grid need no such list: maneuver-1d counts its
    /// detection delays per plot index.)
    pub per_run: usize,
}

impl std::ops::Add for Footprint {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            fixed: self.fixed + o.fixed,
            per_run: self.per_run + o.per_run,
        }
    }
}

impl std::iter::Sum for Footprint {
    fn sum<I: Iterator<Item = Self>>(iter: I) -> Self {
        iter.fold(Self::default(), |a, b| a + b)
    }
}

/// A reduce step's running state that can say how much it holds (for the tests that
/// check a merge's memory does not grow with the number of runs).
pub trait Retained {
    /// The numbers the state holds.
    fn footprint(&self) -> Footprint;
}

impl Retained for argus_sim::MetricsSums {
    fn footprint(&self) -> Footprint {
        Footprint {
            fixed: self.retained(),
            per_run: 0,
        }
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

    /// As [`Splittable::reduce_records`], but returns how much the reduce step's running
    /// state holds once every record is added, instead of the report.
    ///
    /// # Errors
    /// As [`Splittable::reduce_records`].
    fn footprint(
        &self,
        params: &Params,
        count: u64,
        records: &mut dyn Iterator<Item = Result<RecordText, ScenarioError>>,
    ) -> Result<Footprint, ScenarioError>;
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
        self.reduce_stream(&setup, count, &mut parsed::<C>(records))
    }

    fn footprint(
        &self,
        params: &Params,
        count: u64,
        records: &mut dyn Iterator<Item = Result<RecordText, ScenarioError>>,
    ) -> Result<Footprint, ScenarioError> {
        let setup = self.setup(params)?;
        Ok(self
            .fold(&setup, count, &mut parsed::<C>(records))?
            .footprint())
    }
}

/// The records of a stream parsed one at a time.
fn parsed<'a, C: Campaign>(
    records: &'a mut dyn Iterator<Item = Result<RecordText, ScenarioError>>,
) -> impl Iterator<Item = Result<C::Run, ScenarioError>> + 'a {
    records.map(|r| {
        let r = r?;
        serde_json::from_str::<C::Run>(&r.json).map_err(|e| ScenarioError::Record {
            file: r.file.clone(),
            line: r.line,
            message: e.to_string(),
        })
    })
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

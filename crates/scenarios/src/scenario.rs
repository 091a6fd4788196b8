//! The scenario framework: a paper experiment implements [`Scenario`] in its own file
//! under `scenarios/` and is registered with one line in [`crate::scenarios::all`].

use std::collections::BTreeMap;
use std::ops::Range;

use argus_sim::{SensorSpec, Truth};
use indicatif::{ProgressBar, ProgressStyle};

use crate::campaign::Splittable;
use crate::error::CliError;
use crate::report::Report;

/// A numeric parameter a scenario accepts through `--set key=value`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ParamSpec {
    /// Key.
    pub(crate) key: &'static str,
    /// Default value.
    pub(crate) default: f64,
    /// Smallest allowed value (inclusive).
    pub(crate) min: f64,
    /// Largest allowed value (inclusive).
    pub(crate) max: f64,
    /// Unit and meaning, one line.
    pub(crate) help: &'static str,
}

impl ParamSpec {
    /// A parameter `key` with its default, allowed range and one-line help.
    pub(crate) const fn new(
        key: &'static str,
        default: f64,
        min: f64,
        max: f64,
        help: &'static str,
    ) -> Self {
        Self {
            key,
            default,
            min,
            max,
            help,
        }
    }
}

/// Validated parameter values (every key of the scenario's specs is present).
///
/// `--set key=a,b,c` gives a key a list of values (each checked like a single one): the
/// map holds the first, [`Params::list`] all of them, and [`Params::get`] refuses a key
/// set to a list, so only a scenario that reads the key with [`Params::list`] accepts one.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct Params(BTreeMap<String, f64>, BTreeMap<String, Vec<f64>>);

impl Params {
    /// The defaults overridden by `key=value` settings, each checked against `specs`.
    ///
    /// # Errors
    /// [`CliError::Usage`] for a setting without `=`, an unknown key (the message lists the
    /// known ones), a non-numeric or non-finite value, or a value outside `[min, max]`
    /// (for a comma list: any of its values).
    pub(crate) fn from_settings(
        specs: &[ParamSpec],
        settings: &[String],
    ) -> Result<Self, CliError> {
        let mut map: BTreeMap<String, f64> = specs
            .iter()
            .map(|p| (p.key.to_owned(), p.default))
            .collect();
        let mut lists: BTreeMap<String, Vec<f64>> = BTreeMap::new();
        for s in settings {
            let (k, v) = s
                .split_once('=')
                .ok_or_else(|| CliError::Usage(format!("--set {s}: expected key=value")))?;
            let (k, v) = (k.trim(), v.trim());
            let spec = specs.iter().find(|p| p.key == k).ok_or_else(|| {
                let known: Vec<&str> = specs.iter().map(|p| p.key).collect();
                CliError::Usage(format!(
                    "--set {k}: unknown parameter (known: {})",
                    known.join(", ")
                ))
            })?;
            let mut xs = Vec::new();
            for item in v.split(',').map(str::trim) {
                let x: f64 = item.parse().map_err(|_| {
                    CliError::Usage(format!("--set {k}={v}: {item:?} is not a number"))
                })?;
                if !x.is_finite() || x < spec.min || x > spec.max {
                    return Err(CliError::Usage(format!(
                        "--set {k}={v}: {item} must lie in [{}, {}] ({})",
                        spec.min, spec.max, spec.help
                    )));
                }
                xs.push(x);
            }
            if let Some(&first) = xs.first() {
                map.insert(k.to_owned(), first);
            }
            if xs.len() > 1 {
                lists.insert(k.to_owned(), xs);
            } else {
                lists.remove(k);
            }
        }
        Ok(Self(map, lists))
    }

    /// The value of `key`.
    ///
    /// # Errors
    /// [`CliError::Usage`] if the scenario asks for a key it did not declare (a bug in
    /// the scenario, reported rather than panicking).
    pub(crate) fn get(&self, key: &str) -> Result<f64, CliError> {
        if let Some(xs) = self.1.get(key) {
            return Err(CliError::Usage(format!(
                "--set {key}: takes one value here, got a list of {}",
                xs.len()
            )));
        }
        self.0
            .get(key)
            .copied()
            .ok_or_else(|| CliError::Usage(format!("parameter {key} is not declared")))
    }

    /// All values of `key`: the list given as `--set key=a,b,…`, else its one value.
    ///
    /// # Errors
    /// [`CliError::Usage`] if the scenario asks for a key it did not declare.
    pub(crate) fn list(&self, key: &str) -> Result<Vec<f64>, CliError> {
        match self.1.get(key) {
            Some(xs) => Ok(xs.clone()),
            None => self
                .0
                .get(key)
                .map(|&x| vec![x])
                .ok_or_else(|| CliError::Usage(format!("parameter {key} is not declared"))),
        }
    }

    /// All values.
    #[must_use]
    pub(crate) fn as_map(&self) -> &BTreeMap<String, f64> {
        &self.0
    }
}

/// Progress of a campaign: an indicatif bar on a terminal's stderr, silent otherwise.
/// Safe to tick from rayon's threads.
#[derive(Debug, Clone)]
pub(crate) struct Progress(Option<ProgressBar>);

impl Progress {
    /// A bar of `len` steps if stderr is a terminal, else a silent handle.
    #[must_use]
    pub(crate) fn new(len: u64, visible: bool) -> Self {
        if !visible {
            return Self(None);
        }
        let bar = ProgressBar::new(len);
        if let Ok(style) =
            ProgressStyle::with_template("{bar:40} {pos}/{len} runs  {elapsed_precise} (eta {eta})")
        {
            bar.set_style(style);
        }
        Self(Some(bar))
    }

    /// One step done.
    pub(crate) fn tick(&self) {
        if let Some(b) = &self.0 {
            b.inc(1);
        }
    }

    /// Removes the bar.
    pub(crate) fn finish(&self) {
        if let Some(b) = &self.0 {
            b.finish_and_clear();
        }
    }
}

/// What a scenario run gets.
#[derive(Debug, Clone)]
pub(crate) struct RunContext {
    /// Run indices to compute (`--runs N` is `0..N`; `--runs A..B` a sub-range).
    pub(crate) runs: Range<u64>,
    /// Base seed.
    pub(crate) seed: u64,
    /// Validated parameters.
    pub(crate) params: Params,
    /// Progress handle: tick once per run.
    pub(crate) progress: Progress,
}

/// A paper experiment (or the framework's own `cv-polar`).
pub(crate) trait Scenario: Sync {
    /// Name on the command line (`kebab-case`).
    fn name(&self) -> &'static str;
    /// One line for `argus scenarios`.
    fn description(&self) -> &'static str;
    /// Monte Carlo runs when `--runs` is not given (the paper's count).
    fn default_runs(&self) -> u64;
    /// Parameters settable with `--set`.
    fn params(&self) -> Vec<ParamSpec>;
    /// The truth and sensors of one run (for `argus simulate`; a scenario whose truth is
    /// itself random may use `seed`).
    ///
    /// # Errors
    /// Whatever building the scene reports.
    fn scene(&self, params: &Params) -> Result<(Truth, Vec<SensorSpec>), CliError>;
    /// Runs the Monte Carlo campaign.
    ///
    /// # Errors
    /// Whatever the simulation or the filters report.
    fn run(&self, ctx: &RunContext) -> Result<Report, CliError>;
    /// The campaign as per-run records and a reduce step, when the scenario provides
    /// one ([`crate::campaign::Campaign`]): `argus run` then also writes
    /// `runs/<A>-<B>.jsonl`, and `argus merge` recomputes the report from split
    /// campaigns. `None` (the default): the scenario runs whole only.
    fn splittable(&self) -> Option<&dyn Splittable> {
        None
    }
}

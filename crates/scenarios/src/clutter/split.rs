//! `clutter` as a splittable campaign: a run's record holds the five filters' records of
//! every configuration (SNR × density), each drawn from the configuration's own stream
//! `run_rng(seed + 1000·si + di, run)` as the whole campaign always did; the reduce step
//! adds them, run after run, to each configuration's per-filter sums ([`ConfigSums`]).

use argus_core_math::anees_interval;
use argus_sim::{ChaCha8Rng, MetricsSums, RunRecord, run_rng};

use super::{
    Clutter, ConfigResult, DENSITIES, FilterResult, Prepared, SNRS_DB, config, predicted_rmse,
    report,
};
use crate::campaign::{Campaign, Footprint, Retained};
use crate::error::ScenarioError;
use crate::params::Params;
use crate::report::Report;

/// The configurations, in (SNR, density) order.
pub(crate) struct Setup {
    configs: Vec<Prepared>,
}

/// The seed of configuration (`si`, `di`) in a campaign with base seed `seed`.
fn config_seed(seed: u64, si: usize, di: usize) -> u64 {
    seed.wrapping_add(1000 * si as u64 + di as u64)
}

impl Campaign for Clutter {
    type Setup = Setup;
    /// Per configuration, the five filters' records.
    type Run = Vec<Vec<RunRecord>>;
    type Sums = Vec<ConfigSums>;

    fn setup(&self, p: &Params) -> Result<Setup, ScenarioError> {
        let mut configs = Vec::with_capacity(SNRS_DB.len() * DENSITIES.len());
        for &snr in &SNRS_DB {
            for &lam in &DENSITIES {
                configs.push(Prepared::new(&config(p, lam, snr)?)?);
            }
        }
        Ok(Setup { configs })
    }

    fn one_run(
        &self,
        s: &Setup,
        seed: u64,
        run: u64,
        _rng: &mut ChaCha8Rng,
    ) -> Result<Self::Run, ScenarioError> {
        let nd = DENSITIES.len();
        s.configs
            .iter()
            .enumerate()
            .map(|(k, prep)| prep.one(&mut run_rng(config_seed(seed, k / nd, k % nd), run)))
            .collect()
    }

    fn start(&self, s: &Setup, _count: u64) -> Result<Vec<ConfigSums>, ScenarioError> {
        Ok(s.configs.iter().map(|_| ConfigSums::new()).collect())
    }

    fn add(
        &self,
        s: &Setup,
        sums: &mut Vec<ConfigSums>,
        run: Self::Run,
    ) -> Result<(), ScenarioError> {
        for ((prep, acc), filters) in s.configs.iter().zip(sums.iter_mut()).zip(&run) {
            acc.add(prep, filters);
        }
        Ok(())
    }

    fn finish(&self, s: &Setup, sums: Vec<ConfigSums>) -> Result<Report, ScenarioError> {
        let results = s
            .configs
            .iter()
            .zip(&sums)
            .map(|(prep, acc)| result(prep, acc))
            .collect::<Result<Vec<ConfigResult>, _>>()?;
        report(&results)
    }
}

/// One filter's runs in one configuration, as sums.
pub(crate) struct FilterSums {
    /// The metrics over the runs (`None` in the result when they fail: every run lost).
    metrics: MetricsSums,
    /// Runs with this filter's record, and those that lost the track.
    runs: usize,
    lost: usize,
    /// Kept runs; over their second half of the steps: Σ squared position error, Σ NEES
    /// and the number of steps.
    kept: usize,
    se: f64,
    nees: f64,
    count: usize,
}

/// One configuration's runs: the five filters' sums.
pub(crate) struct ConfigSums {
    runs: usize,
    filters: Vec<FilterSums>,
}

impl ConfigSums {
    /// No run yet.
    pub(crate) fn new() -> Self {
        Self {
            runs: 0,
            filters: (0..5)
                .map(|_| FilterSums {
                    metrics: MetricsSums::new(4, 2, 0.5),
                    runs: 0,
                    lost: 0,
                    kept: 0,
                    se: 0.0,
                    nees: 0.0,
                    count: 0,
                })
                .collect(),
        }
    }

    /// Adds the next run's five filter records.
    pub(crate) fn add(&mut self, prep: &Prepared, run: &[RunRecord]) {
        self.runs += 1;
        let half = prep.c.steps / 2;
        for (f, r) in self.filters.iter_mut().zip(run) {
            f.metrics.add(r);
            f.runs += 1;
            if r.lost {
                f.lost += 1;
                continue;
            }
            f.kept += 1;
            for s in r.steps.iter().skip(half) {
                f.se += s.pos_err_sq;
                f.nees += s.nees.unwrap_or(f64::NAN);
                f.count += 1;
            }
        }
    }
}

impl Retained for Vec<ConfigSums> {
    fn footprint(&self) -> Footprint {
        let per_filter = Footprint {
            fixed: 6,
            per_run: 0,
        };
        self.iter()
            .flat_map(|c| &c.filters)
            .map(|f| f.metrics.footprint() + per_filter)
            .sum::<Footprint>()
            + Footprint {
                fixed: self.len(),
                per_run: 0,
            }
    }
}

/// The configuration's results from its sums.
///
/// # Errors
/// The ANEES interval's or the predictors' errors.
pub(crate) fn result(prep: &Prepared, sums: &ConfigSums) -> Result<ConfigResult, ScenarioError> {
    let mut filters = Vec::with_capacity(5);
    for f in &sums.filters {
        let cnt = f.count.max(1) as f64;
        let iv = anees_interval(4, f.kept.max(1), 0.95)?;
        filters.push(FilterResult {
            metrics: f.metrics.finish().ok(),
            lost: f.lost,
            runs: sums.runs,
            anees: f.nees / cnt,
            rmse: (f.se / cnt).sqrt(),
            interval: (iv.lower, iv.upper),
        });
    }
    Ok(ConfigResult {
        filters,
        predicted_nn: predicted_rmse(&prep.nn_pred, &prep.p0)?,
        predicted_hyca: predicted_rmse(&prep.hyca, &prep.p0)?,
        predicted_pda: predicted_rmse(&prep.pda_pred, &prep.p0)?,
    })
}

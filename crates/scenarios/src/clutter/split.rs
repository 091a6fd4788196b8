//! `clutter` as a splittable campaign: a run's record holds the five filters' records of
//! every configuration (SNR × density), each drawn from the configuration's own stream
//! `run_rng(seed + 1000·si + di, run)` as the whole campaign always did; the reduce step
//! regroups them per configuration in run order.

use argus_sim::{ChaCha8Rng, RunRecord, run_rng};

use super::{Clutter, ConfigResult, DENSITIES, Prepared, SNRS_DB, config, report};
use crate::campaign::Campaign;
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

    fn reduce(&self, s: &Setup, runs: &[Self::Run]) -> Result<Report, ScenarioError> {
        let results = s
            .configs
            .iter()
            .enumerate()
            .map(|(k, prep)| {
                let all: Vec<Vec<RunRecord>> =
                    runs.iter().filter_map(|r| r.get(k).cloned()).collect();
                prep.result(&all)
            })
            .collect::<Result<Vec<ConfigResult>, _>>()?;
        report(&results)
    }
}

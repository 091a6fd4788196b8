//! `bias-32` as a splittable campaign. A run's record holds, per (sensors, targets)
//! cell of the campaign (one cell unless `--set sensors=…,… targets=…,…` asks for a
//! sweep), the experiment's [`RunRecord`] drawn from `run_rng(seed, run)` — as every cell
//! of the whole campaign always did — and the run's own computing time, the only value
//! that differs when a run is repeated. The reduce step regroups the records per cell.

use argus_sim::{ChaCha8Rng, run_rng};
use rand_distr::{Distribution, StandardNormal};
use serde::{Deserialize, Serialize};

use super::experiment::{RunRecord, ScenarioConfig, run};
use super::sums::SummarySums;
use super::{Bias32, COMPONENTS, UNITS, config, single_report};
use crate::campaign::{Campaign, Footprint, Retained};
use crate::error::ScenarioError;
use crate::params::Params;
use crate::report::{Report, Row, Series};

/// One (sensors, targets) cell of the campaign.
pub(crate) struct Cell {
    sensors: usize,
    targets: usize,
    config: ScenarioConfig,
}

/// The cells, and whether the campaign is a sweep.
pub(crate) struct Setup {
    cells: Vec<Cell>,
    sweep: bool,
}

/// One cell of one run.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(crate) struct CellRun {
    /// The experiment's record.
    record: RunRecord,
    /// The run's computing time (s), for the cost per plot.
    seconds: f64,
}

/// One cell's runs: the averages' sums, the plots and the computing time summed over the
/// runs (in run order).
pub(crate) struct CellSums {
    sums: SummarySums,
    plots: usize,
    seconds: f64,
}

impl Retained for Vec<CellSums> {
    fn footprint(&self) -> Footprint {
        Footprint {
            fixed: self.iter().map(|c| c.sums.retained() + 2).sum(),
            per_run: 0,
        }
    }
}

impl Campaign for Bias32 {
    type Setup = Setup;
    type Run = Vec<CellRun>;
    type Sums = Vec<CellSums>;

    fn setup(&self, p: &Params) -> Result<Setup, ScenarioError> {
        let (sensors, targets) = (p.list("sensors")?, p.list("targets")?);
        let mut cells = Vec::with_capacity(sensors.len() * targets.len());
        for &s in &sensors {
            for &n in &targets {
                let (s, n) = (s as usize, n as usize);
                cells.push(Cell {
                    sensors: s,
                    targets: n,
                    config: config(p, s, n)?,
                });
            }
        }
        Ok(Setup {
            cells,
            sweep: sensors.len() > 1 || targets.len() > 1,
        })
    }

    fn one_run(
        &self,
        s: &Setup,
        seed: u64,
        run_index: u64,
        _rng: &mut ChaCha8Rng,
    ) -> Result<Vec<CellRun>, ScenarioError> {
        s.cells
            .iter()
            .map(|cell| {
                let started = std::time::Instant::now();
                let mut rng = run_rng(seed, run_index);
                let record = run(&cell.config, &mut || StandardNormal.sample(&mut rng))?;
                Ok(CellRun {
                    record,
                    seconds: started.elapsed().as_secs_f64(),
                })
            })
            .collect()
    }

    fn start(&self, s: &Setup, _count: u64) -> Result<Vec<CellSums>, ScenarioError> {
        Ok(s.cells
            .iter()
            .map(|_| CellSums {
                sums: SummarySums::new(),
                plots: 0,
                seconds: -0.0,
            })
            .collect())
    }

    fn add(
        &self,
        _s: &Setup,
        sums: &mut Vec<CellSums>,
        run: Vec<CellRun>,
    ) -> Result<(), ScenarioError> {
        for (acc, cell) in sums.iter_mut().zip(&run) {
            acc.sums.add(&cell.record);
            acc.plots += cell.record.plots;
            acc.seconds += cell.seconds;
        }
        Ok(())
    }

    fn finish(&self, s: &Setup, sums: Vec<CellSums>) -> Result<Report, ScenarioError> {
        if s.sweep {
            return sweep_report(s, &sums);
        }
        let (Some(cell), Some(acc)) = (s.cells.first(), sums.first()) else {
            return Err(ScenarioError::Degenerate {
                scenario: "bias-32",
                message: "no (sensors, targets) cell".into(),
            });
        };
        let summary = acc.sums.finish(cell.config.sensors.len())?;
        single_report(&cell.config, &summary, acc.plots, acc.seconds)
    }
}

/// The sweep over every (sensors, targets) combination: per combination its computing
/// time per plot and its final bias RMSE, from the runs' records.
fn sweep_report(s: &Setup, sums: &[CellSums]) -> Result<Report, ScenarioError> {
    let mut rows = Vec::new();
    let mut table = Vec::new();
    for (cell, acc) in s.cells.iter().zip(sums) {
        {
            let (s_count, n, c) = (cell.sensors, cell.targets, &cell.config);
            let (plots, elapsed) = (acc.plots, acc.seconds);
            let sum = acc.sums.finish(s_count)?;
            let cost = elapsed / plots.max(1) as f64 * 1e6;
            let tag = format!("s{s_count}_n{n}");
            let what = format!("S={s_count}, N={n}");
            let note = format!("{} runs, {plots} plots, t = {} s", sum.runs, c.duration);
            rows.push(
                Row::new(
                    format!("sweep_{tag}_cost_per_plot"),
                    format!("run time per plot (runs summed), {what}"),
                    cost,
                    "us",
                )
                .note(note.clone()),
            );
            let last = |v: &Vec<[f64; 4]>| v.last().copied().unwrap_or([f64::NAN; 4]);
            let (p, e) = (last(&sum.proposed_rmse), last(&sum.exx_rmse));
            for (k, name) in COMPONENTS.iter().enumerate() {
                rows.push(
                    Row::new(
                        format!("sweep_{tag}_{}_rmse", name.replace(' ', "_")),
                        format!("final {name} RMSE, proposed, {what}"),
                        p[k],
                        UNITS[k],
                    )
                    .note(note.clone()),
                );
            }
            let mut line = vec![s_count as f64, n as f64, plots as f64, cost];
            line.extend(p);
            line.extend(e);
            table.push(line);
        }
    }
    let mut columns: Vec<String> = ["sensors", "targets", "plots", "us_per_plot"]
        .iter()
        .map(|x| (*x).to_owned())
        .collect();
    for m in ["proposed", "exx"] {
        for n in ["br", "bth", "er", "eth"] {
            columns.push(format!("{m}_{n}_final"));
        }
    }
    Ok(Report {
        rows,
        series: vec![Series {
            name: "sweep".into(),
            columns,
            rows: table,
        }],
        figures: Vec::new(),
        notes: vec![
            "Sweep: one campaign per (sensors, targets); sensors at (10 km·s, 0) with offsets s/S s, targets on the 8-column grid continued upward (rows 10 km apart).".to_owned(),
            "Run time per plot includes the local filters, the pseudo-measurement update and EXX (exx=1): each run's own wall time (one thread), summed over the runs, per plot (with one run per combination: its wall time).".to_owned(),
            "summary.json `params` holds the first value of each list; sweep.csv lists every combination (EXX columns NaN when exx=0).".to_owned(),
        ],
    })
}

//! The drag-bearing Monte Carlo statistics: per-plot RMS position and range error, the
//! detections and the final input error of each filter over the runs.

use argus_adaptive::AdaptiveError;

use super::experiment::{DragBearingConfig, DragFilter, DragRun};

/// Monte Carlo statistics over runs.
#[derive(Debug, Clone, PartialEq)]
pub struct McSummary {
    /// Plot times, s.
    pub times: Vec<f64>,
    /// Per filter, per plot: RMS position error over runs, m.
    pub rms_position: [Vec<f64>; 4],
    /// Per filter, per plot: RMS range error over runs, m.
    pub rms_range: [Vec<f64>; 4],
    /// Per filter: detections before the turn, summed over runs.
    pub false_detections: [usize; 4],
    /// Per filter: the first detection after the turn minus the turn time, per run
    /// (`None` when none came).
    pub delays: [Vec<Option<f64>>; 4],
    /// Per filter: the number of runs in which a step failed.
    pub failures: [usize; 4],
    /// Per filter: RMS over runs of the final input-estimate error `|û − Δu|`, m/s²
    /// (runs without an input estimate at the end count `|Δu|`).
    pub final_input_rms: [f64; 4],
    /// Runs reduced.
    pub runs: usize,
}

impl McSummary {
    /// Reduces `runs` (all from the same configuration `cfg`).
    ///
    /// # Errors
    /// [`AdaptiveError::InvalidParameter`] when `runs` is empty or the runs differ in length.
    pub fn from_runs(cfg: &DragBearingConfig, runs: &[DragRun]) -> Result<Self, AdaptiveError> {
        let first = runs.first().ok_or(AdaptiveError::InvalidParameter {
            what: "runs",
            value: 0.0,
            reason: "no run to reduce",
        })?;
        let len = first.times.len();
        if runs
            .iter()
            .any(|r| r.times.len() != len || r.estimates.iter().any(|e| e.len() != len))
        {
            return Err(AdaptiveError::InvalidParameter {
                what: "runs",
                value: runs.len() as f64,
                reason: "runs of different lengths",
            });
        }
        let n = runs.len() as f64;
        let du = cfg.thrust_after() - cfg.thrust_before();
        let per_time = |g: &dyn Fn(&DragRun, usize) -> Option<f64>| -> Vec<f64> {
            (0..len)
                .map(|k| {
                    let s: f64 = runs
                        .iter()
                        .map(|r| g(r, k).map_or(f64::NAN, |e| e * e))
                        .sum();
                    (s / n).sqrt()
                })
                .collect()
        };
        let rms_position =
            DragFilter::ALL.map(|f| per_time(&|r: &DragRun, k| r.position_error(f, k)));
        let rms_range = DragFilter::ALL.map(|f| per_time(&|r: &DragRun, k| r.range_error(f, k)));
        let turn = cfg.turn_time;
        let false_detections = DragFilter::ALL.map(|f| {
            runs.iter()
                .map(|r| {
                    r.detections[f.index()]
                        .iter()
                        .filter(|&&k| r.times.get(k).is_some_and(|&t| t <= turn + 1e-9))
                        .count()
                })
                .sum()
        });
        let delays = DragFilter::ALL.map(|f| {
            runs.iter()
                .map(|r| {
                    r.detections[f.index()]
                        .iter()
                        .filter_map(|&k| r.times.get(k))
                        .find(|&&t| t > turn + 1e-9)
                        .map(|t| t - turn)
                })
                .collect()
        });
        let failures = DragFilter::ALL.map(|f| {
            runs.iter()
                .filter(|r| r.failed_at[f.index()].is_some())
                .count()
        });
        let final_input_rms = DragFilter::ALL.map(|f| {
            let s: f64 = runs
                .iter()
                .map(|r| {
                    r.final_input[f.index()]
                        .map_or(du, |u| u - du)
                        .norm_squared()
                })
                .sum();
            (s / n).sqrt()
        });
        Ok(Self {
            times: first.times.clone(),
            rms_position,
            rms_range,
            false_detections,
            delays,
            failures,
            final_input_rms,
            runs: runs.len(),
        })
    }

    /// Root of the time mean of the squared RMS position error of `filter` over plots with
    /// `t ∈ [from, to]`, m.
    #[must_use]
    pub fn time_rms_position(&self, filter: DragFilter, from: f64, to: f64) -> f64 {
        time_rms(&self.times, &self.rms_position[filter.index()], from, to)
    }

    /// As [`McSummary::time_rms_position`] for the range error, m.
    #[must_use]
    pub fn time_rms_range(&self, filter: DragFilter, from: f64, to: f64) -> f64 {
        time_rms(&self.times, &self.rms_range[filter.index()], from, to)
    }

    /// Mean detection delay after the turn over the runs that detected it, s (NaN if none).
    #[must_use]
    pub fn mean_delay(&self, filter: DragFilter) -> f64 {
        let d: Vec<f64> = self.delays[filter.index()]
            .iter()
            .flatten()
            .copied()
            .collect();
        d.iter().sum::<f64>() / d.len() as f64
    }

    /// Runs in which the turn was not detected.
    #[must_use]
    pub fn missed(&self, filter: DragFilter) -> usize {
        self.delays[filter.index()]
            .iter()
            .filter(|d| d.is_none())
            .count()
    }
}

fn time_rms(times: &[f64], rms: &[f64], from: f64, to: f64) -> f64 {
    let (s, c) = times
        .iter()
        .zip(rms)
        .filter(|(t, _)| **t >= from - 1e-9 && **t <= to + 1e-9)
        .fold((0.0, 0usize), |(s, c), (_, e)| (s + e * e, c + 1));
    (s / c as f64).sqrt()
}

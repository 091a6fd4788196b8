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
    /// Per filter: Σ over the runs that detected the turn of the first detection after it
    /// minus the turn time, s (in run order).
    pub delay_sum: [f64; 4],
    /// Per filter: the runs that detected the turn.
    pub detected: [usize; 4],
    /// Per filter: the longest of those delays, s (−∞ when none).
    pub delay_max: [f64; 4],
    /// Per filter: the number of runs in which a step failed.
    pub failures: [usize; 4],
    /// Per filter: RMS over runs of the final input-estimate error `|û − Δu|`, m/s²
    /// (runs without an input estimate at the end count `|Δu|`).
    pub final_input_rms: [f64; 4],
    /// Runs reduced.
    pub runs: usize,
}

/// The statistics accumulated one run at a time, in run order: per-plot sums of the
/// squared errors and per-filter counts and sums, never a run's series, so that reducing
/// any number of runs holds the same numbers. Each sum adds the same values in the same
/// order as a pass over all the runs (starting at −0.0, as `Iterator::sum` does).
#[derive(Debug, Clone, PartialEq)]
pub struct McSums {
    cfg: DragBearingConfig,
    times: Vec<f64>,
    runs: usize,
    /// A run of another length than the first.
    ragged: bool,
    pos_sq: [Vec<f64>; 4],
    range_sq: [Vec<f64>; 4],
    false_detections: [usize; 4],
    delay_sum: [f64; 4],
    detected: [usize; 4],
    delay_max: [f64; 4],
    failures: [usize; 4],
    input_sq: [f64; 4],
}

impl McSums {
    /// No run yet, for runs of configuration `cfg`.
    #[must_use]
    pub fn new(cfg: &DragBearingConfig) -> Self {
        Self {
            cfg: *cfg,
            times: Vec::new(),
            runs: 0,
            ragged: false,
            pos_sq: std::array::from_fn(|_| Vec::new()),
            range_sq: std::array::from_fn(|_| Vec::new()),
            false_detections: [0; 4],
            delay_sum: [-0.0; 4],
            detected: [0; 4],
            delay_max: [f64::NEG_INFINITY; 4],
            failures: [0; 4],
            input_sq: [-0.0; 4],
        }
    }

    /// Adds the next run.
    pub fn add(&mut self, r: &DragRun) {
        if self.runs == 0 {
            self.times.clone_from(&r.times);
            let len = r.times.len();
            self.pos_sq = std::array::from_fn(|_| vec![-0.0; len]);
            self.range_sq = std::array::from_fn(|_| vec![-0.0; len]);
        }
        self.runs += 1;
        let len = self.times.len();
        if r.times.len() != len || r.estimates.iter().any(|e| e.len() != len) {
            self.ragged = true;
        }
        if self.ragged {
            return;
        }
        let sq = |e: Option<f64>| e.map_or(f64::NAN, |e| e * e);
        let turn = self.cfg.turn_time;
        let du = self.cfg.thrust_after() - self.cfg.thrust_before();
        for f in DragFilter::ALL {
            let i = f.index();
            for k in 0..len {
                self.pos_sq[i][k] += sq(r.position_error(f, k));
                self.range_sq[i][k] += sq(r.range_error(f, k));
            }
            self.false_detections[i] += r.detections[i]
                .iter()
                .filter(|&&k| r.times.get(k).is_some_and(|&t| t <= turn + 1e-9))
                .count();
            let delay = r.detections[i]
                .iter()
                .filter_map(|&k| r.times.get(k))
                .find(|&&t| t > turn + 1e-9)
                .map(|t| t - turn);
            if let Some(d) = delay {
                self.delay_sum[i] += d;
                self.detected[i] += 1;
                self.delay_max[i] = self.delay_max[i].max(d);
            }
            if r.failed_at[i].is_some() {
                self.failures[i] += 1;
            }
            self.input_sq[i] += r.final_input[i].map_or(du, |u| u - du).norm_squared();
        }
    }

    /// How many numbers the sums hold (8 per plot and a fixed few, whatever the runs).
    #[must_use]
    pub fn retained(&self) -> usize {
        self.times.len() + 8 * self.times.len() + 7 * 4 + 2
    }

    /// The statistics of the runs added.
    ///
    /// # Errors
    /// [`AdaptiveError::InvalidParameter`] when no run was added or the runs differ in
    /// length.
    pub fn finish(&self) -> Result<McSummary, AdaptiveError> {
        if self.runs == 0 {
            return Err(AdaptiveError::InvalidParameter {
                what: "runs",
                value: 0.0,
                reason: "no run to reduce",
            });
        }
        if self.ragged {
            return Err(AdaptiveError::InvalidParameter {
                what: "runs",
                value: self.runs as f64,
                reason: "runs of different lengths",
            });
        }
        let n = self.runs as f64;
        let rms = |v: &Vec<f64>| v.iter().map(|s| (s / n).sqrt()).collect::<Vec<f64>>();
        Ok(McSummary {
            times: self.times.clone(),
            rms_position: self.pos_sq.each_ref().map(rms),
            rms_range: self.range_sq.each_ref().map(rms),
            false_detections: self.false_detections,
            delay_sum: self.delay_sum,
            detected: self.detected,
            delay_max: self.delay_max,
            failures: self.failures,
            final_input_rms: self.input_sq.map(|s| (s / n).sqrt()),
            runs: self.runs,
        })
    }
}

impl McSummary {
    /// Reduces `runs` (all from the same configuration `cfg`): a fold through [`McSums`].
    ///
    /// # Errors
    /// [`AdaptiveError::InvalidParameter`] when `runs` is empty or the runs differ in length.
    pub fn from_runs(cfg: &DragBearingConfig, runs: &[DragRun]) -> Result<Self, AdaptiveError> {
        let mut sums = McSums::new(cfg);
        for r in runs {
            sums.add(r);
        }
        sums.finish()
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
        self.delay_sum[filter.index()] / self.detected[filter.index()] as f64
    }

    /// Runs in which the turn was not detected.
    #[must_use]
    pub fn missed(&self, filter: DragFilter) -> usize {
        self.runs - self.detected[filter.index()]
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

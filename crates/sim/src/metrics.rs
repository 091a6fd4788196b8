//! Metrics over Monte Carlo runs: RMSE per time step, ANEES and ANIS with their 95 %
//! chi-square intervals, time averages after a warm-up share, and track losses.

use argus_core_math::{Gaussian, Vector, anees_interval};
use serde::{Deserialize, Serialize};

use crate::error::{SimError, probability};

/// One time step of one run: squared errors and consistency statistics.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StepRecord {
    /// Time (s).
    pub time: f64,
    /// Squared position error `‖p̂ − p‖²` (m²).
    pub pos_err_sq: f64,
    /// Squared velocity error `‖v̂ − v‖²` (m²/s²).
    pub vel_err_sq: f64,
    /// NEES `(x̂ − x)ᵀ P⁻¹ (x̂ − x)`, when an estimate exists.
    pub nees: Option<f64>,
    /// NIS `νᵀ S⁻¹ ν` of the plot used at this step, when there was one.
    pub nis: Option<f64>,
}

impl StepRecord {
    /// The record of a 2-D estimate (`[x, vx, y, vy]`) against the true state, with the NIS
    /// of the step's update if any.
    #[must_use]
    pub fn from_estimate_2d(
        time: f64,
        estimate: &Gaussian<4>,
        truth: &Vector<4>,
        nis: Option<f64>,
    ) -> Self {
        let e = estimate.mean() - truth;
        Self {
            time,
            pos_err_sq: e[0] * e[0] + e[2] * e[2],
            vel_err_sq: e[1] * e[1] + e[3] * e[3],
            nees: Some(estimate.mahalanobis_sq(truth)),
            nis,
        }
    }

    /// The record of a 3-D estimate (`[x, vx, y, vy, z, vz]`).
    #[must_use]
    pub fn from_estimate_3d(
        time: f64,
        estimate: &Gaussian<6>,
        truth: &Vector<6>,
        nis: Option<f64>,
    ) -> Self {
        let e = estimate.mean() - truth;
        Self {
            time,
            pos_err_sq: e[0] * e[0] + e[2] * e[2] + e[4] * e[4],
            vel_err_sq: e[1] * e[1] + e[3] * e[3] + e[5] * e[5],
            nees: Some(estimate.mahalanobis_sq(truth)),
            nis,
        }
    }
}

/// One run's record: its steps (the same time grid in every run) and whether the track
/// was lost (by the scenario's own criterion).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunRecord {
    /// The steps, in time order.
    pub steps: Vec<StepRecord>,
    /// Whether the track was lost. Lost runs are counted, and left out of every average.
    pub lost: bool,
}

/// Per-time-step metrics over runs.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StepMetrics {
    /// Time (s), from the first kept run.
    pub time: f64,
    /// RMS position error (m): `sqrt(mean over runs of ‖p̂ − p‖²)`.
    pub rmse_pos: f64,
    /// RMS velocity error (m/s).
    pub rmse_vel: f64,
    /// Average NEES over the runs that have one; `None` if none has.
    pub anees: Option<f64>,
    /// Average NIS over the runs with an update at this step.
    pub anis: Option<f64>,
    /// Runs averaged for ANEES.
    pub nees_runs: usize,
    /// Runs averaged for ANIS.
    pub nis_runs: usize,
}

/// Metrics of a campaign.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Metrics {
    /// Per-step metrics.
    pub steps: Vec<StepMetrics>,
    /// Runs reduced.
    pub runs: usize,
    /// Runs whose track was lost (left out of every average).
    pub lost: usize,
    /// State dimension (the NEES degrees of freedom).
    pub state_dim: usize,
    /// Measurement dimension (the NIS degrees of freedom).
    pub meas_dim: usize,
    /// Index of the first step in the time averages (`ceil(warmup · steps)`).
    pub first_averaged_step: usize,
    /// RMS position error over runs and the steps after warm-up (m):
    /// `sqrt(mean of ‖p̂ − p‖²)`.
    pub avg_rmse_pos: f64,
    /// RMS velocity error over runs and the steps after warm-up (m/s).
    pub avg_rmse_vel: f64,
    /// ANEES over runs and the steps after warm-up; `None` without NEES values.
    pub avg_anees: Option<f64>,
    /// ANIS over runs and the steps after warm-up.
    pub avg_anis: Option<f64>,
    /// 95 % interval of a per-step ANEES over the kept runs: `χ²_{n·N}(0.025, 0.975)/N`.
    pub anees_interval: Option<Interval>,
    /// 95 % interval of a per-step ANIS.
    pub anis_interval: Option<Interval>,
    /// 95 % interval of the time-averaged ANEES (`n · N · K` degrees of freedom over `N · K`
    /// values, treating steps as independent, which they are not exactly: indicative).
    pub avg_anees_interval: Option<Interval>,
}

/// A two-sided acceptance interval `[lower, upper]`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Interval {
    /// Lower bound.
    pub lower: f64,
    /// Upper bound.
    pub upper: f64,
}

impl Interval {
    /// Whether `x` lies inside `[lower, upper]`.
    #[must_use]
    pub fn contains(&self, x: f64) -> bool {
        x >= self.lower && x <= self.upper
    }
}

/// The per-step sums over the kept runs.
#[derive(Debug, Clone, Copy, PartialEq)]
struct StepSums {
    /// Time of the first kept run's step.
    time: f64,
    pos: f64,
    vel: f64,
    nees: f64,
    nees_runs: usize,
    nis: f64,
    nis_runs: usize,
    runs: usize,
}

/// `(Σ, count)`.
type Pooled = (f64, usize);

fn pool(acc: &mut Pooled, x: f64) {
    acc.0 += x;
    acc.1 += 1;
}

fn pooled_mean(p: Pooled) -> Option<f64> {
    (p.1 > 0).then(|| p.0 / p.1 as f64)
}

/// [`Metrics`] accumulated one run at a time, in run order: per-step sums and the
/// pooled sums of the time averages, so that reducing any number of runs holds a few
/// numbers per step and none per run. Each sum adds the same values in the same order
/// as [`Metrics::from_runs`] over all the runs, which is a fold over this.
#[derive(Debug, Clone, PartialEq)]
pub struct MetricsSums {
    state_dim: usize,
    meas_dim: usize,
    warmup: f64,
    runs: usize,
    lost: usize,
    /// The first run's step count (the grid every run must share).
    steps_per_run: Option<usize>,
    first_averaged_step: usize,
    /// The first run of another step count: `(index, steps)`.
    ragged: Option<(usize, usize)>,
    steps: Vec<StepSums>,
    tail_pos: Pooled,
    tail_vel: Pooled,
    tail_nees: Pooled,
    tail_nis: Pooled,
}

impl MetricsSums {
    /// Empty sums; `warmup` as in [`Metrics::from_runs`] (checked by
    /// [`MetricsSums::finish`]).
    #[must_use]
    pub fn new(state_dim: usize, meas_dim: usize, warmup: f64) -> Self {
        Self {
            state_dim,
            meas_dim,
            warmup,
            runs: 0,
            lost: 0,
            steps_per_run: None,
            first_averaged_step: 0,
            ragged: None,
            steps: Vec::new(),
            tail_pos: (0.0, 0),
            tail_vel: (0.0, 0),
            tail_nees: (0.0, 0),
            tail_nis: (0.0, 0),
        }
    }

    /// Adds the next run.
    pub fn add(&mut self, run: &RunRecord) {
        self.add_steps(run.lost, &run.steps);
    }

    /// Adds the next run given as its steps and whether its track was lost.
    pub fn add_steps(&mut self, lost: bool, steps: &[StepRecord]) {
        let index = self.runs;
        self.runs += 1;
        let k = *self.steps_per_run.get_or_insert_with(|| {
            self.first_averaged_step = ((self.warmup.clamp(0.0, 1.0) * steps.len() as f64).ceil()
                as usize)
                .min(steps.len());
            steps.len()
        });
        if self.steps.is_empty() {
            // Sized by the first run, so that the sums hold as much after one run as after
            // any number; the times are the first kept run's.
            self.steps = vec![
                StepSums {
                    time: f64::NAN,
                    pos: 0.0,
                    vel: 0.0,
                    nees: 0.0,
                    nees_runs: 0,
                    nis: 0.0,
                    nis_runs: 0,
                    runs: 0,
                };
                k
            ];
        }
        if steps.len() != k {
            self.ragged.get_or_insert((index, steps.len()));
        }
        if lost {
            self.lost += 1;
        }
        if lost || self.ragged.is_some() {
            return;
        }
        if self.lost + 1 == self.runs {
            // The first kept run.
            for (acc, s) in self.steps.iter_mut().zip(steps) {
                acc.time = s.time;
            }
        }
        for (acc, s) in self.steps.iter_mut().zip(steps) {
            acc.pos += s.pos_err_sq;
            acc.vel += s.vel_err_sq;
            acc.runs += 1;
            if let Some(v) = s.nees {
                acc.nees += v;
                acc.nees_runs += 1;
            }
            if let Some(v) = s.nis {
                acc.nis += v;
                acc.nis_runs += 1;
            }
        }
        for s in steps.iter().skip(self.first_averaged_step) {
            pool(&mut self.tail_pos, s.pos_err_sq);
            pool(&mut self.tail_vel, s.vel_err_sq);
            if let Some(v) = s.nees {
                pool(&mut self.tail_nees, v);
            }
            if let Some(v) = s.nis {
                pool(&mut self.tail_nis, v);
            }
        }
    }

    /// How many numbers the sums hold: 8 per step plus a fixed few, whatever the number
    /// of runs added.
    #[must_use]
    pub fn retained(&self) -> usize {
        8 * self.steps.len() + 16
    }

    /// The metrics of the runs added.
    ///
    /// # Errors
    /// As [`Metrics::from_runs`]: [`SimError::InvalidParameter`] for `warmup ∉ [0, 1]`,
    /// [`SimError::Empty`] with no run or no kept run, [`SimError::RaggedRuns`] when runs
    /// have different step counts.
    pub fn finish(&self) -> Result<Metrics, SimError> {
        probability("warm-up share", self.warmup)?;
        let Some(k) = self.steps_per_run else {
            return Err(SimError::Empty { what: "run" });
        };
        if let Some((run, got)) = self.ragged {
            return Err(SimError::RaggedRuns {
                first: 0,
                run,
                expected: k,
                got,
            });
        }
        let n = self.runs - self.lost;
        if n == 0 {
            return Err(SimError::Empty {
                what: "run that kept its track",
            });
        }
        let interval = |dim: usize, count: usize| {
            if dim == 0 || count == 0 {
                Ok(None)
            } else {
                anees_interval(dim, count, 0.95).map(|iv| {
                    Some(Interval {
                        lower: iv.lower,
                        upper: iv.upper,
                    })
                })
            }
        };
        let steps = self
            .steps
            .iter()
            .map(|s| {
                let mean = |sum: f64, count: usize| pooled_mean((sum, count));
                StepMetrics {
                    time: if s.runs > 0 { s.time } else { f64::NAN },
                    rmse_pos: mean(s.pos, s.runs).unwrap_or(0.0).sqrt(),
                    rmse_vel: mean(s.vel, s.runs).unwrap_or(0.0).sqrt(),
                    anees: mean(s.nees, s.nees_runs),
                    anis: mean(s.nis, s.nis_runs),
                    nees_runs: s.nees_runs,
                    nis_runs: s.nis_runs,
                }
            })
            .collect();
        Ok(Metrics {
            runs: self.runs,
            lost: self.lost,
            state_dim: self.state_dim,
            meas_dim: self.meas_dim,
            first_averaged_step: self.first_averaged_step,
            avg_rmse_pos: pooled_mean(self.tail_pos).unwrap_or(f64::NAN).sqrt(),
            avg_rmse_vel: pooled_mean(self.tail_vel).unwrap_or(f64::NAN).sqrt(),
            avg_anees: pooled_mean(self.tail_nees),
            avg_anis: pooled_mean(self.tail_nis),
            anees_interval: interval(self.state_dim, n)?,
            anis_interval: interval(self.meas_dim, n)?,
            avg_anees_interval: interval(self.state_dim, self.tail_nees.1)?,
            steps,
        })
    }
}

impl Metrics {
    /// Reduces runs (in the order given, so the result is independent of how they were
    /// computed) into per-step and time-averaged metrics. `warmup` is the share of steps
    /// excluded from the time averages (seed 000 excludes the first 25 %). A fold of the
    /// runs through [`MetricsSums`].
    ///
    /// # References
    /// NEES, NIS, their averages and chi-square intervals: Bar-Shalom, Li & Kirubarajan
    /// (2001), §5.4.2 and §11.2.2.
    ///
    /// # Errors
    /// [`SimError::Empty`] with no run or no kept run, [`SimError::RaggedRuns`] when runs
    /// have different step counts, [`SimError::InvalidParameter`] for `warmup ∉ [0, 1]`.
    pub fn from_runs(
        runs: &[RunRecord],
        state_dim: usize,
        meas_dim: usize,
        warmup: f64,
    ) -> Result<Self, SimError> {
        let mut sums = MetricsSums::new(state_dim, meas_dim, warmup);
        for r in runs {
            sums.add(r);
        }
        sums.finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn step(t: f64, p: f64, v: f64, nees: f64) -> StepRecord {
        StepRecord {
            time: t,
            pos_err_sq: p,
            vel_err_sq: v,
            nees: Some(nees),
            nis: None,
        }
    }

    #[test]
    fn hand_computed_metrics() {
        // Two kept runs and one lost run, two steps. Hand values:
        // step 0 RMSE_pos = sqrt((9 + 16)/2) = sqrt(12.5); step 1 = sqrt((1 + 3)/2) = sqrt(2);
        // ANEES step 1 = (2 + 6)/2 = 4. With warm-up 0.5 only step 1 is averaged:
        // avg RMSE_pos = sqrt(2), avg ANEES = 4, avg RMSE_vel = sqrt((4 + 0)/2) = sqrt(2).
        let runs = vec![
            RunRecord {
                steps: vec![step(0.0, 9.0, 1.0, 1.0), step(1.0, 1.0, 4.0, 2.0)],
                lost: false,
            },
            RunRecord {
                steps: vec![step(0.0, 16.0, 1.0, 3.0), step(1.0, 3.0, 0.0, 6.0)],
                lost: false,
            },
            RunRecord {
                steps: vec![step(0.0, 1e9, 1e9, 1e9), step(1.0, 1e9, 1e9, 1e9)],
                lost: true,
            },
        ];
        let m = Metrics::from_runs(&runs, 4, 2, 0.5).unwrap();
        assert_eq!(m.lost, 1);
        assert_eq!(m.first_averaged_step, 1);
        assert!((m.steps[0].rmse_pos - 12.5f64.sqrt()).abs() < 1e-12);
        assert!((m.steps[1].rmse_pos - 2f64.sqrt()).abs() < 1e-12);
        assert!((m.steps[1].anees.unwrap() - 4.0).abs() < 1e-12);
        assert!((m.avg_rmse_pos - 2f64.sqrt()).abs() < 1e-12);
        assert!((m.avg_rmse_vel - 2f64.sqrt()).abs() < 1e-12);
        assert!((m.avg_anees.unwrap() - 4.0).abs() < 1e-12);
        assert!(m.avg_anis.is_none());
        // Per-step interval over N = 2 kept runs of a 4-dim NEES: χ²₈(0.025)/2, χ²₈(0.975)/2
        // = 2.17973/2, 17.5345/2 (chi-square table, 8 dof).
        let iv = m.anees_interval.unwrap();
        assert!((iv.lower - 2.179_731 / 2.0).abs() < 1e-5, "{iv:?}");
        assert!((iv.upper - 17.534_546 / 2.0).abs() < 1e-5, "{iv:?}");
    }

    #[test]
    fn sums_hold_the_same_numbers_whatever_the_runs() {
        // A lost first run sizes the sums; the times come from the first kept run (1.5,
        // 2.5), and the metrics equal those of the same runs in another order of the lost
        // one (lost runs are left out of every sum).
        let lost = RunRecord {
            steps: vec![step(0.0, 1e9, 1e9, 1e9), step(1.0, 1e9, 1e9, 1e9)],
            lost: true,
        };
        let kept = |p: f64| RunRecord {
            steps: vec![step(1.5, p, 1.0, 2.0), step(2.5, p, 1.0, 4.0)],
            lost: false,
        };
        let mut sums = MetricsSums::new(4, 2, 0.5);
        sums.add(&lost);
        let after_one = sums.retained();
        for p in [1.0, 2.0, 3.0] {
            sums.add(&kept(p));
        }
        // Tolerance: none — the sums are sized by the first run's two steps.
        assert_eq!(sums.retained(), after_one);
        let m = sums.finish().unwrap();
        assert_eq!(m.steps[0].time.to_bits(), 1.5f64.to_bits());
        assert_eq!(m.lost, 1);
        let other = Metrics::from_runs(&[kept(1.0), kept(2.0), lost, kept(3.0)], 4, 2, 0.5);
        let other = other.unwrap();
        assert_eq!(format!("{:?}", m.steps), format!("{:?}", other.steps));
        assert_eq!(m.avg_rmse_pos.to_bits(), other.avg_rmse_pos.to_bits());
    }

    #[test]
    fn rejects_ragged_and_empty() {
        let a = RunRecord {
            steps: vec![step(0.0, 1.0, 1.0, 1.0)],
            lost: false,
        };
        let b = RunRecord {
            steps: vec![],
            lost: false,
        };
        assert!(matches!(
            Metrics::from_runs(&[a.clone(), b], 4, 2, 0.0),
            Err(SimError::RaggedRuns { run: 1, .. })
        ));
        assert!(matches!(
            Metrics::from_runs(&[], 4, 2, 0.0),
            Err(SimError::Empty { .. })
        ));
        assert!(Metrics::from_runs(&[a], 4, 2, 1.5).is_err());
    }
}

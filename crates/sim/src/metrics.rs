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

fn mean(xs: impl Iterator<Item = f64>) -> Option<f64> {
    let (s, n) = xs.fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    (n > 0).then(|| s / n as f64)
}

impl Metrics {
    /// Reduces runs (in the order given, so the result is independent of how they were
    /// computed) into per-step and time-averaged metrics. `warmup` is the share of steps
    /// excluded from the time averages (seed 000 excludes the first 25 %).
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
        probability("warm-up share", warmup)?;
        let first = runs.first().ok_or(SimError::Empty { what: "run" })?;
        let k = first.steps.len();
        for (i, r) in runs.iter().enumerate() {
            if r.steps.len() != k {
                return Err(SimError::RaggedRuns {
                    first: 0,
                    run: i,
                    expected: k,
                    got: r.steps.len(),
                });
            }
        }
        let kept: Vec<&RunRecord> = runs.iter().filter(|r| !r.lost).collect();
        let lost = runs.len() - kept.len();
        if kept.is_empty() {
            return Err(SimError::Empty {
                what: "run that kept its track",
            });
        }
        let n = kept.len();
        let steps: Vec<StepMetrics> = (0..k)
            .map(|j| {
                let at = |r: &&RunRecord| r.steps.get(j).copied();
                let recs: Vec<StepRecord> = kept.iter().filter_map(at).collect();
                let nees: Vec<f64> = recs.iter().filter_map(|s| s.nees).collect();
                let nis: Vec<f64> = recs.iter().filter_map(|s| s.nis).collect();
                StepMetrics {
                    time: recs.first().map_or(f64::NAN, |s| s.time),
                    rmse_pos: mean(recs.iter().map(|s| s.pos_err_sq))
                        .unwrap_or(0.0)
                        .sqrt(),
                    rmse_vel: mean(recs.iter().map(|s| s.vel_err_sq))
                        .unwrap_or(0.0)
                        .sqrt(),
                    anees: mean(nees.iter().copied()),
                    anis: mean(nis.iter().copied()),
                    nees_runs: nees.len(),
                    nis_runs: nis.len(),
                }
            })
            .collect();
        let first_averaged_step = ((warmup * k as f64).ceil() as usize).min(k);
        let tail = || {
            kept.iter()
                .flat_map(|r| r.steps.iter().skip(first_averaged_step))
        };
        let avg_nees_values = tail().filter_map(|s| s.nees).count();
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
        Ok(Self {
            runs: runs.len(),
            lost,
            state_dim,
            meas_dim,
            first_averaged_step,
            avg_rmse_pos: mean(tail().map(|s| s.pos_err_sq))
                .unwrap_or(f64::NAN)
                .sqrt(),
            avg_rmse_vel: mean(tail().map(|s| s.vel_err_sq))
                .unwrap_or(f64::NAN)
                .sqrt(),
            avg_anees: mean(tail().filter_map(|s| s.nees)),
            avg_anis: mean(tail().filter_map(|s| s.nis)),
            anees_interval: interval(state_dim, n)?,
            anis_interval: interval(meas_dim, n)?,
            avg_anees_interval: interval(state_dim, avg_nees_values)?,
            steps,
        })
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

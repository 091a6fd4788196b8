//! What the real-traffic report needs of the runs, accumulated one run at a time in run
//! order: per configuration the sums behind the table's means, and per grid time the
//! sums behind the completeness and GOSPA curves; the first run's map points. Never a
//! run's record beyond the first's map, so that reducing any number of runs holds the
//! same numbers. Each sum adds the same values in the same order as a pass over all the
//! records would (the means of present values start at 0.0, the plain sums at −0.0, as
//! they always did).

use super::setup::{ConfigScore, RealRun};
use crate::campaign::{Footprint, Retained};

/// `(Σ, count)` of the present values.
pub(super) type Present = (f64, usize);

fn present(acc: &mut Present, v: Option<f64>) {
    if let Some(v) = v {
        acc.0 += v;
        acc.1 += 1;
    }
}

/// The mean of the present values (`None` when none was).
pub(super) fn mean(p: Present) -> Option<f64> {
    (p.1 > 0).then(|| p.0 / p.1 as f64)
}

/// The table's optional values, in this order.
pub(super) const OPTIONAL: usize = 9;
fn optional(c: &ConfigScore) -> [Option<f64>; OPTIONAL] {
    [
        c.completeness,
        c.breaks_per_aircraft_hour,
        c.spurious_fraction,
        c.position_rmse,
        c.velocity_rmse,
        c.position_p95,
        c.time_to_confirm_mean,
        c.spurious_fraction_extended,
        c.smoothed_position_rmse,
    ]
}

/// The table's plain values, in this order.
pub(super) const PLAIN: usize = 7;
fn plain(c: &ConfigScore) -> [f64; PLAIN] {
    [
        c.id_swaps as f64,
        c.false_tracks_per_step,
        c.truths_never_tracked as f64,
        c.confirmed_tracks as f64,
        c.gospa_mean,
        c.gospa_missed_mean,
        c.gospa_false_mean,
    ]
}

/// One configuration's sums.
pub(super) struct ConfigSums {
    pub(super) optional: [Present; OPTIONAL],
    pub(super) plain: [f64; PLAIN],
    /// Per grid time: completeness (present values) and Σ GOSPA.
    pub(super) completeness: Vec<Present>,
    pub(super) gospa: Vec<f64>,
    /// Whether every run so far had this configuration.
    pub(super) complete: bool,
    /// Σ NEES against the smoothed truth and the rows it sums (issue 18).
    pub(super) nees_sum: f64,
    pub(super) nees_count: usize,
}

/// Every configuration's sums, the plot counts and the first run's grid and map.
pub(crate) struct RealSums {
    pub(super) runs: usize,
    pub(super) plots: f64,
    pub(super) target_plots: f64,
    pub(super) grid: Vec<f64>,
    pub(super) configs: Vec<ConfigSums>,
    pub(super) map_plots: Vec<(f64, f64)>,
    pub(super) map_tracks: Vec<(f64, f64)>,
}

impl RealSums {
    /// No run yet, for `configs` tracker configurations.
    pub(super) fn new(configs: usize) -> Self {
        Self {
            runs: 0,
            plots: -0.0,
            target_plots: -0.0,
            grid: Vec::new(),
            configs: (0..configs)
                .map(|_| ConfigSums {
                    optional: [(0.0, 0); OPTIONAL],
                    plain: [-0.0; PLAIN],
                    completeness: Vec::new(),
                    gospa: Vec::new(),
                    complete: true,
                    nees_sum: -0.0,
                    nees_count: 0,
                })
                .collect(),
            map_plots: Vec::new(),
            map_tracks: Vec::new(),
        }
    }

    /// Adds the next run.
    pub(super) fn add(&mut self, run: RealRun) {
        if self.runs == 0 {
            self.grid = run
                .configs
                .first()
                .map(|c| c.series.iter().map(|g| g.0).collect())
                .unwrap_or_default();
            for c in &mut self.configs {
                c.completeness = vec![(0.0, 0); self.grid.len()];
                c.gospa = vec![-0.0; self.grid.len()];
            }
            self.map_plots = run.map_plots;
            self.map_tracks = run.map_tracks;
        }
        self.runs += 1;
        self.plots += run.plots as f64;
        self.target_plots += run.target_plots as f64;
        for (i, acc) in self.configs.iter_mut().enumerate() {
            let Some(c) = run.configs.get(i) else {
                acc.complete = false;
                continue;
            };
            for (a, v) in acc.optional.iter_mut().zip(optional(c)) {
                present(a, v);
            }
            for (a, v) in acc.plain.iter_mut().zip(plain(c)) {
                *a += v;
            }
            acc.nees_sum += c.nees_sum;
            acc.nees_count += c.nees_count;
            for (k, (comp, gos)) in acc.completeness.iter_mut().zip(&mut acc.gospa).enumerate() {
                present(comp, c.series.get(k).and_then(|g| g.1));
                *gos += c.series.get(k).map_or(f64::NAN, |g| g.2);
            }
        }
    }
}

impl Retained for RealSums {
    fn footprint(&self) -> Footprint {
        Footprint {
            fixed: 3
                + self.grid.len()
                + 2 * (self.map_plots.len() + self.map_tracks.len())
                + self
                    .configs
                    .iter()
                    .map(|c| 2 * OPTIONAL + PLAIN + 3 * c.gospa.len() + 3)
                    .sum::<usize>(),
            per_run: 0,
        }
    }
}

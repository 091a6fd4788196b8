//! What the surveillance report needs of the runs, accumulated one run at a time in run
//! order: per configuration, per scan, the scores summed over the runs, and the pooled
//! and per-run sums of the table — never a run's record, so that reducing any number of
//! runs holds the same numbers. Each sum adds the same values in the same order as a
//! pass over all the records would (starting at −0.0, as `Iterator::sum` does).

use super::setup::{CONFIGS, ScanScore, Setup, SurvRun};
use crate::campaign::{Footprint, Retained};

/// The per-scan scores, in the order of the series' columns (then `confirmed`).
pub(super) const FIELDS: [&str; 8] = [
    "ospa",
    "gospa",
    "gospa_loc",
    "gospa_missed",
    "gospa_false",
    "missed",
    "false",
    "breaks",
];

/// A scan's [`FIELDS`] and its confirmed-track count, with GOSPA cut-off `c` and order `p`.
fn values(x: &ScanScore, c: f64, p: f64) -> [f64; 9] {
    [
        x.ospa,
        x.gospa,
        x.loc,
        x.missed as f64 * 0.5 * c.powf(p),
        x.false_tracks as f64 * 0.5 * c.powf(p),
        x.missed as f64,
        x.false_tracks as f64,
        x.breaks as f64,
        x.confirmed as f64,
    ]
}

/// One configuration's sums over the runs.
pub(super) struct ConfigSums {
    /// Per scan, Σ over the runs of [`values`] (0 for a scan a run lacks).
    pub(super) per_scan: Vec<[f64; 9]>,
    /// GOSPA localisation and assigned pairs, pooled over the runs and the scans after
    /// the warm-up.
    pub(super) loc_sum: f64,
    pub(super) assigned: usize,
    /// Σ and count of the times to confirm; targets never tracked.
    pub(super) ttc_sum: f64,
    pub(super) ttc_count: usize,
    pub(super) never: usize,
    /// Σ over the runs: false-track rate, false track ids, tracks seen, breaks, id swaps.
    pub(super) false_rate: f64,
    pub(super) false_ids: f64,
    pub(super) seen: f64,
    pub(super) breaks: f64,
    pub(super) id_swaps: f64,
    /// Whether every run so far had this configuration.
    pub(super) complete: bool,
}

/// Every configuration's sums.
pub(crate) struct SurvSums {
    pub(super) runs: usize,
    pub(super) configs: Vec<ConfigSums>,
}

impl SurvSums {
    /// No run yet.
    pub(super) fn new(s: &Setup) -> Self {
        Self {
            runs: 0,
            configs: CONFIGS
                .iter()
                .map(|_| ConfigSums {
                    per_scan: vec![[-0.0; 9]; s.scans],
                    loc_sum: 0.0,
                    assigned: 0,
                    ttc_sum: -0.0,
                    ttc_count: 0,
                    never: 0,
                    false_rate: -0.0,
                    false_ids: -0.0,
                    seen: -0.0,
                    breaks: -0.0,
                    id_swaps: -0.0,
                    complete: true,
                })
                .collect(),
        }
    }

    /// Adds the next run.
    pub(super) fn add(&mut self, s: &Setup, run: &SurvRun) {
        self.runs += 1;
        let (c, p) = (s.ospa.cutoff(), s.ospa.order());
        for (i, acc) in self.configs.iter_mut().enumerate() {
            let Some(r) = run.configs.get(i) else {
                acc.complete = false;
                continue;
            };
            for (k, sum) in acc.per_scan.iter_mut().enumerate() {
                let v = r.scans.get(k).map_or([0.0; 9], |x| values(x, c, p));
                for (a, x) in sum.iter_mut().zip(v) {
                    *a += x;
                }
            }
            for x in (0..s.scans)
                .filter(|&k| s.time(k) >= s.warmup)
                .filter_map(|k| r.scans.get(k))
            {
                acc.loc_sum += x.loc;
                acc.assigned += x.assigned;
            }
            for t in &r.time_to_confirm {
                match t {
                    Some(t) => {
                        acc.ttc_sum += t;
                        acc.ttc_count += 1;
                    }
                    None => acc.never += 1,
                }
            }
            acc.false_rate += r.false_tracks_per_scan;
            acc.false_ids += r.false_track_ids as f64;
            acc.seen += r.tracks_seen as f64;
            acc.breaks += r.breaks as f64;
            acc.id_swaps += r.id_swaps as f64;
        }
    }
}

impl Retained for SurvSums {
    fn footprint(&self) -> Footprint {
        Footprint {
            fixed: 1 + self
                .configs
                .iter()
                .map(|c| 9 * c.per_scan.len() + 11)
                .sum::<usize>(),
            per_run: 0,
        }
    }
}

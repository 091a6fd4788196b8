//! Scoring: sample truth and confirmed tracks on the grid, assign, and reduce.

use argus_sim::{TargetId, TrackScan, TrackStatistics};

use crate::assign;
use crate::config::{MAX_GRID_STEPS, Scorer};
use crate::error::ScoreError;
use crate::grid::{TrackCursor, TruthCursor};
use crate::input::{TrackHistory, TruthPath};
use crate::report::{GridPoint, Score, Summary, TruthScore};

/// Per-truth bookkeeping: presence, and segments (SIAP NU, TT, TL).
#[derive(Debug, Clone, Default)]
struct Segments {
    points: usize,
    assigned: usize,
    first: Option<f64>,
    last: f64,
    /// The open segment: (track, start time, grid index and time of its last point).
    open: Option<(usize, f64, usize, f64)>,
    count: usize,
    tracked: f64,
    longest: f64,
}

impl Segments {
    /// Extends the open segment with track `j` at grid index `k`, or opens a new one.
    fn on_assigned(&mut self, j: usize, k: usize, t: f64) {
        match &mut self.open {
            Some((tr, _, last_k, last_t)) if *tr == j && *last_k + 1 == k => {
                *last_k = k;
                *last_t = t;
            }
            _ => {
                self.close();
                self.open = Some((j, t, k, t));
            }
        }
    }

    /// Closes the open segment unless it was extended at grid index `k`.
    fn close_unless_at(&mut self, k: usize) {
        if matches!(self.open, Some((_, _, last_k, _)) if last_k != k) {
            self.close();
        }
    }

    /// Closes the open segment: one more segment, `last − start` of time tracked.
    fn close(&mut self) {
        if let Some((_, start, _, last)) = self.open.take() {
            let d = last - start;
            self.count += 1;
            self.tracked += d;
            self.longest = self.longest.max(d);
        }
    }
}

impl Scorer {
    /// Scores `tracks` against `truth` (see `docs/scoring.md` for every definition).
    ///
    /// # Errors
    /// [`ScoreError::NoTruth`] for an empty truth; [`ScoreError::GridTooLong`] for a grid
    /// of more than [`MAX_GRID_STEPS`] steps; [`ScoreError::Sim`] from the metric code
    /// (not expected with validated input).
    pub fn score(&self, tracks: &[TrackHistory], truth: &[TruthPath]) -> Result<Score, ScoreError> {
        let cfg = &self.config;
        let (lo, hi) = truth
            .iter()
            .flat_map(|p| [p.samples()[0].t, p.samples()[p.samples().len() - 1].t])
            .fold(None, |acc: Option<(f64, f64)>, t| {
                Some(acc.map_or((t, t), |(a, b)| (a.min(t), b.max(t))))
            })
            .ok_or_else(|| ScoreError::NoTruth {
                file: "(truth given in code)".to_string(),
            })?;
        let start = cfg.start.unwrap_or(lo);
        let end = cfg.end.unwrap_or(hi).max(start);
        let span = end - start;
        // 1e-9 relative slack so that an end on the grid is included despite round-off.
        let steps = (span / cfg.step * (1.0 + 1e-12) + 1e-9).floor() + 1.0;
        if steps > MAX_GRID_STEPS as f64 || truth.len() > u32::MAX as usize {
            return Err(ScoreError::GridTooLong {
                steps,
                span,
                step: cfg.step,
                max: MAX_GRID_STEPS,
            });
        }
        let steps = steps as usize;

        let mut truth_cur = TruthCursor::new(truth, cfg.max_truth_gap);
        let mut track_cur = TrackCursor::new(tracks, cfg.max_track_age);
        let (mut here_truth, mut here_track) = (Vec::new(), Vec::new());
        let mut scans = Vec::with_capacity(steps);
        let mut series = Vec::with_capacity(steps);
        let mut seg = vec![Segments::default(); truth.len()];
        let mut track_on_grid = vec![false; tracks.len()];
        let mut assigned_to = vec![None; truth.len()];
        let mut pos_err = Vec::new();
        let (mut sum_e2, mut sum_v2, mut sum_e, mut sum_v) = (0.0, 0.0, 0.0, 0.0);
        let (mut j_sum, mut n_sum, mut na_sum) = (0usize, 0usize, 0usize);
        let (mut g_sum, mut loc_sum, mut miss_sum, mut false_sum) = (0.0, 0.0, 0.0, 0.0);
        let inv_p = 1.0 / cfg.gospa_order;

        for k in 0..steps {
            let t = start + k as f64 * cfg.step;
            truth_cur.at(t, &mut here_truth);
            track_cur.at(t, &mut here_track);
            let st = assign::step(
                t,
                &here_truth,
                &here_track,
                cfg.assign_cutoff,
                &self.gospa,
                cfg.gospa_cutoff,
                cfg.gospa_order,
            )?;

            for a in assigned_to.iter_mut() {
                *a = None;
            }
            let mut pairs = Vec::with_capacity(st.pairs.len());
            for &(jl, il) in &st.pairs {
                let (i, x) = here_truth[il];
                let (j, y) = here_track[jl];
                let e = (x.pos - y.pos).norm();
                let v = (x.vel - y.vel).norm();
                sum_e2 += e * e;
                sum_v2 += v * v;
                sum_e += e;
                sum_v += v;
                pos_err.push(e);
                assigned_to[i] = Some(j);
                pairs.push((j as u64, TargetId(i as u32)));
            }
            for &(i, _) in &here_truth {
                let s = &mut seg[i];
                s.points += 1;
                s.first.get_or_insert(t);
                s.last = t;
                if let Some(j) = assigned_to[i] {
                    s.assigned += 1;
                    s.on_assigned(j, k, t);
                }
            }
            // Unassigned or absent at k: the segment ends.
            for s in &mut seg {
                s.close_unless_at(k);
            }
            for &(j, _) in &here_track {
                track_on_grid[j] = true;
            }

            let (jn, nn, nan) = (here_truth.len(), here_track.len(), pairs.len());
            j_sum += jn;
            n_sum += nn;
            na_sum += nan;
            let g = &st.gospa;
            let gospa = (g.localisation + g.missed + g.false_targets).powf(inv_p);
            g_sum += gospa;
            loc_sum += g.localisation;
            miss_sum += g.missed;
            false_sum += g.false_targets;
            series.push(GridPoint {
                t,
                truths: jn,
                tracks: nn,
                assigned: nan,
                completeness: ratio(nan as f64, jn as f64),
                gospa,
                gospa_localisation: g.localisation,
                gospa_missed: g.missed,
                gospa_false: g.false_targets,
            });
            scans.push(TrackScan::new(
                t,
                here_truth
                    .iter()
                    .map(|&(i, _)| TargetId(i as u32))
                    .collect(),
                here_track.iter().map(|&(j, _)| j as u64).collect(),
                pairs,
            )?);
        }
        for s in &mut seg {
            s.close();
        }

        let stats = TrackStatistics::from_scans(&scans)?;
        let ttc: Vec<Option<f64>> = {
            let mut v = vec![None; truth.len()];
            for &(g, d) in &stats.time_to_confirm {
                v[g.0 as usize] = d;
            }
            v
        };
        let confirmed: Vec<f64> = ttc.iter().flatten().copied().collect();
        let never = seg
            .iter()
            .zip(&ttc)
            .filter(|(s, d)| s.points > 0 && d.is_none())
            .count();
        let kf = steps as f64;
        let naf = na_sum as f64;
        let aircraft_hours = j_sum as f64 * cfg.step / 3600.0;
        let lifetime: f64 = seg.iter().filter_map(|s| s.first.map(|f| s.last - f)).sum();
        let tl: f64 = seg.iter().map(|s| s.longest).sum();
        let tt: f64 = seg.iter().map(|s| s.tracked).sum();
        let changes: usize = seg.iter().map(|s| s.count.saturating_sub(1)).sum();
        let summary = Summary {
            grid_start: start,
            grid_end: start + (steps - 1) as f64 * cfg.step,
            grid_times: steps,
            truths: truth.len(),
            tracks: tracks.len(),
            tracks_on_grid: track_on_grid.iter().filter(|&&b| b).count(),
            truth_points: j_sum,
            track_points: n_sum,
            assigned_points: na_sum,
            aircraft_hours,
            completeness: ratio(naf, j_sum as f64),
            spurious_fraction: ratio((n_sum - na_sum) as f64, n_sum as f64),
            false_tracks_per_step: (n_sum - na_sum) as f64 / kf,
            breaks: stats.breaks,
            breaks_per_aircraft_hour: ratio(stats.breaks as f64, aircraft_hours),
            id_swaps: stats.id_swaps,
            position_rmse: ratio(sum_e2, naf).map(f64::sqrt),
            velocity_rmse: ratio(sum_v2, naf).map(f64::sqrt),
            position_p95: percentile_nearest_rank(&mut pos_err, 0.95),
            position_accuracy: ratio(sum_e, naf),
            velocity_accuracy: ratio(sum_v, naf),
            time_to_confirm_mean: ratio(confirmed.iter().sum(), confirmed.len() as f64),
            truths_never_tracked: never,
            longest_segment: ratio(tl, lifetime),
            track_number_change_rate: ratio(changes as f64, tt),
            gospa_mean: g_sum / kf,
            gospa_localisation_mean: loc_sum / kf,
            gospa_missed_mean: miss_sum / kf,
            gospa_false_mean: false_sum / kf,
        };
        let truths = truth
            .iter()
            .zip(&seg)
            .zip(&ttc)
            .map(|((p, s), d)| TruthScore {
                name: p.name().to_string(),
                points: s.points,
                assigned: s.assigned,
                time_to_confirm: *d,
                segments: s.count,
                longest_segment: s.longest,
            })
            .collect();
        Ok(Score {
            config: *cfg,
            summary,
            truths,
            series,
        })
    }
}

/// `num / den`, `None` when `den` is zero.
fn ratio(num: f64, den: f64) -> Option<f64> {
    (den > 0.0).then(|| num / den)
}

/// The nearest-rank percentile: the smallest value with at least `q` of the values at or
/// below it (`sorted[⌈q n⌉ − 1]`); `None` for no value.
pub(crate) fn percentile_nearest_rank(values: &mut [f64], q: f64) -> Option<f64> {
    if values.is_empty() {
        return None;
    }
    values.sort_by(f64::total_cmp);
    let rank = (q * values.len() as f64).ceil().max(1.0) as usize;
    Some(values[rank.min(values.len()) - 1])
}

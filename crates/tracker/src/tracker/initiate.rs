//! Two-point initiation from the plots no track used.

use argus_filters::two_point_cv2;

use super::{Initiator, ScanReport, Tracker};
use crate::assign::gnn;
use crate::plot::ScanPoint;
use crate::{Track, TrackId, TrackStatus};

impl Tracker {
    /// Two-point initiation: pairs earlier unused plots (initiators) with this scan's
    /// unused plots through the velocity gate, by GNN on the normalised distance.
    ///
    /// In a synchronous scan (`sector = None`) every plot is at `time`. In a sector
    /// (`Some(min_dt)`) plot `j` is at `self.point_times[j]`, `time` is the sector's
    /// start, and a pair needs `min_dt ≤ Δt ≤ max_initiation_interval` (half a
    /// revolution at least: the two plots come from different revolutions).
    pub(super) fn initiate(&mut self, time: f64, sector: Option<f64>, report: &mut ScanReport) {
        let cfg = &self.config;
        let points = &self.points;
        let times = sector.map(|_| self.point_times.as_slice());
        let min_dt = sector.unwrap_or(0.0);
        let t_of = |j: usize| times.map_or(time, |t| t[j]);
        let t_last = times.map_or(time, |t| t.iter().copied().fold(time, f64::max));
        self.initiators
            .retain(|i| time - i.time <= cfg.max_initiation_interval);
        self.edges.clear();
        let plot_trace = r_max_trace(points);
        for (row, init) in self.initiators.iter().enumerate() {
            let dt = t_last - init.time;
            if dt <= 0.0 || dt < min_dt {
                continue;
            }
            let r = cfg.max_speed * dt
                + cfg.velocity_gate_sigmas * (init.covariance.trace() + plot_trace).sqrt();
            let (used, edges) = (&self.used, &mut self.edges);
            self.grid.query(&init.position, [r, r], |j| {
                if used[j] {
                    return;
                }
                let dt = t_of(j) - init.time;
                if times.is_some() && (dt < min_dt || dt > cfg.max_initiation_interval) {
                    return;
                }
                let z2 = &points[j];
                let lim = cfg.max_speed * dt
                    + cfg.velocity_gate_sigmas
                        * (init.covariance.trace() + z2.covariance.trace()).sqrt();
                let d = (z2.position - init.position).norm();
                if d <= lim {
                    edges.push((row, j, (d / lim).powi(2)));
                }
            });
        }
        let miss = vec![1.0 + 1e-9; self.initiators.len()];
        let out = gnn(self.initiators.len(), points.len(), &self.edges, &miss);
        let mut matched = vec![false; self.initiators.len()];
        let reference = self.sensors[self.scan_sensor]
            .polar
            .as_ref()
            .map(|pm| pm.reference);
        for (row, col) in out.into_iter().enumerate() {
            let Some(j) = col else { continue };
            let init = self.initiators[row];
            let z2 = &points[j];
            let time = t_of(j);
            let dt = time - init.time;
            let score = self.config.score.map_or(0.0, |sc| {
                let lim = self.config.max_speed * dt
                    + self.config.velocity_gate_sigmas
                        * (init.covariance.trace() + z2.covariance.trace()).sqrt();
                let v_gate = std::f64::consts::PI * lim * lim;
                (sc.new_target_density / sc.clutter_density).ln()
                    + (sc.p_detection / (sc.clutter_density * v_gate)).ln()
            });
            let Ok(estimate) = two_point_cv2(
                &init.position,
                &init.covariance,
                &z2.position,
                &z2.covariance,
                dt,
            ) else {
                continue;
            };
            let Some(state) = self.est.start(estimate, reference) else {
                continue;
            };
            let id = TrackId(self.next_id);
            let mut track = Track {
                id,
                status: TrackStatus::Tentative,
                estimate,
                time,
                initiated: time,
                confirmed_at: None,
                opportunities: 2,
                hits: 2,
                consecutive_misses: 0,
                deletion: None,
                last_hit: true,
                score,
                peak_score: score,
                state,
                plot: self.point_plots.get(j).copied(),
                looks: Vec::new(),
                revision: 0,
            };
            matched[row] = true;
            self.used[j] = true;
            self.next_id += 1;
            let confirm_now = match &self.config.score {
                Some(sc) => score >= sc.confirm_threshold(),
                None => self.config.confirm_m <= 2,
            };
            if confirm_now {
                track.status = TrackStatus::Confirmed;
                track.confirmed_at = Some(time);
                report.confirmed.push(id);
            }
            report.initiated.push(id);
            self.tracks.push(track);
        }
        let mut k = 0;
        self.initiators.retain(|_| {
            k += 1;
            !matched[k - 1]
        });
        for (j, p) in points.iter().enumerate() {
            if !self.used[j] {
                self.initiators.push(Initiator {
                    time: t_of(j),
                    position: p.position,
                    covariance: p.covariance,
                });
            }
        }
    }
}

/// The largest plot covariance trace of a scan (for the initiation query box).
fn r_max_trace(points: &[ScanPoint]) -> f64 {
    points
        .iter()
        .map(|p| p.covariance.trace())
        .fold(0.0, f64::max)
}

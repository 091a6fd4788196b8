//! Gating and association: GNN, and JPDA for confirmed tracks.

use argus_core_math::{Gaussian, Vector};

use super::Tracker;
use crate::assign::{clusters, gnn};
use crate::estimator::{Estimator, TrackGate};
use crate::jpda::marginals;
use crate::plot::ScanPoint;
use crate::{AssociationConfig, TrackStatus};

impl Tracker {
    /// Indexes `self.points` in the grid and marks every plot unused.
    pub(super) fn index_points(&mut self) {
        self.grid.rebuild(self.points.iter().map(|p| p.position));
        self.used.clear();
        self.used.resize(self.points.len(), false);
    }

    /// Gates and assigns the plots of a scan or a sector (the predictions made): the
    /// per-track results reset, the confirmed tracks by JPDA or GNN as configured, then
    /// the tentative tracks by GNN on the plots left.
    pub(super) fn associate_all(&mut self, r_max: [f64; 2]) {
        self.assigned.clear();
        self.assigned.resize(self.tracks.len(), None);
        self.jpda.iter_mut().for_each(Vec::clear);
        self.jpda.resize(self.tracks.len(), Vec::new());
        self.jpda_dl.clear();
        self.jpda_dl.resize(self.tracks.len(), None);
        if let AssociationConfig::Jpda {
            p_detection,
            clutter_density,
            max_exact_events,
        } = self.config.association
        {
            self.associate_jpda(r_max, p_detection, clutter_density, max_exact_events);
        } else {
            self.associate(TrackStatus::Confirmed, r_max);
        }
        self.associate(TrackStatus::Tentative, r_max);
    }

    /// How track `k`, predicted at `pred`, gates: per mode for an IMM or aircraft-IMM
    /// track, with the EKF's polar prediction when it has one.
    fn track_gate<'a>(&'a self, k: usize, pred: &'a Gaussian<4>) -> TrackGate<'a> {
        if let (Estimator::Imm(imm), Some(Some(ip))) = (&self.est, self.imm_predicted.get(k)) {
            return TrackGate::Imm(imm, ip);
        }
        let polar_sensor = self.sensors[self.scan_sensor].polar.as_ref();
        if let Some(g) = self.est.aircraft_gate(&self.tracks[k].state, polar_sensor) {
            return TrackGate::Aircraft(g);
        }
        let polar = self
            .polar_mp
            .get(k)
            .and_then(Option::as_ref)
            .zip(self.sensors[self.scan_sensor].polar.as_ref());
        TrackGate::Single { pred, polar }
    }

    /// Calls `f(plot, νᵀS⁻¹ν, ln-likelihood per m²)` for every unused plot inside track
    /// `k`'s gate (`νᵀS⁻¹ν ≤ gamma`), found through the grid. An IMM track is gated per
    /// mode (a plot in any mode's gate, at its smallest normalised distance, with the
    /// mode-mixed likelihood), as IMM-JPDA needs: gating on the moment-matched prediction
    /// alone, dominated by the quiet mode, loses aircraft entering a turn.
    fn gate_track(
        &self,
        k: usize,
        pred: &Gaussian<4>,
        gamma: f64,
        r_max: [f64; 2],
        mut f: impl FnMut(usize, f64, f64),
    ) {
        let gate = self.track_gate(k, pred);
        let (centre, half) = gate.query_box(gamma, r_max);
        let (points, used) = (&self.points, &self.used);
        self.grid.query(&centre, half, |j| {
            // The gate ellipse lies inside the box (|ν_i| ≤ √(γ S_ii) ≤ half_i): skip the
            // plots of the cells met that are outside it before forming S.
            if used[j] || !in_box(&points[j].position, &centre, half) {
                return;
            }
            if let Some((nis, ll)) = gate.innovation(&points[j])
                && nis <= gamma
            {
                f(j, nis, ll);
            }
        });
    }

    /// Gates the unused plots against the tracks of one status and assigns by GNN.
    pub(super) fn associate(&mut self, status: TrackStatus, r_max: [f64; 2]) {
        let gamma = self.gate.gamma();
        let mut edges = std::mem::take(&mut self.edges);
        edges.clear();
        let mut rows: Vec<usize> = Vec::new();
        for (k, track) in self.tracks.iter().enumerate() {
            if track.status != status {
                continue;
            }
            let Some(pred) = self.predicted[k].as_ref() else {
                continue;
            };
            let row = rows.len();
            let mut any = false;
            self.gate_track(k, pred, gamma, r_max, |j, nis, _| {
                edges.push((row, j, nis));
                any = true;
            });
            if any {
                rows.push(k);
            }
        }
        self.edges = edges;
        if rows.is_empty() {
            return;
        }
        let miss = vec![gamma * (1.0 + 1e-9) + 1e-12; rows.len()];
        let out = gnn(rows.len(), self.points.len(), &self.edges, &miss);
        for (row, col) in out.into_iter().enumerate() {
            if let Some(j) = col {
                self.assigned[rows[row]] = Some(j);
                self.used[j] = true;
            }
        }
    }

    /// JPDA for the confirmed tracks: gated pairs with likelihood ratios, clusters,
    /// marginals; every gated plot is spent. With the IMM, gating is per mode and the
    /// likelihood is the mode mixture (IMM-JPDA).
    pub(super) fn associate_jpda(
        &mut self,
        r_max: [f64; 2],
        p_d: f64,
        lambda: f64,
        max_events: usize,
    ) {
        let gamma = self.gate.gamma();
        let miss = 1.0 - p_d * self.gate.p_gate();
        let mut pairs: Vec<(usize, usize, f64)> = Vec::new();
        for (k, track) in self.tracks.iter().enumerate() {
            if track.status != TrackStatus::Confirmed {
                continue;
            }
            let Some(pred) = self.predicted[k].as_ref() else {
                continue;
            };
            self.gate_track(k, pred, gamma, r_max, |j, _, ll| {
                let g = p_d * ll.exp() / lambda;
                if g.is_finite() {
                    pairs.push((k, j, g));
                }
            });
        }
        let simple: Vec<(usize, usize)> = pairs.iter().map(|&(k, j, _)| (k, j)).collect();
        for group in clusters(self.tracks.len(), self.points.len(), &simple) {
            let mut rows: Vec<usize> = group.iter().map(|&e| pairs[e].0).collect();
            let mut cols: Vec<usize> = group.iter().map(|&e| pairs[e].1).collect();
            rows.sort_unstable();
            rows.dedup();
            cols.sort_unstable();
            cols.dedup();
            let local: Vec<(usize, usize, f64)> = group
                .iter()
                .map(|&e| {
                    let (k, j, g) = pairs[e];
                    (
                        rows.binary_search(&k).unwrap_or(0),
                        cols.binary_search(&j).unwrap_or(0),
                        g,
                    )
                })
                .collect();
            let (beta, _) = marginals(rows.len(), cols.len(), &local, miss, max_events);
            for (&e, b) in group.iter().zip(beta) {
                let (k, j, _) = pairs[e];
                self.jpda[k].push((j, b));
                self.used[j] = true;
            }
        }
        let mut sum_g = vec![0.0; self.tracks.len()];
        for &(k, _, g) in &pairs {
            sum_g[k] += g;
        }
        for (k, w) in self.jpda.iter().enumerate() {
            if w.is_empty() {
                continue;
            }
            self.jpda_dl[k] = Some((miss + sum_g[k]).ln());
            // A hit for track management: the plot of largest weight.
            self.assigned[k] = w.iter().max_by(|a, b| a.1.total_cmp(&b.1)).map(|&(j, _)| j);
        }
    }
}

/// The largest plot variance per axis of `points`, for the grid query boxes.
pub(super) fn r_max(points: &[ScanPoint]) -> [f64; 2] {
    points.iter().fold([0.0_f64; 2], |acc, p| {
        [
            acc[0].max(p.covariance[(0, 0)]),
            acc[1].max(p.covariance[(1, 1)]),
        ]
    })
}

/// Whether `p` lies in the box `centre ± half`.
fn in_box(p: &Vector<2>, centre: &Vector<2>, half: [f64; 2]) -> bool {
    (p[0] - centre[0]).abs() <= half[0] && (p[1] - centre[1]).abs() <= half[1]
}

//! The tracker: scans in, tracks out.

use argus_association::Gate;
use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{MeasurementPrediction, two_point_cv2};
use argus_imm::{ImmEstimate, ImmPrediction, MultiImmEstimate, moment_match};

use crate::assign::{Edge, clusters, gnn};
use crate::estimator::{
    Estimators, gate_box, imm_gate_box, imm_innovation, imm_jpda_update, imm_step, innovation,
    jpda_update, multi_update, polar_half,
};
use crate::grid::Grid;
use crate::jpda::marginals;
use crate::plot::{ScanPoint, SensorModel};
use crate::{
    AssociationConfig, DeletionReason, Plot, SensorId, Track, TrackId, TrackStatus, TrackerConfig,
    TrackerError,
};

/// What one scan did.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ScanReport {
    /// The scan time (s).
    pub time: f64,
    /// Plots in the scan.
    pub plots: usize,
    /// Plots assigned to existing tracks.
    pub assigned: usize,
    /// Tracks initiated (tentative, or confirmed at once when `confirm_m = 2`).
    pub initiated: Vec<TrackId>,
    /// Tracks confirmed in this scan.
    pub confirmed: Vec<TrackId>,
    /// Tracks deleted in this scan.
    pub deleted: Vec<TrackId>,
}

/// An unused plot waiting for a second one to start a track.
#[derive(Debug, Clone, Copy)]
struct Initiator {
    time: f64,
    position: Vector<2>,
    covariance: Matrix<2, 2>,
}

/// The multi-target tracker (see the crate documentation).
#[derive(Debug, Clone)]
pub struct Tracker {
    config: TrackerConfig,
    est: Estimators,
    sensors: Vec<SensorModel>,
    gate: Gate,
    time: Option<f64>,
    next_id: u64,
    tracks: Vec<Track>,
    deleted: Vec<Track>,
    initiators: Vec<Initiator>,
    // Scratch buffers reused from scan to scan.
    /// The current scan's sensor (index into `sensors`).
    scan_sensor: usize,
    grid: Grid,
    points: Vec<ScanPoint>,
    predicted: Vec<Option<Gaussian<4>>>,
    imm_predicted: Vec<Option<ImmPrediction<4, 2>>>,
    /// EKF on polar plots: each track's measurement prediction in `(r, θ)`.
    polar_mp: Vec<Option<MeasurementPrediction<4, 2>>>,
    assigned: Vec<Option<usize>>,
    used: Vec<bool>,
    edges: Vec<Edge>,
    /// JPDA per track: (plot, β) pairs, and the score increment `ln(B + Σ G)`.
    jpda: Vec<Vec<(usize, f64)>>,
    jpda_dl: Vec<Option<f64>>,
}

impl Tracker {
    /// A tracker with no tracks.
    ///
    /// # Errors
    /// [`TrackerError::InvalidConfig`] naming the first bad field.
    pub fn new(config: TrackerConfig) -> Result<Self, TrackerError> {
        config.validate()?;
        let est = Estimators::new(&config)?;
        let sensors = config
            .sensors
            .iter()
            .map(SensorModel::new)
            .collect::<Result<Vec<_>, _>>()?;
        let gate = Gate::from_probability(config.gate_probability, 2)?;
        let grid = Grid::new(config.grid_cell);
        Ok(Self {
            config,
            est,
            sensors,
            gate,
            time: None,
            next_id: 0,
            tracks: Vec::new(),
            deleted: Vec::new(),
            initiators: Vec::new(),
            scan_sensor: 0,
            grid,
            points: Vec::new(),
            predicted: Vec::new(),
            imm_predicted: Vec::new(),
            polar_mp: Vec::new(),
            assigned: Vec::new(),
            used: Vec::new(),
            edges: Vec::new(),
            jpda: Vec::new(),
            jpda_dl: Vec::new(),
        })
    }

    /// The configuration.
    #[must_use]
    pub fn config(&self) -> &TrackerConfig {
        &self.config
    }

    /// The gate in use.
    #[must_use]
    pub fn gate(&self) -> &Gate {
        &self.gate
    }

    /// The time of the last scan processed.
    #[must_use]
    pub fn time(&self) -> Option<f64> {
        self.time
    }

    /// The live (tentative and confirmed) tracks, in id order.
    #[must_use]
    pub fn tracks(&self) -> &[Track] {
        &self.tracks
    }

    /// The deleted tracks not yet taken, in order of deletion.
    #[must_use]
    pub fn deleted(&self) -> &[Track] {
        &self.deleted
    }

    /// Takes the deleted tracks (so that memory does not grow in long runs).
    pub fn take_deleted(&mut self) -> Vec<Track> {
        std::mem::take(&mut self.deleted)
    }

    /// Checks a plot's (or a scan's) time and sensor against the configuration and the
    /// time before it; returns the sensor's index.
    fn check_time_sensor(
        &self,
        index: usize,
        time: f64,
        sensor: SensorId,
        previous: Option<f64>,
    ) -> Result<usize, TrackerError> {
        if !time.is_finite() {
            return Err(TrackerError::NonFinite {
                index,
                sensor,
                what: "time",
            });
        }
        let Some(s) = self.sensors.iter().position(|s| s.id == sensor) else {
            return Err(TrackerError::UnknownSensor {
                index,
                time,
                sensor,
            });
        };
        if let Some(previous) = previous
            && time < previous
        {
            return Err(TrackerError::TimeOrder {
                index,
                time,
                previous,
            });
        }
        Ok(s)
    }

    /// Checks one plot against the configuration and the time before it, and makes its
    /// scan point (a polar plot converted).
    fn check_plot(
        &self,
        index: usize,
        plot: &Plot,
        previous: Option<f64>,
    ) -> Result<ScanPoint, TrackerError> {
        let s = self.check_time_sensor(index, plot.time(), plot.sensor(), previous)?;
        self.sensors[s].point(index, plot, self.est.multi.is_none())
    }

    /// Processes a time-ordered stream of plots: consecutive plots with the same time
    /// and sensor form one scan. Every plot is checked before any track is touched.
    ///
    /// A sensor scan with no plot at all still counts as a miss for every track; feed
    /// it with [`Tracker::process_scan`].
    ///
    /// # Errors
    /// [`TrackerError::TimeOrder`], [`TrackerError::UnknownSensor`],
    /// [`TrackerError::NonFinite`], [`TrackerError::PlotCovariance`],
    /// [`TrackerError::NonPositiveRange`], [`TrackerError::NoPolarNoise`],
    /// [`TrackerError::NotPolar`], [`TrackerError::Conversion`] naming the first bad
    /// plot; the tracker is then unchanged.
    pub fn process(&mut self, plots: &[Plot]) -> Result<Vec<ScanReport>, TrackerError> {
        let mut previous = self.time;
        for (index, plot) in plots.iter().enumerate() {
            self.check_plot(index, plot, previous)?;
            previous = Some(plot.time());
        }
        let mut reports = Vec::new();
        let mut start = 0;
        while start < plots.len() {
            let (t, s) = (plots[start].time(), plots[start].sensor());
            let len = plots[start..]
                .iter()
                .take_while(|p| p.sensor() == s && p.time().total_cmp(&t).is_eq())
                .count();
            reports.push(self.process_scan(t, s, &plots[start..start + len])?);
            start += len;
        }
        Ok(reports)
    }

    /// Processes one scan: every plot of `plots` must have time `time` and sensor
    /// `sensor` (an empty slice is a scan that saw nothing).
    ///
    /// Steps: convert the polar plots; predict every live track to `time`; gate the plots
    /// near each confirmed track (grid query, then the chi-square gate on the innovation)
    /// and assign by GNN (or weigh by JPDA); the same for tentative tracks with the plots
    /// left; update, count hits and misses, confirm and delete; pair the plots still
    /// unused with earlier unused plots through the velocity gate to initiate tentative
    /// tracks; keep the rest as initiators.
    ///
    /// # Errors
    /// As [`Tracker::process`], and [`TrackerError::MixedScan`] for a plot of another
    /// time or sensor; the tracker is then unchanged. A track whose filter step fails is
    /// deleted ([`DeletionReason::FilterFailure`]); the others go on.
    pub fn process_scan(
        &mut self,
        time: f64,
        sensor: SensorId,
        plots: &[Plot],
    ) -> Result<ScanReport, TrackerError> {
        let s = self.check_time_sensor(0, time, sensor, self.time)?;
        let mut points = std::mem::take(&mut self.points);
        points.clear();
        for (index, plot) in plots.iter().enumerate() {
            if plot.sensor() != sensor || !plot.time().total_cmp(&time).is_eq() {
                self.points = points;
                return Err(TrackerError::MixedScan {
                    index,
                    time,
                    sensor,
                });
            }
            match self.sensors[s].point(index, plot, self.est.multi.is_none()) {
                Ok(p) => points.push(p),
                Err(e) => {
                    self.points = points;
                    return Err(e);
                }
            }
        }
        self.points = points;
        self.scan_sensor = s;
        Ok(self.run_scan(time))
    }

    /// The scan proper, on checked plots (in `self.points`).
    fn run_scan(&mut self, time: f64) -> ScanReport {
        let n_plots = self.points.len();
        let mut report = ScanReport {
            time,
            plots: n_plots,
            ..ScanReport::default()
        };
        self.time = Some(time);
        self.grid.rebuild(self.points.iter().map(|p| p.position));
        self.used.clear();
        self.used.resize(n_plots, false);
        // Largest plot variance per axis, for the grid query boxes.
        let r_max = self.points.iter().fold([0.0_f64; 2], |acc, p| {
            [
                acc[0].max(p.covariance[(0, 0)]),
                acc[1].max(p.covariance[(1, 1)]),
            ]
        });
        let polar_sensor = self.sensors[self.scan_sensor].polar;
        // EKF on polar plots: each track's measurement prediction in (r, θ) (left empty
        // otherwise, so the KF path does not touch it).
        let ekf_polar = self.est.ekf.is_some()
            && polar_sensor.is_some()
            && self.points.iter().any(|p| p.polar.is_some());

        // 1. Predict (a multi-IMM track's state becomes its prediction).
        self.predicted.clear();
        self.imm_predicted.clear();
        self.polar_mp.clear();
        for track in &mut self.tracks {
            let dt = time - track.time;
            let (pred, imm_pred) = match (&self.est.imm, &track.imm, &self.est.multi) {
                (Some(imm), Some(est), _) => {
                    let p = if dt > 0.0 {
                        imm.predict(est, dt).ok()
                    } else {
                        Some(est.into_prediction())
                    };
                    let combined = p.as_ref().and_then(|p| {
                        let w = p.log_predicted_probabilities().map(f64::exp);
                        moment_match(&w, p.modes()).ok()
                    });
                    (combined, p)
                }
                (_, _, Some(multi)) => {
                    let combined = track.multi.as_mut().and_then(|m| {
                        if dt > 0.0 {
                            **m = multi.predict(m, dt).ok()?;
                        }
                        m.combined().ok()
                    });
                    (combined, None)
                }
                _ => (self.est.predict_single(&track.estimate, dt), None),
            };
            if ekf_polar {
                let mp = pred
                    .as_ref()
                    .and_then(|p| self.est.polar_prediction(p, polar_sensor.as_ref()));
                self.polar_mp.push(mp);
            }
            self.predicted.push(pred);
            // Only IMM trackers keep the mode-conditioned predictions (a large value to
            // move per track for nothing otherwise); look them up with `get`.
            if self.est.imm.is_some() {
                self.imm_predicted.push(imm_pred);
            }
        }

        // 2–3. Gate and assign, confirmed tracks first, then tentative ones.
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

        // 4. Update, count, confirm, delete.
        let polar_model = polar_sensor.as_ref().map(|pm| &pm.model);
        for (k, track) in self.tracks.iter_mut().enumerate() {
            let Some(pred) = self.predicted[k].take() else {
                track.delete(DeletionReason::FilterFailure);
                report.deleted.push(track.id);
                continue;
            };
            let hit = self.assigned[k];
            let points = &self.points;
            let posterior: Option<(Gaussian<4>, Option<f64>)> = match (
                &self.est.imm,
                self.imm_predicted.get_mut(k).and_then(Option::take),
                &self.est.multi,
            ) {
                (Some(imm), Some(ip), _) if !self.jpda[k].is_empty() => {
                    imm_jpda_update(imm, &ip, &self.jpda[k], points).map(|(g, e)| {
                        track.imm = Some(e);
                        (g, None)
                    })
                }
                (Some(imm), Some(ip), _) => {
                    imm_step(imm, ip, hit.map(|j| &points[j])).map(|(g, ll, e)| {
                        track.imm = Some(e);
                        (g, ll)
                    })
                }
                (_, _, Some(multi)) => match (hit, track.multi.as_mut(), &polar_sensor) {
                    (None, _, _) => Some((pred, None)),
                    (Some(j), Some(m), Some(pm)) => points[j]
                        .polar
                        .and_then(|z| multi_update(multi, m, pm, &z))
                        .map(|(state, g, ll)| {
                            **m = state;
                            (g, Some(ll))
                        }),
                    _ => None,
                },
                _ if !self.jpda[k].is_empty() => {
                    jpda_update(&self.est, &pred, polar_model, &self.jpda[k], points)
                        .map(|g| (g, None))
                }
                _ => match hit {
                    Some(j) => self
                        .est
                        .update_single(&pred, polar_model, &points[j])
                        .map(|(g, ll)| (g, Some(ll))),
                    None => Some((pred, None)),
                },
            };
            let Some((posterior, log_likelihood)) = posterior else {
                track.delete(DeletionReason::FilterFailure);
                report.deleted.push(track.id);
                continue;
            };
            if hit.is_some() {
                report.assigned += 1;
            }
            track.estimate = posterior;
            track.time = time;
            if let Some(sc) = &self.config.score {
                track.score += match (self.jpda_dl[k], log_likelihood) {
                    (Some(dl), _) => dl,
                    (None, Some(ll)) => (sc.p_detection / sc.clutter_density).ln() + ll,
                    (None, None) => (1.0 - sc.p_detection * self.gate.p_gate()).ln(),
                };
                track.peak_score = track.peak_score.max(track.score);
            }
            if let Some(event) = track.count(hit.is_some(), &self.config) {
                match event {
                    TrackStatus::Confirmed => report.confirmed.push(track.id),
                    _ => report.deleted.push(track.id),
                }
            }
        }

        // 5. Initiate from unused plots.
        self.initiate(time, &mut report);

        // Move the deleted tracks out.
        self.deleted.extend(
            self.tracks
                .extract_if(.., |t| t.status == TrackStatus::Deleted),
        );
        report
    }

    /// The EKF's polar prediction of track `k` with its polar model, when the estimator is
    /// the EKF and the scan has polar plots.
    fn polar_of(
        &self,
        k: usize,
    ) -> Option<(&MeasurementPrediction<4, 2>, &argus_sensors::Polar2D<4>)> {
        let mp = self.polar_mp.get(k)?.as_ref()?;
        let pm = self.sensors[self.scan_sensor].polar.as_ref()?;
        Some((mp, &pm.model))
    }

    /// The query box of track `k`: the Cartesian gate box, widened to hold the EKF's polar
    /// gate when it has one.
    fn query_box(
        &self,
        k: usize,
        pred: &Gaussian<4>,
        gamma: f64,
        r_max: [f64; 2],
    ) -> (Vector<2>, [f64; 2]) {
        let (centre, mut half) = gate_box(pred, gamma, r_max);
        if let (Some(Some(mp)), Some(pm)) = (
            self.polar_mp.get(k),
            self.sensors[self.scan_sensor].polar.as_ref(),
        ) {
            let h = polar_half(mp, gamma, pm.conversion_stretch);
            half = [half[0].max(h), half[1].max(h)];
        }
        (centre, half)
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
        let imm = (self.est.imm.as_ref()).zip(self.imm_predicted.get(k).and_then(Option::as_ref));
        let (centre, half) = match imm {
            Some((_, ip)) => imm_gate_box(ip, gamma, r_max),
            None => self.query_box(k, pred, gamma, r_max),
        };
        let polar = self.polar_of(k);
        let (points, used) = (&self.points, &self.used);
        self.grid.query(&centre, half, |j| {
            // The gate ellipse lies inside the box (|ν_i| ≤ √(γ S_ii) ≤ half_i): skip the
            // plots of the cells met that are outside it before forming S.
            if used[j] || !in_box(&points[j].position, &centre, half) {
                return;
            }
            let gated = match imm {
                Some((imm, ip)) => imm_innovation(imm, ip, &points[j]),
                None => innovation(pred, polar, &points[j]),
            };
            if let Some((nis, ll)) = gated
                && nis <= gamma
            {
                f(j, nis, ll);
            }
        });
    }

    /// Gates the unused plots against the tracks of one status and assigns by GNN.
    fn associate(&mut self, status: TrackStatus, r_max: [f64; 2]) {
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
    fn associate_jpda(&mut self, r_max: [f64; 2], p_d: f64, lambda: f64, max_events: usize) {
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

    /// Two-point initiation: pairs earlier unused plots (initiators) with this scan's
    /// unused plots through the velocity gate, by GNN on the normalised distance.
    fn initiate(&mut self, time: f64, report: &mut ScanReport) {
        let cfg = &self.config;
        let points = &self.points;
        self.initiators
            .retain(|i| time - i.time <= cfg.max_initiation_interval);
        self.edges.clear();
        let plot_trace = r_max_trace(points);
        for (row, init) in self.initiators.iter().enumerate() {
            let dt = time - init.time;
            if dt <= 0.0 {
                continue;
            }
            let r = cfg.max_speed * dt
                + cfg.velocity_gate_sigmas * (init.covariance.trace() + plot_trace).sqrt();
            let (used, edges) = (&self.used, &mut self.edges);
            self.grid.query(&init.position, [r, r], |j| {
                if used[j] {
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
                imm: None,
                multi: None,
            };
            if self.est.imm.is_some() || self.est.multi.is_some() {
                let Ok(start) = ImmEstimate::from_common(estimate, [0.5, 0.5]) else {
                    continue;
                };
                if self.est.multi.is_some() {
                    let Some(reference) = reference else { continue };
                    track.multi = Some(Box::new(MultiImmEstimate::new(start, reference)));
                } else {
                    track.imm = Some(start);
                }
            }
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
                    time,
                    position: p.position,
                    covariance: p.covariance,
                });
            }
        }
    }
}

/// Whether `p` lies in the box `centre ± half`.
fn in_box(p: &Vector<2>, centre: &Vector<2>, half: [f64; 2]) -> bool {
    (p[0] - centre[0]).abs() <= half[0] && (p[1] - centre[1]).abs() <= half[1]
}

/// The largest plot covariance trace of a scan (for the initiation query box).
fn r_max_trace(points: &[ScanPoint]) -> f64 {
    points
        .iter()
        .map(|p| p.covariance.trace())
        .fold(0.0, f64::max)
}

impl Track {
    pub(crate) fn delete(&mut self, reason: DeletionReason) {
        self.status = TrackStatus::Deleted;
        self.deletion = Some(reason);
    }

    /// Counts one opportunity; returns the new status when it changed.
    fn count(&mut self, hit: bool, cfg: &TrackerConfig) -> Option<TrackStatus> {
        self.opportunities += 1;
        self.last_hit = hit;
        if hit {
            self.hits += 1;
            self.consecutive_misses = 0;
        } else {
            self.consecutive_misses += 1;
        }
        if worst_position_sigma(self.estimate.cov()) > cfg.max_position_sigma {
            self.delete(DeletionReason::CovarianceGrowth);
            return Some(TrackStatus::Deleted);
        }
        if let Some(sc) = &cfg.score {
            return self.count_score(sc, cfg);
        }
        match self.status {
            TrackStatus::Tentative => {
                if self.hits >= cfg.confirm_m {
                    self.status = TrackStatus::Confirmed;
                    self.confirmed_at = Some(self.time);
                    Some(TrackStatus::Confirmed)
                } else if i64::from(self.hits) + i64::from(cfg.confirm_n)
                    - i64::from(self.opportunities)
                    < i64::from(cfg.confirm_m)
                {
                    self.delete(DeletionReason::NotConfirmed);
                    Some(TrackStatus::Deleted)
                } else {
                    None
                }
            }
            TrackStatus::Confirmed if self.consecutive_misses >= cfg.max_misses => {
                self.delete(DeletionReason::Misses);
                Some(TrackStatus::Deleted)
            }
            _ => None,
        }
    }
}

impl Track {
    /// Status change by track score (see [`crate::ScoreConfig`]).
    fn count_score(&mut self, sc: &crate::ScoreConfig, cfg: &TrackerConfig) -> Option<TrackStatus> {
        match self.status {
            TrackStatus::Tentative if self.score >= sc.confirm_threshold() => {
                self.status = TrackStatus::Confirmed;
                self.confirmed_at = Some(self.time);
                Some(TrackStatus::Confirmed)
            }
            TrackStatus::Tentative if self.score <= sc.delete_threshold() => {
                self.delete(DeletionReason::Score);
                Some(TrackStatus::Deleted)
            }
            TrackStatus::Confirmed if self.peak_score - self.score >= sc.delete_drop => {
                self.delete(DeletionReason::Score);
                Some(TrackStatus::Deleted)
            }
            TrackStatus::Confirmed if self.consecutive_misses >= cfg.max_misses => {
                self.delete(DeletionReason::Misses);
                Some(TrackStatus::Deleted)
            }
            _ => None,
        }
    }
}

/// Square root of the largest eigenvalue of the position block of `[x, vx, y, vy]`.
fn worst_position_sigma(p: &Matrix<4, 4>) -> f64 {
    let (a, b, c) = (p[(0, 0)], p[(0, 2)], p[(2, 2)]);
    let half = 0.5 * (a - c);
    (0.5 * (a + c) + (half * half + b * b).sqrt()).sqrt()
}

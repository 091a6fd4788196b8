//! The tracker: scans in, tracks out.

use argus_association::Gate;
use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{GaussianFilter, Kf, two_point_cv2};
use argus_imm::{Imm, ImmEstimate, ImmPrediction, MarkovMatrix, moment_match};
use argus_motion_models::Cv2D;
use argus_sensors::CartesianPosition;

use crate::assign::{Edge, clusters, gnn};
use crate::grid::Grid;
use crate::jpda::marginals;
use crate::{
    AssociationConfig, DeletionReason, EstimatorConfig, SensorId, Track, TrackId, TrackStatus,
    TrackerConfig, TrackerError,
};

/// One Cartesian position plot `(x, y)` with its covariance (e.g. a converted polar
/// plot), from one sensor at one time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plot {
    /// Time (s).
    pub time: f64,
    /// The sensor that made it.
    pub sensor: SensorId,
    /// Position `(x, y)` (m).
    pub position: Vector<2>,
    /// Its covariance (m²): finite, symmetric, positive definite.
    pub covariance: Matrix<2, 2>,
}

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
    filter: Kf<Cv2D>,
    imm: Option<Imm<Kf<Cv2D>, 4, 2>>,
    gate: Gate,
    time: Option<f64>,
    next_id: u64,
    tracks: Vec<Track>,
    deleted: Vec<Track>,
    initiators: Vec<Initiator>,
    // Scratch buffers reused from scan to scan.
    grid: Grid,
    models: Vec<CartesianPosition<4, 2>>,
    predicted: Vec<Option<Gaussian<4>>>,
    imm_predicted: Vec<Option<ImmPrediction<4, 2>>>,
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
        let filter = Kf::new(Cv2D::discrete(config.sigma_a)?);
        let imm = match config.estimator {
            EstimatorConfig::Kf => None,
            EstimatorConfig::ImmCv2 {
                sigma_a_low,
                sigma_a_high,
                p_stay,
            } => {
                let markov = MarkovMatrix::new([[p_stay, 1.0 - p_stay], [1.0 - p_stay, p_stay]])
                    .map_err(|_| TrackerError::InvalidConfig {
                        field: "estimator.p_stay",
                        value: p_stay,
                        reason: "does not make a Markov matrix",
                    })?;
                let filters = [
                    Kf::new(Cv2D::discrete(sigma_a_low)?),
                    Kf::new(Cv2D::discrete(sigma_a_high)?),
                ];
                Some(
                    Imm::new(filters, markov).map_err(|_| TrackerError::InvalidConfig {
                        field: "estimator",
                        value: p_stay,
                        reason: "the IMM rejected it",
                    })?,
                )
            }
        };
        let gate = Gate::from_probability(config.gate_probability, 2)?;
        let grid = Grid::new(config.grid_cell);
        Ok(Self {
            config,
            filter,
            imm,
            gate,
            time: None,
            next_id: 0,
            tracks: Vec::new(),
            deleted: Vec::new(),
            initiators: Vec::new(),
            grid,
            models: Vec::new(),
            predicted: Vec::new(),
            imm_predicted: Vec::new(),
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

    /// Checks one plot against the configuration and the time before it, and builds its
    /// measurement model.
    fn check_plot(
        &self,
        index: usize,
        plot: &Plot,
        previous: Option<f64>,
    ) -> Result<CartesianPosition<4, 2>, TrackerError> {
        let non_finite = |what| TrackerError::NonFinite {
            index,
            sensor: plot.sensor,
            what,
        };
        if !plot.time.is_finite() {
            return Err(non_finite("time"));
        }
        if !self.config.sensors.contains(&plot.sensor) {
            return Err(TrackerError::UnknownSensor {
                index,
                time: plot.time,
                sensor: plot.sensor,
            });
        }
        if let Some(previous) = previous
            && plot.time < previous
        {
            return Err(TrackerError::TimeOrder {
                index,
                time: plot.time,
                previous,
            });
        }
        if !plot.position.iter().all(|v| v.is_finite()) {
            return Err(non_finite("position"));
        }
        if !plot.covariance.iter().all(|v| v.is_finite()) {
            return Err(non_finite("covariance"));
        }
        CartesianPosition::<4, 2>::cv(plot.covariance).map_err(|source| {
            TrackerError::PlotCovariance {
                index,
                time: plot.time,
                sensor: plot.sensor,
                source,
            }
        })
    }

    /// Processes a time-ordered stream of plots: consecutive plots with the same time
    /// and sensor form one scan. Every plot is checked before any track is touched.
    ///
    /// A sensor scan with no plot at all still counts as a miss for every track; feed
    /// it with [`Tracker::process_scan`].
    ///
    /// # Errors
    /// [`TrackerError::TimeOrder`], [`TrackerError::UnknownSensor`],
    /// [`TrackerError::NonFinite`], [`TrackerError::PlotCovariance`] naming the first
    /// bad plot; the tracker is then unchanged.
    pub fn process(&mut self, plots: &[Plot]) -> Result<Vec<ScanReport>, TrackerError> {
        let mut previous = self.time;
        for (index, plot) in plots.iter().enumerate() {
            self.check_plot(index, plot, previous)?;
            previous = Some(plot.time);
        }
        let mut reports = Vec::new();
        let mut start = 0;
        while start < plots.len() {
            let (t, s) = (plots[start].time, plots[start].sensor);
            let len = plots[start..]
                .iter()
                .take_while(|p| p.sensor == s && p.time.total_cmp(&t).is_eq())
                .count();
            reports.push(self.process_scan(t, s, &plots[start..start + len])?);
            start += len;
        }
        Ok(reports)
    }

    /// Processes one scan: every plot of `plots` must have time `time` and sensor
    /// `sensor` (an empty slice is a scan that saw nothing).
    ///
    /// Steps: predict every live track to `time`; gate the plots near each confirmed
    /// track (grid query, then the chi-square gate on the innovation) and assign by GNN;
    /// the same for tentative tracks with the plots left; update, count hits and
    /// misses, confirm and delete; pair the plots still unused with earlier unused plots
    /// through the velocity gate to initiate tentative tracks; keep the rest as
    /// initiators.
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
        let scan_plot = Plot {
            time,
            sensor,
            position: Vector::<2>::zeros(),
            covariance: Matrix::<2, 2>::identity(),
        };
        self.check_plot(0, &scan_plot, self.time)?;
        let mut models = std::mem::take(&mut self.models);
        models.clear();
        for (index, plot) in plots.iter().enumerate() {
            if plot.sensor != sensor || !plot.time.total_cmp(&time).is_eq() {
                self.models = models;
                return Err(TrackerError::MixedScan {
                    index,
                    time,
                    sensor,
                });
            }
            match self.check_plot(index, plot, self.time) {
                Ok(m) => models.push(m),
                Err(e) => {
                    self.models = models;
                    return Err(e);
                }
            }
        }
        self.models = models;
        Ok(self.run_scan(time, plots))
    }

    /// The scan proper, on checked plots (their models are in `self.models`).
    fn run_scan(&mut self, time: f64, plots: &[Plot]) -> ScanReport {
        let mut report = ScanReport {
            time,
            plots: plots.len(),
            ..ScanReport::default()
        };
        self.time = Some(time);
        self.grid.rebuild(plots.iter().map(|p| p.position));
        self.used.clear();
        self.used.resize(plots.len(), false);
        // Largest plot variance per axis, for the grid query boxes.
        let r_max = plots.iter().fold([0.0_f64; 2], |acc, p| {
            [
                acc[0].max(p.covariance[(0, 0)]),
                acc[1].max(p.covariance[(1, 1)]),
            ]
        });

        // 1. Predict.
        self.predicted.clear();
        self.imm_predicted.clear();
        for track in &self.tracks {
            let dt = time - track.time;
            match (&self.imm, &track.imm) {
                (Some(imm), Some(est)) => {
                    let p = if dt > 0.0 {
                        imm.predict(est, dt).ok()
                    } else {
                        Some(est.into_prediction())
                    };
                    let combined = p.as_ref().and_then(|p| {
                        let w = p.log_predicted_probabilities().map(f64::exp);
                        moment_match(&w, p.modes()).ok()
                    });
                    self.predicted.push(combined);
                    self.imm_predicted.push(p);
                }
                _ => {
                    let pred = if dt > 0.0 {
                        self.filter.predict(&track.estimate, dt).ok()
                    } else {
                        Some(track.estimate)
                    };
                    self.predicted.push(pred);
                    self.imm_predicted.push(None);
                }
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
            self.associate_jpda(plots, r_max, p_detection, clutter_density, max_exact_events);
        } else {
            self.associate(TrackStatus::Confirmed, plots, r_max);
        }
        self.associate(TrackStatus::Tentative, plots, r_max);

        // 4. Update, count, confirm, delete.
        for (k, track) in self.tracks.iter_mut().enumerate() {
            let Some(pred) = self.predicted[k].take() else {
                track.delete(DeletionReason::FilterFailure);
                report.deleted.push(track.id);
                continue;
            };
            let hit = self.assigned[k];
            let (posterior, imm_posterior) = match (&self.imm, self.imm_predicted[k].take()) {
                (Some(imm), Some(ip)) => {
                    imm_step(imm, ip, hit.map(|j| (&self.models[j], &plots[j])))
                }
                _ if !self.jpda[k].is_empty() => (
                    jpda_update(&self.filter, &pred, &self.jpda[k], &self.models, plots)
                        .map(|g| (g, None)),
                    None,
                ),
                _ => (
                    match hit {
                        Some(j) => self
                            .filter
                            .update(&pred, &self.models[j], &plots[j].position)
                            .map(|(post, innov)| (post, Some(innov.log_likelihood)))
                            .ok(),
                        None => Some((pred, None)),
                    },
                    None,
                ),
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
            track.imm = imm_posterior;
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
        self.initiate(time, plots, &mut report);

        // Move the deleted tracks out.
        self.deleted.extend(
            self.tracks
                .extract_if(.., |t| t.status == TrackStatus::Deleted),
        );
        report
    }

    /// Gates the unused plots against the tracks of one status and assigns by GNN.
    fn associate(&mut self, status: TrackStatus, plots: &[Plot], r_max: [f64; 2]) {
        let gamma = self.gate.gamma();
        self.edges.clear();
        let mut rows: Vec<usize> = Vec::new();
        for (k, track) in self.tracks.iter().enumerate() {
            if track.status != status {
                continue;
            }
            let Some(pred) = self.predicted[k].as_ref() else {
                continue;
            };
            let (centre, half) = gate_box(pred, gamma, r_max);
            let row = rows.len();
            let (filter, models, used, edges) =
                (&self.filter, &self.models, &self.used, &mut self.edges);
            let mut any = false;
            self.grid.query(&centre, half, |j| {
                // The gate ellipse lies inside the box (|ν_i| ≤ √(γ S_ii) ≤ half_i):
                // skip the plots of the cells met that are outside it before forming S.
                if used[j] || !in_box(&plots[j].position, &centre, half) {
                    return;
                }
                let Ok(mp) = filter.predict_measurement(pred, &models[j]) else {
                    return;
                };
                let Ok(innov) = mp.innovation(&models[j], &plots[j].position) else {
                    return;
                };
                if innov.nis <= gamma {
                    edges.push((row, j, innov.nis));
                    any = true;
                }
            });
            if any {
                rows.push(k);
            }
        }
        if rows.is_empty() {
            return;
        }
        let miss = vec![gamma * (1.0 + 1e-9) + 1e-12; rows.len()];
        let out = gnn(rows.len(), plots.len(), &self.edges, &miss);
        for (row, col) in out.into_iter().enumerate() {
            if let Some(j) = col {
                self.assigned[rows[row]] = Some(j);
                self.used[j] = true;
            }
        }
    }

    /// JPDA for the confirmed tracks: gated pairs with likelihood ratios, clusters,
    /// marginals; every gated plot is spent.
    fn associate_jpda(
        &mut self,
        plots: &[Plot],
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
            let (centre, half) = gate_box(pred, gamma, r_max);
            let (filter, models) = (&self.filter, &self.models);
            self.grid.query(&centre, half, |j| {
                if !in_box(&plots[j].position, &centre, half) {
                    return;
                }
                let Ok(mp) = filter.predict_measurement(pred, &models[j]) else {
                    return;
                };
                let Ok(innov) = mp.innovation(&models[j], &plots[j].position) else {
                    return;
                };
                let g = p_d * innov.log_likelihood.exp() / lambda;
                if innov.nis <= gamma && g.is_finite() {
                    pairs.push((k, j, g));
                }
            });
        }
        let simple: Vec<(usize, usize)> = pairs.iter().map(|&(k, j, _)| (k, j)).collect();
        for group in clusters(self.tracks.len(), plots.len(), &simple) {
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
    fn initiate(&mut self, time: f64, plots: &[Plot], report: &mut ScanReport) {
        let cfg = &self.config;
        self.initiators
            .retain(|i| time - i.time <= cfg.max_initiation_interval);
        self.edges.clear();
        let plot_trace = r_max_trace(plots);
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
                let z2 = &plots[j];
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
        let out = gnn(self.initiators.len(), plots.len(), &self.edges, &miss);
        let mut matched = vec![false; self.initiators.len()];
        for (row, col) in out.into_iter().enumerate() {
            let Some(j) = col else { continue };
            let init = self.initiators[row];
            let z2 = &plots[j];
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
            matched[row] = true;
            self.used[j] = true;
            let id = TrackId(self.next_id);
            self.next_id += 1;
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
            };
            if self.imm.is_some() {
                match ImmEstimate::from_common(estimate, [0.5, 0.5]) {
                    Ok(e) => track.imm = Some(e),
                    Err(_) => continue,
                }
            }
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
        for (j, plot) in plots.iter().enumerate() {
            if !self.used[j] {
                self.initiators.push(Initiator {
                    time,
                    position: plot.position,
                    covariance: plot.covariance,
                });
            }
        }
    }
}

/// The JPDA (PDA) update: the moment-matched mixture of the prediction (weight
/// `β₀ = 1 − Σ β_j`) and the Kalman update with each plot (weight `β_j`), which is the
/// standard PDA update when all plots share one `R` (Bar-Shalom & Tse 1975).
fn jpda_update(
    filter: &Kf<Cv2D>,
    pred: &Gaussian<4>,
    weights: &[(usize, f64)],
    models: &[CartesianPosition<4, 2>],
    plots: &[Plot],
) -> Option<Gaussian<4>> {
    let b0 = (1.0 - weights.iter().map(|w| w.1).sum::<f64>()).max(0.0);
    let mut parts: Vec<(f64, Gaussian<4>)> = Vec::with_capacity(weights.len() + 1);
    parts.push((b0, *pred));
    for &(j, b) in weights {
        let (post, _) = filter.update(pred, &models[j], &plots[j].position).ok()?;
        parts.push((b, post));
    }
    let total: f64 = parts.iter().map(|p| p.0).sum();
    if !(total.is_finite() && total > 0.0) {
        return None;
    }
    let mut mean = Vector::<4>::zeros();
    for (w, g) in &parts {
        mean += g.mean() * (*w / total);
    }
    let mut cov = Matrix::<4, 4>::zeros();
    for (w, g) in &parts {
        let d = g.mean() - mean;
        cov += (g.cov() + d * d.transpose()) * (*w / total);
    }
    Gaussian::from_symmetrized(mean, &cov).ok()
}

/// One IMM update (or coast through a miss): the moment-matched posterior with the
/// plot's total log-likelihood, and the IMM estimate; `None` posterior on failure.
fn imm_step(
    imm: &Imm<Kf<Cv2D>, 4, 2>,
    pred: ImmPrediction<4, 2>,
    hit: Option<(&CartesianPosition<4, 2>, &Plot)>,
) -> (
    Option<(Gaussian<4>, Option<f64>)>,
    Option<ImmEstimate<4, 2>>,
) {
    let (est, ll) = match hit {
        Some((model, plot)) => match imm.update(&pred, model, &plot.position) {
            Ok(u) => (u.estimate, Some(u.log_likelihood)),
            Err(_) => return (None, None),
        },
        None => (pred.into_estimate(), None),
    };
    match est.combined() {
        Ok(c) => (Some((c, ll)), Some(est)),
        Err(_) => (None, None),
    }
}

/// Whether `p` lies in the box `centre ± half`.
fn in_box(p: &Vector<2>, centre: &Vector<2>, half: [f64; 2]) -> bool {
    (p[0] - centre[0]).abs() <= half[0] && (p[1] - centre[1]).abs() <= half[1]
}

/// The largest plot covariance trace of a scan (for the initiation query box).
fn r_max_trace(plots: &[Plot]) -> f64 {
    plots
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

/// The axis-aligned box around a predicted track that holds its chi-square gate for any plot
/// whose position variances are at most `r_max`: centre `(x, y)` and half-widths
/// `√(γ (P_xx + R_max,xx))`, `√(γ (P_yy + R_max,yy))`.
fn gate_box(pred: &Gaussian<4>, gamma: f64, r_max: [f64; 2]) -> (Vector<2>, [f64; 2]) {
    let p = pred.cov();
    let centre = Vector::<2>::new(pred.mean()[0], pred.mean()[2]);
    let half = [
        (gamma * (p[(0, 0)] + r_max[0])).sqrt(),
        (gamma * (p[(2, 2)] + r_max[1])).sqrt(),
    ];
    (centre, half)
}

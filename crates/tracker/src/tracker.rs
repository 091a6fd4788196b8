//! The tracker: scans in, tracks out.

use argus_association::Gate;
use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::MeasurementPrediction;
use argus_imm::ImmPrediction;

use crate::assign::Edge;
use crate::estimator::Estimator;
use crate::grid::Grid;
use crate::plot::{ScanPoint, SensorModel};
use crate::state::SavedState;
use crate::{
    DeletionReason, Plot, SensorId, Track, TrackId, TrackStatus, TrackerConfig, TrackerError,
};

mod associate;
mod initiate;
mod predict;
mod sector;

use sector::{Role, SectorState};

/// What one scan, or one sector of a rotating sensor, did.
#[derive(Debug, Clone, PartialEq)]
pub struct ScanReport {
    /// The scan time (s); for a sector, the time up to which the beam was followed
    /// (the sector's end, or the last time seen for [`Tracker::flush`]).
    pub time: f64,
    /// The sector's start (s); the scan time for a synchronous scan.
    pub start: f64,
    /// The scan's or the sector's sensor.
    pub sensor: SensorId,
    /// Whether this is a sector of a rotating sensor (else a synchronous scan, in which
    /// every live track takes part).
    pub sector: bool,
    /// Sectors only: the tracks that had their opportunity in it (updated by a plot or
    /// missed), in id order, tracks initiated in it excluded. Empty for a synchronous
    /// scan.
    pub visited: Vec<TrackId>,
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

impl ScanReport {
    fn new(time: f64, sensor: SensorId) -> Self {
        Self {
            time,
            start: time,
            sensor,
            sector: false,
            visited: Vec::new(),
            plots: 0,
            assigned: 0,
            initiated: Vec::new(),
            confirmed: Vec::new(),
            deleted: Vec::new(),
        }
    }
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
    est: Estimator,
    sensors: Vec<SensorModel>,
    gate: Gate,
    time: Option<f64>,
    /// The latest time accepted (plots, scans, [`Tracker::advance_to`]): what the next
    /// plot must not precede.
    latest: Option<f64>,
    /// The rotating sensors' sectors (empty without rotating sensors).
    sectors: Vec<SectorState>,
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
    /// A sector's plot times (parallel to `points`; empty in a synchronous scan).
    point_times: Vec<f64>,
    /// The plots of `points` as given (parallel to `points`), for [`Track::plot`].
    point_plots: Vec<Plot>,
    /// A sector's role of each track.
    roles: Vec<Role>,
    /// An IMM track's prediction to its plot's time.
    modes: Vec<Option<ImmPrediction<4, 2>>>,
    /// A sector's looked-at tracks' states before their look prediction, for the
    /// estimator whose state becomes its prediction (the aircraft IMM; the multi-IMM is
    /// refused with rotating sensors): restored before predicting again to the plot's own
    /// time, or when the track is carried. Copies out of the tracks' boxes into this
    /// reused buffer, so a sector allocates nothing for them.
    saved: Vec<Option<SavedState>>,
}

impl Tracker {
    /// A tracker with no tracks.
    ///
    /// # Errors
    /// [`TrackerError::InvalidConfig`] naming the first bad field.
    pub fn new(config: TrackerConfig) -> Result<Self, TrackerError> {
        config.validate()?;
        let est = Estimator::new(&config)?;
        let sensors = config
            .sensors
            .iter()
            .map(SensorModel::new)
            .collect::<Result<Vec<_>, _>>()?;
        let gate = Gate::from_probability(config.gate_probability, 2)?;
        let grid = Grid::new(config.grid_cell);
        let sectors = SectorState::for_config(&config);
        Ok(Self {
            config,
            est,
            sensors,
            gate,
            time: None,
            latest: None,
            sectors,
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
            point_times: Vec::new(),
            point_plots: Vec::new(),
            roles: Vec::new(),
            modes: Vec::new(),
            saved: Vec::new(),
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

    /// The time of the last scan processed (for a sector: its [`ScanReport::time`]).
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
        self.sensors[s].point(index, plot, self.est.takes_cartesian())
    }

    /// Processes a time-ordered stream of plots: consecutive plots with the same time
    /// and sensor form one scan of a synchronous sensor; a rotating sensor's plots are
    /// buffered into its sectors, and a sector is processed when a plot (of any sensor)
    /// at or after its end arrives (see the crate docs, "One sector"; the rest waits for
    /// later plots, [`Tracker::advance_to`] or [`Tracker::flush`]). Every plot is checked
    /// before any track is touched.
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
        let mut previous = self.latest;
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
            let group = &plots[start..start + len];
            if self.sectors.is_empty() {
                reports.push(self.process_scan(t, s, group)?);
            } else {
                self.close_sectors(t, &mut reports);
                match self.sector_of(s) {
                    Some(i) => self.buffer(i, start, group)?,
                    None => reports.push(self.process_scan(t, s, group)?),
                }
            }
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
        let s = self.check_time_sensor(0, time, sensor, self.latest)?;
        self.check_synchronous(time, s)?;
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
            match self.sensors[s].point(index, plot, self.est.takes_cartesian()) {
                Ok(p) => points.push(p),
                Err(e) => {
                    self.points = points;
                    return Err(e);
                }
            }
        }
        self.points = points;
        self.point_times.clear();
        self.point_plots.clear();
        self.point_plots.extend_from_slice(plots);
        self.scan_sensor = s;
        Ok(self.run_scan(time))
    }

    /// The scan proper, on checked plots (in `self.points`).
    fn run_scan(&mut self, time: f64) -> ScanReport {
        let n_plots = self.points.len();
        let mut report = ScanReport {
            plots: n_plots,
            ..ScanReport::new(time, self.sensors[self.scan_sensor].id)
        };
        self.time = Some(time);
        self.latest = Some(self.latest.map_or(time, |l| l.max(time)));
        self.index_points();
        // Largest plot variance per axis, for the grid query boxes.
        let r_max = associate::r_max(&self.points);
        let polar_sensor = self.sensors[self.scan_sensor].polar;
        // EKF on polar plots: each track's measurement prediction in (r, θ).
        let ekf_polar = self.ekf_polar(polar_sensor.as_ref());

        // 1. Predict (a multi-IMM track's state becomes its prediction).
        self.clear_predictions();
        for k in 0..self.tracks.len() {
            let dt = time - self.tracks[k].time;
            self.predict_track(k, dt, ekf_polar, polar_sensor.as_ref());
        }

        // 2–3. Gate and assign, confirmed tracks first, then tentative ones.
        self.associate_all(r_max);

        // 4. Update, count, confirm, delete.
        for (k, track) in self.tracks.iter_mut().enumerate() {
            let Some(pred) = self.predicted[k].take() else {
                track.delete(DeletionReason::FilterFailure);
                track.plot = None;
                report.deleted.push(track.id);
                continue;
            };
            let hit = self.assigned[k];
            let plot = hit.map(|j| self.point_plots[j]);
            let posterior = self.est.update(
                &mut track.state,
                pred,
                self.imm_predicted.get_mut(k).and_then(Option::take),
                hit,
                &self.jpda[k],
                &self.points,
                polar_sensor.as_ref(),
            );
            conclude(
                &self.config,
                self.gate.p_gate(),
                track,
                &mut report,
                posterior,
                plot,
                self.jpda_dl[k],
                time,
            );
        }

        // 5. Initiate from unused plots.
        self.initiate(time, None, &mut report);

        // Move the deleted tracks out.
        self.deleted.extend(
            self.tracks
                .extract_if(.., |t| t.status == TrackStatus::Deleted),
        );
        report
    }
}

/// The track score's increment for one opportunity (with [`TrackerConfig::score`]): the
/// JPDA increment `dl` when given, a hit's `ln(P_D / λ) + ln N`, or a miss's
/// `ln(1 − P_D P_G)`.
fn add_score(
    config: &TrackerConfig,
    p_gate: f64,
    track: &mut Track,
    dl: Option<f64>,
    log_likelihood: Option<f64>,
) {
    if let Some(sc) = &config.score {
        track.score += match (dl, log_likelihood) {
            (Some(dl), _) => dl,
            (None, Some(ll)) => (sc.p_detection / sc.clutter_density).ln() + ll,
            (None, None) => (1.0 - sc.p_detection * p_gate).ln(),
        };
        track.peak_score = track.peak_score.max(track.score);
    }
}

/// Concludes one track's step in a scan or a sector, `plot` the plot assigned to it (a
/// hit) or `None` (a miss): a failed filter step (`outcome` `None`) deletes the track; otherwise its posterior becomes the estimate at `time`, the
/// track score takes the opportunity's increment ([`add_score`]) and the hit or miss is
/// counted for confirmation and deletion, each event recorded in `report`. Returns
/// whether the step succeeded.
#[allow(clippy::too_many_arguments)]
fn conclude(
    config: &TrackerConfig,
    p_gate: f64,
    track: &mut Track,
    report: &mut ScanReport,
    outcome: Option<(Gaussian<4>, Option<f64>)>,
    plot: Option<Plot>,
    dl: Option<f64>,
    time: f64,
) -> bool {
    let hit = plot.is_some();
    track.plot = plot;
    let Some((posterior, log_likelihood)) = outcome else {
        track.delete(DeletionReason::FilterFailure);
        report.deleted.push(track.id);
        return false;
    };
    if hit {
        report.assigned += 1;
    }
    track.estimate = posterior;
    track.revision = track.revision.wrapping_add(1);
    track.time = time;
    add_score(config, p_gate, track, dl, log_likelihood);
    if let Some(event) = track.count(hit, config) {
        match event {
            TrackStatus::Confirmed => report.confirmed.push(track.id),
            _ => report.deleted.push(track.id),
        }
    }
    true
}

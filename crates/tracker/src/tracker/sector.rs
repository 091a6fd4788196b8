//! Rotating sensors: their plots buffered into sectors, and one sector's step (see the
//! crate docs, "One sector").

use std::f64::consts::{PI, TAU};

use argus_core_math::Vector;

use super::{ScanReport, Tracker};
use crate::estimator::Estimator;
use crate::track::Look;
use crate::{
    DeletionReason, EstimatorConfig, Plot, Rotation, SensorId, Track, TrackStatus, TrackerConfig,
    TrackerError,
};

/// One rotating sensor's sectors: the open one and its buffered plots.
#[derive(Debug, Clone)]
pub(crate) struct SectorState {
    /// The sensor (index into the tracker's sensors).
    sensor: usize,
    rotation: Rotation,
    /// Sector length `sector_fraction × period` (s).
    length: f64,
    /// The open sector, `[north_time + k L, north_time + (k + 1) L)`; `None` before the
    /// sensor's first plot.
    index: Option<i64>,
    /// The open sector's plots so far, and their times.
    points: Vec<crate::plot::ScanPoint>,
    times: Vec<f64>,
    /// The open sector's plots as given (parallel to `points`).
    plots: Vec<Plot>,
}

/// A track's part in one sector.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Role {
    /// The beam does not reach its gate in this sector (or it had its opportunity this
    /// revolution already).
    Out,
    /// The beam crosses its predicted azimuth at `time`; `closes`: the beam leaves its
    /// gate before the sector's end (unassigned, it misses; else it is carried).
    Look { time: f64, closes: bool },
}

impl SectorState {
    /// One state per rotating sensor of `config`, in sensor order.
    pub(crate) fn for_config(config: &TrackerConfig) -> Vec<Self> {
        config
            .sensors
            .iter()
            .enumerate()
            .filter_map(|(sensor, s)| {
                s.rotation.map(|rotation| Self {
                    sensor,
                    rotation,
                    length: config.sector_fraction * rotation.period,
                    index: None,
                    points: Vec::new(),
                    times: Vec::new(),
                    plots: Vec::new(),
                })
            })
            .collect()
    }

    fn start(&self, k: i64) -> f64 {
        #[allow(clippy::cast_precision_loss)]
        let k = k as f64;
        self.rotation.north_time + k * self.length
    }

    fn end(&self, k: i64) -> f64 {
        self.start(k + 1)
    }

    /// The sector holding `t`.
    #[allow(clippy::cast_possible_truncation)]
    fn index_of(&self, t: f64) -> i64 {
        let mut k = ((t - self.rotation.north_time) / self.length).floor() as i64;
        while self.end(k) <= t {
            k += 1;
        }
        while self.start(k) > t {
            k -= 1;
        }
        k
    }

    /// The open sector's end, once the sensor has started.
    fn open_end(&self) -> Option<f64> {
        self.index.map(|k| self.end(k))
    }
}

impl Tracker {
    /// The index in `self.sectors` of sensor `id`, when it rotates.
    pub(super) fn sector_of(&self, id: SensorId) -> Option<usize> {
        self.sectors
            .iter()
            .position(|ss| self.sensors[ss.sensor].id == id)
    }

    /// Makes sensor `id` a rotating radar with `rotation` (or replaces its rotation), as if
    /// the configuration had said so; the other sensors' sectors are kept as they are.
    /// Only before the sensor's first plot: the caller ([`crate::Session`]) checks that
    /// for a sensor configured synchronous, this refuses a rotating sensor whose sectors
    /// have started.
    ///
    /// # Errors
    /// [`TrackerError::LateRotation`] for an unknown sensor or a started one;
    /// [`TrackerError::InvalidConfig`] for a bad rotation or one the estimator cannot take
    /// (the multi-IMM). The tracker is then unchanged.
    pub(crate) fn set_rotation(
        &mut self,
        id: SensorId,
        rotation: Rotation,
    ) -> Result<(), TrackerError> {
        let Some(s) = self.sensors.iter().position(|m| m.id == id) else {
            return Err(TrackerError::LateRotation {
                sensor: id,
                reason: "the configuration has no such sensor",
            });
        };
        if self
            .sectors
            .iter()
            .any(|ss| ss.sensor == s && ss.index.is_some())
        {
            return Err(TrackerError::LateRotation {
                sensor: id,
                reason: "the sensor's sectors have started (its first plot was taken)",
            });
        }
        let mut config = self.config.clone();
        config.sensors[s].rotation = Some(rotation);
        config.validate()?;
        self.config = config;
        let mut old = std::mem::take(&mut self.sectors);
        self.sectors = SectorState::for_config(&self.config)
            .into_iter()
            .map(
                |fresh| match old.iter().position(|ss| ss.sensor == fresh.sensor) {
                    Some(k) if fresh.sensor != s => old.swap_remove(k),
                    _ => fresh,
                },
            )
            .collect();
        Ok(())
    }

    /// Refuses a synchronous scan of a rotating sensor, or one that would come after a
    /// sector end not yet processed.
    pub(super) fn check_synchronous(&self, time: f64, s: usize) -> Result<(), TrackerError> {
        let sensor = self.sensors[s].id;
        if self.sectors.iter().any(|ss| ss.sensor == s) {
            return Err(TrackerError::RotatingScan {
                time,
                sensor,
                reason: "a rotating sensor's plots go through process (by sectors)",
            });
        }
        if self
            .sectors
            .iter()
            .any(|ss| ss.open_end().is_some_and(|e| e <= time))
        {
            return Err(TrackerError::RotatingScan {
                time,
                sensor,
                reason: "a rotating sensor's sector ends before it: call advance_to(time) first",
            });
        }
        Ok(())
    }

    /// Buffers a group of plots (one time, rotating sensor `self.sectors[i]`, already
    /// checked; `start`: the first one's index in the caller's slice).
    pub(super) fn buffer(
        &mut self,
        i: usize,
        start: usize,
        group: &[Plot],
    ) -> Result<(), TrackerError> {
        let Some(first) = group.first() else {
            return Ok(());
        };
        let t = first.time();
        let s = self.sectors[i].sensor;
        if self.sectors[i].index.is_none() {
            self.sectors[i].index = Some(self.sectors[i].index_of(t));
        }
        let cartesian_ok = self.est.takes_cartesian();
        for (n, plot) in group.iter().enumerate() {
            let p = self.sensors[s].point(start + n, plot, cartesian_ok)?;
            self.sectors[i].points.push(p);
            self.sectors[i].times.push(t);
            self.sectors[i].plots.push(*plot);
        }
        self.latest = Some(self.latest.map_or(t, |l| l.max(t)));
        Ok(())
    }

    /// Processes, in order of their ends, every sector that ends at or before `t`.
    pub(super) fn close_sectors(&mut self, t: f64, reports: &mut Vec<ScanReport>) {
        loop {
            let mut due: Option<(usize, f64)> = None;
            for (i, ss) in self.sectors.iter().enumerate() {
                if let Some(end) = ss.open_end()
                    && end <= t
                    && due.is_none_or(|(_, e)| end < e)
                {
                    due = Some((i, end));
                }
            }
            let Some((i, end)) = due else { break };
            let ss = &self.sectors[i];
            let Some(k) = ss.index else { break };
            let start = ss.start(k);
            if let Some(r) = self.run_sector(i, start, end) {
                reports.push(r);
            }
            // Nothing can happen in the sectors of a long silence once no track is left:
            // go straight to the one holding `t`.
            let ss = &mut self.sectors[i];
            ss.index = Some(if self.tracks.is_empty() && ss.points.is_empty() {
                ss.index_of(t).max(k + 1)
            } else {
                k + 1
            });
        }
    }

    /// Tells the tracker that time has reached `t` with no plot (e.g. a sector or north
    /// marker message): every sector of a rotating sensor ending at or before `t` is
    /// processed (its tracks not swept miss), and later plots must not precede `t`.
    ///
    /// # Errors
    /// [`TrackerError::NonFiniteTime`]; [`TrackerError::TimeOrder`] (index 0) when `t`
    /// precedes a time already processed. The tracker is then unchanged.
    pub fn advance_to(&mut self, t: f64) -> Result<Vec<ScanReport>, TrackerError> {
        if !t.is_finite() {
            return Err(TrackerError::NonFiniteTime { time: t });
        }
        if let Some(previous) = self.latest
            && t < previous
        {
            return Err(TrackerError::TimeOrder {
                index: 0,
                time: t,
                previous,
            });
        }
        let mut reports = Vec::new();
        self.close_sectors(t, &mut reports);
        self.latest = Some(t);
        Ok(reports)
    }

    /// The end of the earliest open sector (the next time at which
    /// [`Tracker::advance_to`] or a plot processes one), `None` before any rotating
    /// sensor's first plot.
    #[must_use]
    pub fn next_sector_end(&self) -> Option<f64> {
        self.sectors
            .iter()
            .filter_map(SectorState::open_end)
            .min_by(f64::total_cmp)
    }

    /// Processes what the open sectors hold, up to the latest time seen (for the end of
    /// a stream): tracks whose gate the beam has swept by then update or miss, the
    /// others are carried. The sectors stay open: later plots of them are processed when
    /// they close, and a track never has two opportunities in one revolution.
    pub fn flush(&mut self) -> Vec<ScanReport> {
        let mut reports = Vec::new();
        let Some(latest) = self.latest else {
            return reports;
        };
        for i in 0..self.sectors.len() {
            let ss = &self.sectors[i];
            let Some(k) = ss.index else { continue };
            let start = ss.start(k);
            if let Some(r) = self.run_sector(i, start, latest.max(start)) {
                reports.push(r);
            }
        }
        reports
    }

    /// One sector `[t0, t_close)` of `self.sectors[i]`: its buffered plots against the
    /// tracks whose gate the beam sweeps (see the crate docs). `None` when nothing could
    /// happen (no plot, no track to look at).
    fn run_sector(&mut self, i: usize, t0: f64, t_close: f64) -> Option<ScanReport> {
        let ss = &mut self.sectors[i];
        std::mem::swap(&mut self.points, &mut ss.points);
        std::mem::swap(&mut self.point_times, &mut ss.times);
        std::mem::swap(&mut self.point_plots, &mut ss.plots);
        ss.points.clear();
        ss.times.clear();
        ss.plots.clear();
        let (s, rot) = (ss.sensor, ss.rotation);
        self.scan_sensor = s;
        let sensor = self.sensors[s];
        let n_plots = self.points.len();
        let gamma = self.gate.gamma();
        let r_max = super::associate::r_max(&self.points);
        let sigma_a = sweep_sigma_a(&self.config);

        // Which tracks the beam looks at, and when.
        self.roles.clear();
        let mut looks = 0;
        let sweep = Sweep {
            rot: &rot,
            origin: &sensor.position,
            noise: sensor.polar.map(|pm| pm.sigmas),
            r_trace: r_max[0] + r_max[1],
            gamma,
            sigma_a,
        };
        for track in &mut self.tracks {
            let look = track.looks.get(s).copied().unwrap_or(Look::NONE);
            // The last computation said the beam reaches its gate only after this sector.
            if look.revision == track.revision && look.quiet_until >= t_close {
                self.roles.push(Role::Out);
                continue;
            }
            let not_before = look.visited + 0.5 * rot.period;
            let (role, quiet_until) = sweep.role(track, t0, t_close, not_before);
            if let Some(q) = quiet_until {
                let revision = track.revision;
                let l = look_mut(track, s);
                l.quiet_until = q;
                l.revision = revision;
            }
            looks += usize::from(matches!(role, Role::Look { .. }));
            self.roles.push(role);
        }
        if n_plots == 0 && looks == 0 {
            return None;
        }
        let mut report = ScanReport {
            start: t0,
            sector: true,
            plots: n_plots,
            ..ScanReport::new(t_close, sensor.id)
        };
        self.time = Some(t_close);
        self.index_points();
        let polar_sensor = sensor.polar;
        let ekf_polar = self.ekf_polar(polar_sensor.as_ref());
        let is_imm = matches!(self.est, Estimator::Imm(_));
        // The aircraft IMM's state becomes its prediction: keep the state before it.
        self.saved.clear();

        // Predict each looked-at track to its crossing time (never backwards).
        self.clear_predictions();
        for k in 0..self.tracks.len() {
            let Role::Look { time, .. } = self.roles[k] else {
                self.saved.push(None);
                self.predicted.push(None);
                if is_imm {
                    self.imm_predicted.push(None);
                }
                if ekf_polar {
                    self.polar_mp.push(None);
                }
                continue;
            };
            self.saved.push(self.tracks[k].state.save());
            let dt = (time - self.tracks[k].time).max(0.0);
            self.predict_track(k, dt, ekf_polar, polar_sensor.as_ref());
        }

        // One global association over the sector, as in a scan.
        self.associate_all(r_max);

        // Update (at the plot's own time), miss (swept, nothing assigned) or carry.
        for (k, track) in self.tracks.iter_mut().enumerate() {
            let Role::Look { time: look, closes } = self.roles[k] else {
                continue;
            };
            let Some(pred) = self.predicted[k].take() else {
                track.delete(DeletionReason::FilterFailure);
                track.plot = None;
                report.deleted.push(track.id);
                continue;
            };
            let hit = self.assigned[k];
            let plot = hit.map(|j| self.point_plots[j]);
            let weights = &self.jpda[k];
            if hit.is_none() && weights.is_empty() && !closes {
                // Carried: the state is as it was before the look prediction.
                if let Some(saved) = self.saved[k].take() {
                    track.state.restore(saved);
                }
                continue;
            }
            let (posterior, at) = match hit {
                Some(j) if weights.is_empty() => {
                    let tj = self.point_times[j];
                    // Predict from the state before the look prediction.
                    if let Some(saved) = self.saved[k].take() {
                        track.state.restore(saved);
                    }
                    self.modes.clear();
                    let pj = self.est.predict(
                        &mut track.state,
                        &track.estimate,
                        (tj - track.time).max(0.0),
                        &mut self.modes,
                    );
                    let post = pj.and_then(|pj| {
                        self.est.update(
                            &mut track.state,
                            pj,
                            self.modes.pop().flatten(),
                            hit,
                            &[],
                            &self.points,
                            polar_sensor.as_ref(),
                        )
                    });
                    (post, tj)
                }
                _ => {
                    let post = self.est.update(
                        &mut track.state,
                        pred,
                        self.imm_predicted.get_mut(k).and_then(Option::take),
                        hit,
                        weights,
                        &self.points,
                        polar_sensor.as_ref(),
                    );
                    (post, look)
                }
            };
            let time = track.time.max(at);
            if super::conclude(
                &self.config,
                self.gate.p_gate(),
                track,
                &mut report,
                posterior,
                plot,
                self.jpda_dl[k],
                time,
            ) {
                visit(track, s, time);
                report.visited.push(track.id);
            }
        }

        // Initiation across revolutions, each plot at its own time.
        let before = self.tracks.len();
        self.initiate(t0, Some(0.5 * rot.period), &mut report);
        for track in &mut self.tracks[before..] {
            let t = track.time;
            visit(track, s, t);
        }
        self.deleted.extend(
            self.tracks
                .extract_if(.., |t| t.status == TrackStatus::Deleted),
        );
        Some(report)
    }
}

/// Sensor `s`'s memory of `track`, made when missing.
fn look_mut(track: &mut Track, s: usize) -> &mut Look {
    if track.looks.len() <= s {
        track.looks.resize(s + 1, Look::NONE);
    }
    &mut track.looks[s]
}

/// Records that `track` had its opportunity from sensor `s` at `t`.
fn visit(track: &mut Track, s: usize, t: f64) {
    look_mut(track, s).visited = t;
}

/// The acceleration σ that bounds a track's position uncertainty growth for the sweep
/// window (the manoeuvre mode's for the IMMs).
fn sweep_sigma_a(config: &TrackerConfig) -> f64 {
    match config.estimator {
        EstimatorConfig::ImmCv2 { sigma_a_high, .. }
        | EstimatorConfig::MultiImm { sigma_a_high, .. } => sigma_a_high.max(config.sigma_a),
        _ => config.sigma_a,
    }
}

/// What the beam of one sensor sees of a track's gate.
struct Sweep<'a> {
    rot: &'a Rotation,
    origin: &'a Vector<2>,
    /// `(σ_r, σ_θ)` of a polar sensor.
    noise: Option<[f64; 2]>,
    /// The largest plot covariance trace of the sector (m²).
    r_trace: f64,
    gamma: f64,
    sigma_a: f64,
}

impl Sweep<'_> {
    /// The track's position relative to the sensor, extrapolated on its mean velocity.
    fn relative(&self, track: &Track, t: f64) -> (f64, f64) {
        let m = track.estimate.mean();
        let dt = t - track.time;
        (
            m[0] + m[1] * dt - self.origin[0],
            m[2] + m[3] * dt - self.origin[1],
        )
    }

    /// Half the time the beam takes to sweep the track's gate at `t` (s): the gate's
    /// bounding circle, radius `√(γ (tr P_pos(t) + R))`, seen from the sensor, `P_pos(t)`
    /// the position covariance extrapolated on the CV model with `sigma_a` and `R` the
    /// larger of the sector's plots' and the sensor's polar noise at that range.
    fn half_sweep(&self, track: &Track, t: f64) -> f64 {
        let p = track.estimate.cov();
        let dt = (t - track.time).max(0.0);
        let q = 0.5 * self.sigma_a * self.sigma_a * dt.powi(4);
        let pos = p[(0, 0)]
            + p[(2, 2)]
            + 2.0 * dt * (p[(0, 1)] + p[(2, 3)])
            + dt * dt * (p[(1, 1)] + p[(3, 3)])
            + q;
        let (x, y) = self.relative(track, t);
        let rho = x.hypot(y);
        let noise = self
            .noise
            .map_or(0.0, |[sr, sa]| sr * sr + rho * rho * sa * sa);
        let h = (self.gamma * (pos + self.r_trace.max(noise))).sqrt();
        let delta = if rho > h { (h / rho).asin() } else { PI };
        delta / TAU * self.rot.period
    }

    /// The track's role in the sector `[t0, t_close)` when its next opportunity cannot
    /// come before `not_before`: the first beam crossing of its predicted azimuth whose
    /// sweep of its gate has not ended before `t0` (refined twice on the extrapolated
    /// azimuth), looked at when that sweep starts before `t_close`. With it, when the
    /// sweep starts after `t_close`, that start: no later sector ending before it needs
    /// to look again while the track's estimate is unchanged.
    fn role(&self, track: &Track, t0: f64, t_close: f64, not_before: f64) -> (Role, Option<f64>) {
        let half0 = self.half_sweep(track, t0);
        let after = (t0 - half0).max(not_before);
        let (x, y) = self.relative(track, after);
        let mut tc = self.rot.crossing_after(y.atan2(x), after);
        for _ in 0..2 {
            let (x, y) = self.relative(track, tc);
            tc = self
                .rot
                .crossing_after(y.atan2(x), tc - 0.5 * self.rot.period);
        }
        let half = self.half_sweep(track, tc);
        if tc <= not_before {
            return (Role::Out, None);
        }
        if tc - half >= t_close {
            return (Role::Out, Some(tc - half));
        }
        let role = Role::Look {
            time: tc,
            closes: tc + half < t_close,
        };
        (role, None)
    }
}

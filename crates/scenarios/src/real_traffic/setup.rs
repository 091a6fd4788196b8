//! `real-traffic`'s parameters, shared setup and one run: plots, tracking, scoring.

use argus_geo::Geodetic;
use argus_score::{ScoreConfig, Scorer, TrackHistory, TrackRow, TruthPath, TruthSample};
use argus_sim::{ChaCha8Rng, Rotation, run_rng};
use argus_tracker::smooth::TrackSmoother;
use argus_tracker::{
    AssociationConfig, EstimatorConfig, EstimatorState, Plot, RotationDirection, SensorConfig,
    TrackStatus, Tracker, TrackerConfig,
};
use serde::{Deserialize, Serialize};

use super::radar::{self, Radar};
use super::smooth::{SmoothedTruth, nees_against, smoothed_history, smoothed_truth};
use super::truth::{self, Path};
use crate::error::{ParamProblem, ScenarioError};
use crate::params::Params;
use crate::scenario::{Simulated, TruthRow};
use crate::tracker_params;

/// The radar's sensor id (the held-out check's plot files are of sensor 1).
const RADAR: u32 = 1;

/// The diagnostic score extends every truth path by dead reckoning for this long (s): a
/// track coasting after its aircraft's last ADS-B sample (the sample's area ends ~110 km
/// from CDG, inside the radar's 150 km) is then not counted as spurious.
pub(crate) const EXTENSION: f64 = 25.0;

/// Track positions on the map are kept every this many seconds.
const MAP_STEP: f64 = 20.0;

/// One tracker configuration with its name in the table and summary.
#[derive(Debug, Clone)]
pub(crate) struct Named {
    pub(crate) name: &'static str,
    pub(crate) config: TrackerConfig,
}

/// What a `real-traffic` campaign shares between runs.
pub(crate) struct Setup {
    pub(crate) paths: Vec<Path>,
    pub(crate) radar: Radar,
    pub(crate) duration: f64,
    pub(crate) trackers: Vec<Named>,
    pub(crate) scorer: Scorer,
    /// The truth inside the coverage, as the scorer takes it.
    pub(crate) truth: Vec<TruthPath>,
    /// The same, each path extended [`EXTENSION`] s past its end by dead reckoning.
    pub(crate) truth_extended: Vec<TruthPath>,
    /// The cleaning's counts (records, aircraft, drops per rule).
    pub(crate) cleaning: argus_adsb::CleaningReport,
    /// The covered truth RTS-smoothed, for the NEES (`super::smooth`).
    pub(crate) truth_smoothed: Vec<SmoothedTruth>,
    /// The scorer's assignment cutoff (m), also the NEES's track-to-truth cutoff.
    pub(crate) cutoff: f64,
}

/// One configuration's score in one run.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(crate) struct ConfigScore {
    pub(crate) completeness: Option<f64>,
    pub(crate) breaks_per_aircraft_hour: Option<f64>,
    pub(crate) breaks: usize,
    pub(crate) id_swaps: usize,
    pub(crate) spurious_fraction: Option<f64>,
    /// The spurious fraction against the truth extended past each path's end.
    pub(crate) spurious_fraction_extended: Option<f64>,
    pub(crate) false_tracks_per_step: f64,
    pub(crate) position_rmse: Option<f64>,
    pub(crate) velocity_rmse: Option<f64>,
    pub(crate) position_p95: Option<f64>,
    pub(crate) time_to_confirm_mean: Option<f64>,
    pub(crate) truths_never_tracked: usize,
    pub(crate) gospa_mean: f64,
    pub(crate) gospa_localisation_mean: f64,
    pub(crate) gospa_missed_mean: f64,
    pub(crate) gospa_false_mean: f64,
    pub(crate) confirmed_tracks: usize,
    pub(crate) aircraft_hours: f64,
    /// The position RMSE of the same tracks smoothed over their lives (RTS for the KF, the
    /// IMM smoother for the two-mode IMM; `None` for the aircraft IMM: `super::smooth`).
    #[serde(default)]
    pub(crate) smoothed_position_rmse: Option<f64>,
    /// `Σ NEES` of the confirmed rows' `[x, vx, y, vy]` against the smoothed truth, and
    /// the number of rows.
    #[serde(default)]
    pub(crate) nees_sum: f64,
    #[serde(default)]
    pub(crate) nees_count: usize,
    /// Per grid time: `(t, completeness, GOSPA)`.
    pub(crate) series: Vec<(f64, Option<f64>, f64)>,
}

/// One run's record.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(crate) struct RealRun {
    pub(crate) plots: usize,
    pub(crate) target_plots: usize,
    pub(crate) configs: Vec<ConfigScore>,
    /// The first configuration's confirmed track positions every [`MAP_STEP`] s.
    pub(crate) map_tracks: Vec<(f64, f64)>,
    /// The plots of the first minute, for the map.
    pub(crate) map_plots: Vec<(f64, f64)>,
}

fn conflict(key: &str, value: f64, reason: String) -> ScenarioError {
    ScenarioError::param(key, ParamProblem::Conflict { value, reason })
}

impl Setup {
    pub(crate) fn new(p: &Params) -> Result<Self, ScenarioError> {
        let site = Geodetic::from_degrees(
            p.get("radar_lat")?,
            p.get("radar_lon")?,
            p.get("radar_alt")?,
        )?;
        let (paths, cleaning) = truth::load(site)?;
        let (min_range, max_range) = (p.get("min_range")?, p.get("max_range")?);
        if min_range >= max_range {
            return Err(conflict(
                "min_range",
                min_range,
                format!("must be below max_range={max_range}"),
            ));
        }
        // A switch: values of 0.5 and above turn clockwise.
        let clockwise = p.get("clockwise")? >= 0.5;
        let radar = Radar {
            sensor: argus_sensors::SensorId(RADAR),
            period: p.get("period")?,
            rotation: if clockwise {
                Rotation::Clockwise
            } else {
                Rotation::Counterclockwise
            },
            north_time: p.get("north_time")?,
            sigma_range: p.get("sigma_r")?,
            sigma_azimuth: p.get("sigma_az_deg")?.to_radians(),
            p_detection: p.get("p_d")?,
            clutter_per_revolution: p.get("clutter")?,
            min_range,
            max_range,
        };
        let duration = p.get("duration")?;
        let trackers = trackers(p, &radar)?;
        let cutoff = p.get("cutoff")?;
        let scorer = Scorer::new(ScoreConfig {
            step: p.get("score_step")?,
            start: Some(0.0),
            end: Some(duration),
            assign_cutoff: cutoff,
            gospa_cutoff: cutoff,
            ..ScoreConfig::default()
        })?;
        let truth = covered_truth(&paths, &radar, duration)?;
        let truth_extended = extended(&truth)?;
        let truth_smoothed = smoothed_truth(&truth)?;
        if truth.is_empty() {
            return Err(ScenarioError::Degenerate {
                scenario: "real-traffic",
                message: "no aircraft inside the coverage: move the radar or widen max_range"
                    .to_owned(),
            });
        }
        Ok(Self {
            paths,
            radar,
            duration,
            trackers,
            scorer,
            truth,
            truth_extended,
            cleaning,
            truth_smoothed,
            cutoff,
        })
    }

    /// Run `run`'s plots.
    pub(crate) fn plots(
        &self,
        rng: &mut ChaCha8Rng,
    ) -> Result<Vec<argus_sim::LabelledPlot>, ScenarioError> {
        radar::plots(&self.radar, &self.paths, self.duration, rng)
    }

    /// Run `run`'s plots and the truth, for `argus simulate`.
    pub(crate) fn simulated(&self, seed: u64, run: u64) -> Result<Simulated, ScenarioError> {
        let plots = self.plots(&mut run_rng(seed, run))?;
        let truth = self
            .paths
            .iter()
            .flat_map(|p| {
                p.samples
                    .iter()
                    .filter(|s| s.t < self.duration)
                    .map(|s| TruthRow {
                        t: s.t,
                        target: p.name.clone(),
                        x: s.x,
                        vx: s.vx,
                        y: s.y,
                        vy: s.vy,
                    })
            })
            .collect();
        Ok(Simulated { plots, truth })
    }

    pub(crate) fn one_run(
        &self,
        _run: u64,
        rng: &mut ChaCha8Rng,
    ) -> Result<RealRun, ScenarioError> {
        let labelled = self.plots(rng)?;
        let plots: Vec<Plot> = labelled.iter().map(|l| l.plot).collect();
        let target_plots = labelled
            .iter()
            .filter(|l| matches!(l.origin, argus_sim::Origin::Target(_)))
            .count();
        let mut configs = Vec::with_capacity(self.trackers.len());
        let mut map_tracks = Vec::new();
        for (k, named) in self.trackers.iter().enumerate() {
            let records = track_with_estimates(
                &named.config,
                &plots,
                self.radar.period * named.config.sector_fraction,
            )?;
            let mut histories = Vec::with_capacity(records.len());
            let mut estimates = Vec::with_capacity(records.len());
            let mut states = Vec::with_capacity(records.len());
            for r in records {
                histories.push(r.history);
                estimates.push(r.estimates);
                states.push(r.states);
            }
            if let Ok(path) = std::env::var("ARGUS_DEBUG_TRACKS") {
                let mut t = String::from("t,track,status,x,vx,y,vy\n");
                for h in &histories {
                    for r in h.rows() {
                        t.push_str(&format!(
                            "{},{},{},{},{},{},{}\n",
                            r.t,
                            h.name(),
                            if r.confirmed {
                                "confirmed"
                            } else {
                                "tentative"
                            },
                            r.x,
                            r.vx,
                            r.y,
                            r.vy
                        ));
                    }
                }
                std::fs::write(format!("{path}.{}.csv", named.name), t).ok();
            }
            if k == 0 {
                for h in &histories {
                    let mut next = f64::NEG_INFINITY;
                    for r in h.rows() {
                        if r.confirmed && r.t >= next {
                            map_tracks.push((r.x, r.y));
                            next = r.t + MAP_STEP;
                        }
                    }
                }
            }
            let score = self.scorer.score(&histories, &self.truth)?;
            let smoother = TrackSmoother::new(&named.config)?;
            let smoothed = histories
                .iter()
                .zip(estimates.iter().zip(&states))
                .map(|(h, (e, s))| smoothed_history(&smoother, h, e, s))
                .collect::<Result<Vec<_>, _>>()?;
            let smoothed_position_rmse = self
                .scorer
                .score(&smoothed, &self.truth)?
                .summary
                .position_rmse;
            let (nees_sum, nees_count) =
                nees_against(&histories, &estimates, &self.truth_smoothed, self.cutoff);
            let extended = self.scorer.score(&histories, &self.truth_extended)?;
            let s = &score.summary;
            configs.push(ConfigScore {
                completeness: s.completeness,
                breaks_per_aircraft_hour: s.breaks_per_aircraft_hour,
                breaks: s.breaks,
                id_swaps: s.id_swaps,
                spurious_fraction: s.spurious_fraction,
                spurious_fraction_extended: extended.summary.spurious_fraction,
                false_tracks_per_step: s.false_tracks_per_step,
                position_rmse: s.position_rmse,
                velocity_rmse: s.velocity_rmse,
                position_p95: s.position_p95,
                time_to_confirm_mean: s.time_to_confirm_mean,
                truths_never_tracked: s.truths_never_tracked,
                gospa_mean: s.gospa_mean,
                gospa_localisation_mean: s.gospa_localisation_mean,
                gospa_missed_mean: s.gospa_missed_mean,
                gospa_false_mean: s.gospa_false_mean,
                confirmed_tracks: histories
                    .iter()
                    .filter(|h| h.rows().iter().any(|r| r.confirmed))
                    .count(),
                aircraft_hours: s.aircraft_hours,
                smoothed_position_rmse,
                nees_sum,
                nees_count,
                series: score
                    .series
                    .iter()
                    .map(|g| (g.t, g.completeness, g.gospa))
                    .collect(),
            });
        }
        let map_plots = labelled
            .iter()
            .take_while(|l| l.plot.time() < 60.0)
            .filter_map(|l| match l.plot.measurement() {
                argus_sensors::Measurement::Polar(m) => {
                    Some((m.range() * m.azimuth().cos(), m.range() * m.azimuth().sin()))
                }
                _ => None,
            })
            .collect();
        Ok(RealRun {
            plots: plots.len(),
            target_plots,
            configs,
            map_tracks,
            map_plots,
        })
    }
}

/// The tracker configurations: GNN and JPDA, each with a KF, the two-CV IMM and the
/// aircraft IMM per track.
fn trackers(p: &Params, radar: &Radar) -> Result<Vec<Named>, ScenarioError> {
    let direction = match radar.rotation {
        Rotation::Clockwise => RotationDirection::Clockwise,
        Rotation::Counterclockwise => RotationDirection::Counterclockwise,
    };
    let rotation = argus_tracker::Rotation::clockwise(radar.period)
        .with_direction(direction)
        .with_north_time(radar.north_time);
    let sensor = SensorConfig::polar(
        argus_tracker::SensorId(RADAR),
        [0.0, 0.0],
        radar.sigma_range,
        radar.sigma_azimuth,
    )
    .with_rotation(rotation);
    let mut base = TrackerConfig::new(vec![sensor]);
    tracker_params::apply_all(
        &[
            tracker_params::KF_SIGMA_A,
            tracker_params::SECTOR_FRACTION,
            tracker_params::CONFIRM_M,
            tracker_params::CONFIRM_N,
            tracker_params::MAX_MISSES,
        ],
        p,
        &mut base,
    )?;
    base.max_initiation_interval = p.get("init_revolutions")? * radar.period;
    tracker_params::MAX_SPEED.apply(p, &mut base)?;
    if p.get("score")? >= 0.5 {
        tracker_params::set_track_score(
            p,
            &mut base,
            radar.p_detection,
            radar.clutter_density().max(1e-12),
        )?;
    }
    let imm = tracker_params::imm_cv2(p, &base)?;
    // The tracker's λ is per m² per scan (here: per revolution); a floor keeps JPDA's
    // weights finite without clutter.
    let jpda = tracker_params::jpda(
        p,
        &base,
        radar.p_detection,
        radar.clutter_density().max(1e-12),
    )?;
    let aircraft = tracker_params::aircraft(
        p,
        &base,
        &[
            tracker_params::AC_CV_SIGMA_LOW,
            tracker_params::AC_CV_SIGMA_HIGH,
            tracker_params::AC_CT_SIGMA_A,
            tracker_params::AC_CT_SIGMA_OMEGA_DEG,
        ],
    )?;
    let with = |estimator, association| TrackerConfig {
        estimator,
        association,
        ..base.clone()
    };
    let out = vec![
        Named {
            name: "gnn_kf",
            config: with(EstimatorConfig::Kf, AssociationConfig::Gnn),
        },
        Named {
            name: "gnn_imm",
            config: with(imm, AssociationConfig::Gnn),
        },
        Named {
            name: "jpda_kf",
            config: with(EstimatorConfig::Kf, jpda),
        },
        Named {
            name: "jpda_imm",
            config: with(imm, jpda),
        },
        Named {
            name: "gnn_aircraft",
            config: with(aircraft, AssociationConfig::Gnn),
        },
        Named {
            name: "jpda_aircraft",
            config: with(aircraft, jpda),
        },
    ];
    for n in &out {
        n.config.validate()?;
    }
    Ok(out)
}

/// Runs `config` over `plots` (fed a `chunk` of seconds at a time, as a stream) and
/// returns every track's rows: its state each time it was updated or missed, with each
/// row's estimate (mean and covariance) for smoothing and the NEES.
/// A row's combined estimate and, for the two-mode IMM, the track's IMM state; for the
/// aircraft IMM its state (boxed: 584 bytes).
type RowEstimate = (argus_core_math::Gaussian<4>, EstimatorState);

/// One track's rows as the tracker gave them: its history, and per row its combined
/// estimate and its estimator state ([`argus_tracker::Track::state`]), for smoothing.
pub(crate) struct TrackRecord {
    pub(crate) history: TrackHistory,
    pub(crate) estimates: Vec<argus_core_math::Gaussian<4>>,
    pub(crate) states: Vec<EstimatorState>,
}

pub(crate) fn track_with_estimates(
    config: &TrackerConfig,
    plots: &[Plot],
    chunk: f64,
) -> Result<Vec<TrackRecord>, ScenarioError> {
    let mut tracker = Tracker::new(config.clone())?;
    let mut rows: std::collections::BTreeMap<u64, Vec<(TrackRow, RowEstimate)>> =
        std::collections::BTreeMap::new();
    let mut record = |tracker: &mut Tracker| {
        for tr in tracker.tracks().iter().chain(tracker.deleted()) {
            let deleted = tr.status() == TrackStatus::Deleted;
            let r = rows.entry(tr.id().0).or_default();
            // A deleted track's last row (not confirmed: the track is gone from then on,
            // as the tracks CSV's `deleted` row says).
            if !deleted && r.last().is_some_and(|l| l.0.t >= tr.time()) {
                continue;
            }
            let x = tr.estimate().mean();
            r.push((
                TrackRow {
                    t: tr.time(),
                    confirmed: tr.status() == TrackStatus::Confirmed,
                    x: x[0],
                    vx: x[1],
                    y: x[2],
                    vy: x[3],
                },
                (*tr.estimate(), tr.state().clone()),
            ));
        }
        tracker.take_deleted();
    };
    let mut start = 0;
    while start < plots.len() {
        let end_t = plots[start].time() + chunk;
        let len = plots[start..]
            .iter()
            .take_while(|p| p.time() < end_t)
            .count()
            .max(1);
        tracker.process(&plots[start..start + len])?;
        record(&mut tracker);
        start += len;
    }
    tracker.flush();
    record(&mut tracker);
    rows.into_iter()
        .filter(|(_, r)| !r.is_empty())
        .map(|(id, r)| {
            let (rows, estimates): (Vec<TrackRow>, Vec<RowEstimate>) = r.into_iter().unzip();
            let (estimates, states): (Vec<_>, Vec<_>) = estimates.into_iter().unzip();
            let h = TrackHistory::new(id.to_string(), rows).map_err(ScenarioError::from)?;
            Ok(TrackRecord {
                history: h,
                estimates,
                states,
            })
        })
        .collect()
}

/// The truth samples inside the radar's coverage, per path (a path leaving and
/// re-entering the coverage has a gap the scorer does not interpolate across).
fn covered_truth(
    paths: &[Path],
    radar: &Radar,
    duration: f64,
) -> Result<Vec<TruthPath>, ScenarioError> {
    let mut out = Vec::new();
    for p in paths {
        let samples: Vec<TruthSample> = p
            .samples
            .iter()
            .filter(|s| {
                s.t < duration && (radar.min_range..=radar.max_range).contains(&s.x.hypot(s.y))
            })
            .map(|s| TruthSample {
                t: s.t,
                x: s.x,
                vx: s.vx,
                y: s.y,
                vy: s.vy,
            })
            .collect();
        if !samples.is_empty() {
            out.push(TruthPath::new(p.name.clone(), samples)?);
        }
    }
    Ok(out)
}

/// Each path followed for [`EXTENSION`] s past its last sample at its last velocity, a
/// sample every 5 s (the scorer interpolates only across gaps of at most 10 s).
fn extended(truth: &[TruthPath]) -> Result<Vec<TruthPath>, ScenarioError> {
    truth
        .iter()
        .map(|p| {
            let mut samples = p.samples().to_vec();
            if let Some(&last) = p.samples().last() {
                let mut dt = 5.0;
                while dt <= EXTENSION {
                    samples.push(TruthSample {
                        t: last.t + dt,
                        x: last.x + last.vx * dt,
                        y: last.y + last.vy * dt,
                        ..last
                    });
                    dt += 5.0;
                }
            }
            Ok(TruthPath::new(p.name(), samples)?)
        })
        .collect()
}

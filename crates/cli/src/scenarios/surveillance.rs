//! `surveillance`: the multi-target tracker on an air-traffic surveillance picture
//! (issue 9). One 2-D radar at the origin covers a disc of radius `range` (200 km);
//! `targets` aircraft (200) fly random sequences of constant-velocity and coordinated-turn
//! segments (`argus_sim` truth segments); the radar scans every `period` (5 s), detects
//! each aircraft with probability `p_d` (0.9) and reports range and azimuth with noise
//! σr, σθ; Poisson clutter adds on average `clutter` false plots per scan, uniform over
//! the covered disc. Every plot (target or clutter) is converted to Cartesian with the
//! unbiased conversion and its covariance ([`argus_sensors::convert_polar`],
//! [`ConversionMethod::Unbiased`], evaluated at the plot) and fed to
//! [`argus_tracker::Tracker`].
//!
//! Four tracker configurations run on the same plots of every run: GNN with a Kalman
//! filter per track (`gnn_kf`), GNN with a two-mode CV IMM per track (`gnn_imm`), JPDA
//! with a Kalman filter (`jpda_kf`) and JPDA with the IMM (IMM-JPDA, `jpda_imm`).
//!
//! At each scan the confirmed tracks' positions are scored against the truth with
//! OSPA and GOSPA (α = 2, cut-off `cutoff`, order `order`; GOSPA split into
//! localisation, missed and false costs, [`argus_sim::Gospa`]) and associated to the
//! truths by the optimal assignment within `cutoff` ([`TrackScan::assign`]), from which
//! [`TrackStatistics`] gives track breaks, id swaps, time to confirm and the false-track
//! rate. Reported per configuration: the means after the confirmation period (`warmup`)
//! and the per-run track statistics; per scan: OSPA, GOSPA and its split, missed and
//! false counts and breaks, each averaged over the runs.
//!
//! # Random draws
//! Run `i`'s truth is drawn from `run_rng(truth_seed, i)` (so `--seed` changes the noise
//! and clutter, `--set truth_seed` the traffic), per aircraft in order: start position
//! (uniform in the disc of radius `start_radius`), speed, heading, then its segments
//! (CV duration, turn duration, turn rate and sense, alternating, CV first, until the
//! horizon is covered). The plots come from `run_rng(seed, i)`: first the target plots by
//! [`argus_sim::generate_plots`] (in its documented order), then per scan the clutter
//! count and, per clutter plot, its radius and azimuth. `argus simulate surveillance
//! --run 0` therefore writes run 0's truth and target plots (without the clutter, which
//! is drawn here).
//!
//! Clutter is drawn here rather than by `argus_sim`'s polar clutter box because a box
//! in (range, azimuth) is uniform per m·rad, hence denser per m² near the radar (∝ 1/r),
//! whereas JPDA takes one spatial density `λ`. Here it is uniform per m² over the disc:
//! `λ = clutter / (π range²)`, and JPDA is given that `λ`.

use std::f64::consts::{PI, TAU};

use argus_core_math::Vector;
use argus_sensors::{ConversionMethod, Measurement, convert_polar};
use argus_sim::{
    ChaCha8Rng, Detection, Gospa, KinematicState, Ospa, Schedule, Segment, SensorId, SensorKind,
    SensorSpec, TargetId, TrackScan, TrackStatistics, Trajectory, Truth, generate_plots, run_rng,
};
use argus_tracker::{
    AssociationConfig, EstimatorConfig, Plot, TrackStatus, Tracker, TrackerConfig,
};
use rand_distr::{Distribution, OpenClosed01, Poisson, StandardUniform};
use serde::{Deserialize, Serialize};

use crate::campaign::{Campaign, Splittable, in_process};
use crate::error::CliError;
use crate::report::{Figure, Line, LineStyle, Report, Row, Series};
use crate::scenario::{ParamSpec, Params, RunContext, Scenario};

/// The `surveillance` scenario.
pub(crate) struct Surveillance;

/// The tracker configurations compared: summary key prefix and legend label.
const CONFIGS: [(&str, &str); 4] = [
    ("gnn_kf", "GNN, KF"),
    ("gnn_imm", "GNN, IMM"),
    ("jpda_kf", "JPDA, KF"),
    ("jpda_imm", "JPDA, IMM"),
];

/// The radar's id in `argus_sim` and in the tracker.
const RADAR: u32 = 0;

/// Clutter density floor given to JPDA when `clutter = 0` (it needs `λ > 0`): one false
/// plot per thousand scans over the coverage.
const MIN_CLUTTER_PER_SCAN: f64 = 1e-3;

/// Everything a campaign shares between runs, from the parameters.
pub(crate) struct Setup {
    targets: usize,
    duration: f64,
    period: f64,
    scans: usize,
    range: f64,
    start_radius: f64,
    speed: (f64, f64),
    cv_duration: (f64, f64),
    turn_duration: (f64, f64),
    turn_rate: (f64, f64),
    sigma_r: f64,
    sigma_az: f64,
    clutter: f64,
    radar: SensorSpec,
    truth_seed: u64,
    warmup: f64,
    ospa: Ospa,
    gospa: Gospa,
    trackers: Vec<TrackerConfig>,
}

/// One scan's scores for one configuration (counts as `f64` for the averages).
#[derive(Debug, Clone, Copy, Serialize, Deserialize, Default)]
pub(crate) struct ScanScore {
    /// OSPA distance (m).
    ospa: f64,
    /// GOSPA distance (m).
    gospa: f64,
    /// GOSPA localisation cost `Σ d^p` over assigned pairs (m^p).
    loc: f64,
    /// Assigned pairs.
    assigned: usize,
    /// Missed truths.
    missed: usize,
    /// False confirmed tracks (GOSPA).
    false_tracks: usize,
    /// Confirmed tracks.
    confirmed: usize,
    /// Track breaks at this scan (a truth tracked at the previous scan, untracked now).
    breaks: usize,
}

/// Reads one number from a scan's scores.
type ScoreOf<'a> = dyn Fn(&ScanScore) -> f64 + 'a;

/// One configuration's results in one run.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(crate) struct ConfigRun {
    scans: Vec<ScanScore>,
    breaks: usize,
    id_swaps: usize,
    /// Per target: time to confirm (s), `None` if never tracked.
    time_to_confirm: Vec<Option<f64>>,
    false_tracks_per_scan: f64,
    false_track_ids: usize,
    tracks_seen: usize,
}

/// One run: one entry per [`CONFIGS`] item.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(crate) struct SurvRun {
    configs: Vec<ConfigRun>,
}

fn unit(rng: &mut ChaCha8Rng) -> f64 {
    StandardUniform.sample(rng)
}

fn between(rng: &mut ChaCha8Rng, (lo, hi): (f64, f64)) -> f64 {
    lo + (hi - lo) * unit(rng)
}

impl Setup {
    fn new(p: &Params) -> Result<Self, CliError> {
        let pair = |lo: &str, hi: &str| -> Result<(f64, f64), CliError> {
            let (a, b) = (p.get(lo)?, p.get(hi)?);
            if a > b {
                return Err(CliError::Usage(format!(
                    "--set {lo}={a} exceeds {hi}={b}: the range is empty"
                )));
            }
            Ok((a, b))
        };
        let duration = p.get("duration")?;
        let period = p.get("period")?;
        let range = p.get("range")?;
        let start_radius = p.get("start_radius")?;
        if start_radius > range {
            return Err(CliError::Usage(format!(
                "--set start_radius={start_radius} exceeds range={range}"
            )));
        }
        let speed = pair("speed_min", "speed_max")?;
        let p_d = p.get("p_d")?;
        let sigma_r = p.get("sigma_r")?;
        let sigma_az = p.get("sigma_az_deg")?.to_radians();
        let clutter = p.get("clutter")?;
        let radar = SensorSpec::new(
            SensorId(RADAR),
            Vector::<3>::zeros(),
            SensorKind::Polar {
                sigma_range: sigma_r,
                sigma_azimuth: sigma_az,
            },
            Schedule::Periodic {
                period,
                offset: 0.0,
            },
        )?
        .with_detection(Detection::Probability(p_d))?;
        let cutoff = p.get("cutoff")?;
        let order = p.get("order")?;
        let area = PI * range * range;
        let mut base = TrackerConfig::new(vec![argus_tracker::SensorId(RADAR)]);
        base.sigma_a = p.get("kf_sigma_a")?;
        // The tracker's defaults assume ≤ 350 m/s and 5 s scans: widen them with the
        // scenario (fastest aircraft + 20 %, unused plots kept for 2.4 scans).
        base.max_speed = base.max_speed.max(1.2 * speed.1);
        base.max_initiation_interval = 2.4 * period;
        let imm = EstimatorConfig::ImmCv2 {
            sigma_a_low: p.get("imm_sigma_low")?,
            sigma_a_high: p.get("imm_sigma_high")?,
            p_stay: p.get("imm_p_stay")?,
        };
        let jpda = AssociationConfig::Jpda {
            p_detection: p_d,
            clutter_density: clutter.max(MIN_CLUTTER_PER_SCAN) / area,
            max_exact_events: p.get("jpda_max_events")? as usize,
        };
        let trackers = vec![
            base.clone(),
            TrackerConfig {
                estimator: imm,
                ..base.clone()
            },
            TrackerConfig {
                association: jpda,
                ..base.clone()
            },
            TrackerConfig {
                association: jpda,
                estimator: imm,
                ..base
            },
        ];
        for c in &trackers {
            c.validate()?;
        }
        let seed = p.get("truth_seed")?;
        Ok(Self {
            targets: p.get("targets")? as usize,
            duration,
            period,
            // Scans at k·period, k = 0 ..= ⌊duration/period⌋ (1e-9 guards a ratio that
            // is whole but rounds just below).
            scans: (duration / period + 1e-9).floor() as usize + 1,
            range,
            start_radius,
            speed,
            cv_duration: pair("cv_min", "cv_max")?,
            turn_duration: pair("turn_min", "turn_max")?,
            turn_rate: pair("turn_rate_min", "turn_rate_max")?,
            sigma_r,
            sigma_az,
            clutter,
            radar,
            truth_seed: seed as u64,
            warmup: p.get("warmup")?,
            ospa: Ospa::new(cutoff, order)?,
            gospa: Gospa::new(cutoff, order)?,
            trackers,
        })
    }

    /// The traffic of run `run`: `targets` aircraft present from 0 to beyond the last
    /// scan (the last segment runs half a period past `duration`, so the last scan is
    /// inside every trajectory).
    fn truth(&self, run: u64) -> Result<Truth, CliError> {
        let rng = &mut run_rng(self.truth_seed, run);
        let end = self.duration + 0.5 * self.period;
        let mut truth = Truth::new();
        for _ in 0..self.targets {
            let r = self.start_radius * unit(rng).sqrt();
            let phi = TAU * unit(rng);
            let speed = between(rng, self.speed);
            let heading = TAU * unit(rng);
            let mut segments = Vec::new();
            let mut t = 0.0;
            let mut turn = false;
            while t < end {
                let seg = if turn {
                    let d = between(rng, self.turn_duration).min(end - t);
                    let rate = between(rng, self.turn_rate).to_radians();
                    let sense = if unit(rng) < 0.5 { -1.0 } else { 1.0 };
                    Segment::Turn {
                        duration: d,
                        rate: sense * rate,
                    }
                } else {
                    Segment::ConstantVelocity {
                        duration: between(rng, self.cv_duration).min(end - t),
                    }
                };
                // A zero-length draw (min = max = 0) would never advance: stop there.
                if seg.duration() <= 0.0 {
                    segments.push(Segment::ConstantVelocity { duration: end - t });
                    break;
                }
                t += seg.duration();
                segments.push(seg);
                turn = !turn;
            }
            let start = KinematicState::planar(
                r * phi.cos(),
                r * phi.sin(),
                speed * heading.cos(),
                speed * heading.sin(),
            );
            truth.add(Trajectory::new(0.0, start, segments)?);
        }
        Ok(truth)
    }

    /// The tracker's plots of every scan: the converted target plots, then the clutter.
    fn plots(&self, truth: &Truth, rng: &mut ChaCha8Rng) -> Result<Vec<Vec<Plot>>, CliError> {
        let raw = generate_plots(truth, std::slice::from_ref(&self.radar), rng)?;
        let mut scans: Vec<Vec<Plot>> = vec![Vec::new(); self.scans];
        for p in &raw {
            let k = (p.plot.time() / self.period).round();
            let Measurement::Polar(m) = p.plot.measurement() else {
                continue;
            };
            let (range, azimuth) = (m.range(), m.azimuth());
            // A noisy range at or below zero (a target over the radar) is no plot.
            if k < 0.0 || range <= 0.0 {
                continue;
            }
            if let Some(scan) = scans.get_mut(k as usize) {
                scan.push(self.convert(k as usize, range, azimuth)?);
            }
        }
        let count = if self.clutter > 0.0 {
            Some(
                Poisson::new(self.clutter)
                    .map_err(|e| CliError::Usage(format!("--set clutter: {e}")))?,
            )
        } else {
            None
        };
        for (k, scan) in scans.iter_mut().enumerate() {
            let n: f64 = count.map_or(0.0, |c| c.sample(rng));
            for _ in 0..n as u64 {
                // Uniform per m² over the disc: r = R √u (u in (0, 1], so r > 0).
                let u: f64 = OpenClosed01.sample(rng);
                let azimuth = TAU * unit(rng) - PI;
                scan.push(self.convert(k, self.range * u.sqrt(), azimuth)?);
            }
        }
        Ok(scans)
    }

    fn convert(&self, k: usize, range: f64, azimuth: f64) -> Result<Plot, CliError> {
        let c = convert_polar(
            range,
            azimuth,
            self.sigma_r,
            self.sigma_az,
            ConversionMethod::Unbiased,
        )?;
        Ok(Plot::cartesian(
            self.time(k),
            argus_tracker::SensorId(RADAR),
            c.position,
            c.covariance,
        )?)
    }

    fn time(&self, k: usize) -> f64 {
        k as f64 * self.period
    }

    /// Runs one tracker configuration over the scans and scores it.
    fn track(
        &self,
        config: &TrackerConfig,
        scans: &[Vec<Plot>],
        truth: &[Vec<(TargetId, Vector<2>)>],
    ) -> Result<ConfigRun, CliError> {
        let mut tracker = Tracker::new(config.clone())?;
        let mut scores = Vec::with_capacity(scans.len());
        let mut track_scans = Vec::with_capacity(scans.len());
        let mut tracked = vec![false; self.targets];
        let mut now = vec![false; self.targets];
        let mut confirmed: Vec<(u64, Vector<2>)> = Vec::new();
        let mut estimates: Vec<Vector<2>> = Vec::new();
        for (k, (plots, truths)) in scans.iter().zip(truth).enumerate() {
            let t = self.time(k);
            tracker.process_scan(t, argus_tracker::SensorId(RADAR), plots)?;
            // Deleted tracks are not scored: drop them so memory stays flat.
            drop(tracker.take_deleted());
            confirmed.clear();
            confirmed.extend(
                tracker
                    .tracks()
                    .iter()
                    .filter(|tr| tr.status() == TrackStatus::Confirmed)
                    .map(|tr| {
                        let m = tr.estimate().mean();
                        (tr.id().0, Vector::<2>::new(m[0], m[2]))
                    }),
            );
            estimates.clear();
            estimates.extend(confirmed.iter().map(|c| c.1));
            let truth_xy: Vec<Vector<2>> = truths.iter().map(|g| g.1).collect();
            let g = self.gospa.distance(&truth_xy, &estimates)?;
            let o = self.ospa.distance(&truth_xy, &estimates)?;
            let scan = TrackScan::assign(t, truths, &confirmed, self.ospa.cutoff())?;
            now.iter_mut().for_each(|x| *x = false);
            for &(_, g) in scan.pairs() {
                if let Some(x) = now.get_mut(g.0 as usize) {
                    *x = true;
                }
            }
            let breaks = tracked.iter().zip(&now).filter(|&(&a, &b)| a && !b).count();
            std::mem::swap(&mut tracked, &mut now);
            track_scans.push(scan);
            scores.push(ScanScore {
                ospa: o.distance,
                gospa: g.distance,
                loc: g.localisation,
                assigned: g.assigned,
                missed: g.missed_count,
                false_tracks: g.false_count,
                confirmed: confirmed.len(),
                breaks,
            });
        }
        let stats = TrackStatistics::from_scans(&track_scans)?;
        Ok(ConfigRun {
            scans: scores,
            breaks: stats.breaks,
            id_swaps: stats.id_swaps,
            time_to_confirm: stats.time_to_confirm.iter().map(|x| x.1).collect(),
            false_tracks_per_scan: stats.false_tracks_per_scan,
            false_track_ids: stats.false_track_ids,
            tracks_seen: stats.tracks_seen,
        })
    }
}

impl Scenario for Surveillance {
    fn name(&self) -> &'static str {
        "surveillance"
    }

    fn description(&self) -> &'static str {
        "issue 9: 200 aircraft, 200 km radar, 5 s scans, P_D 0.9, clutter; GNN/JPDA, KF/IMM trackers; OSPA, GOSPA, track statistics"
    }

    fn default_runs(&self) -> u64 {
        20
    }

    fn params(&self) -> Vec<ParamSpec> {
        vec![
            ParamSpec::new("targets", 200.0, 1.0, 100_000.0, "number of aircraft"),
            ParamSpec::new("duration", 300.0, 10.0, 1e5, "time of the last scan (s)"),
            ParamSpec::new("period", 5.0, 0.1, 60.0, "scan period (s)"),
            ParamSpec::new(
                "range",
                200_000.0,
                1e3,
                1e7,
                "radius of the radar coverage (m)",
            ),
            ParamSpec::new(
                "start_radius",
                110_000.0,
                0.0,
                1e7,
                "aircraft start uniformly in a disc of this radius (m)",
            ),
            ParamSpec::new("speed_min", 100.0, 0.0, 2000.0, "slowest aircraft (m/s)"),
            ParamSpec::new("speed_max", 300.0, 0.0, 2000.0, "fastest aircraft (m/s)"),
            ParamSpec::new("cv_min", 20.0, 0.0, 1e5, "shortest straight segment (s)"),
            ParamSpec::new("cv_max", 120.0, 0.0, 1e5, "longest straight segment (s)"),
            ParamSpec::new("turn_min", 10.0, 0.0, 1e5, "shortest turn (s)"),
            ParamSpec::new("turn_max", 40.0, 0.0, 1e5, "longest turn (s)"),
            ParamSpec::new(
                "turn_rate_min",
                1.0,
                0.0,
                30.0,
                "slowest turn rate (deg/s), either sense",
            ),
            ParamSpec::new(
                "turn_rate_max",
                3.0,
                0.0,
                30.0,
                "fastest turn rate (deg/s), either sense",
            ),
            ParamSpec::new("p_d", 0.9, 0.05, 1.0, "detection probability"),
            ParamSpec::new("sigma_r", 50.0, 1e-3, 1e4, "range noise σ (m)"),
            ParamSpec::new("sigma_az_deg", 0.1, 1e-6, 10.0, "azimuth noise σ (deg)"),
            ParamSpec::new(
                "clutter",
                500.0,
                0.0,
                1e6,
                "mean false plots per scan, uniform over the coverage disc",
            ),
            ParamSpec::new(
                "cutoff",
                1000.0,
                1.0,
                1e6,
                "OSPA/GOSPA cut-off c, also the track-to-truth distance limit (m)",
            ),
            ParamSpec::new("order", 2.0, 1.0, 10.0, "OSPA/GOSPA order p"),
            ParamSpec::new(
                "warmup",
                30.0,
                0.0,
                1e5,
                "scans before this time (s) are left out of the time averages",
            ),
            ParamSpec::new(
                "kf_sigma_a",
                3.0,
                0.0,
                100.0,
                "KF tracks' white-acceleration σ (m/s²)",
            ),
            ParamSpec::new(
                "imm_sigma_low",
                0.5,
                0.0,
                100.0,
                "IMM quiet mode's white-acceleration σ (m/s²)",
            ),
            ParamSpec::new(
                "imm_sigma_high",
                10.0,
                0.0,
                100.0,
                "IMM manoeuvre mode's white-acceleration σ (m/s²)",
            ),
            ParamSpec::new(
                "imm_p_stay",
                0.95,
                1e-3,
                0.999,
                "IMM probability of staying in a mode per scan",
            ),
            ParamSpec::new(
                "jpda_max_events",
                1000.0,
                1.0,
                1e7,
                "JPDA: largest cluster enumerated exactly (joint events)",
            ),
            ParamSpec::new(
                "truth_seed",
                1.0,
                0.0,
                9e15,
                "seed of the traffic (run i uses stream i)",
            ),
        ]
    }

    fn scene(&self, params: &Params) -> Result<(Truth, Vec<SensorSpec>), CliError> {
        let s = Setup::new(params)?;
        Ok((s.truth(0)?, vec![s.radar.clone()]))
    }

    fn run(&self, ctx: &RunContext) -> Result<Report, CliError> {
        let records = Splittable::records(self, ctx)?;
        self.reduce_records(&ctx.params, &in_process(records, &ctx.runs))
    }

    fn splittable(&self) -> Option<&dyn Splittable> {
        Some(self)
    }
}

impl Campaign for Surveillance {
    type Setup = Setup;
    type Run = SurvRun;

    fn setup(&self, params: &Params) -> Result<Setup, CliError> {
        Setup::new(params)
    }

    fn one_run(&self, s: &Setup, run: u64, rng: &mut ChaCha8Rng) -> Result<SurvRun, CliError> {
        let truth = s.truth(run)?;
        let scans = s.plots(&truth, rng)?;
        let truth_xy = (0..s.scans)
            .map(|k| {
                truth
                    .targets()
                    .iter()
                    .map(|(id, tr)| {
                        let x = tr.state_at(s.time(k))?;
                        Ok((*id, Vector::<2>::new(x.position.x, x.position.y)))
                    })
                    .collect::<Result<Vec<_>, CliError>>()
            })
            .collect::<Result<Vec<_>, CliError>>()?;
        let configs = s
            .trackers
            .iter()
            .map(|c| s.track(c, &scans, &truth_xy))
            .collect::<Result<Vec<_>, CliError>>()?;
        Ok(SurvRun { configs })
    }

    #[allow(clippy::too_many_lines)]
    fn reduce(&self, s: &Setup, runs: &[SurvRun]) -> Result<Report, CliError> {
        if runs.is_empty() {
            return Err(CliError::Usage("surveillance: no runs".into()));
        }
        let n_runs = runs.len() as f64;
        let (c, p) = (s.ospa.cutoff(), s.ospa.order());
        // GOSPA with no track at all: every one of the n truths is missed at c^p/2
        // (Rahmathullah et al. 2017, α = 2), so d^p = n c^p / 2 and d = c (n/2)^{1/p}.
        let no_tracks = c * (s.targets as f64 / 2.0).powf(1.0 / p);
        let times: Vec<f64> = (0..s.scans).map(|k| s.time(k)).collect();
        let after: Vec<usize> = (0..s.scans).filter(|&k| s.time(k) >= s.warmup).collect();
        if after.is_empty() {
            return Err(CliError::Usage(format!(
                "--set warmup={} leaves no scan (the last is at {} s)",
                s.warmup,
                s.time(s.scans - 1)
            )));
        }
        let mut rows = vec![
            Row::new("gospa_no_tracks", "GOSPA with no tracks", no_tracks, "m").note(format!(
                "c (n/2)^(1/p): c = {c} m, p = {p}, n = {}",
                s.targets
            )),
        ];
        let mut columns = vec!["t".to_owned()];
        let mut per_scan: Vec<Vec<f64>> = times.iter().map(|&t| vec![t]).collect();
        let mut ospa_lines = Vec::new();
        let mut gospa_lines = Vec::new();
        let mut count_lines = Vec::new();
        for (i, (key, label)) in CONFIGS.iter().enumerate() {
            let cfg: Vec<&ConfigRun> = runs.iter().filter_map(|r| r.configs.get(i)).collect();
            if cfg.len() != runs.len() {
                return Err(CliError::Usage(format!(
                    "surveillance: a run record lacks configuration {key}"
                )));
            }
            let score = |k: usize, f: &dyn Fn(&ScanScore) -> f64| -> f64 {
                cfg.iter()
                    .map(|r| r.scans.get(k).map_or(0.0, f))
                    .sum::<f64>()
                    / n_runs
            };
            let fields: [(&str, &ScoreOf<'_>); 8] = [
                ("ospa", &|x| x.ospa),
                ("gospa", &|x| x.gospa),
                ("gospa_loc", &|x| x.loc),
                ("gospa_missed", &|x| x.missed as f64 * 0.5 * c.powf(p)),
                ("gospa_false", &|x| x.false_tracks as f64 * 0.5 * c.powf(p)),
                ("missed", &|x| x.missed as f64),
                ("false", &|x| x.false_tracks as f64),
                ("breaks", &|x| x.breaks as f64),
            ];
            let mut means = Vec::with_capacity(fields.len());
            for (name, f) in &fields {
                columns.push(format!("{key}_{name}"));
                let mut sum_after = 0.0;
                for (k, row) in per_scan.iter_mut().enumerate() {
                    let v = score(k, *f);
                    row.push(v);
                    if s.time(k) >= s.warmup {
                        sum_after += v;
                    }
                }
                means.push(sum_after / after.len() as f64);
            }
            columns.push(format!("{key}_confirmed"));
            for (k, row) in per_scan.iter_mut().enumerate() {
                row.push(score(k, &|x| x.confirmed as f64));
            }
            let col = |j: usize| -> Vec<(f64, f64)> {
                let idx = 1 + i * (fields.len() + 1) + j;
                per_scan
                    .iter()
                    .map(|r| (r[0], r.get(idx).copied().unwrap_or(0.0)))
                    .collect()
            };
            ospa_lines.push(Line {
                label: (*label).to_owned(),
                points: col(0),
                style: LineStyle::Solid,
            });
            gospa_lines.push(Line {
                label: (*label).to_owned(),
                points: col(1),
                style: LineStyle::Solid,
            });
            count_lines.push(Line {
                label: format!("{label}: missed"),
                points: col(5),
                style: LineStyle::Solid,
            });
            count_lines.push(Line {
                label: format!("{label}: false"),
                points: col(6),
                style: LineStyle::Points,
            });
            // Localisation per assigned target, pooled over runs and scans after warm-up.
            let (loc_sum, assigned): (f64, usize) = cfg
                .iter()
                .flat_map(|r| after.iter().filter_map(|&k| r.scans.get(k)))
                .fold((0.0, 0), |(l, a), x| (l + x.loc, a + x.assigned));
            let loc_mean = if assigned > 0 {
                (loc_sum / assigned as f64).powf(1.0 / p)
            } else {
                0.0
            };
            let ttc: Vec<f64> = cfg
                .iter()
                .flat_map(|r| r.time_to_confirm.iter().flatten().copied())
                .collect();
            let never: usize = cfg
                .iter()
                .map(|r| r.time_to_confirm.iter().filter(|x| x.is_none()).count())
                .sum();
            let ttc_mean = if ttc.is_empty() {
                0.0
            } else {
                ttc.iter().sum::<f64>() / ttc.len() as f64
            };
            let per_run =
                |f: &dyn Fn(&ConfigRun) -> f64| cfg.iter().map(|r| f(r)).sum::<f64>() / n_runs;
            let after_note = format!(
                "mean over {} runs × scans at t ≥ {} s",
                runs.len(),
                s.warmup
            );
            rows.extend([
                Row::new(
                    format!("{key}_gospa"),
                    format!("{label}: GOSPA"),
                    means[1],
                    "m",
                )
                .note(format!("{after_note}; no tracks: {no_tracks:.0} m")),
                Row::new(
                    format!("{key}_ospa"),
                    format!("{label}: OSPA"),
                    means[0],
                    "m",
                )
                .note(after_note.clone()),
                Row::new(
                    format!("{key}_localisation"),
                    format!("{label}: position error of assigned targets"),
                    loc_mean,
                    "m",
                )
                .note(format!(
                    "(Σ GOSPA localisation / Σ assigned)^(1/p), pooled, t ≥ {} s",
                    s.warmup
                )),
                Row::new(
                    format!("{key}_missed"),
                    format!("{label}: missed targets per scan"),
                    means[5],
                    "-",
                )
                .note(format!("GOSPA split; {after_note}")),
                Row::new(
                    format!("{key}_false"),
                    format!("{label}: false tracks per scan"),
                    means[6],
                    "-",
                )
                .note(format!("GOSPA split; {after_note}")),
                Row::new(
                    format!("{key}_false_track_rate"),
                    format!("{label}: false-track rate"),
                    per_run(&|r| r.false_tracks_per_scan),
                    "1/scan",
                )
                .note("confirmed tracks assigned to no truth, per scan, whole run"),
                Row::new(
                    format!("{key}_false_track_ids"),
                    format!("{label}: false tracks per run"),
                    per_run(&|r| r.false_track_ids as f64),
                    "-",
                )
                .note(format!(
                    "distinct confirmed tracks never assigned; of {:.1} tracks seen",
                    per_run(&|r| r.tracks_seen as f64)
                )),
                Row::new(
                    format!("{key}_breaks"),
                    format!("{label}: track breaks per run"),
                    per_run(&|r| r.breaks as f64),
                    "-",
                )
                .note(format!("{} targets, {} scans", s.targets, s.scans)),
                Row::new(
                    format!("{key}_id_swaps"),
                    format!("{label}: id swaps per run"),
                    per_run(&|r| r.id_swaps as f64),
                    "-",
                ),
                Row::new(
                    format!("{key}_time_to_confirm"),
                    format!("{label}: time to confirm"),
                    ttc_mean,
                    "s",
                )
                .note(format!(
                    "mean over tracked targets; {:.2} targets per run never tracked",
                    never as f64 / n_runs
                )),
            ]);
        }
        let figure = |name: &str, title: &str, y: &str, lines: Vec<Line>| Figure {
            name: name.into(),
            title: format!(
                "surveillance: {title} ({} runs, {} targets)",
                runs.len(),
                s.targets
            ),
            x_label: "time (s)".into(),
            y_label: y.into(),
            lines,
        };
        gospa_lines.push(Line {
            label: "no tracks".into(),
            points: times.iter().map(|&t| (t, no_tracks)).collect(),
            style: LineStyle::Bound,
        });
        Ok(Report {
            rows,
            series: vec![Series {
                name: "per_scan".into(),
                columns,
                rows: per_scan,
            }],
            figures: vec![
                figure("ospa", "OSPA", "OSPA (m)", ospa_lines),
                figure("gospa", "GOSPA", "GOSPA (m)", gospa_lines),
                figure(
                    "missed_false",
                    "missed targets and false tracks",
                    "per scan (-)",
                    count_lines,
                ),
            ],
            notes: vec![format!(
                "clutter {} plots/scan (λ = {:.3e} /m²); plots: polar σr = {} m, σθ = {:.3}°, unbiased conversion with its covariance",
                s.clutter,
                s.clutter / (PI * s.range * s.range),
                s.sigma_r,
                s.sigma_az.to_degrees()
            )],
        })
    }
}

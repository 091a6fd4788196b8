//! `surveillance`: the multi-target tracker on an air-traffic surveillance picture
//! (issue 9). One 2-D radar at the origin covers a disc of radius `range` (200 km);
//! `targets` aircraft (200) fly random sequences of constant-velocity and coordinated-turn
//! segments (`argus_sim` truth segments); the radar scans every `period` (5 s), detects
//! each aircraft with probability `p_d` (0.9) and reports range and azimuth with noise
//! σr, σθ; Poisson clutter adds on average `clutter` false plots per scan, uniform over
//! the covered disc. Every plot (target or clutter) is converted to Cartesian with the
//! unbiased conversion and its covariance ([`argus_sensors::convert_polar`],
//! [`ConversionMethod::Unbiased`], evaluated at the plot) and fed to
//! [`argus_tracker::Tracker`]; the aircraft IMM takes the polar plots as measured.
//!
//! Five tracker configurations run on the same plots of every run: the recommended
//! `default` (JPDA with the aircraft IMM per track, updated with the polar plots
//! themselves, confirmation and deletion by the track score with the clutter density,
//! deletion after 4 misses; docs/surveillance.md says why), then GNN with a Kalman filter
//! per track (`gnn_kf`), GNN with a two-mode CV IMM per track (`gnn_imm`), JPDA with a
//! Kalman filter (`jpda_kf`) and JPDA with the IMM (IMM-JPDA, `jpda_imm`), all four with
//! M-of-N confirmation on the converted plots.
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

mod report;
mod setup;
mod sums;

use argus_core_math::Vector;
use argus_sim::{ChaCha8Rng, SensorSpec, Truth};

use crate::campaign::{Campaign, Splittable, run_whole};
use crate::context::RunContext;
use crate::error::ScenarioError;
use crate::params::{ParamSpec, Params};
use crate::report::Report;
use crate::scenario::Scenario;
use crate::tracker_params::{self as tp, TrackerParam};
use setup::{Setup, SurvRun};
use sums::SurvSums;

/// The `surveillance` scenario.
pub(crate) struct Surveillance;

/// The default configuration's aircraft IMM: quiet CV mode σ_a.
const AC_CV_SIGMA_LOW: TrackerParam = tp::AC_CV_SIGMA_LOW
    .range(1e-3, 100.0)
    .help("default: aircraft IMM's quiet CV mode σ_a (m/s²)");
/// The default configuration's aircraft IMM: manoeuvre CV mode σ_a.
const AC_CV_SIGMA_HIGH: TrackerParam = tp::AC_CV_SIGMA_HIGH
    .range(1e-3, 100.0)
    .help("default: aircraft IMM's manoeuvre CV mode σ_a (m/s²)");
/// The default configuration's aircraft IMM: turn-rate random walk.
const AC_CT_SIGMA_OMEGA_DEG: TrackerParam =
    tp::AC_CT_SIGMA_OMEGA_DEG.help("default: aircraft IMM's turn-rate random walk σ_ω (deg/s²)");
/// The default configuration's deletion after misses.
const DEFAULT_MAX_MISSES: TrackerParam = tp::MAX_MISSES
    .key("default_max_misses")
    .help("default: a confirmed track is deleted after this many misses in a row");

impl Scenario for Surveillance {
    fn name(&self) -> &'static str {
        "surveillance"
    }

    fn description(&self) -> &'static str {
        "issues 9, 18: 200 aircraft, 200 km radar, 5 s scans, P_D 0.9, clutter; the default tracker and GNN/JPDA × KF/IMM; OSPA, GOSPA, track statistics"
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
            tp::KF_SIGMA_A.spec(3.0),
            tp::IMM_SIGMA_LOW.spec(0.5),
            tp::IMM_SIGMA_HIGH.spec(10.0),
            tp::IMM_P_STAY.spec(0.95),
            AC_CV_SIGMA_LOW.spec(0.3),
            AC_CV_SIGMA_HIGH.spec(8.0),
            AC_CT_SIGMA_OMEGA_DEG.spec(0.5),
            DEFAULT_MAX_MISSES.spec(4.0),
            tp::FALSE_CONFIRM
                .help("default: track score's probability of confirming a false track")
                .spec(1e-4),
            tp::DELETE_DROP
                .help("default: a confirmed track is deleted this far below its peak score")
                .spec(9.0),
            tp::NEW_TARGET_DENSITY
                .help("default: track score's new targets per m² per scan")
                .spec(1e-11),
            tp::JPDA_MAX_EVENTS.spec(1000.0),
            ParamSpec::new(
                "truth_seed",
                1.0,
                0.0,
                9e15,
                "seed of the traffic (run i uses stream i)",
            ),
        ]
    }

    fn scene(&self, params: &Params) -> Result<(Truth, Vec<SensorSpec>), ScenarioError> {
        let s = Setup::new(params)?;
        Ok((s.truth(0)?, vec![s.radar.clone()]))
    }

    fn run(&self, ctx: &RunContext<'_>) -> Result<Report, ScenarioError> {
        run_whole(self, ctx)
    }

    fn splittable(&self) -> Option<&dyn Splittable> {
        Some(self)
    }
}

impl Campaign for Surveillance {
    type Setup = Setup;
    type Run = SurvRun;
    type Sums = SurvSums;

    fn setup(&self, params: &Params) -> Result<Setup, ScenarioError> {
        Setup::new(params)
    }

    fn one_run(
        &self,
        s: &Setup,
        _seed: u64,
        run: u64,
        rng: &mut ChaCha8Rng,
    ) -> Result<SurvRun, ScenarioError> {
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
                    .collect::<Result<Vec<_>, ScenarioError>>()
            })
            .collect::<Result<Vec<_>, ScenarioError>>()?;
        let configs = s
            .trackers
            .iter()
            .map(|c| s.track(c, &scans, &truth_xy))
            .collect::<Result<Vec<_>, ScenarioError>>()?;
        Ok(SurvRun { configs })
    }

    fn start(&self, s: &Setup, _count: u64) -> Result<SurvSums, ScenarioError> {
        Ok(SurvSums::new(s))
    }

    fn add(&self, s: &Setup, sums: &mut SurvSums, run: SurvRun) -> Result<(), ScenarioError> {
        sums.add(s, &run);
        Ok(())
    }

    fn finish(&self, s: &Setup, sums: SurvSums) -> Result<Report, ScenarioError> {
        report::reduce(s, &sums)
    }
}

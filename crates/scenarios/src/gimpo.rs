//! `gimpo`: seed 000 (Jeon et al. 2010). The IMM (CV + two fixed-rate CT models) on the
//! Gimpo approach of Table 1, plotted by a rotating beam, with fixed measurement noise of
//! 0.2 … 2 × the truth (Figs. 5, 7), the multi-IMM noise estimator of eqs (8)–(14) from
//! the same starts (Figs. 6, 7), the mean mode probabilities (Fig. 4) and one run's
//! trajectory (Fig. 3); beside it, the variational, evidence and difference estimators of
//! `argus-imm`, which estimate range and azimuth variances separately.

//!
//! Split in three: [`estimate`] builds the estimators and runs them over one run's plots
//! (the plots themselves from [`estimate::simulate`]), [`report`] turns the runs into the
//! table, series and figures; this file holds the scene and the campaign.

mod estimate;
mod report;
mod sums;

use argus_sim::{KinematicState, Schedule, Segment, SensorSpec, Trajectory, Truth, generate_plots};

use crate::campaign::{Campaign, Splittable, run_whole};
use crate::context::RunContext;
use crate::error::ScenarioError;
use crate::params::{ParamSpec, Params};
use crate::polar_scene::{first_trajectory, polar_radar};
use crate::report::Report;
use crate::scenario::Scenario;

/// The `gimpo` scenario.
pub(crate) struct Gimpo;

/// Table 1 of seed 000: (duration s, turn rate deg/s; 0 = CV).
const SEGMENTS: [(f64, f64); 10] = [
    (330.0, 0.0),
    (63.0, 1.5),
    (120.0, 0.0),
    (57.0, -0.25),
    (105.0, 0.0),
    (43.0, -2.0),
    (122.0, 0.0),
    (23.0, -2.5),
    (70.0, -0.5),
    (86.0, 0.0),
];
impl Scenario for Gimpo {
    fn name(&self) -> &'static str {
        "gimpo"
    }

    fn description(&self) -> &'static str {
        "seed 000: IMM with fixed R, the multi-IMM noise estimator (eqs 8-14), and the variational and evidence estimators on the Gimpo approach"
    }

    fn default_runs(&self) -> u64 {
        100
    }

    fn params(&self) -> Vec<ParamSpec> {
        vec![
            ParamSpec {
                key: "sigma_r",
                default: 70.0,
                min: 1e-3,
                max: 1e5,
                help: "true range noise σ (m)",
            },
            ParamSpec {
                key: "sigma_az_deg",
                default: 0.08,
                min: 1e-6,
                max: 10.0,
                help: "true azimuth noise σ (deg)",
            },
            ParamSpec {
                key: "period",
                default: 5.0,
                min: 0.1,
                max: 60.0,
                help: "antenna period (s)",
            },
            ParamSpec {
                key: "omega_deg",
                default: 3.0,
                min: 0.01,
                max: 30.0,
                help: "CT models' turn rate ±ω (deg/s)",
            },
            ParamSpec {
                key: "p",
                default: 0.1,
                min: 0.001,
                max: 0.49,
                help: "multi-IMM grid spacing p (eq 14)",
            },
            ParamSpec {
                key: "clip",
                default: 0.05,
                min: 0.0,
                max: 0.99,
                help: "per-step clip of the reference change (0 = none)",
            },
            ParamSpec {
                key: "vb_rho",
                default: 0.97,
                min: 0.5,
                max: 1.0,
                help: "variational estimator's forgetting factor",
            },
            ParamSpec {
                key: "ev_spacing",
                default: 0.2,
                min: 0.01,
                max: 1.0,
                help: "evidence estimator: hypotheses at e^(±h), h = ln(1 + spacing)",
            },
            ParamSpec {
                key: "ev_rho",
                default: 1.0,
                min: 0.5,
                max: 1.0,
                help: "evidence estimator: forgetting factor of the accumulated evidence",
            },
            ParamSpec {
                key: "ev_clip",
                default: 0.05,
                min: 0.0,
                max: 0.99,
                help: "evidence estimator: per-step clip of the anchor's change (0 = none)",
            },
            ParamSpec {
                key: "ev_settle",
                default: 15.0,
                min: 0.0,
                max: 1000.0,
                help: "evidence estimator: report the post-fit moments after this many unclipped steps (0 = the fitted evidence G/B)",
            },
            ParamSpec {
                key: "ev_observed",
                default: 0.0,
                min: 0.0,
                max: 1.0,
                help: "evidence estimator: 1 = each plot's fitted curvature as its information (as first built), 0 = the expected information",
            },
            ParamSpec {
                key: "df_rho",
                default: 1.0,
                min: 0.5,
                max: 1.0,
                help: "difference estimator: forgetting factor per third difference",
            },
            ParamSpec {
                key: "gibbs_block",
                default: 4.0,
                min: 1.0,
                max: 8.0,
                help: "Gibbs smoother: consecutive modes drawn jointly (integer)",
            },
            ParamSpec {
                key: "gibbs_burn_in",
                default: 20.0,
                min: 0.0,
                max: 100_000.0,
                help: "Gibbs smoother: sweeps discarded per run (integer)",
            },
            ParamSpec {
                key: "gibbs_sweeps",
                default: 200.0,
                min: 1.0,
                max: 100_000.0,
                help: "Gibbs smoother: sweeps averaged per run (integer)",
            },
        ]
    }

    fn scene(&self, p: &Params) -> Result<(Truth, Vec<SensorSpec>), ScenarioError> {
        let mut truth = Truth::new();
        let segments = SEGMENTS
            .iter()
            .map(|&(duration, w)| {
                if w == 0.0 {
                    Segment::ConstantVelocity { duration }
                } else {
                    Segment::Turn {
                        duration,
                        rate: w.to_radians(),
                    }
                }
            })
            .collect();
        truth.add(Trajectory::new(
            0.0,
            KinematicState::planar(-60_000.0, -20_000.0, 90.0, 0.0),
            segments,
        )?);
        let radar = polar_radar(p, |period| Schedule::RotatingBeam {
            period,
            azimuth_at_zero: 0.0,
        })?;
        Ok((truth, vec![radar]))
    }

    fn run(&self, ctx: &RunContext<'_>) -> Result<Report, ScenarioError> {
        run_whole(self, ctx)
    }

    fn splittable(&self) -> Option<&dyn Splittable> {
        Some(self)
    }
}

/// What a `gimpo` campaign shares between its runs and the reduce step.
pub(crate) struct Setup {
    params: Params,
    truth: Truth,
    sensors: Vec<SensorSpec>,
    est: estimate::Estimators,
    traj: Trajectory,
    /// Plot times after the two initialising plots: the same in every run (the beam
    /// timing depends on the truth only, not on the noise draws).
    times: Vec<f64>,
}

impl Campaign for Gimpo {
    type Setup = Setup;
    type Run = estimate::RunOut;
    type Sums = sums::Sums;

    fn setup(&self, p: &Params) -> Result<Setup, ScenarioError> {
        let (truth, sensors) = self.scene(p)?;
        let est = estimate::Estimators::new(p)?;
        let traj = first_trajectory(&truth, "gimpo")?;
        // Any generator gives the same times (only the noise depends on it).
        let times: Vec<f64> = generate_plots(&truth, &sensors, &mut argus_sim::run_rng(0, 0))?
            .iter()
            .skip(2)
            .map(|pl| pl.plot.time())
            .collect();
        Ok(Setup {
            params: p.clone(),
            truth,
            sensors,
            est,
            traj,
            times,
        })
    }

    fn one_run(
        &self,
        s: &Setup,
        seed: u64,
        run: u64,
        rng: &mut argus_sim::ChaCha8Rng,
    ) -> Result<estimate::RunOut, ScenarioError> {
        let plots = estimate::simulate(&s.truth, &s.sensors, rng)?;
        s.est.run(&s.traj, seed, run, &plots)
    }

    /// Per-step sums and a few final ratios per run ([`sums::Sums`]): a merge of any
    /// number of runs holds the per-step sums, not the runs' records.
    fn start(&self, s: &Setup, count: u64) -> Result<sums::Sums, ScenarioError> {
        let t_end = s.traj.end();
        let first = s
            .times
            .iter()
            .position(|t| *t >= report::WARMUP * t_end)
            .unwrap_or(0);
        let expected = usize::try_from(count).unwrap_or(usize::MAX);
        Ok(sums::Sums::new(s.times.clone(), first, expected))
    }

    fn add(
        &self,
        _s: &Setup,
        sums: &mut sums::Sums,
        run: estimate::RunOut,
    ) -> Result<(), ScenarioError> {
        sums.add(&run);
        Ok(())
    }

    fn finish(&self, s: &Setup, sums: sums::Sums) -> Result<Report, ScenarioError> {
        report::report(&s.params, s.est.clip, &sums.finish()?)
    }
}

//! `gimpo`: seed 000 (Jeon et al. 2010). The IMM (CV + two fixed-rate CT models) on the
//! Gimpo approach of Table 1, plotted by a rotating beam, with fixed measurement noise of
//! 0.2 … 2 × the truth (Figs. 5, 7), the multi-IMM noise estimator of eqs (8)–(14) from
//! the same starts (Figs. 6, 7), the mean mode probabilities (Fig. 4) and one run's
//! trajectory (Fig. 3); beside it, the variational, evidence and difference estimators of
//! `argus-imm`, which estimate range and azimuth variances separately.

use argus_core_math::Vector;
use argus_filters::{Kf, two_point_cv2};
use argus_imm::{
    DifferenceEstimate, DifferenceNoiseImm, EvidenceEstimate, EvidenceNoiseImm, Imm, ImmEstimate,
    MarkovMatrix, MultiImm, MultiImmEstimate, NoiseGrid, NoiseVariances, PlotConversion,
    UnbiasedConversion, VariationalEstimate, VariationalNoiseImm,
};
use argus_motion_models::{CoordinatedTurn, Cv2D, PlanarModel};
use argus_sensors::{Measurement, PolarMeasurement};
use argus_sim::{
    KinematicState, Schedule, Segment, SensorId, SensorKind, SensorSpec, Trajectory, Truth,
    generate_plots, monte_carlo,
};

use crate::error::CliError;
use crate::report::{Figure, Line, LineStyle, Report, Row, Series};
use crate::scenario::{ParamSpec, Params, RunContext, Scenario};

/// The `gimpo` scenario.
pub(crate) struct Gimpo;

/// Initial (or fixed) noise factors of the paper: R = f × truth.
const STARTS: [f64; 5] = [0.2, 0.5, 1.0, 1.5, 2.0];
/// Share of the time left out of the RMS (paper §3.4: the first 25 %).
const WARMUP: f64 = 0.25;
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
/// Published / reference values: the independent re-implementation quoted in issue 4
/// (100 runs, p = 0.1, ±5 % clip): final variance ratio from each start.
const REFERENCE_RATIO: [f64; 5] = [0.98, 1.01, 1.03, 1.05, 1.07];

type PaperImm = Imm<Kf<PlanarModel>, 4, 3>;

/// The paper's IMM (§3.1): CV σv = 0.1 m/s², CT ±ω σv = 0.5 m/s², Markov matrix eq (20).
fn paper_imm(omega_deg: f64) -> Result<PaperImm, CliError> {
    let ct = |w: f64| -> Result<Kf<PlanarModel>, CliError> {
        Ok(Kf::new(PlanarModel::from(
            CoordinatedTurn::from_degrees_per_second(w, 0.5)?,
        )))
    };
    let cv = Kf::new(PlanarModel::from(Cv2D::discrete(0.1)?));
    let pi = MarkovMatrix::new([[0.95, 0.025, 0.025], [0.05, 0.95, 0.0], [0.05, 0.0, 0.95]])?;
    Ok(Imm::new([cv, ct(omega_deg)?, ct(-omega_deg)?], pi)?)
}

/// Everything one run records, per step after the two initialising plots.
#[derive(Debug, Clone, Default)]
struct RunOut {
    /// Squared position error of the fixed-R IMM, per start factor.
    fixed_se: [Vec<f64>; 5],
    /// Mode probabilities (CV, CT+, CT−) of the IMM with the true R.
    mu: Vec<[f64; 3]>,
    /// Paper's multi-IMM: squared error and variance ratio, per start.
    multi_se: [Vec<f64>; 5],
    multi_ratio: [Vec<f64>; 5],
    /// Variational estimator: squared error and (range, azimuth) ratios, per start.
    vb_se: [Vec<f64>; 5],
    vb_ratio: [Vec<[f64; 2]>; 5],
    /// Evidence estimator: squared error and (range, azimuth) ratios, per start.
    ev_se: [Vec<f64>; 5],
    ev_ratio: [Vec<[f64; 2]>; 5],
    /// Difference estimator: squared error and (range, azimuth) ratios, per start.
    df_se: [Vec<f64>; 5],
    df_ratio: [Vec<[f64; 2]>; 5],
    /// Run 0 only: truth, converted plots and the multi-IMM (start 1) estimate.
    track: Vec<[f64; 6]>,
}

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
        ]
    }

    fn scene(&self, p: &Params) -> Result<(Truth, Vec<SensorSpec>), CliError> {
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
        let radar = SensorSpec::new(
            SensorId(1),
            Vector::<3>::zeros(),
            SensorKind::Polar {
                sigma_range: p.get("sigma_r")?,
                sigma_azimuth: p.get("sigma_az_deg")?.to_radians(),
            },
            Schedule::RotatingBeam {
                period: p.get("period")?,
                azimuth_at_zero: 0.0,
            },
        )?;
        Ok((truth, vec![radar]))
    }

    #[allow(clippy::too_many_lines)]
    fn run(&self, ctx: &RunContext) -> Result<Report, CliError> {
        let p = &ctx.params;
        let (truth, sensors) = self.scene(p)?;
        let true_var =
            NoiseVariances::from_sigmas(p.get("sigma_r")?, p.get("sigma_az_deg")?.to_radians())?;
        let imm = paper_imm(p.get("omega_deg")?)?;
        let clip = match p.get("clip")? {
            c if c > 0.0 => Some(c),
            _ => None,
        };
        let multi = MultiImm::new(imm.clone(), NoiseGrid::<5>::common(p.get("p")?)?, clip)?;
        let vb = VariationalNoiseImm::new(imm.clone(), p.get("vb_rho")?)?;
        let ev = EvidenceNoiseImm::new(
            imm.clone(),
            p.get("ev_spacing")?,
            p.get("ev_rho")?,
            match p.get("ev_clip")? {
                c if c > 0.0 => Some(c),
                _ => None,
            },
        )?;
        let ev = match p.get("ev_settle")? {
            k if k >= 1.0 => ev.with_post_fit(k.round() as usize),
            _ => ev,
        };
        let ev = if p.get("ev_observed")? >= 0.5 {
            ev.with_observed_information()
        } else {
            ev
        };
        let df = DifferenceNoiseImm::new(imm.clone(), p.get("df_rho")?)?;
        let conv = UnbiasedConversion::<4>::new(0, 2)?;
        let traj = truth
            .targets()
            .first()
            .map(|(_, t)| t.clone())
            .ok_or(CliError::Usage("gimpo: no target".into()))?;
        let scaled = |f: f64| NoiseVariances::new(true_var.range() * f, true_var.azimuth() * f);

        let one_run = |run: u64, rng: &mut argus_sim::ChaCha8Rng| -> Result<RunOut, CliError> {
            let plots: Vec<(f64, PolarMeasurement)> = generate_plots(&truth, &sensors, rng)?
                .iter()
                .filter_map(|pl| match pl.plot.measurement() {
                    Measurement::Polar(m) => Some((pl.plot.time(), *m)),
                    _ => None,
                })
                .collect();
            let (Some((t1, p1)), Some((t2, p2))) = (plots.first(), plots.get(1)) else {
                return Err(CliError::Usage("gimpo: fewer than two plots".into()));
            };
            let init = |var: &NoiseVariances| -> Result<ImmEstimate<4, 3>, CliError> {
                let (z1, r1) = argus_imm::unbiased_conversion(p1, var)?;
                let (z2, r2) = argus_imm::unbiased_conversion(p2, var)?;
                let g = two_point_cv2(&z1, &r1, &z2, &r2, t2 - t1)?;
                Ok(ImmEstimate::from_common(g, [1.0 / 3.0; 3])?)
            };
            let truth_pos =
                |t: f64| -> Result<Vector<4>, CliError> { Ok(traj.state_at(t)?.state_2d()) };
            let se =
                |x: &Vector<4>, tr: &Vector<4>| (x[0] - tr[0]).powi(2) + (x[2] - tr[2]).powi(2);
            let mut out = RunOut::default();
            let rest = plots.get(2..).unwrap_or(&[]);
            for (i, f) in STARTS.iter().enumerate() {
                let var0 = scaled(*f)?;
                // (a) fixed R.
                let mut est = init(&var0)?;
                let mut prev = *t2;
                for (t, pl) in rest {
                    let (m, z) = conv.convert(pl, &var0)?;
                    est = imm.step(&est, t - prev, &m, &z)?.estimate;
                    prev = *t;
                    let c = est.combined()?;
                    out.fixed_se[i].push(se(c.mean(), &truth_pos(*t)?));
                    if i == 2 {
                        out.mu.push(est.mode_probabilities());
                    }
                }
                // (b) the paper's multi-IMM.
                let mut mest = MultiImmEstimate::new(init(&var0)?, var0);
                let mut prev = *t2;
                for (t, pl) in rest {
                    mest = multi.step(&mest, t - prev, pl, &conv)?.estimate;
                    prev = *t;
                    let c = mest.combined()?;
                    let tr = truth_pos(*t)?;
                    out.multi_se[i].push(se(c.mean(), &tr));
                    out.multi_ratio[i].push(mest.reference().range() / true_var.range());
                    if i == 2 && run == 0 {
                        let (z, _) = argus_imm::unbiased_conversion(pl, mest.reference())?;
                        out.track
                            .push([tr[0], tr[2], z[0], z[1], c.mean()[0], c.mean()[2]]);
                    }
                }
                // Variational estimator.
                let mut vest = VariationalEstimate::new(init(&var0)?, var0, 2.0)?;
                let mut prev = *t2;
                for (t, pl) in rest {
                    vest = vb.step(&vest, t - prev, pl, &conv)?.0;
                    prev = *t;
                    let c = vest.imm().combined()?;
                    out.vb_se[i].push(se(c.mean(), &truth_pos(*t)?));
                    let v = vest.variances()?;
                    out.vb_ratio[i].push([
                        v.range() / true_var.range(),
                        v.azimuth() / true_var.azimuth(),
                    ]);
                }
                // Evidence estimator.
                let mut eest = EvidenceEstimate::new(init(&var0)?, var0, 2.0)?;
                let mut prev = *t2;
                for (t, pl) in rest {
                    eest = ev.step(&eest, t - prev, pl, &conv)?;
                    prev = *t;
                    let c = eest.combined()?;
                    out.ev_se[i].push(se(c.mean(), &truth_pos(*t)?));
                    let v = eest.variances();
                    out.ev_ratio[i].push([
                        v.range() / true_var.range(),
                        v.azimuth() / true_var.azimuth(),
                    ]);
                }
                // Difference estimator.
                let mut dest = DifferenceEstimate::new(init(&var0)?, var0, 2.0)?;
                let mut prev = *t2;
                for (t, pl) in rest {
                    dest = df.step(&dest, t - prev, pl, &conv)?.0;
                    prev = *t;
                    let c = dest.imm().combined()?;
                    out.df_se[i].push(se(c.mean(), &truth_pos(*t)?));
                    let v = dest.variances()?;
                    out.df_ratio[i].push([
                        v.range() / true_var.range(),
                        v.azimuth() / true_var.azimuth(),
                    ]);
                }
            }
            Ok(out)
        };
        let progress = &ctx.progress;
        let runs = monte_carlo(ctx.seed, ctx.runs.clone(), one_run, || progress.tick())?;
        progress.finish();

        // Plot times are the same in every run (the beam timing depends on the truth only).
        let times: Vec<f64> = {
            let mut rng = argus_sim::run_rng(ctx.seed, 0);
            generate_plots(&truth, &sensors, &mut rng)?
                .iter()
                .skip(2)
                .map(|pl| pl.plot.time())
                .collect()
        };
        let n_runs = runs.len() as f64;
        let t_end = traj.end();
        let first = times.iter().position(|t| *t >= WARMUP * t_end).unwrap_or(0);
        let rms_tail = |get: &dyn Fn(&RunOut) -> &Vec<f64>| -> f64 {
            let (mut s, mut n) = (0.0_f64, 0.0_f64);
            for r in &runs {
                for v in get(r).iter().skip(first) {
                    s += v;
                    n += 1.0;
                }
            }
            (s / n.max(1.0)).sqrt()
        };
        let per_step_rms = |get: &dyn Fn(&RunOut) -> &Vec<f64>| -> Vec<f64> {
            (0..times.len())
                .map(|k| (runs.iter().filter_map(|r| get(r).get(k)).sum::<f64>() / n_runs).sqrt())
                .collect()
        };
        let mean_sd_last = |vals: Vec<f64>| -> (f64, f64) {
            let m = vals.iter().sum::<f64>() / vals.len().max(1) as f64;
            let v =
                vals.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (vals.len().max(2) - 1) as f64;
            (m, v.sqrt())
        };

        let true_rms = rms_tail(&|r| &r.fixed_se[2]);
        let mut rows = Vec::new();
        let row = |key: String,
                   quantity: String,
                   paper: Option<f64>,
                   paper_text: Option<String>,
                   ours: f64,
                   unit: &str,
                   note: String| Row {
            key,
            quantity,
            paper,
            paper_text,
            ours,
            unit: unit.into(),
            note,
        };
        for (i, f) in STARTS.iter().enumerate() {
            let fixed = rms_tail(&|r| &r.fixed_se[i]);
            rows.push(row(
                format!("rms_fixed_{f}"),
                format!("RMS pos. error, fixed R = {f} × truth"),
                None,
                Some("Fig. 5/7: grows as R departs from truth, faster below".into()),
                fixed,
                "m",
                format!(
                    "{:+.2} % vs true R; t ≥ {:.0} % of the flight",
                    100.0 * (fixed / true_rms - 1.0),
                    WARMUP * 100.0
                ),
            ));
        }
        for (i, f) in STARTS.iter().enumerate() {
            let (m, sd) = mean_sd_last(
                runs.iter()
                    .filter_map(|r| r.multi_ratio[i].last().copied())
                    .collect(),
            );
            rows.push(row(
                format!("ratio_multi_{f}"),
                format!("multi-IMM final R ratio from {f}"),
                Some(REFERENCE_RATIO[i]),
                Some(format!(
                    "paper: within 5 % of 1; re-implementation {}",
                    REFERENCE_RATIO[i]
                )),
                m,
                "-",
                format!("per-run sd {sd:.3}; p = {}, clip {:?}", p.get("p")?, clip),
            ));
        }
        for (i, f) in STARTS.iter().enumerate() {
            let dynr = rms_tail(&|r| &r.multi_se[i]);
            rows.push(row(
                format!("rms_multi_{f}"),
                format!("RMS pos. error, multi-IMM from {f}"),
                Some(true_rms),
                Some("paper: within 0.5 % of true R (Fig. 7)".into()),
                dynr,
                "m",
                format!("{:+.2} % vs true R", 100.0 * (dynr / true_rms - 1.0)),
            ));
        }
        for (i, f) in STARTS.iter().enumerate() {
            let (mr, sdr) = mean_sd_last(
                runs.iter()
                    .filter_map(|r| r.vb_ratio[i].last().map(|v| v[0]))
                    .collect(),
            );
            let (ma, sda) = mean_sd_last(
                runs.iter()
                    .filter_map(|r| r.vb_ratio[i].last().map(|v| v[1]))
                    .collect(),
            );
            let dynr = rms_tail(&|r| &r.vb_se[i]);
            rows.push(row(
                format!("ratio_vb_range_{f}"),
                format!("variational: final σr² ratio from {f}"),
                Some(1.0),
                Some("goal: within 3 % (beyond the paper)".into()),
                mr,
                "-",
                format!("per-run sd {sdr:.3}"),
            ));
            rows.push(row(
                format!("ratio_vb_azimuth_{f}"),
                format!("variational: final σθ² ratio from {f}"),
                Some(1.0),
                Some("goal: within 3 % (beyond the paper)".into()),
                ma,
                "-",
                format!("per-run sd {sda:.3}"),
            ));
            rows.push(row(
                format!("rms_vb_{f}"),
                format!("RMS pos. error, variational from {f}"),
                Some(true_rms),
                Some("true-R IMM".into()),
                dynr,
                "m",
                format!("{:+.2} % vs true R", 100.0 * (dynr / true_rms - 1.0)),
            ));
        }
        for (i, f) in STARTS.iter().enumerate() {
            let last = |c: usize| -> Vec<f64> {
                runs.iter()
                    .filter_map(|r| r.ev_ratio[i].last().map(|v| v[c]))
                    .collect()
            };
            let (mr, sdr) = mean_sd_last(last(0));
            let (ma, sda) = mean_sd_last(last(1));
            let dynr = rms_tail(&|r| &r.ev_se[i]);
            for (axis, sym, m, sd) in [("range", "σr²", mr, sdr), ("azimuth", "σθ²", ma, sda)]
            {
                rows.push(row(
                    format!("ratio_ev_{axis}_{f}"),
                    format!("evidence: final {sym} ratio from {f}"),
                    Some(1.0),
                    Some("goal: within 3 % (beyond the paper)".into()),
                    m,
                    "-",
                    format!("per-run sd {sd:.3}"),
                ));
            }
            rows.push(row(
                format!("rms_ev_{f}"),
                format!("RMS pos. error, evidence from {f}"),
                Some(true_rms),
                Some("true-R IMM".into()),
                dynr,
                "m",
                format!("{:+.2} % vs true R", 100.0 * (dynr / true_rms - 1.0)),
            ));
        }
        for (i, f) in STARTS.iter().enumerate() {
            let last = |c: usize| -> Vec<f64> {
                runs.iter()
                    .filter_map(|r| r.df_ratio[i].last().map(|v| v[c]))
                    .collect()
            };
            let (mr, sdr) = mean_sd_last(last(0));
            let (ma, sda) = mean_sd_last(last(1));
            let dynr = rms_tail(&|r| &r.df_se[i]);
            for (axis, sym, m, sd) in [("range", "σr²", mr, sdr), ("azimuth", "σθ²", ma, sda)]
            {
                rows.push(row(
                    format!("ratio_df_{axis}_{f}"),
                    format!("difference: final {sym} ratio from {f}"),
                    Some(1.0),
                    Some("goal: within 3 % (beyond the paper)".into()),
                    m,
                    "-",
                    format!("per-run sd {sd:.3}"),
                ));
            }
            rows.push(row(
                format!("rms_df_{f}"),
                format!("RMS pos. error, difference from {f}"),
                Some(true_rms),
                Some("true-R IMM".into()),
                dynr,
                "m",
                format!("{:+.2} % vs true R", 100.0 * (dynr / true_rms - 1.0)),
            ));
        }

        // Series and figures.
        let mean_ratio = |i: usize| -> Vec<f64> {
            (0..times.len())
                .map(|k| {
                    runs.iter()
                        .filter_map(|r| r.multi_ratio[i].get(k))
                        .sum::<f64>()
                        / n_runs
                })
                .collect()
        };
        let mean_vb = |i: usize, c: usize| -> Vec<f64> {
            (0..times.len())
                .map(|k| {
                    runs.iter()
                        .filter_map(|r| r.vb_ratio[i].get(k).map(|v| v[c]))
                        .sum::<f64>()
                        / n_runs
                })
                .collect()
        };
        let mean_mu: Vec<[f64; 3]> = (0..times.len())
            .map(|k| {
                let mut m = [0.0; 3];
                for r in &runs {
                    if let Some(v) = r.mu.get(k) {
                        for (a, b) in m.iter_mut().zip(v) {
                            *a += b / n_runs;
                        }
                    }
                }
                m
            })
            .collect();
        let mean_ev = |i: usize, c: usize| -> Vec<f64> {
            (0..times.len())
                .map(|k| {
                    runs.iter()
                        .filter_map(|r| r.ev_ratio[i].get(k).map(|v| v[c]))
                        .sum::<f64>()
                        / n_runs
                })
                .collect()
        };
        let ev_r: Vec<Vec<f64>> = (0..5).map(|i| mean_ev(i, 0)).collect();
        let ev_a: Vec<Vec<f64>> = (0..5).map(|i| mean_ev(i, 1)).collect();
        let mean_df = |i: usize, c: usize| -> Vec<f64> {
            (0..times.len())
                .map(|k| {
                    runs.iter()
                        .filter_map(|r| r.df_ratio[i].get(k).map(|v| v[c]))
                        .sum::<f64>()
                        / n_runs
                })
                .collect()
        };
        let df_r: Vec<Vec<f64>> = (0..5).map(|i| mean_df(i, 0)).collect();
        let df_a: Vec<Vec<f64>> = (0..5).map(|i| mean_df(i, 1)).collect();
        let ratios: Vec<Vec<f64>> = (0..5).map(mean_ratio).collect();
        let vb_r: Vec<Vec<f64>> = (0..5).map(|i| mean_vb(i, 0)).collect();
        let vb_a: Vec<Vec<f64>> = (0..5).map(|i| mean_vb(i, 1)).collect();
        let fixed_rms: Vec<Vec<f64>> = (0..5).map(|i| per_step_rms(&|r| &r.fixed_se[i])).collect();
        let mut columns = vec![
            "t".to_owned(),
            "mu_cv".into(),
            "mu_ct_pos".into(),
            "mu_ct_neg".into(),
        ];
        for f in STARTS {
            columns.push(format!("ratio_multi_{f}"));
        }
        for f in STARTS {
            columns.push(format!("ratio_vb_range_{f}"));
            columns.push(format!("ratio_vb_azimuth_{f}"));
        }
        for f in STARTS {
            columns.push(format!("ratio_ev_range_{f}"));
            columns.push(format!("ratio_ev_azimuth_{f}"));
        }
        for f in STARTS {
            columns.push(format!("ratio_df_range_{f}"));
            columns.push(format!("ratio_df_azimuth_{f}"));
        }
        for f in STARTS {
            columns.push(format!("rms_fixed_{f}"));
        }
        let series_rows = (0..times.len())
            .map(|k| {
                let mut v = vec![times[k]];
                v.extend(mean_mu[k]);
                v.extend(ratios.iter().map(|r| r[k]));
                for i in 0..5 {
                    v.push(vb_r[i][k]);
                    v.push(vb_a[i][k]);
                }
                for i in 0..5 {
                    v.push(ev_r[i][k]);
                    v.push(ev_a[i][k]);
                }
                for i in 0..5 {
                    v.push(df_r[i][k]);
                    v.push(df_a[i][k]);
                }
                v.extend(fixed_rms.iter().map(|r| r[k]));
                v
            })
            .collect();
        let pts = |ys: &[f64]| -> Vec<(f64, f64)> {
            times.iter().zip(ys).map(|(t, y)| (*t, *y)).collect()
        };
        let track = runs.first().map(|r| r.track.clone()).unwrap_or_default();
        let nr = runs.len();
        let figures = vec![
            Figure {
                name: "fig3_trajectory".into(),
                title: "gimpo: truth, plots and multi-IMM estimate (run 0, start 1)".into(),
                x_label: "x (m)".into(),
                y_label: "y (m)".into(),
                lines: vec![
                    Line {
                        label: "true".into(),
                        points: track.iter().map(|v| (v[0], v[1])).collect(),
                        style: LineStyle::Solid,
                    },
                    Line {
                        label: "plots (converted)".into(),
                        points: track.iter().map(|v| (v[2], v[3])).collect(),
                        style: LineStyle::Points,
                    },
                    Line {
                        label: "estimate".into(),
                        points: track.iter().map(|v| (v[4], v[5])).collect(),
                        style: LineStyle::Solid,
                    },
                ],
            },
            Figure {
                name: "fig4_mode_probabilities".into(),
                title: format!("gimpo: mean mode probabilities, true R ({nr} runs)"),
                x_label: "time (s)".into(),
                y_label: "probability".into(),
                lines: ["CV", "CT +ω", "CT −ω"]
                    .iter()
                    .enumerate()
                    .map(|(j, l)| Line {
                        label: (*l).into(),
                        points: times
                            .iter()
                            .zip(&mean_mu)
                            .map(|(t, m)| (*t, m[j]))
                            .collect(),
                        style: LineStyle::Solid,
                    })
                    .collect(),
            },
            Figure {
                name: "fig5_rms_fixed_r".into(),
                title: format!("gimpo: RMS position error with fixed R ({nr} runs)"),
                x_label: "time (s)".into(),
                y_label: "RMS position error (m)".into(),
                lines: STARTS
                    .iter()
                    .zip(&fixed_rms)
                    .map(|(f, r)| Line {
                        label: format!("R = {f} × truth"),
                        points: pts(r),
                        style: LineStyle::Solid,
                    })
                    .collect(),
            },
            Figure {
                name: "fig6_ratio".into(),
                title: format!("gimpo: estimated / true noise variance, mean of {nr} runs"),
                x_label: "time (s)".into(),
                y_label: "variance ratio".into(),
                lines: STARTS
                    .iter()
                    .zip(&ratios)
                    .map(|(f, r)| Line {
                        label: format!("multi-IMM from {f}"),
                        points: pts(r),
                        style: LineStyle::Solid,
                    })
                    .chain(STARTS.iter().zip(&vb_a).map(|(f, r)| Line {
                        label: format!("variational σθ² from {f}"),
                        points: pts(r),
                        style: LineStyle::Bound,
                    }))
                    .chain(STARTS.iter().zip(&ev_a).map(|(f, r)| Line {
                        label: format!("evidence σθ² from {f}"),
                        points: pts(r),
                        style: LineStyle::Points,
                    }))
                    .collect(),
            },
            Figure {
                name: "fig6_evidence_ratio".into(),
                title: format!(
                    "gimpo: evidence estimator, estimated / true variance per axis, mean of {nr} runs"
                ),
                x_label: "time (s)".into(),
                y_label: "variance ratio".into(),
                lines: STARTS
                    .iter()
                    .zip(&ev_r)
                    .map(|(f, r)| Line {
                        label: format!("σr² from {f}"),
                        points: pts(r),
                        style: LineStyle::Solid,
                    })
                    .chain(STARTS.iter().zip(&ev_a).map(|(f, r)| Line {
                        label: format!("σθ² from {f}"),
                        points: pts(r),
                        style: LineStyle::Bound,
                    }))
                    .collect(),
            },
            Figure {
                name: "fig6_difference_ratio".into(),
                title: format!(
                    "gimpo: difference estimator, estimated / true variance per axis, mean of {nr} runs"
                ),
                x_label: "time (s)".into(),
                y_label: "variance ratio".into(),
                lines: STARTS
                    .iter()
                    .zip(&df_r)
                    .map(|(f, r)| Line {
                        label: format!("σr² from {f}"),
                        points: pts(r),
                        style: LineStyle::Solid,
                    })
                    .chain(STARTS.iter().zip(&df_a).map(|(f, r)| Line {
                        label: format!("σθ² from {f}"),
                        points: pts(r),
                        style: LineStyle::Bound,
                    }))
                    .collect(),
            },
            Figure {
                name: "fig7_rms_vs_r".into(),
                title: format!("gimpo: RMS position error (t ≥ 25 %) vs R factor ({nr} runs)"),
                x_label: "R factor (fixed, or initial)".into(),
                y_label: "RMS position error (m)".into(),
                lines: vec![
                    Line {
                        label: "static R".into(),
                        points: STARTS
                            .iter()
                            .enumerate()
                            .map(|(i, f)| (*f, rms_tail(&|r| &r.fixed_se[i])))
                            .collect(),
                        style: LineStyle::Solid,
                    },
                    Line {
                        label: "dynamic R (multi-IMM)".into(),
                        points: STARTS
                            .iter()
                            .enumerate()
                            .map(|(i, f)| (*f, rms_tail(&|r| &r.multi_se[i])))
                            .collect(),
                        style: LineStyle::Solid,
                    },
                    Line {
                        label: "dynamic R (variational)".into(),
                        points: STARTS
                            .iter()
                            .enumerate()
                            .map(|(i, f)| (*f, rms_tail(&|r| &r.vb_se[i])))
                            .collect(),
                        style: LineStyle::Solid,
                    },
                    Line {
                        label: "dynamic R (evidence)".into(),
                        points: STARTS
                            .iter()
                            .enumerate()
                            .map(|(i, f)| (*f, rms_tail(&|r| &r.ev_se[i])))
                            .collect(),
                        style: LineStyle::Solid,
                    },
                    Line {
                        label: "dynamic R (difference)".into(),
                        points: STARTS
                            .iter()
                            .enumerate()
                            .map(|(i, f)| (*f, rms_tail(&|r| &r.df_se[i])))
                            .collect(),
                        style: LineStyle::Solid,
                    },
                ],
            },
        ];
        Ok(Report {
            rows,
            series: vec![Series { name: "per_step".into(), columns, rows: series_rows }],
            figures,
            notes: vec![
                "multi-IMM: seed 000 eqs (8)-(14), likelihood with |2πS|^-1/2 (the paper's eq 5/9 misprint corrected)".into(),
                "reference ratios are an independent re-implementation's (issue 4), not read off the paper's Fig. 6".into(),
                "the paper's rule estimates one common scale of R (range and azimuth ratios are identical)".into(),
                "variational: one IMM + inverse-gamma recursion on polar post-fit residuals, range and azimuth separately".into(),
                "evidence: five IMMs (anchor, ±h in range, ±h in azimuth); per axis the observed score of each step's fitted log-likelihood curve with the expected information ½w², accumulated over the track; post-fit read-out once settled".into(),
                "evidence: range meets the 3 % goal, azimuth does NOT (≈ +6 %: the turns no mode matches inflate cross-range innovations; docs/papers/000-gimpo.md)".into(),
                "difference: one IMM under variances estimated from third differences of the raw plots (they cancel any locally quadratic truth, so their expectation is the noise whatever the IMM's models); the start stays only in the prior's 2 pseudo-differences".into(),
            ],
        })
    }
}

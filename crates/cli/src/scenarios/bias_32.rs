//! `argus run bias-32`: multisensor registration of seed 004 (SPEC §004) — bias RMSE of
//! the pseudo-measurement method and EXX (paper Figs. 3–6), track 1 and 32 RMSE of
//! sensor 1 with and without compensation (Figs. 8–11). The scenario itself lives in
//! `argus_registration::simulation`; this file runs it through `argus_sim::monte_carlo`.

use argus_core_math::Vector;
use argus_registration::simulation::{ScenarioConfig, Summary, run};
use argus_registration::{Initiation, Linearization, RegistrationError};
use argus_sim::{
    KinematicState, Schedule, Segment, SensorId, SensorKind, SensorSpec, Trajectory, Truth,
    monte_carlo,
};
use rand_distr::{Distribution, StandardNormal};

use crate::error::CliError;
use crate::report::{Figure, Line, LineStyle, Report, Row, Series};
use crate::scenario::{ParamSpec, Params, RunContext, Scenario};

pub(crate) struct Bias32;

fn reg(e: RegistrationError) -> CliError {
    CliError::Usage(format!("bias-32: registration: {e}"))
}

fn config(p: &Params) -> Result<ScenarioConfig, CliError> {
    let sensors = p.get("sensors")? as usize;
    let targets = p.get("targets")? as usize;
    let mut c = ScenarioConfig::grid(sensors, targets).map_err(reg)?;
    c.recorded = if targets >= 32 {
        vec![0, 31]
    } else {
        vec![0, targets - 1]
    };
    c.duration = p.get("duration")?;
    c.linearization = if p.get("lin_at_plot")? > 0.5 {
        Linearization::AtPlot
    } else {
        Linearization::AtPrediction
    };
    c.initiation = if p.get("two_point")? > 0.5 {
        Initiation::TwoPoint
    } else {
        Initiation::Given
    };
    c.run_exx = p.get("exx")? > 0.5;
    c.validate().map_err(reg)?;
    Ok(c)
}

impl Scenario for Bias32 {
    fn name(&self) -> &'static str {
        "bias-32"
    }

    fn description(&self) -> &'static str {
        "seed 004: bias estimation with pseudo-measurements vs EXX, two async radars, 32 targets, compensation"
    }

    fn default_runs(&self) -> u64 {
        100
    }

    fn params(&self) -> Vec<ParamSpec> {
        vec![
            ParamSpec {
                key: "sensors",
                default: 2.0,
                min: 2.0,
                max: 64.0,
                help: "number of radars (at 10 km spacing on the x axis)",
            },
            ParamSpec {
                key: "targets",
                default: 32.0,
                min: 1.0,
                max: 4096.0,
                help: "number of targets (8-column grid)",
            },
            ParamSpec {
                key: "duration",
                default: 300.0,
                min: 2.0,
                max: 1e5,
                help: "last plot time (s)",
            },
            ParamSpec {
                key: "lin_at_plot",
                default: 0.0,
                min: 0.0,
                max: 1.0,
                help: "1: evaluate B, C, R at the plot (paper); 0: at the prediction",
            },
            ParamSpec {
                key: "two_point",
                default: 0.0,
                min: 0.0,
                max: 1.0,
                help: "1: two-point initiation from biased plots; 0: bias-free start (paper)",
            },
            ParamSpec {
                key: "exx",
                default: 1.0,
                min: 0.0,
                max: 1.0,
                help: "1: also run EXX",
            },
        ]
    }

    fn scene(&self, p: &Params) -> Result<(Truth, Vec<SensorSpec>), CliError> {
        let c = config(p)?;
        let mut truth = Truth::new();
        for x in &c.targets {
            truth.add(Trajectory::new(
                0.0,
                KinematicState::planar(x[0], x[2], x[1], x[3]),
                vec![Segment::ConstantVelocity {
                    duration: c.duration,
                }],
            )?);
        }
        let mut specs = Vec::new();
        for (s, setup) in c.sensors.iter().enumerate() {
            let pos = setup.sensor.position();
            specs.push(SensorSpec::new(
                SensorId(s as u32 + 1),
                Vector::<3>::new(pos[0], pos[1], 0.0),
                SensorKind::Polar {
                    sigma_range: 10.0,
                    sigma_azimuth: 1e-3,
                },
                Schedule::Periodic {
                    period: setup.period,
                    offset: setup.offset,
                },
            )?);
        }
        Ok((truth, specs))
    }

    #[allow(clippy::too_many_lines)]
    fn run(&self, ctx: &RunContext) -> Result<Report, CliError> {
        let c = config(&ctx.params)?;
        let started = std::time::Instant::now();
        let one = |_: u64, rng: &mut argus_sim::ChaCha8Rng| -> Result<_, CliError> {
            run(&c, &mut || StandardNormal.sample(rng)).map_err(reg)
        };
        let progress = &ctx.progress;
        let recs = monte_carlo(ctx.seed, ctx.runs.clone(), one, || progress.tick())?;
        progress.finish();
        let elapsed = started.elapsed().as_secs_f64();
        let plots: usize = recs.iter().map(|r| r.plots).sum();
        let s = Summary::from_runs(&recs, c.sensors.len()).map_err(reg)?;
        let end = s.times.len().saturating_sub(1);
        let at = |t: f64| s.index_at(t);
        let comp = [
            "range offset",
            "azimuth offset",
            "range scale",
            "azimuth scale",
        ];
        let units = ["m", "rad", "-", "-"];
        let mut rows = Vec::new();
        let row = |key: String,
                   q: String,
                   paper: Option<f64>,
                   text: Option<&str>,
                   ours: f64,
                   unit: &str,
                   note: String| Row {
            key,
            quantity: q,
            paper,
            paper_text: text.map(str::to_owned),
            ours,
            unit: unit.into(),
            note,
        };
        for (k, name) in comp.iter().enumerate() {
            for (tag, t) in [
                ("10s", 10.0),
                ("100s", 100.0),
                ("final", s.times.get(end).copied().unwrap_or(0.0)),
            ] {
                let i = at(t);
                let p = s.proposed_rmse.get(i).map_or(f64::NAN, |v| v[k]);
                rows.push(row(
                    format!("proposed_{}_{tag}", name.replace(' ', "_")),
                    format!("{name} RMSE, proposed, t={t:.0} s"),
                    None,
                    Some("Figs. 3-6: below EXX"),
                    p,
                    units[k],
                    format!("{} runs", s.runs),
                ));
                if let Some(e) = s.exx_rmse.get(i) {
                    rows.push(row(
                        format!("exx_{}_{tag}", name.replace(' ', "_")),
                        format!("{name} RMSE, EXX, t={t:.0} s"),
                        None,
                        Some("Figs. 3-6"),
                        e[k],
                        units[k],
                        format!("{} runs", s.runs),
                    ));
                }
            }
        }
        let nees_note = format!("expected {} (chi-square dof)", s.bias_dim);
        rows.push(row(
            "proposed_anees_final".into(),
            "bias ANEES, proposed, final".into(),
            Some(s.bias_dim as f64),
            Some("consistent"),
            s.proposed_anees.get(end).copied().unwrap_or(f64::NAN),
            "-",
            nees_note.clone(),
        ));
        if let Some(e) = s.exx_anees.get(end) {
            rows.push(row(
                "exx_anees_final".into(),
                "bias ANEES, EXX, final".into(),
                Some(s.bias_dim as f64),
                Some("consistent"),
                *e,
                "-",
                nees_note,
            ));
        }
        for tr in &s.tracks {
            let n = tr.pos_biased.len();
            let avg = |v: &Vec<f64>| v.iter().skip(n / 2).sum::<f64>() / (n - n / 2).max(1) as f64;
            let id = tr.target + 1;
            for (what, b, cmp, rf, unit) in [
                (
                    "position",
                    &tr.pos_biased,
                    &tr.pos_compensated,
                    &tr.pos_reference,
                    "m",
                ),
                (
                    "velocity",
                    &tr.vel_biased,
                    &tr.vel_compensated,
                    &tr.vel_reference,
                    "m/s",
                ),
            ] {
                rows.push(row(
                    format!("track{id}_{what}_biased"),
                    format!("track {id} (sensor 1) {what} RMSE, no compensation"),
                    None,
                    Some("Figs. 8-11"),
                    avg(b),
                    unit,
                    "mean over the second half of the run".into(),
                ));
                rows.push(row(
                    format!("track{id}_{what}_compensated"),
                    format!("track {id} (sensor 1) {what} RMSE, compensated"),
                    None,
                    Some("Figs. 8-11: lower"),
                    avg(cmp),
                    unit,
                    format!("reduction {:.1} %", 100.0 * (1.0 - avg(cmp) / avg(b))),
                ));
                rows.push(row(
                    format!("track{id}_{what}_reference"),
                    format!("track {id} (sensor 1) {what} RMSE, bias-free plots"),
                    None,
                    None,
                    avg(rf),
                    unit,
                    "same filter and noise without bias".into(),
                ));
            }
        }
        rows.push(row(
            "cost_per_plot".into(),
            "wall time per plot (all threads)".into(),
            None,
            None,
            elapsed / plots.max(1) as f64 * 1e6,
            "us",
            format!(
                "{} sensors, {} targets, {plots} plots",
                c.sensors.len(),
                c.targets.len()
            ),
        ));

        let mut cols = vec!["t".to_owned()];
        for m in ["proposed", "exx"] {
            for n in ["br", "bth", "er", "eth"] {
                cols.push(format!("{m}_{n}"));
            }
            cols.push(format!("{m}_anees"));
        }
        let bias_rows = (0..s.times.len())
            .map(|i| {
                let mut r = vec![s.times.get(i).copied().unwrap_or(f64::NAN)];
                for (rm, an) in [
                    (&s.proposed_rmse, &s.proposed_anees),
                    (&s.exx_rmse, &s.exx_anees),
                ] {
                    r.extend(rm.get(i).copied().unwrap_or([f64::NAN; 4]));
                    r.push(an.get(i).copied().unwrap_or(f64::NAN));
                }
                r
            })
            .collect();
        let mut series = vec![Series {
            name: "bias_rmse".into(),
            columns: cols,
            rows: bias_rows,
        }];
        let mut figures = Vec::new();
        for (k, name) in comp.iter().enumerate() {
            let line = |label: &str, v: &Vec<[f64; 4]>| Line {
                label: label.into(),
                points: s.times.iter().zip(v).map(|(t, x)| (*t, x[k])).collect(),
                style: LineStyle::Solid,
            };
            figures.push(Figure {
                name: format!("fig{}_{}", 3 + k, name.replace(' ', "_")),
                title: format!("{name} bias RMSE (paper Fig. {}), {} runs", 3 + k, s.runs),
                x_label: "time (s)".into(),
                y_label: format!("RMSE ({})", units[k]),
                lines: vec![line("proposed", &s.proposed_rmse), line("EXX", &s.exx_rmse)],
            });
        }
        for (j, tr) in s.tracks.iter().enumerate() {
            let id = tr.target + 1;
            series.push(Series {
                name: format!("track{id}"),
                columns: [
                    "t",
                    "pos_biased",
                    "pos_comp",
                    "pos_ref",
                    "vel_biased",
                    "vel_comp",
                    "vel_ref",
                    "anees_comp",
                ]
                .iter()
                .map(|x| (*x).to_owned())
                .collect(),
                rows: (0..tr.times.len())
                    .map(|i| {
                        [
                            &tr.times,
                            &tr.pos_biased,
                            &tr.pos_compensated,
                            &tr.pos_reference,
                            &tr.vel_biased,
                            &tr.vel_compensated,
                            &tr.vel_reference,
                            &tr.anees_compensated,
                        ]
                        .iter()
                        .map(|v| v.get(i).copied().unwrap_or(f64::NAN))
                        .collect()
                    })
                    .collect(),
            });
            for (w, (b, cmp, rf, unit)) in [
                (
                    "position",
                    (&tr.pos_biased, &tr.pos_compensated, &tr.pos_reference, "m"),
                ),
                (
                    "velocity",
                    (
                        &tr.vel_biased,
                        &tr.vel_compensated,
                        &tr.vel_reference,
                        "m/s",
                    ),
                ),
            ] {
                let pts = |v: &Vec<f64>| {
                    tr.times
                        .iter()
                        .zip(v)
                        .map(|(t, x)| (*t, *x))
                        .collect::<Vec<_>>()
                };
                let fig = 8 + 2 * j + usize::from(w == "velocity");
                figures.push(Figure {
                    name: format!("fig{fig}_track{id}_{w}"),
                    title: format!("track {id} (sensor 1) {w} RMSE (paper Fig. {fig})"),
                    x_label: "time (s)".into(),
                    y_label: format!("RMSE ({unit})"),
                    lines: vec![
                        Line {
                            label: "no compensation".into(),
                            points: pts(b),
                            style: LineStyle::Solid,
                        },
                        Line {
                            label: "compensated".into(),
                            points: pts(cmp),
                            style: LineStyle::Solid,
                        },
                        Line {
                            label: "bias-free plots".into(),
                            points: pts(rf),
                            style: LineStyle::Bound,
                        },
                    ],
                });
            }
        }
        let notes = vec![
            "Paper figures give curves only (no numbers): the paper column states the published claim.".to_owned(),
            format!("Linearisation: {:?}; initiation: {:?}; truth is noise-free CV.", c.linearization, c.initiation),
            "EXX slot rule: consecutive disjoint plot triples per target with at least two sensors.".to_owned(),
        ];
        Ok(Report {
            rows,
            series,
            figures,
            notes,
        })
    }
}

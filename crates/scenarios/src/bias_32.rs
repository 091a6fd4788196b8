//! `argus run bias-32`: multisensor registration of seed 004 (SPEC §004) — bias RMSE of
//! the pseudo-measurement method and EXX (paper Figs. 3–6), track 1 and 32 RMSE of
//! sensor 1 with and without compensation (Figs. 8–11). The scenario itself lives in
//! [`experiment`]; this file runs it through `argus_sim::monte_carlo`.
//!
//! `--set sensors=2,4,8 --set targets=32,128,512` runs a sweep instead: one campaign per
//! combination, reporting the cost per plot and the final bias RMSE of each (table rows,
//! `summary.json` and `sweep.csv`). Extra sensors sit on the x axis at 10 km spacing with
//! offsets `s/S` s; extra targets continue the 8-column grid upward (rows 10 km apart).

mod campaign;
pub mod experiment;
mod sums;

use argus_core_math::Vector;
use argus_registration::{Initiation, Linearization};
use argus_sim::{
    Bias, KinematicState, Schedule, Segment, SensorId, SensorKind, SensorSpec, Trajectory, Truth,
};
use experiment::{ScenarioConfig, Summary};

use crate::campaign::{Splittable, run_whole};
use crate::context::RunContext;
use crate::error::ScenarioError;
use crate::params::{ParamSpec, Params};
use crate::report::{Figure, Line, LineStyle, Report, Row, Series};
use crate::scenario::Scenario;

pub(crate) struct Bias32;

/// The scenario for `sensors` radars and `targets` targets with the other parameters of `p`.
fn config(p: &Params, sensors: usize, targets: usize) -> Result<ScenarioConfig, ScenarioError> {
    let mut c = ScenarioConfig::grid(sensors, targets)?;
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
    c.validate()?;
    Ok(c)
}

/// The single-campaign configuration (`sensors` and `targets` one value each).
fn single_config(p: &Params) -> Result<ScenarioConfig, ScenarioError> {
    config(p, p.get("sensors")? as usize, p.get("targets")? as usize)
}

const COMPONENTS: [&str; 4] = [
    "range offset",
    "azimuth offset",
    "range scale",
    "azimuth scale",
];
const UNITS: [&str; 4] = ["m", "rad", "-", "-"];

impl Scenario for Bias32 {
    fn name(&self) -> &'static str {
        "bias-32"
    }

    fn description(&self) -> &'static str {
        "seed 004: bias estimation with pseudo-measurements vs EXX, two async radars (true bias 20 m, 2 mrad, 3e-5, 2e-4 each), 32 targets, compensation"
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
                help: "number of radars (at 10 km spacing on the x axis); a comma list sweeps",
            },
            ParamSpec {
                key: "targets",
                default: 32.0,
                min: 1.0,
                max: 4096.0,
                help: "number of targets (8-column grid); a comma list sweeps",
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

    /// The truth and the radars of one run, each radar with its true bias, so that
    /// `argus simulate bias-32` writes the biased plots the registration sees
    /// (β = [20 m, 2 mrad, 3e-5, 2e-4] on every radar).
    fn scene(&self, p: &Params) -> Result<(Truth, Vec<SensorSpec>), ScenarioError> {
        let c = single_config(p)?;
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
            let sig = setup.sensor.sigmas(1.0);
            let b = setup.bias.as_vector();
            specs.push(
                SensorSpec::new(
                    SensorId(s as u32 + 1),
                    Vector::<3>::new(pos[0], pos[1], 0.0),
                    SensorKind::Polar {
                        sigma_range: sig.range(),
                        sigma_azimuth: sig.azimuth(),
                    },
                    Schedule::Periodic {
                        period: setup.period,
                        offset: setup.offset,
                    },
                )?
                .with_bias(Bias {
                    range_offset: b[0],
                    azimuth_offset: b[1],
                    elevation_offset: 0.0,
                    range_scale: b[2],
                    azimuth_scale: b[3],
                })?,
            );
        }
        Ok((truth, specs))
    }

    fn run(&self, ctx: &RunContext<'_>) -> Result<Report, ScenarioError> {
        run_whole(self, ctx)
    }

    fn splittable(&self) -> Option<&dyn Splittable> {
        Some(self)
    }
}

/// The report of one campaign of configuration `c` from its runs' averages `s`, their
/// `plots` and `elapsed`, the runs' summed computing time (s).
///
/// # Errors
/// The summary's errors.
#[allow(clippy::too_many_lines)]
fn single_report(
    c: &ScenarioConfig,
    s: &Summary,
    plots: usize,
    elapsed: f64,
) -> Result<Report, ScenarioError> {
    let end = s.times.len().saturating_sub(1);
    let at = |t: f64| s.index_at(t);
    let (comp, units) = (COMPONENTS, UNITS);
    let mut rows = Vec::new();
    for (k, name) in comp.iter().enumerate() {
        for (tag, t) in [
            ("10s", 10.0),
            ("100s", 100.0),
            ("final", s.times.get(end).copied().unwrap_or(0.0)),
        ] {
            let i = at(t);
            let key = name.replace(' ', "_");
            let p = s.proposed_rmse.get(i).map_or(f64::NAN, |v| v[k]);
            rows.push(
                Row::new(
                    format!("proposed_{key}_{tag}"),
                    format!("{name} RMSE, proposed, t={t:.0} s"),
                    p,
                    units[k],
                )
                .paper_text("Figs. 3-6: below EXX")
                .note(format!("{} runs", s.runs)),
            );
            if let Some(v) = s.proposed_predicted.get(i) {
                rows.push(
                    Row::new(
                        format!("proposed_{key}_{tag}_predicted"),
                        format!(
                            "{name} RMSE the proposed estimator predicts (sqrt mean Σ), t={t:.0} s"
                        ),
                        v[k],
                        units[k],
                    )
                    .note("its own covariance; over-confident (see ANEES)"),
                );
            }
            if let Some(e) = s.exx_rmse.get(i) {
                rows.push(
                    Row::new(
                        format!("exx_{key}_{tag}"),
                        format!("{name} RMSE, EXX, t={t:.0} s"),
                        e[k],
                        units[k],
                    )
                    .paper_text("Figs. 3-6")
                    .note(format!("{} runs", s.runs)),
                );
            }
        }
    }
    let nees_note = format!("expected {} (chi-square dof)", s.bias_dim);
    rows.push(
        Row::new(
            "proposed_anees_final",
            "bias ANEES, proposed, final",
            s.proposed_anees.get(end).copied().unwrap_or(f64::NAN),
            "-",
        )
        .paper(s.bias_dim as f64)
        .paper_text("consistent")
        .note(nees_note.clone()),
    );
    if let Some(e) = s.exx_anees.get(end) {
        rows.push(
            Row::new("exx_anees_final", "bias ANEES, EXX, final", *e, "-")
                .paper(s.bias_dim as f64)
                .paper_text("consistent")
                .note(nees_note),
        );
    }
    for tr in &s.tracks {
        let id = tr.target + 1;
        // The second half (steady state) and the first 20 s (the transient in which the
        // bias-free start is pulled to the biased plots).
        let n = tr.pos_biased.len();
        let early = tr.times.iter().take_while(|&&t| t <= 20.0).count();
        let mean = |v: &Vec<f64>, a: usize, b: usize| {
            let b = b.min(v.len());
            v.get(a..b)
                .map_or(f64::NAN, |w| w.iter().sum::<f64>() / w.len().max(1) as f64)
        };
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
            for (win, lo, hi, wnote) in [
                ("", n / 2, n, "mean over the second half of the run"),
                ("_0_20s", 0, early, "mean over 0-20 s (transient)"),
            ] {
                let (vb, vc) = (mean(b, lo, hi), mean(cmp, lo, hi));
                rows.push(
                    Row::new(
                        format!("track{id}_{what}_biased{win}"),
                        format!("track {id} (sensor 1) {what} RMSE, no compensation"),
                        vb,
                        unit,
                    )
                    .paper_text("Figs. 8-11")
                    .note(wnote),
                );
                rows.push(
                    Row::new(
                        format!("track{id}_{what}_compensated{win}"),
                        format!("track {id} (sensor 1) {what} RMSE, compensated"),
                        vc,
                        unit,
                    )
                    .paper_text("Figs. 8-11: lower")
                    .note(format!(
                        "{wnote}; reduction {:.1} %",
                        100.0 * (1.0 - vc / vb)
                    )),
                );
                rows.push(
                    Row::new(
                        format!("track{id}_{what}_reference{win}"),
                        format!("track {id} (sensor 1) {what} RMSE, bias-free plots"),
                        mean(rf, lo, hi),
                        unit,
                    )
                    .note(format!("{wnote}; same filter and noise without bias")),
                );
            }
        }
    }
    rows.push(
        Row::new(
            "cost_per_plot",
            "run time per plot (each run's wall time, summed over the runs)",
            elapsed / plots.max(1) as f64 * 1e6,
            "us",
        )
        .note(format!(
            "{} sensors, {} targets, {plots} plots",
            c.sensors.len(),
            c.targets.len()
        )),
    );

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
        "Paper figures give curves only (no numbers): the paper column states the published claim."
            .to_owned(),
        format!(
            "Linearisation: {:?}; initiation: {:?}; truth is noise-free CV.",
            c.linearization, c.initiation
        ),
        "EXX slot rule: consecutive disjoint plot triples per target with at least two sensors."
            .to_owned(),
    ];
    Ok(Report {
        rows,
        series,
        figures,
        notes,
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)] // test code: a failure should panic with its message

    use super::*;
    use crate::context::NoProgress;
    use crate::error::ParamProblem;

    fn ctx(settings: &[&str]) -> Result<RunContext<'static>, ScenarioError> {
        let settings: Vec<String> = settings.iter().map(|s| (*s).to_owned()).collect();
        Ok(RunContext {
            runs: 0..1,
            seed: 5,
            params: Params::from_settings(&Bias32.params(), &settings)?,
            progress: &NoProgress,
        })
    }

    #[test]
    fn comma_lists_run_a_sweep() {
        // 2 × 2 combinations, 1 run of 3 s each: one sweep.csv row and 5 table rows per
        // combination (cost per plot and the four bias components).
        let c = ctx(&["sensors=2,3", "targets=4,9", "duration=3", "exx=0"]).unwrap();
        let report = Bias32.run(&c).unwrap();
        let sweep = report.series.iter().find(|s| s.name == "sweep").unwrap();
        assert_eq!(sweep.rows.len(), 4);
        assert_eq!(report.rows.len(), 4 * 5);
        for (row, (s, n)) in sweep.rows.iter().zip([(2, 4), (2, 9), (3, 4), (3, 9)]) {
            assert_eq!((row[0] as usize, row[1] as usize), (s, n));
            // Plots: every sensor sees every target at 1 s steps over [offset, 3 s], the
            // offset k/s s, sensor 0's 1 s (its first scan after the start, issue 17).
            let per_sensor: usize = (0..s)
                .map(|k| {
                    let offset = if k == 0 { 1.0 } else { k as f64 / s as f64 };
                    (0..=3).filter(|&t| f64::from(t) + offset <= 3.0).count()
                })
                .sum();
            assert_eq!(row[2] as usize, per_sensor * n);
            assert!(row[3] > 0.0 && row[4].is_finite() && row[5].is_finite());
        }
        assert!(
            report
                .rows
                .iter()
                .any(|r| r.key == "sweep_s3_n9_azimuth_offset_rmse")
        );
    }

    #[test]
    fn lists_are_refused_where_one_value_is_needed() {
        // A list is checked value by value, and a single-value key (or `simulate`'s
        // scene) refuses one with a usage error naming the key.
        assert!(matches!(
            ctx(&["targets=32,0"]),
            Err(ScenarioError::Param { key, problem: ParamProblem::OutOfRange { .. } }) if key == "targets"
        ));
        assert!(matches!(
            ctx(&["targets=32,x"]),
            Err(ScenarioError::Param {
                problem: ParamProblem::NotANumber { .. },
                ..
            })
        ));
        let c = ctx(&["sensors=2,4"]).unwrap();
        assert!(matches!(
            Bias32.scene(&c.params),
            Err(ScenarioError::Param { key, problem: ParamProblem::List { len: 2 } }) if key == "sensors"
        ));
        let c = ctx(&["duration=3,4"]).unwrap();
        assert!(
            matches!(Bias32.run(&c), Err(ScenarioError::Param { key, problem: ParamProblem::List { .. } }) if key == "duration")
        );
    }

    #[test]
    fn simulated_plots_carry_the_true_bias() {
        // `argus simulate bias-32`: the radars of the scene have β = [20 m, 2 mrad, 3e-5, 2e-4].
        let c = ctx(&[]).unwrap();
        let (_, sensors) = Bias32.scene(&c.params).unwrap();
        assert_eq!(sensors.len(), 2);
        for s in &sensors {
            let b = s.bias();
            assert!((b.range_offset - 20.0).abs() < 1e-12);
            assert!((b.azimuth_offset - 2e-3).abs() < 1e-15);
            assert!((b.range_scale - 3e-5).abs() < 1e-18);
            assert!((b.azimuth_scale - 2e-4).abs() < 1e-18);
        }
    }
}

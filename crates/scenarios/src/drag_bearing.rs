//! `argus run drag-bearing`: seed 001 (Lee & Kim 1987) §5.2, Figs. 5–7 — a planar target
//! with quadratic drag turning 90° to the right at 50 s, seen in bearing only from the
//! origin; continuous–discrete EKF and truncated second-order filter (TSOF), each plain
//! and with GLRT detection + MRAS input estimation.
//!
//! The Monte Carlo lives in [`experiment`] (also used by the
//! crate's reduced tests; its docs state α, the prior and every other choice); this file
//! runs it in parallel and draws Figs. 5–7 (x, y and range of the first run against the
//! reference trajectory) plus the Monte Carlo RMS errors. Run `i` with base seed `s`
//! uses `ChaCha8Rng::seed_from_u64((s − 1)·2³² + i)`, so the default seed 1 reproduces
//! the tests' runs. Results: `docs/papers/001-drag-bearing.md`.

pub(crate) mod experiment;
pub(crate) mod statistics;

use argus_adaptive::AdaptiveError;
use argus_core_math::Vector;
use argus_sim::{
    KinematicState, Schedule, Segment, SensorId, SensorKind, SensorSpec, Trajectory, Truth,
};
use experiment::{DragBearingConfig, DragFilter, DragRun, reference_trajectory, simulate_run};
use serde::{Deserialize, Serialize};
use statistics::McSums;

use crate::campaign::{Campaign, Footprint, Retained, Splittable, run_whole};
use crate::context::RunContext;
use crate::error::ScenarioError;
use crate::params::{ParamSpec, Params};
use crate::report::{Figure, Line, LineStyle, Report, Row, Series};
use crate::scenario::Scenario;

/// The scenario.
pub(crate) struct DragBearing;

fn err(e: AdaptiveError) -> ScenarioError {
    ScenarioError::Config {
        scenario: "drag-bearing",
        source: e,
    }
}

fn config(p: &Params) -> Result<DragBearingConfig, ScenarioError> {
    let c = DragBearingConfig {
        dt: p.get("dt")?,
        duration: p.get("duration")?,
        turn_time: p.get("turn_time")?,
        alpha: p.get("alpha")?,
        q: p.get("q")?,
        sigma_bearing: p.get("sigma_bearing_deg")?.to_radians(),
        sigma_pos0: p.get("sigma_pos0")?,
        sigma_vel0: p.get("sigma_vel0")?,
        substeps: p.get("substeps")? as usize,
        max_age: p.get("m")? as usize,
        min_age: p.get("n")? as usize,
        eta: p.get("eta")?,
        sigma_input: p.get("sigma_input")?,
    };
    c.validate().map_err(err)?;
    Ok(c)
}

/// Run seed: `(seed − 1)·2³² + run` (see the module docs).
fn run_seed(seed: u64, run: u64) -> u64 {
    seed.wrapping_sub(1).wrapping_shl(32).wrapping_add(run)
}

/// Extracts one plotted quantity from a state.
type Component = fn(&Vector<4>) -> f64;

fn key(f: DragFilter) -> String {
    f.name().to_lowercase().replace('+', "_")
}

impl Scenario for DragBearing {
    fn name(&self) -> &'static str {
        "drag-bearing"
    }

    fn description(&self) -> &'static str {
        "seed 001: bearing-only drag target turning at 50 s, EKF and truncated second-order filter, plain and with GLRT+MRAS"
    }

    fn default_runs(&self) -> u64 {
        100
    }

    fn params(&self) -> Vec<ParamSpec> {
        let d = DragBearingConfig::default();
        vec![
            ParamSpec::new("dt", d.dt, 0.01, 100.0, "bearing interval (s)"),
            ParamSpec::new("duration", d.duration, 1.0, 1e5, "run length (s)"),
            ParamSpec::new(
                "turn_time",
                d.turn_time,
                0.0,
                1e5,
                "time of the thrust change (s)",
            ),
            ParamSpec::new("alpha", d.alpha, 0.0, 10.0, "drag coefficient alpha (1/m)"),
            ParamSpec::new("q", d.q, 0.0, 1e3, "velocity white-noise density (m^2/s^3)"),
            ParamSpec::new(
                "sigma_bearing_deg",
                d.sigma_bearing.to_degrees(),
                1e-4,
                30.0,
                "bearing noise (deg, 1 sigma)",
            ),
            ParamSpec::new(
                "sigma_pos0",
                d.sigma_pos0,
                1e-3,
                1e5,
                "prior position sigma per axis (m)",
            ),
            ParamSpec::new(
                "sigma_vel0",
                d.sigma_vel0,
                1e-4,
                1e3,
                "prior velocity sigma per axis (m/s)",
            ),
            ParamSpec::new(
                "substeps",
                d.substeps as f64,
                1.0,
                1e4,
                "RK4 substeps per prediction",
            ),
            ParamSpec::new("m", d.max_age as f64, 0.0, 1000.0, "GLRT window M (plots)"),
            ParamSpec::new(
                "n",
                d.min_age as f64,
                0.0,
                1000.0,
                "GLRT shortest onset age N (plots)",
            ),
            ParamSpec::new("eta", d.eta, 1e-3, 1e6, "GLRT threshold"),
            ParamSpec::new(
                "sigma_input",
                d.sigma_input,
                1e-4,
                1e4,
                "prior sigma of each thrust-change component (m/s^2)",
            ),
        ]
    }

    /// The noise-free trajectory as sim segments: one constant-acceleration segment per
    /// plot interval with the interval's mean acceleration (velocities exact at the plot
    /// times; positions within the drag curvature of one interval). The sim has no
    /// bearing-only sensor: a polar sensor with the bearing σ stands in (use only its
    /// azimuth; its range σ is set to 1 m and means nothing here).
    fn scene(&self, p: &Params) -> Result<(Truth, Vec<SensorSpec>), ScenarioError> {
        let c = config(p)?;
        let traj = reference_trajectory(&c).map_err(err)?;
        let segments = traj
            .windows(2)
            .filter_map(|w| match w {
                [a, b] => Some(Segment::Accelerate {
                    duration: c.dt,
                    accel: Vector::<3>::new((b[1] - a[1]) / c.dt, (b[3] - a[3]) / c.dt, 0.0),
                }),
                _ => None,
            })
            .collect();
        let x0 = c.initial_truth();
        let mut truth = Truth::new();
        truth.add(Trajectory::new(
            0.0,
            KinematicState::planar(x0[0], x0[2], x0[1], x0[3]),
            segments,
        )?);
        let sensor = SensorSpec::new(
            SensorId(1),
            Vector::<3>::zeros(),
            SensorKind::Polar {
                sigma_range: 1.0,
                sigma_azimuth: c.sigma_bearing,
            },
            Schedule::Periodic {
                period: c.dt,
                offset: c.dt,
            },
        )?;
        Ok((truth, vec![sensor]))
    }

    fn run(&self, ctx: &RunContext<'_>) -> Result<Report, ScenarioError> {
        run_whole(self, ctx)
    }

    fn splittable(&self) -> Option<&dyn Splittable> {
        Some(self)
    }
}

/// A [`DragRun`] as plain arrays (the vectors' components in order): one line of a
/// split campaign's per-run file.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(crate) struct DragRecord {
    times: Vec<f64>,
    truth: Vec<[f64; 4]>,
    estimates: [Vec<[f64; 4]>; 4],
    detections: [Vec<usize>; 4],
    final_input: [Option<[f64; 2]>; 4],
    failed_at: [Option<usize>; 4],
}

fn arrays(v: &[Vector<4>]) -> Vec<[f64; 4]> {
    v.iter().map(|x| (*x).into()).collect()
}

fn vectors(v: &[[f64; 4]]) -> Vec<Vector<4>> {
    v.iter().map(|x| Vector::<4>::from(*x)).collect()
}

impl From<&DragRun> for DragRecord {
    fn from(r: &DragRun) -> Self {
        Self {
            times: r.times.clone(),
            truth: arrays(&r.truth),
            estimates: r.estimates.each_ref().map(|e| arrays(e)),
            detections: r.detections.clone(),
            final_input: r.final_input.map(|u| u.map(Into::into)),
            failed_at: r.failed_at,
        }
    }
}

impl From<&DragRecord> for DragRun {
    fn from(r: &DragRecord) -> Self {
        Self {
            times: r.times.clone(),
            truth: vectors(&r.truth),
            estimates: r.estimates.each_ref().map(|e| vectors(e)),
            detections: r.detections.clone(),
            final_input: r.final_input.map(|u| u.map(Vector::<2>::from)),
            failed_at: r.failed_at,
        }
    }
}

/// What the reduce step keeps: the statistics' sums and the first run (its trajectory
/// and estimates feed the `first_run` series and Figs. 5–7).
pub(crate) struct DragSums {
    sums: McSums,
    first: Option<DragRun>,
}

impl Retained for DragSums {
    fn footprint(&self) -> Footprint {
        let first = self.first.as_ref().map_or(0, |r| {
            r.times.len()
                + 4 * r.truth.len()
                + r.estimates.iter().map(|e| 4 * e.len()).sum::<usize>()
        });
        Footprint {
            fixed: self.sums.retained() + first,
            per_run: 0,
        }
    }
}

impl Campaign for DragBearing {
    type Setup = DragBearingConfig;
    type Run = DragRecord;
    type Sums = DragSums;

    fn setup(&self, p: &Params) -> Result<DragBearingConfig, ScenarioError> {
        config(p)
    }

    fn one_run(
        &self,
        c: &DragBearingConfig,
        seed: u64,
        run: u64,
        _rng: &mut argus_sim::ChaCha8Rng,
    ) -> Result<DragRecord, ScenarioError> {
        let r = simulate_run(c, run_seed(seed, run)).map_err(err)?;
        Ok(DragRecord::from(&r))
    }

    fn start(&self, c: &DragBearingConfig, _count: u64) -> Result<DragSums, ScenarioError> {
        Ok(DragSums {
            sums: McSums::new(c),
            first: None,
        })
    }

    fn add(
        &self,
        _c: &DragBearingConfig,
        sums: &mut DragSums,
        run: DragRecord,
    ) -> Result<(), ScenarioError> {
        let run = DragRun::from(&run);
        sums.sums.add(&run);
        if sums.first.is_none() {
            sums.first = Some(run);
        }
        Ok(())
    }

    #[allow(clippy::too_many_lines)]
    fn finish(&self, c: &DragBearingConfig, sums: DragSums) -> Result<Report, ScenarioError> {
        let c = *c;
        let s = sums.sums.finish().map_err(err)?;
        let (turn, end) = (c.turn_time, c.duration);
        let last = (end - 10.0).max(turn);
        let mut rows = Vec::new();
        for f in DragFilter::ALL {
            let k = key(f);
            rows.push(Row::with_text(
                format!("{k}_rms_pos_before_turn"),
                format!("{} RMS position error before the turn", f.name()),
                None,
                s.time_rms_position(f, 0.0, turn),
                "m",
                "time mean of the MC mean square, t <= turn; range unobservable (radial motion)",
            ));
            rows.push(Row::with_text(
                format!("{k}_rms_pos_after_turn"),
                format!("{} RMS position error after the turn", f.name()),
                None,
                s.time_rms_position(f, turn, end),
                "m",
                "t >= turn",
            ));
            rows.push(Row::with_text(
                format!("{k}_rms_pos_final"),
                format!("{} RMS position error, final 10 s", f.name()),
                if f.adaptive() {
                    Some("tracks the turn (Figs. 5-7)")
                } else {
                    None
                },
                s.time_rms_position(f, last, end),
                "m",
                "issue 8: smaller with input estimation than without",
            ));
            rows.push(Row::with_text(
                format!("{k}_rms_range_final"),
                format!("{} RMS range error, final 10 s", f.name()),
                if f.adaptive() { Some("Fig. 7") } else { None },
                s.time_rms_range(f, last, end),
                "m",
                "",
            ));
            rows.push(Row::with_text(
                format!("{k}_failed_runs"),
                format!("{} runs with a failed step", f.name()),
                None,
                s.failures[f.index()] as f64,
                "-",
                "the filter then coasts on predictions",
            ));
            if f.adaptive() {
                rows.push(Row::with_text(
                    format!("{k}_delay_mean"),
                    format!("{} mean detection delay after the turn", f.name()),
                    None,
                    s.mean_delay(f),
                    "s",
                    &format!("missed in {} runs", s.missed(f)),
                ));
                rows.push(Row::with_text(
                    format!("{k}_false_detections"),
                    format!("{} detections before the turn", f.name()),
                    None,
                    s.false_detections[f.index()] as f64,
                    "-",
                    "summed over runs",
                ));
                rows.push(Row::with_text(
                    format!("{k}_input_error"),
                    format!("{} final thrust-change error |u_hat - du|", f.name()),
                    None,
                    s.final_input_rms[f.index()],
                    "m/s^2",
                    &format!(
                        "RMS over runs; |du| = {:.2} m/s^2",
                        (c.thrust_after() - c.thrust_before()).norm()
                    ),
                ));
            }
        }
        rows.push(Row::with_text(
            "tsof_vs_ekf_early".into(),
            "adaptive TSOF / EKF RMS position, first 10 s after the turn".into(),
            Some("TSOF better early, EKF better in steady state"),
            s.time_rms_position(DragFilter::TsofGlrtMras, turn, turn + 10.0)
                / s.time_rms_position(DragFilter::EkfGlrtMras, turn, turn + 10.0),
            "-",
            "ratio < 1: TSOF better",
        ));

        // Per-time RMS and the first run's trajectories.
        let mut columns = vec!["t".to_owned()];
        for f in DragFilter::ALL {
            columns.push(format!("rms_pos_{}", key(f)));
            columns.push(format!("rms_range_{}", key(f)));
        }
        let rms_rows = (0..s.times.len())
            .map(|k| {
                let mut r = vec![s.times.get(k).copied().unwrap_or(f64::NAN)];
                for f in DragFilter::ALL {
                    let i = f.index();
                    r.push(s.rms_position[i].get(k).copied().unwrap_or(f64::NAN));
                    r.push(s.rms_range[i].get(k).copied().unwrap_or(f64::NAN));
                }
                r
            })
            .collect();
        let mut series = vec![Series {
            name: "rms".into(),
            columns,
            rows: rms_rows,
        }];
        let mut figures = Vec::new();
        if let Some(r0) = &sums.first {
            let mut columns = vec![
                "t".to_owned(),
                "x_true".to_owned(),
                "y_true".to_owned(),
                "range_true".to_owned(),
            ];
            for f in DragFilter::ALL {
                for q in ["x", "y", "range"] {
                    columns.push(format!("{q}_{}", key(f)));
                }
            }
            let data = r0
                .times
                .iter()
                .zip(&r0.truth)
                .enumerate()
                .map(|(k, (t, x))| {
                    let mut r = vec![*t, x[0], x[2], x[0].hypot(x[2])];
                    for f in DragFilter::ALL {
                        let e = r0.estimates[f.index()]
                            .get(k)
                            .copied()
                            .unwrap_or_else(|| Vector::<4>::repeat(f64::NAN));
                        r.extend([e[0], e[2], e[0].hypot(e[2])]);
                    }
                    r
                })
                .collect();
            series.push(Series {
                name: "first_run".into(),
                columns,
                rows: data,
            });
            let comp: [(&str, &str, Component); 3] = [
                ("x", "x (m)", |v| v[0]),
                ("y", "y (m)", |v| v[2]),
                ("range", "range (m)", |v| v[0].hypot(v[2])),
            ];
            for (fig, (name, label, g)) in (5..).zip(comp) {
                let mut lines = vec![Line {
                    label: "truth".into(),
                    points: r0
                        .times
                        .iter()
                        .zip(&r0.truth)
                        .map(|(t, x)| (*t, g(x)))
                        .collect(),
                    style: LineStyle::Bound,
                }];
                for f in DragFilter::ALL {
                    lines.push(Line {
                        label: f.name().into(),
                        points: r0
                            .times
                            .iter()
                            .zip(&r0.estimates[f.index()])
                            .map(|(t, x)| (*t, g(x)))
                            .collect(),
                        style: LineStyle::Solid,
                    });
                }
                figures.push(Figure {
                    name: format!("fig{fig}_{name}"),
                    title: format!("Fig. {fig}: {name} estimated vs truth (first run)"),
                    x_label: "time (s)".into(),
                    y_label: label.into(),
                    lines,
                });
            }
        }
        figures.push(Figure {
            name: "rms_position".into(),
            title: "RMS position error over the runs".into(),
            x_label: "time (s)".into(),
            y_label: "RMS position error (m)".into(),
            lines: DragFilter::ALL
                .iter()
                .map(|f| Line {
                    label: f.name().into(),
                    points: s
                        .times
                        .iter()
                        .zip(&s.rms_position[f.index()])
                        .map(|(t, e)| (*t, *e))
                        .collect(),
                    style: LineStyle::Solid,
                })
                .collect(),
        });
        let x0 = c.initial_truth();
        Ok(Report {
            rows,
            series,
            figures,
            notes: vec![
                format!(
                    "alpha = {} 1/m (not in the paper; ours); truth starts at ({:.1}, {:.1}) m = (10000, 10000) ft with (20, 20) ft/s, cruise thrust balancing drag; at {} s the thrust steps to the cruise thrust of (30, -30) ft/s",
                    c.alpha, x0[0], x0[2], c.turn_time
                ),
                format!(
                    "prior (range unobservable before the turn): mean = truth + N(0, P0), P0 = diag({0}^2, {1}^2, {0}^2, {1}^2) (m, m/s); filters know alpha, q and the cruise thrust before the turn",
                    c.sigma_pos0, c.sigma_vel0
                ),
                format!(
                    "bearing sigma {:.3} deg every {} s; GLRT persistent 2-D input, M = {}, N = {}, eta = {}, input prior sigma {} m/s^2 per axis",
                    c.sigma_bearing.to_degrees(),
                    c.dt,
                    c.max_age,
                    c.min_age,
                    c.eta,
                    c.sigma_input
                ),
                "the paper gives figures only (no numbers)".into(),
            ],
        })
    }
}

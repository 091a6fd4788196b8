//! The `real-traffic` report: each configuration's score against the ADS-B truth
//! (means over the runs), completeness and GOSPA over time, and the map.

use super::setup::{ConfigScore, EXTENSION, RealRun, Setup};
use crate::error::ScenarioError;
use crate::report::{Figure, Line, LineStyle, Report, Row, Series};

/// Mean of the present values (`None` when none is).
fn mean(values: impl Iterator<Item = Option<f64>>) -> Option<f64> {
    let (mut sum, mut n) = (0.0, 0usize);
    for v in values.flatten() {
        sum += v;
        n += 1;
    }
    (n > 0).then(|| sum / n as f64)
}

/// The report of `runs` (in run order).
///
/// # Errors
/// [`ScenarioError::Degenerate`] for no run or a record without a configuration.
pub(super) fn reduce(s: &Setup, runs: &[RealRun]) -> Result<Report, ScenarioError> {
    let degenerate = |message: String| ScenarioError::Degenerate {
        scenario: "real-traffic",
        message,
    };
    if runs.is_empty() {
        return Err(degenerate("no runs".into()));
    }
    let n = runs.len() as f64;
    let mut rows = vec![
        Row::new(
            "aircraft",
            "aircraft in the extract",
            s.cleaning.aircraft as f64,
            "-",
        ),
        Row::new(
            "flight_segments",
            "flight segments after cleaning",
            s.paths.len() as f64,
            "-",
        )
        .note(format!(
            "{} of {} records kept",
            s.cleaning.kept, s.cleaning.records
        )),
        Row::new(
            "truths_in_coverage",
            "segments inside the coverage",
            s.truth.len() as f64,
            "-",
        ),
        Row::new(
            "plots",
            "plots per run",
            runs.iter().map(|r| r.plots as f64).sum::<f64>() / n,
            "-",
        ),
        Row::new(
            "target_plots",
            "aircraft plots per run",
            runs.iter().map(|r| r.target_plots as f64).sum::<f64>() / n,
            "-",
        ),
    ];
    let mut completeness_lines = Vec::new();
    let mut gospa_lines = Vec::new();
    let mut columns = vec!["t".to_owned()];
    let grid: Vec<f64> = runs[0]
        .configs
        .first()
        .map(|c| c.series.iter().map(|g| g.0).collect())
        .unwrap_or_default();
    let mut series_rows: Vec<Vec<f64>> = grid.iter().map(|&t| vec![t]).collect();
    for (i, named) in s.trackers.iter().enumerate() {
        let cfg: Vec<&ConfigScore> = runs.iter().filter_map(|r| r.configs.get(i)).collect();
        if cfg.len() != runs.len() {
            return Err(degenerate(format!(
                "a run record lacks configuration {}",
                named.name
            )));
        }
        let key = named.name;
        let opt = |f: &dyn Fn(&ConfigScore) -> Option<f64>| mean(cfg.iter().map(|c| f(c)));
        let val = |f: &dyn Fn(&ConfigScore) -> f64| cfg.iter().map(|c| f(c)).sum::<f64>() / n;
        let push = |rows: &mut Vec<Row>,
                    what: &str,
                    quantity: &str,
                    v: Option<f64>,
                    unit: &str,
                    goal: &str| {
            let row = Row::new(
                format!("{key}_{what}"),
                format!("{key}: {quantity}"),
                v.unwrap_or(f64::NAN),
                unit,
            );
            rows.push(if goal.is_empty() {
                row
            } else {
                row.paper_text(goal)
            });
        };
        push(
            &mut rows,
            "completeness",
            "completeness",
            opt(&|c| c.completeness),
            "-",
            "≥ 0.985 (issue 18)",
        );
        push(
            &mut rows,
            "breaks_per_aircraft_hour",
            "track breaks per aircraft-hour",
            opt(&|c| c.breaks_per_aircraft_hour),
            "1/h",
            "≤ 0.1",
        );
        push(
            &mut rows,
            "id_swaps",
            "identity swaps",
            Some(val(&|c| c.id_swaps as f64)),
            "-",
            "reported",
        );
        push(
            &mut rows,
            "spurious_fraction",
            "spurious confirmed-track time",
            opt(&|c| c.spurious_fraction),
            "-",
            "≤ 0.005",
        );
        push(
            &mut rows,
            "false_tracks_per_step",
            "false confirmed tracks per grid step",
            Some(val(&|c| c.false_tracks_per_step)),
            "-",
            "",
        );
        push(
            &mut rows,
            "position_rmse",
            "position RMSE",
            opt(&|c| c.position_rmse),
            "m",
            "≤ 90",
        );
        push(
            &mut rows,
            "velocity_rmse",
            "velocity RMSE",
            opt(&|c| c.velocity_rmse),
            "m/s",
            "≤ 10",
        );
        push(
            &mut rows,
            "position_p95",
            "95th-percentile position error",
            opt(&|c| c.position_p95),
            "m",
            "",
        );
        push(
            &mut rows,
            "time_to_confirm",
            "mean time to confirm",
            opt(&|c| c.time_to_confirm_mean),
            "s",
            "",
        );
        push(
            &mut rows,
            "never_tracked",
            "truths never tracked",
            Some(val(&|c| c.truths_never_tracked as f64)),
            "-",
            "",
        );
        push(
            &mut rows,
            "confirmed_tracks",
            "confirmed tracks",
            Some(val(&|c| c.confirmed_tracks as f64)),
            "-",
            "",
        );
        push(
            &mut rows,
            "gospa",
            "mean GOSPA",
            Some(val(&|c| c.gospa_mean)),
            "m",
            "",
        );
        push(
            &mut rows,
            "gospa_missed",
            "mean GOSPA missed part",
            Some(val(&|c| c.gospa_missed_mean)),
            "m²",
            "",
        );
        push(
            &mut rows,
            "gospa_false",
            "mean GOSPA false part",
            Some(val(&|c| c.gospa_false_mean)),
            "m²",
            "",
        );
        push(
            &mut rows,
            "spurious_fraction_truth_extended",
            &format!("spurious time, each truth extended {EXTENSION} s past its end"),
            opt(&|c| c.spurious_fraction_extended),
            "-",
            "diagnostic",
        );
        // Issue 19: the same tracks RTS-smoothed (Kalman-filter trackers only).
        let smoothed = opt(&|c| c.smoothed_position_rmse);
        if let (Some(sm), Some(f)) = (smoothed, opt(&|c| c.position_rmse)) {
            rows.push(
                Row::new(
                    format!("{key}_smooth_rms_ratio"),
                    format!("{key}: position RMSE, smoothed / filtered tracks"),
                    sm / f,
                    "-",
                )
                .paper_text("reported (issue 19)")
                .note(format!(
                    "each track RTS-smoothed over its life (the tracker's CV KF): {sm:.1} m against {f:.1} m, same scorer"
                )),
            );
        }
        // Issue 18: NEES of [x, vx, y, vy] against the RTS-smoothed ADS-B truth.
        let count: usize = cfg.iter().map(|c| c.nees_count).sum();
        if count > 0 {
            let anees = cfg.iter().map(|c| c.nees_sum).sum::<f64>() / count as f64;
            let band = argus_core_math::anees_interval(4, count, 0.99)
                .map_err(|e| degenerate(format!("NEES band: {e}")))?;
            rows.push(
                Row::new(
                    format!("{key}_nees_cv_vs_smoothed_truth"),
                    format!("{key}: NEES of [x, vx, y, vy] against the smoothed ADS-B truth"),
                    anees,
                    "-",
                )
                .paper_text("reported (issue 18)")
                .note(format!(
                    "mean over {count} confirmed rows; 99 % band of χ²(4n)/n [{:.3}, {:.3}] (rows are correlated: the band is narrower than the spread to expect)",
                    band.lower, band.upper
                )),
            );
        }
        columns.push(format!("{key}_completeness"));
        columns.push(format!("{key}_gospa"));
        let mut comp = Vec::with_capacity(grid.len());
        let mut gos = Vec::with_capacity(grid.len());
        for (k, (&t, row)) in grid.iter().zip(series_rows.iter_mut()).enumerate() {
            let c = mean(cfg.iter().map(|c| c.series.get(k).and_then(|g| g.1))).unwrap_or(f64::NAN);
            let g = cfg
                .iter()
                .map(|c| c.series.get(k).map_or(f64::NAN, |g| g.2))
                .sum::<f64>()
                / n;
            row.push(c);
            row.push(g);
            comp.push((t, c));
            gos.push((t, g));
        }
        completeness_lines.push(Line {
            label: key.to_owned(),
            points: comp,
            style: LineStyle::Solid,
        });
        gospa_lines.push(Line {
            label: key.to_owned(),
            points: gos,
            style: LineStyle::Solid,
        });
    }
    let km = |(x, y): (f64, f64)| (x / 1000.0, y / 1000.0);
    let truth_points: Vec<(f64, f64)> = s
        .truth
        .iter()
        .flat_map(|p| p.samples().iter().step_by(20).map(|q| km((q.x, q.y))))
        .collect();
    let map = Figure {
        name: "map".into(),
        title: format!(
            "ADS-B truth, plots (first minute) and {} tracks (first run)",
            s.trackers[0].name
        ),
        x_label: "east of the radar (km)".into(),
        y_label: "north of the radar (km)".into(),
        lines: vec![
            Line {
                label: "ADS-B truth (every 20 s)".into(),
                points: truth_points,
                style: LineStyle::Points,
            },
            Line {
                label: "plots, first minute".into(),
                points: runs[0].map_plots.iter().copied().map(km).collect(),
                style: LineStyle::Points,
            },
            Line {
                label: "confirmed tracks (every 20 s)".into(),
                points: runs[0].map_tracks.iter().copied().map(km).collect(),
                style: LineStyle::Points,
            },
        ],
    };
    let figure = |name: &str, title: &str, y: &str, lines| Figure {
        name: name.into(),
        title: title.into(),
        x_label: "time (s)".into(),
        y_label: y.into(),
        lines,
    };
    let c = &s.cleaning;
    Ok(Report {
        rows,
        series: vec![Series { name: "score_over_time".into(), columns, rows: series_rows }],
        figures: vec![
            map,
            figure("completeness", "Completeness over time", "completeness", completeness_lines),
            figure("gospa", "GOSPA over time", "GOSPA (m)", gospa_lines),
        ],
        notes: vec![
            format!(
                "ADS-B cleaning (argus-adsb, docs/adsb.md): {} records, {} aircraft; dropped: {} missing position, {} on ground, {} missing altitude, {} altitude out of bounds, {} duplicate time, {} stale position, {} position spike, {} altitude spike, {} in short segments; {} gap splits; {} flights kept",
                c.records, c.aircraft, c.missing_position, c.on_ground, c.missing_altitude, c.altitude_out_of_bounds, c.duplicate_time, c.stale_position, c.position_spike, c.altitude_spike, c.short_segment, c.gap_splits, c.flights
            ),
            "scored on the ADS-B truth inside the coverage; grid, assignment and every definition: docs/scoring.md".to_owned(),
        ],
    })
}

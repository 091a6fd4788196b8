//! The `real-traffic` report: each configuration's score against the ADS-B truth
//! (means over the runs), completeness and GOSPA over time, and the map.

use super::setup::{EXTENSION, Setup};
use super::sums::{RealSums, mean};
use crate::error::ScenarioError;
use crate::report::{Figure, Line, LineStyle, Report, Row, Series};

/// The report of the runs summed in `sums`.
///
/// # Errors
/// [`ScenarioError::Degenerate`] for no run or a record without a configuration.
pub(super) fn reduce(s: &Setup, sums: &RealSums) -> Result<Report, ScenarioError> {
    let degenerate = |message: String| ScenarioError::Degenerate {
        scenario: "real-traffic",
        message,
    };
    if sums.runs == 0 {
        return Err(degenerate("no runs".into()));
    }
    let n = sums.runs as f64;
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
        Row::new("plots", "plots per run", sums.plots / n, "-"),
        Row::new(
            "target_plots",
            "aircraft plots per run",
            sums.target_plots / n,
            "-",
        ),
    ];
    let mut completeness_lines = Vec::new();
    let mut gospa_lines = Vec::new();
    let mut columns = vec!["t".to_owned()];
    let grid = &sums.grid;
    let mut series_rows: Vec<Vec<f64>> = grid.iter().map(|&t| vec![t]).collect();
    for (i, named) in s.trackers.iter().enumerate() {
        let Some(cfg) = sums.configs.get(i).filter(|c| c.complete) else {
            return Err(degenerate(format!(
                "a run record lacks configuration {}",
                named.name
            )));
        };
        let key = named.name;
        // The indices of `sums::optional` and `sums::plain`.
        let opt = |j: usize| mean(cfg.optional[j]);
        let val = |j: usize| cfg.plain[j] / n;
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
            opt(0),
            "-",
            "≥ 0.985 (issue 18)",
        );
        push(
            &mut rows,
            "breaks_per_aircraft_hour",
            "track breaks per aircraft-hour",
            opt(1),
            "1/h",
            "≤ 0.1",
        );
        push(
            &mut rows,
            "id_swaps",
            "identity swaps",
            Some(val(0)),
            "-",
            "reported",
        );
        push(
            &mut rows,
            "spurious_fraction",
            "spurious confirmed-track time",
            opt(2),
            "-",
            "≤ 0.005",
        );
        push(
            &mut rows,
            "false_tracks_per_step",
            "false confirmed tracks per grid step",
            Some(val(1)),
            "-",
            "",
        );
        push(
            &mut rows,
            "position_rmse",
            "position RMSE",
            opt(3),
            "m",
            "≤ 90",
        );
        push(
            &mut rows,
            "velocity_rmse",
            "velocity RMSE",
            opt(4),
            "m/s",
            "≤ 10",
        );
        push(
            &mut rows,
            "position_p95",
            "95th-percentile position error",
            opt(5),
            "m",
            "",
        );
        push(
            &mut rows,
            "time_to_confirm",
            "mean time to confirm",
            opt(6),
            "s",
            "",
        );
        push(
            &mut rows,
            "never_tracked",
            "truths never tracked",
            Some(val(2)),
            "-",
            "",
        );
        push(
            &mut rows,
            "confirmed_tracks",
            "confirmed tracks",
            Some(val(3)),
            "-",
            "",
        );
        push(&mut rows, "gospa", "mean GOSPA", Some(val(4)), "m", "");
        push(
            &mut rows,
            "gospa_missed",
            "mean GOSPA missed part",
            Some(val(5)),
            "m²",
            "",
        );
        push(
            &mut rows,
            "gospa_false",
            "mean GOSPA false part",
            Some(val(6)),
            "m²",
            "",
        );
        push(
            &mut rows,
            "spurious_fraction_truth_extended",
            &format!("spurious time, each truth extended {EXTENSION} s past its end"),
            opt(7),
            "-",
            "diagnostic",
        );
        // Issue 19: the same tracks smoothed (KF, two-mode IMM and aircraft-IMM trackers).
        if let (Some(sm), Some(f)) = (opt(8), opt(3)) {
            rows.push(
                Row::new(
                    format!("{key}_smooth_rms_ratio"),
                    format!("{key}: position RMSE, smoothed / filtered tracks"),
                    sm / f,
                    "-",
                )
                .paper_text("reported (issue 19)")
                .note(format!(
                    "each track smoothed over its life ({}): {sm:.1} m against {f:.1} m, same scorer",
                    if key.ends_with("_imm") {
                        "argus_imm's IMM smoother of the tracker's two-mode IMM"
                    } else {
                        "RTS of the tracker's CV KF"
                    }
                )),
            );
        }
        // Issue 18: NEES of [x, vx, y, vy] against the RTS-smoothed ADS-B truth.
        let count = cfg.nees_count;
        if count > 0 {
            let anees = cfg.nees_sum / count as f64;
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
            let c = cfg
                .completeness
                .get(k)
                .and_then(|p| mean(*p))
                .unwrap_or(f64::NAN);
            let g = cfg.gospa.get(k).copied().unwrap_or(f64::NAN) / n;
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
                points: sums.map_plots.iter().copied().map(km).collect(),
                style: LineStyle::Points,
            },
            Line {
                label: "confirmed tracks (every 20 s)".into(),
                points: sums.map_tracks.iter().copied().map(km).collect(),
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

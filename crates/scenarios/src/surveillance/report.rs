//! The surveillance report: OSPA / GOSPA and the track counts per configuration, over
//! the scans after the warm-up, with their per-scan series and figures.

use std::f64::consts::PI;

use super::setup::{CONFIGS, Setup};
use super::sums::{FIELDS, SurvSums};
use crate::error::{ParamProblem, ScenarioError};
use crate::report::{Figure, Line, LineStyle, Report, Row, Series};

/// The report of the runs summed in `sums` of the campaign `s`.
///
/// # Errors
/// [`ScenarioError::Degenerate`] for no run or a record without a configuration,
/// [`ScenarioError::Param`] for a warm-up that leaves no scan.
#[allow(clippy::too_many_lines)]
pub(super) fn reduce(s: &Setup, sums: &SurvSums) -> Result<Report, ScenarioError> {
    if sums.runs == 0 {
        return Err(ScenarioError::Degenerate {
            scenario: "surveillance",
            message: "no runs".into(),
        });
    }
    let n_runs = sums.runs as f64;
    let (c, p) = (s.ospa.cutoff(), s.ospa.order());
    // GOSPA with no track at all: every one of the n truths is missed at c^p/2
    // (Rahmathullah et al. 2017, α = 2), so d^p = n c^p / 2 and d = c (n/2)^{1/p}.
    let no_tracks = c * (s.targets as f64 / 2.0).powf(1.0 / p);
    let times: Vec<f64> = (0..s.scans).map(|k| s.time(k)).collect();
    let after: Vec<usize> = (0..s.scans).filter(|&k| s.time(k) >= s.warmup).collect();
    if after.is_empty() {
        let problem = ParamProblem::Conflict {
            value: s.warmup,
            reason: format!("leaves no scan (the last is at {} s)", s.time(s.scans - 1)),
        };
        return Err(ScenarioError::param("warmup", problem));
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
        let Some(cfg) = sums.configs.get(i).filter(|c| c.complete) else {
            return Err(ScenarioError::Degenerate {
                scenario: "surveillance",
                message: format!("a run record lacks configuration {key}"),
            });
        };
        let score =
            |k: usize, j: usize| -> f64 { cfg.per_scan.get(k).map_or(0.0, |v| v[j]) / n_runs };
        let mut means = Vec::with_capacity(FIELDS.len());
        for (j, name) in FIELDS.iter().enumerate() {
            columns.push(format!("{key}_{name}"));
            let mut sum_after = 0.0;
            for (k, row) in per_scan.iter_mut().enumerate() {
                let v = score(k, j);
                row.push(v);
                if s.time(k) >= s.warmup {
                    sum_after += v;
                }
            }
            means.push(sum_after / after.len() as f64);
        }
        columns.push(format!("{key}_confirmed"));
        for (k, row) in per_scan.iter_mut().enumerate() {
            row.push(score(k, FIELDS.len()));
        }
        let col = |j: usize| -> Vec<(f64, f64)> {
            let idx = 1 + i * (FIELDS.len() + 1) + j;
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
        let (loc_sum, assigned) = (cfg.loc_sum, cfg.assigned);
        let loc_mean = if assigned > 0 {
            (loc_sum / assigned as f64).powf(1.0 / p)
        } else {
            0.0
        };
        let never = cfg.never;
        let ttc_mean = if cfg.ttc_count == 0 {
            0.0
        } else {
            cfg.ttc_sum / cfg.ttc_count as f64
        };
        let per_run = |sum: f64| sum / n_runs;
        let after_note = format!("mean over {} runs × scans at t ≥ {} s", sums.runs, s.warmup);
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
                per_run(cfg.false_rate),
                "1/scan",
            )
            .note("confirmed tracks assigned to no truth, per scan, whole run"),
            Row::new(
                format!("{key}_false_track_ids"),
                format!("{label}: false tracks per run"),
                per_run(cfg.false_ids),
                "-",
            )
            .note(format!(
                "distinct confirmed tracks never assigned; of {:.1} tracks seen",
                per_run(cfg.seen)
            )),
            Row::new(
                format!("{key}_breaks"),
                format!("{label}: track breaks per run"),
                per_run(cfg.breaks),
                "-",
            )
            .note(format!("{} targets, {} scans", s.targets, s.scans)),
            Row::new(
                format!("{key}_id_swaps"),
                format!("{label}: id swaps per run"),
                per_run(cfg.id_swaps),
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
            sums.runs, s.targets
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

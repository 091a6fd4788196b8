//! `clutter`'s report: per configuration the filters' RMSE, ANEES and loss rows, the
//! predicted RMSE rows, the sweep series and the RMSE / loss figures.

use super::{ConfigResult, DENSITIES, FILTERS, FilterResult, Predicted, SNRS_DB};
use crate::error::ScenarioError;
use crate::report::{Figure, Line, LineStyle, Report, Row, Series};

/// The report of the configurations' results (`configs[si · DENSITIES.len() + di]` for
/// SNR `si` and density `di`).
///
/// # Errors
/// A missing configuration (a bug, reported).
#[allow(clippy::too_many_lines)]
pub(crate) fn report(configs: &[ConfigResult]) -> Result<Report, ScenarioError> {
    let mut report = Report::default();
    let mut table = Vec::new();
    let mut fig_rmse: Vec<Figure> = Vec::new();
    let mut fig_loss: Vec<Figure> = Vec::new();
    for (si, &snr) in SNRS_DB.iter().enumerate() {
        let mut results = Vec::new();
        for (di, &lam) in DENSITIES.iter().enumerate() {
            let r = configs
                .get(si * DENSITIES.len() + di)
                .cloned()
                .ok_or_else(|| ScenarioError::Degenerate {
                    scenario: "clutter",
                    message: "a configuration without results".into(),
                })?;
            for (name, f) in FILTERS.iter().zip(&r.filters) {
                let key = format!("{name}_{snr:.0}dB_{lam:e}");
                let loss = f.lost as f64 / f.runs.max(1) as f64;
                let inside = f.interval.0 <= f.anees && f.anees <= f.interval.1;
                report.rows.push(
                    Row::new(
                        format!("{key}_rmse"),
                        format!("{name} RMSE, {snr:.0} dB, λ={lam:e}"),
                        f.rmse,
                        "m",
                    )
                    .note(format!(
                        "ANEES {:.2} ({}) in [{:.2}, {:.2}], loss {:.1} %",
                        f.anees,
                        if inside { "inside" } else { "outside" },
                        f.interval.0,
                        f.interval.1,
                        100.0 * loss
                    )),
                );
                table.push(vec![
                    snr,
                    lam,
                    FILTERS.iter().position(|n| n == name).unwrap_or(0) as f64,
                    f.rmse,
                    f.anees,
                    loss,
                    f.metrics.as_ref().map_or(f64::NAN, |m| m.avg_rmse_pos),
                ]);
            }
            for (name, pred, idx) in [
                ("NN", r.predicted_nn, 0usize),
                ("NN-HYCA", r.predicted_hyca, 1),
                ("PDA", r.predicted_pda, 4),
            ] {
                let f = r.filters.get(idx);
                let mc = f.map_or(f64::NAN, |f| f.rmse);
                let loss = f.map_or(f64::NAN, |f| f.lost as f64 / f.runs.max(1) as f64);
                report.rows.push(
                    Row::new(
                        format!("{name}_{snr:.0}dB_{lam:e}_predicted"),
                        format!("{name} predicted RMSE, {snr:.0} dB, λ={lam:e}"),
                        pred.unwrap_or(f64::INFINITY),
                        "m",
                    )
                    .paper_text("off-line prediction")
                    .note(match pred {
                        Some(v) => format!(
                            "Monte Carlo {mc:.2} m ({:+.1} %), loss {:.1} %",
                            100.0 * (v / mc - 1.0),
                            100.0 * loss
                        ),
                        None => format!(
                            "recursion diverges: track loss predicted (Monte Carlo loss {:.1} %)",
                            100.0 * loss
                        ),
                    }),
                );
            }
            results.push((lam, r));
        }
        let mut rmse_lines = Vec::new();
        let mut loss_lines = Vec::new();
        for (i, name) in FILTERS.iter().enumerate() {
            let pts = |f: &dyn Fn(&FilterResult) -> f64| -> Vec<(f64, f64)> {
                results
                    .iter()
                    .filter_map(|(lam, r)| r.filters.get(i).map(|x| (lam.log10(), f(x))))
                    .collect()
            };
            rmse_lines.push(Line {
                label: (*name).into(),
                points: pts(&|x| x.rmse),
                style: LineStyle::Solid,
            });
            loss_lines.push(Line {
                label: (*name).into(),
                points: pts(&|x| x.lost as f64 / x.runs.max(1) as f64),
                style: LineStyle::Solid,
            });
        }
        let pick: [(&str, Predicted); 3] = [
            ("NN predicted", |r| r.predicted_nn),
            ("NN-HYCA predicted", |r| r.predicted_hyca),
            ("PDA predicted", |r| r.predicted_pda),
        ];
        for (label, f) in pick {
            rmse_lines.push(Line {
                label: label.into(),
                points: results
                    .iter()
                    .filter_map(|(lam, r)| f(r).map(|v| (lam.log10(), v)))
                    .collect(),
                style: LineStyle::Points,
            });
        }
        fig_rmse.push(Figure {
            name: format!("clutter_rmse_{snr:.0}db"),
            title: format!("Steady-state position RMSE vs clutter density, {snr:.0} dB"),
            x_label: "log10 clutter density (m⁻²)".into(),
            y_label: "RMSE (m)".into(),
            lines: rmse_lines,
        });
        fig_loss.push(Figure {
            name: format!("clutter_loss_{snr:.0}db"),
            title: format!("Track-loss rate vs clutter density, {snr:.0} dB"),
            x_label: "log10 clutter density (m⁻²)".into(),
            y_label: "track-loss rate".into(),
            lines: loss_lines,
        });
    }
    report.series.push(Series {
        name: "clutter_sweep".into(),
        columns: [
            "snr_db",
            "density",
            "filter",
            "rmse_ss",
            "anees_ss",
            "loss_rate",
            "rmse_warmup_excluded",
        ]
        .iter()
        .map(|s| (*s).to_string())
        .collect(),
        rows: table,
    });
    report.figures.extend(fig_rmse);
    report.figures.extend(fig_loss);
    report.notes.push(format!(
        "filters: 0 NN, 1 NN-HYCA, 2 SN, 3 PSN, 4 PDA; densities {DENSITIES:?} m⁻²; P_D set to p_d at each SNR by the threshold; steady state = second half of the scans over runs that kept the track"
    ));
    Ok(report)
}

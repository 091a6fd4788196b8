//! gimpo's report: the table rows, the per-step series and the figures of seed 000
//! (Figs. 3–7) from the runs' records.

use super::estimate::STARTS;
use super::sums::Sums;
use crate::error::ScenarioError;
use crate::params::Params;
use crate::report::{Figure, Line, LineStyle, Report, Row, Series};

/// Share of the time left out of the RMS (paper §3.4: the first 25 %).
pub(super) const WARMUP: f64 = 0.25;
/// Published / reference values: the independent re-implementation quoted in issue 4
/// (100 runs, p = 0.1, ±5 % clip): final variance ratio from each start.
const REFERENCE_RATIO: [f64; 5] = [0.98, 1.01, 1.03, 1.05, 1.07];

/// The per-step means the series and figures show.
struct Means {
    mu: Vec<[f64; 3]>,
    ratios: Vec<Vec<f64>>,
    vb_r: Vec<Vec<f64>>,
    vb_a: Vec<Vec<f64>>,
    ev_r: Vec<Vec<f64>>,
    ev_a: Vec<Vec<f64>>,
    df_r: Vec<Vec<f64>>,
    df_a: Vec<Vec<f64>>,
    fixed_rms: Vec<Vec<f64>>,
}

impl Means {
    fn new(st: &Sums) -> Self {
        let n_runs = st.n_runs();
        let mean = |v: &Vec<f64>| -> Vec<f64> { v.iter().map(|s| s / n_runs).collect() };
        let axis = |v: &[[Vec<f64>; 2]; 5], c: usize| -> Vec<Vec<f64>> {
            v.iter().map(|a| mean(&a[c])).collect()
        };
        Self {
            mu: st.step_mu.clone(),
            ratios: st.step_multi.iter().map(mean).collect(),
            vb_r: axis(&st.step_vb, 0),
            vb_a: axis(&st.step_vb, 1),
            ev_r: axis(&st.step_ev, 0),
            ev_a: axis(&st.step_ev, 1),
            df_r: axis(&st.step_df, 0),
            df_a: axis(&st.step_df, 1),
            fixed_rms: st
                .step_fixed
                .iter()
                .map(|v| v.iter().map(|s| (s / n_runs).sqrt()).collect())
                .collect(),
        }
    }
}

/// The report of the runs.
///
/// # Errors
/// A parameter that is not declared (a bug, reported).
pub(super) fn report(p: &Params, clip: Option<f64>, st: &Sums) -> Result<Report, ScenarioError> {
    let means = Means::new(st);
    Ok(Report {
        rows: rows(p, clip, st)?,
        series: vec![series(&st.times, &means)],
        figures: figures(st, &means),
        notes: NOTES.iter().map(|n| (*n).to_owned()).collect(),
    })
}

/// Issue 19: the Gibbs (posterior-mean) and the IMM smoother's RMS ratio against the
/// filtered IMM, and both smoothers' ANEES with the 99 % band of the run count.
///
/// # Errors
/// A parameter that is not declared, or a band the chi-square quantile refuses.
fn smoothing_rows(
    p: &Params,
    st: &Sums,
    true_rms: f64,
    rows: &mut Vec<Row>,
) -> Result<(), ScenarioError> {
    let window = format!("t ≥ {:.0} % of the flight", WARMUP * 100.0);
    let gibbs = Sums::rms(st.tail_gibbs);
    let imm = Sums::rms(st.tail_smooth);
    let (block, burn, sweeps) = (
        p.get("gibbs_block")?,
        p.get("gibbs_burn_in")?,
        p.get("gibbs_sweeps")?,
    );
    rows.push(
        Row::new(
            "smooth_rms_ratio",
            "RMS pos. error, Gibbs-smoothed (posterior mean) / filtered IMM (true R)",
            gibbs / true_rms,
            "-",
        )
        .paper_text("issue 19 goal: ≤ 0.6")
        .note(format!(
            "Gibbs smoother of the IMM's jump-Markov model (blocks of {block}, {burn} + {sweeps} sweeps per run): {gibbs:.2} m against {true_rms:.2} m; {window}"
        )),
    );
    rows.push(
        Row::new(
            "imm_smooth_rms_ratio",
            "RMS pos. error, IMM-smoothed / filtered IMM (true R)",
            imm / true_rms,
            "-",
        )
        .paper_text("issue 19 goal: ≤ 0.6")
        .note(format!(
            "fixed-interval IMM smoother (Kim 1994 pairs, backward-likelihood weights): {imm:.2} m against {true_rms:.2} m; {window}"
        )),
    );
    let runs = st.count.max(1);
    let band = argus_core_math::anees_interval(4, runs, 0.99)?;
    let band_text = format!(
        "mean over runs and every step after the start of the NEES of [x, vx, y, vy]; 99 % band of χ²(4n)/n for n = {runs} runs [{:.2}, {:.2}]",
        band.lower, band.upper
    );
    for (key, what, t) in [
        ("smooth_anees", "Gibbs", st.nees_gibbs),
        ("imm_smooth_anees", "IMM", st.nees_smooth),
    ] {
        let a = Sums::mean(t);
        rows.push(
            Row::new(key, format!("ANEES, {what}-smoothed (true R)"), a, "-")
                .paper_text("consistent: inside the 99 % band")
                .note(format!(
                    "{} the band; {band_text}",
                    if band.contains(a) {
                        "inside"
                    } else {
                        "outside"
                    }
                )),
        );
    }
    for (key, v) in [
        ("smooth_anees_lo", band.lower),
        ("smooth_anees_hi", band.upper),
    ] {
        rows.push(Row::new(key, "99 % band of the smoothed ANEES", v, "-").note(band_text.clone()));
    }
    Ok(())
}

/// The table: fixed R, then the multi-IMM, variational, evidence and difference
/// estimators from each start.
fn rows(p: &Params, clip: Option<f64>, st: &Sums) -> Result<Vec<Row>, ScenarioError> {
    let true_rms = Sums::rms(st.tail_fixed[2]);
    let mut rows = Vec::new();
    for (i, f) in STARTS.iter().enumerate() {
        let fixed = Sums::rms(st.tail_fixed[i]);
        rows.push(
            Row::new(
                format!("rms_fixed_{f}"),
                format!("RMS pos. error, fixed R = {f} × truth"),
                fixed,
                "m",
            )
            .paper_text("Fig. 5/7: grows as R departs from truth, faster below")
            .note(format!(
                "{:+.2} % vs true R; t ≥ {:.0} % of the flight",
                100.0 * (fixed / true_rms - 1.0),
                WARMUP * 100.0
            )),
        );
    }
    smoothing_rows(p, st, true_rms, &mut rows)?;
    for (i, f) in STARTS.iter().enumerate() {
        let (m, sd) = st.last_multi[i].mean_sd();
        rows.push(
            Row::new(
                format!("ratio_multi_{f}"),
                format!("multi-IMM final R ratio from {f}"),
                m,
                "-",
            )
            .paper(REFERENCE_RATIO[i])
            .paper_text(format!(
                "paper: within 5 % of 1; re-implementation {}",
                REFERENCE_RATIO[i]
            ))
            .note(format!(
                "per-run sd {sd:.3}; p = {}, clip {:?}",
                p.get("p")?,
                clip
            )),
        );
    }
    for (i, f) in STARTS.iter().enumerate() {
        rows.push(rms_row(
            ("multi", "multi-IMM"),
            *f,
            Sums::rms(st.tail_multi[i]),
            true_rms,
            "paper: within 0.5 % of true R (Fig. 7)",
        ));
    }
    for (estimator, last, tail) in [
        (("vb", "variational"), &st.last_vb, &st.tail_vb),
        (("ev", "evidence"), &st.last_ev, &st.tail_ev),
        (("df", "difference"), &st.last_df, &st.tail_df),
    ] {
        for (i, f) in STARTS.iter().enumerate() {
            for ((axis, sym), ratio) in [("range", "σr²"), ("azimuth", "σθ²")].iter().zip(&last[i])
            {
                let (m, sd) = ratio.mean_sd();
                rows.push(
                    Row::new(
                        format!("ratio_{}_{axis}_{f}", estimator.0),
                        format!("{}: final {sym} ratio from {f}", estimator.1),
                        m,
                        "-",
                    )
                    .paper(1.0)
                    .paper_text("goal: within 3 % (beyond the paper)")
                    .note(format!("per-run sd {sd:.3}")),
                );
            }
            rows.push(rms_row(
                estimator,
                *f,
                Sums::rms(tail[i]),
                true_rms,
                "true-R IMM",
            ));
        }
    }
    Ok(rows)
}

/// The row of an estimator's RMS position error `rms` from the start `f`, against the
/// filtered IMM's with the true R (`true_rms`); `estimator` is its key tag and name.
fn rms_row(estimator: (&str, &str), f: f64, rms: f64, true_rms: f64, paper_text: &str) -> Row {
    let (tag, name) = estimator;
    Row::new(
        format!("rms_{tag}_{f}"),
        format!("RMS pos. error, {name} from {f}"),
        rms,
        "m",
    )
    .paper(true_rms)
    .paper_text(paper_text)
    .note(format!(
        "{:+.2} % vs true R",
        100.0 * (rms / true_rms - 1.0)
    ))
}

/// The per-step series: mode probabilities, the estimators' ratios, the fixed-R RMS.
fn series(times: &[f64], m: &Means) -> Series {
    let per_axis = [
        ("vb", &m.vb_r, &m.vb_a),
        ("ev", &m.ev_r, &m.ev_a),
        ("df", &m.df_r, &m.df_a),
    ];
    let mut columns = vec![
        "t".to_owned(),
        "mu_cv".into(),
        "mu_ct_pos".into(),
        "mu_ct_neg".into(),
    ];
    for f in STARTS {
        columns.push(format!("ratio_multi_{f}"));
    }
    for (tag, _, _) in per_axis {
        for f in STARTS {
            columns.push(format!("ratio_{tag}_range_{f}"));
            columns.push(format!("ratio_{tag}_azimuth_{f}"));
        }
    }
    for f in STARTS {
        columns.push(format!("rms_fixed_{f}"));
    }
    let series_rows = (0..times.len())
        .map(|k| {
            let mut v = vec![times[k]];
            v.extend(m.mu[k]);
            v.extend(m.ratios.iter().map(|r| r[k]));
            for (_, range, azimuth) in per_axis {
                for (r, a) in range.iter().zip(azimuth) {
                    v.push(r[k]);
                    v.push(a[k]);
                }
            }
            v.extend(m.fixed_rms.iter().map(|r| r[k]));
            v
        })
        .collect();
    Series {
        name: "per_step".into(),
        columns,
        rows: series_rows,
    }
}

/// `(t, y)` at each step's time.
fn points(times: &[f64], ys: &[f64]) -> Vec<(f64, f64)> {
    times.iter().zip(ys).map(|(t, y)| (*t, *y)).collect()
}

/// One line per start of the per-step means `means` (one series per start), labelled
/// `label(f)` for the start `f`.
fn per_start<'a>(
    times: &'a [f64],
    means: &'a [Vec<f64>],
    style: LineStyle,
    label: impl Fn(f64) -> String + 'a,
) -> impl Iterator<Item = Line> + 'a {
    STARTS.iter().zip(means).map(move |(f, r)| Line {
        label: label(*f),
        points: points(times, r),
        style,
    })
}

/// Fig. 6 of a per-axis estimator (`what`: `evidence`, `difference`): its σr² and σθ²
/// ratios `range` and `azimuth` from each start, means of `nr` runs.
fn axis_ratio_figure(
    name: &str,
    what: &str,
    times: &[f64],
    (range, azimuth): (&[Vec<f64>], &[Vec<f64>]),
    nr: usize,
) -> Figure {
    Figure {
        name: name.into(),
        title: format!(
            "gimpo: {what} estimator, estimated / true variance per axis, mean of {nr} runs"
        ),
        x_label: "time (s)".into(),
        y_label: "variance ratio".into(),
        lines: per_start(times, range, LineStyle::Solid, |f| format!("σr² from {f}"))
            .chain(per_start(times, azimuth, LineStyle::Bound, |f| {
                format!("σθ² from {f}")
            }))
            .collect(),
    }
}

/// Figs. 3–7.
fn figures(st: &Sums, m: &Means) -> Vec<Figure> {
    let times = &st.times;
    let track = &st.track;
    let nr = st.count;
    vec![
        Figure {
            name: "fig3_trajectory".into(),
            title: "gimpo: truth, plots and multi-IMM estimate (run 0, start 1)".into(),
            x_label: "x (m)".into(),
            y_label: "y (m)".into(),
            lines: [
                ("true", 0, LineStyle::Solid),
                ("plots (converted)", 2, LineStyle::Points),
                ("estimate", 4, LineStyle::Solid),
            ]
            .into_iter()
            .map(|(label, c, style)| Line {
                label: label.into(),
                points: track.iter().map(|v| (v[c], v[c + 1])).collect(),
                style,
            })
            .collect(),
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
                    points: times.iter().zip(&m.mu).map(|(t, m)| (*t, m[j])).collect(),
                    style: LineStyle::Solid,
                })
                .collect(),
        },
        Figure {
            name: "fig5_rms_fixed_r".into(),
            title: format!("gimpo: RMS position error with fixed R ({nr} runs)"),
            x_label: "time (s)".into(),
            y_label: "RMS position error (m)".into(),
            lines: per_start(times, &m.fixed_rms, LineStyle::Solid, |f| {
                format!("R = {f} × truth")
            })
            .collect(),
        },
        Figure {
            name: "fig6_ratio".into(),
            title: format!("gimpo: estimated / true noise variance, mean of {nr} runs"),
            x_label: "time (s)".into(),
            y_label: "variance ratio".into(),
            lines: per_start(times, &m.ratios, LineStyle::Solid, |f| {
                format!("multi-IMM from {f}")
            })
            .chain(per_start(times, &m.vb_a, LineStyle::Bound, |f| {
                format!("variational σθ² from {f}")
            }))
            .chain(per_start(times, &m.ev_a, LineStyle::Points, |f| {
                format!("evidence σθ² from {f}")
            }))
            .collect(),
        },
        axis_ratio_figure(
            "fig6_evidence_ratio",
            "evidence",
            times,
            (&m.ev_r, &m.ev_a),
            nr,
        ),
        axis_ratio_figure(
            "fig6_difference_ratio",
            "difference",
            times,
            (&m.df_r, &m.df_a),
            nr,
        ),
        Figure {
            name: "fig7_rms_vs_r".into(),
            title: format!("gimpo: RMS position error (t ≥ 25 %) vs R factor ({nr} runs)"),
            x_label: "R factor (fixed, or initial)".into(),
            y_label: "RMS position error (m)".into(),
            lines: [
                ("static R", &st.tail_fixed),
                ("dynamic R (multi-IMM)", &st.tail_multi),
                ("dynamic R (variational)", &st.tail_vb),
                ("dynamic R (evidence)", &st.tail_ev),
                ("dynamic R (difference)", &st.tail_df),
            ]
            .into_iter()
            .map(|(label, tail)| Line {
                label: label.into(),
                points: STARTS
                    .iter()
                    .zip(tail)
                    .map(|(f, t)| (*f, Sums::rms(*t)))
                    .collect(),
                style: LineStyle::Solid,
            })
            .collect(),
        },
    ]
}

/// The notes under the table.
const NOTES: [&str; 7] = [
    "multi-IMM: seed 000 eqs (8)-(14), likelihood with |2πS|^-1/2 (the paper's eq 5/9 misprint corrected)",
    "reference ratios are an independent re-implementation's (issue 4), not read off the paper's Fig. 6",
    "the paper's rule estimates one common scale of R (range and azimuth ratios are identical)",
    "variational: one IMM + inverse-gamma recursion on polar post-fit residuals, range and azimuth separately",
    "evidence: five IMMs (anchor, ±h in range, ±h in azimuth); per axis the observed score of each step's fitted log-likelihood curve with the expected information ½w², accumulated over the track; post-fit read-out once settled",
    "evidence: range meets the 3 % goal, azimuth does NOT (≈ +6 %: the turns no mode matches inflate cross-range innovations; docs/papers/000-gimpo.md)",
    "difference: one IMM under variances estimated from third differences of the raw plots (they cancel any locally quadratic truth, so their expectation is the noise whatever the IMM's models); the start stays only in the prior's 2 pseudo-differences",
];

//! A scenario's [`Report`] on the command's side: the table as aligned text, and the
//! output directory (`summary.json`, one CSV per series, one SVG and one PNG per figure).

use std::collections::BTreeMap;
use std::path::Path;

use argus_io::output::{csv_text, write_atomic};
use argus_scenarios::{Report, Row};
use serde::Serialize;

use crate::error::CliError;
use crate::render;

/// The document written as `summary.json`.
#[derive(Debug, Serialize)]
struct Summary<'a> {
    scenario: &'a str,
    seed: u64,
    runs: [u64; 2],
    params: &'a BTreeMap<String, f64>,
    results: BTreeMap<&'a str, &'a Row>,
    notes: &'a [String],
    files: Vec<String>,
}

/// What the run was, for the summary.
#[derive(Debug, Clone)]
pub(crate) struct RunInfo<'a> {
    /// Scenario name.
    pub(crate) scenario: &'a str,
    /// Base seed.
    pub(crate) seed: u64,
    /// Run indices `start..end`.
    pub(crate) runs: std::ops::Range<u64>,
    /// Parameters in effect.
    pub(crate) params: &'a BTreeMap<String, f64>,
    /// Files already written beside the report (e.g. the per-run file), listed in the
    /// summary's `files`.
    pub(crate) extra_files: &'a [String],
}

fn fmt_num(v: f64) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    let a = v.abs();
    if a != 0.0 && !(1e-3..1e6).contains(&a) {
        format!("{v:.4e}")
    } else {
        format!("{v:.4}")
    }
}

/// The table as aligned text: quantity | paper | ours | unit | note.
#[must_use]
pub(crate) fn table_text(report: &Report) -> String {
    let mut cells: Vec<[String; 5]> = vec![[
        "quantity".into(),
        "paper".into(),
        "ours".into(),
        "unit".into(),
        "note".into(),
    ]];
    for r in &report.rows {
        let paper = match (&r.paper, &r.paper_text) {
            (Some(v), Some(t)) => format!("{} ({t})", fmt_num(*v)),
            (Some(v), None) => fmt_num(*v),
            (None, Some(t)) => t.clone(),
            (None, None) => "-".into(),
        };
        cells.push([
            r.quantity.clone(),
            paper,
            fmt_num(r.ours),
            r.unit.clone(),
            r.note.clone(),
        ]);
    }
    let mut widths = [0usize; 5];
    for c in &cells {
        for (w, s) in widths.iter_mut().zip(c.iter()) {
            *w = (*w).max(s.chars().count());
        }
    }
    let mut out = String::new();
    for (i, c) in cells.iter().enumerate() {
        let line: Vec<String> = c
            .iter()
            .zip(widths.iter())
            .map(|(s, w)| format!("{s:<w$}"))
            .collect();
        out.push_str(line.join(" | ").trim_end());
        out.push('\n');
        if i == 0 {
            let rule: Vec<String> = widths.iter().map(|w| "-".repeat(*w)).collect();
            out.push_str(&rule.join("-|-"));
            out.push('\n');
        }
    }
    for n in &report.notes {
        out.push_str(&format!("note: {n}\n"));
    }
    out
}

/// Writes `summary.json`, one CSV per series and one SVG and one PNG per figure into `dir`, each
/// atomically. Returns the paths written.
///
/// # Errors
/// [`CliError::Io`] or [`CliError::Plot`].
pub(crate) fn write(
    report: &Report,
    dir: &Path,
    info: &RunInfo<'_>,
) -> Result<Vec<String>, CliError> {
    let mut files = Vec::new();
    for s in &report.series {
        let path = dir.join(format!("{}.csv", s.name));
        write_atomic(&path, csv_text(&s.columns, &s.rows).as_bytes())?;
        files.push(path.display().to_string());
    }
    for f in &report.figures {
        let path = dir.join(format!("{}.svg", f.name));
        let svg = render::svg(f).map_err(|message| CliError::Plot {
            file: path.clone(),
            message,
        })?;
        write_atomic(&path, svg.as_bytes())?;
        files.push(path.display().to_string());
        let path = dir.join(format!("{}.png", f.name));
        let png = render::png(f).map_err(|message| CliError::Plot {
            file: path.clone(),
            message,
        })?;
        write_atomic(&path, &png)?;
        files.push(path.display().to_string());
    }
    let summary = Summary {
        scenario: info.scenario,
        seed: info.seed,
        runs: [info.runs.start, info.runs.end],
        params: info.params,
        results: report.rows.iter().map(|r| (r.key.as_str(), r)).collect(),
        notes: &report.notes,
        files: files.iter().chain(info.extra_files).cloned().collect(),
    };
    let path = dir.join("summary.json");
    let json = serde_json::to_string_pretty(&summary)
        .map_err(|e| CliError::io(&path, std::io::Error::other(e.to_string())))?;
    write_atomic(&path, json.as_bytes())?;
    files.push(path.display().to_string());
    Ok(files)
}

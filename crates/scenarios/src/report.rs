//! A scenario's results as data: a table, per-time series and figures, written to the
//! output directory by [`Report::write`] and printed by [`Report::table_text`].

use std::collections::BTreeMap;
use std::path::Path;

use serde::Serialize;

use crate::error::CliError;
use crate::output::{csv_text, write_atomic};
use crate::render;

/// One row of the results table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub(crate) struct Row {
    /// Machine name, the key in `summary.json` (`snake_case`).
    pub(crate) key: String,
    /// Human name of the quantity.
    pub(crate) quantity: String,
    /// The paper's published number, when there is one.
    pub(crate) paper: Option<f64>,
    /// The paper's claim in words, when it gives no number (or in addition to it).
    pub(crate) paper_text: Option<String>,
    /// Our number.
    pub(crate) ours: f64,
    /// Unit (`m`, `m/s`, `-`).
    pub(crate) unit: String,
    /// A note (what it is averaged over, the interval it should fall in …).
    pub(crate) note: String,
}

impl Row {
    /// A row with our number only; add the paper's number, its claim in words and a note with
    /// [`Row::paper`], [`Row::paper_text`] and [`Row::note`].
    pub(crate) fn new(
        key: impl Into<String>,
        quantity: impl Into<String>,
        ours: f64,
        unit: &str,
    ) -> Self {
        Self {
            key: key.into(),
            quantity: quantity.into(),
            paper: None,
            paper_text: None,
            ours,
            unit: unit.into(),
            note: String::new(),
        }
    }

    /// The paper's published number (`None` keeps it absent).
    #[must_use]
    pub(crate) fn paper(mut self, value: impl Into<Option<f64>>) -> Self {
        self.paper = value.into();
        self
    }

    /// The paper's claim in words.
    #[must_use]
    pub(crate) fn paper_text(mut self, text: impl Into<String>) -> Self {
        self.paper_text = Some(text.into());
        self
    }

    /// A note (what the number is averaged over, the interval it should fall in …).
    #[must_use]
    pub(crate) fn note(mut self, note: impl Into<String>) -> Self {
        self.note = note.into();
        self
    }

    /// A row whose paper reference, if any, is a claim in words (no published number).
    pub(crate) fn with_text(
        key: String,
        quantity: String,
        paper_text: Option<&str>,
        ours: f64,
        unit: &str,
        note: &str,
    ) -> Self {
        Self {
            key,
            quantity,
            paper: None,
            paper_text: paper_text.map(str::to_owned),
            ours,
            unit: unit.into(),
            note: note.into(),
        }
    }
}

/// A named table of numbers over time, written as `<name>.csv`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Series {
    /// File stem.
    pub(crate) name: String,
    /// Column names (first usually `t`).
    pub(crate) columns: Vec<String>,
    /// Rows of values, one per time.
    pub(crate) rows: Vec<Vec<f64>>,
}

/// How a line is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum LineStyle {
    /// A solid line.
    Solid,
    /// A thin line for bounds (drawn lighter).
    Bound,
    /// Points only.
    Points,
}

/// One line of a figure.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Line {
    /// Legend text.
    pub(crate) label: String,
    /// `(x, y)` points.
    pub(crate) points: Vec<(f64, f64)>,
    /// Style.
    pub(crate) style: LineStyle,
}

/// A figure described as data; [`render`] draws it.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Figure {
    /// File stem (`<name>.svg`).
    pub(crate) name: String,
    /// Title.
    pub(crate) title: String,
    /// x-axis label with unit, e.g. `time (s)`.
    pub(crate) x_label: String,
    /// y-axis label with unit.
    pub(crate) y_label: String,
    /// The lines.
    pub(crate) lines: Vec<Line>,
}

/// A scenario's results.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct Report {
    /// Table rows, in print order.
    pub(crate) rows: Vec<Row>,
    /// Per-time series.
    pub(crate) series: Vec<Series>,
    /// Figures.
    pub(crate) figures: Vec<Figure>,
    /// Free notes printed under the table.
    pub(crate) notes: Vec<String>,
}

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

impl Report {
    /// The table as aligned text: quantity | paper | ours | unit | note.
    #[must_use]
    pub(crate) fn table_text(&self) -> String {
        let mut cells: Vec<[String; 5]> = vec![[
            "quantity".into(),
            "paper".into(),
            "ours".into(),
            "unit".into(),
            "note".into(),
        ]];
        for r in &self.rows {
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
        for n in &self.notes {
            out.push_str(&format!("note: {n}\n"));
        }
        out
    }

    /// Writes `summary.json`, one CSV per series and one SVG and one PNG per figure into `dir`, each
    /// atomically. Returns the paths written.
    ///
    /// # Errors
    /// [`CliError::Io`] or [`CliError::Plot`].
    pub(crate) fn write(&self, dir: &Path, info: &RunInfo<'_>) -> Result<Vec<String>, CliError> {
        let mut files = Vec::new();
        for s in &self.series {
            let path = dir.join(format!("{}.csv", s.name));
            write_atomic(&path, csv_text(&s.columns, &s.rows).as_bytes())?;
            files.push(path.display().to_string());
        }
        for f in &self.figures {
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
            results: self.rows.iter().map(|r| (r.key.as_str(), r)).collect(),
            notes: &self.notes,
            files: files.iter().chain(info.extra_files).cloned().collect(),
        };
        let path = dir.join("summary.json");
        let json = serde_json::to_string_pretty(&summary)
            .map_err(|e| CliError::io(&path, std::io::Error::other(e.to_string())))?;
        write_atomic(&path, json.as_bytes())?;
        files.push(path.display().to_string());
        Ok(files)
    }
}

//! A scenario's results as data: table rows, per-time series, figures described as data
//! and notes. The command prints the table, writes `summary.json` and the series' CSV,
//! and draws the figures.

use serde::Serialize;

/// One row of the results table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    /// Machine name, the key in `summary.json` (`snake_case`).
    pub key: String,
    /// Human name of the quantity.
    pub quantity: String,
    /// The paper's published number, when there is one.
    pub paper: Option<f64>,
    /// The paper's claim in words, when it gives no number (or in addition to it).
    pub paper_text: Option<String>,
    /// Our number.
    pub ours: f64,
    /// Unit (`m`, `m/s`, `-`).
    pub unit: String,
    /// A note (what it is averaged over, the interval it should fall in …).
    pub note: String,
}

impl Row {
    /// A row with our number only; add the paper's number, its claim in words and a note with
    /// [`Row::paper`], [`Row::paper_text`] and [`Row::note`].
    pub fn new(key: impl Into<String>, quantity: impl Into<String>, ours: f64, unit: &str) -> Self {
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
    pub fn paper(mut self, value: impl Into<Option<f64>>) -> Self {
        self.paper = value.into();
        self
    }

    /// The paper's claim in words.
    #[must_use]
    pub fn paper_text(mut self, text: impl Into<String>) -> Self {
        self.paper_text = Some(text.into());
        self
    }

    /// A note (what the number is averaged over, the interval it should fall in …).
    #[must_use]
    pub fn note(mut self, note: impl Into<String>) -> Self {
        self.note = note.into();
        self
    }

    /// A row whose paper reference, if any, is a claim in words (no published number).
    pub fn with_text(
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
pub struct Series {
    /// File stem.
    pub name: String,
    /// Column names (first usually `t`).
    pub columns: Vec<String>,
    /// Rows of values, one per time.
    pub rows: Vec<Vec<f64>>,
}

/// How a line is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LineStyle {
    /// A solid line.
    Solid,
    /// A thin line for bounds (drawn lighter).
    Bound,
    /// Points only.
    Points,
}

/// One line of a figure.
#[derive(Debug, Clone, PartialEq)]
pub struct Line {
    /// Legend text.
    pub label: String,
    /// `(x, y)` points.
    pub points: Vec<(f64, f64)>,
    /// Style.
    pub style: LineStyle,
}

/// A figure described as data (the command draws it).
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// File stem (`<name>.svg`).
    pub name: String,
    /// Title.
    pub title: String,
    /// x-axis label with unit, e.g. `time (s)`.
    pub x_label: String,
    /// y-axis label with unit.
    pub y_label: String,
    /// The lines.
    pub lines: Vec<Line>,
}

/// A scenario's results.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Report {
    /// Table rows, in print order.
    pub rows: Vec<Row>,
    /// Per-time series.
    pub series: Vec<Series>,
    /// Figures.
    pub figures: Vec<Figure>,
    /// Free notes printed under the table.
    pub notes: Vec<String>,
}

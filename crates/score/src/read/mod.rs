//! Readers for the two files scored: a truth CSV and a tracks CSV.
//!
//! - Truth: columns `t,target,x,vx,y,vy` (the layout `argus simulate` writes; its `z,vz` and
//!   any other column are ignored), one row per aircraft per sample, each aircraft's rows at
//!   strictly increasing times (aircraft may interleave).
//! - Tracks: columns `t,track,x,vx,y,vy` and, when present, `status` (`tentative`,
//!   `confirmed` or `deleted`; only `confirmed` rows are scored). A file without `status`
//!   (a single-target `argus track` file, or another tracker's) has every row confirmed.
//!   Other columns (`sensor`, `reason`, `sigma_x`, `mu_1`, …) are ignored. Each track's
//!   rows at non-decreasing times.
//!
//! Names (`target`, `track`) are kept as text, so ICAO addresses and other trackers'
//! labels work as well as Argus's integers. Every malformed field is reported as
//! `file:line: field 'name': what`.

mod table;

use std::collections::HashMap;
use std::io::Read;
use std::path::Path;

pub use table::{Cell, Column};
use table::{Columns, Csv, Source, Table};

use crate::error::ScoreError;
use crate::input::{TrackHistory, TrackRow, TruthPath, TruthSample};

/// The truth table's columns.
const TRUTH: [&str; 6] = ["t", "target", "x", "vx", "y", "vy"];
/// The tracks table's required columns, then its optional one.
const TRACKS: [&str; 6] = ["t", "track", "x", "vx", "y", "vy"];
const TRACKS_OPTIONAL: [&str; 1] = ["status"];

/// Reads a truth CSV file.
///
/// # Errors
/// [`ScoreError::Io`] when the file cannot be opened, otherwise as [`read_truth_from`].
pub fn read_truth(path: &Path) -> Result<Vec<TruthPath>, ScoreError> {
    let file = open(path)?;
    read_truth_from(file, &path.display().to_string())
}

/// Reads truth CSV text from `reader`; `file` names it in errors.
///
/// # Errors
/// [`ScoreError::MissingColumn`], [`ScoreError::Syntax`], [`ScoreError::Field`] (a number
/// that does not parse or is not finite, an empty name, a sample not after the same
/// aircraft's previous one) and [`ScoreError::NoTruth`] for a file without rows.
pub fn read_truth_from(reader: impl Read, file: &str) -> Result<Vec<TruthPath>, ScoreError> {
    truth(Table::new(Csv::new(reader, file)?, file, &TRUTH, &[])?)
}

/// Reads a truth table given as columns (`names[i]` names `columns[i]`; a DataFrame's, a
/// structured array's), with the checks and errors of [`read_truth_from`]: row `i` is
/// reported as `file:LINE` with `LINE = i + 2`, as if the table were a CSV file.
///
/// # Errors
/// As [`read_truth_from`]; [`ScoreError::Syntax`] for columns of different lengths.
pub fn read_truth_columns(
    names: &[String],
    columns: &[Column<'_>],
    file: &str,
) -> Result<Vec<TruthPath>, ScoreError> {
    truth(Table::new(
        Columns::new(names, columns, file)?,
        file,
        &TRUTH,
        &[],
    )?)
}

fn truth<S: Source>(mut table: Table<'_, S>) -> Result<Vec<TruthPath>, ScoreError> {
    let file = table.file();
    let mut groups = Groups::default();
    while let Some(line) = table.next_row()? {
        let t = table.number(0)?;
        let name = table.name(1)?;
        let sample = TruthSample {
            t,
            x: table.number(2)?,
            vx: table.number(3)?,
            y: table.number(4)?,
            vy: table.number(5)?,
        };
        let prev = groups.push(&name, t, line, sample);
        if let Some((pt, pl)) = prev
            && t <= pt
        {
            return Err(table.field_error(
                0,
                format!(
                    "time {t} is not after target {name}'s previous sample at {pt} (line {pl})"
                ),
            ));
        }
    }
    if groups.items.is_empty() {
        return Err(ScoreError::NoTruth {
            file: file.to_string(),
        });
    }
    groups
        .items
        .into_iter()
        .map(|(name, samples)| TruthPath::new(name, samples))
        .collect()
}

/// Reads a tracks CSV file.
///
/// # Errors
/// [`ScoreError::Io`] when the file cannot be opened, otherwise as [`read_tracks_from`].
pub fn read_tracks(path: &Path) -> Result<Vec<TrackHistory>, ScoreError> {
    let file = open(path)?;
    read_tracks_from(file, &path.display().to_string())
}

/// Reads tracks CSV text from `reader`; `file` names it in errors. A file with a header
/// and no row has no track (every truth is then missed).
///
/// # Errors
/// [`ScoreError::MissingColumn`], [`ScoreError::Syntax`], [`ScoreError::Field`] (a number
/// that does not parse or is not finite, an empty name, an unknown status, a row before
/// the same track's previous one).
pub fn read_tracks_from(reader: impl Read, file: &str) -> Result<Vec<TrackHistory>, ScoreError> {
    tracks(Table::new(
        Csv::new(reader, file)?,
        file,
        &TRACKS,
        &TRACKS_OPTIONAL,
    )?)
}

/// Reads a tracks table given as columns, with the checks and errors of
/// [`read_tracks_from`] (row `i` at `file:LINE`, `LINE = i + 2`, as
/// [`read_truth_columns`]).
///
/// # Errors
/// As [`read_tracks_from`]; [`ScoreError::Syntax`] for columns of different lengths.
pub fn read_tracks_columns(
    names: &[String],
    columns: &[Column<'_>],
    file: &str,
) -> Result<Vec<TrackHistory>, ScoreError> {
    tracks(Table::new(
        Columns::new(names, columns, file)?,
        file,
        &TRACKS,
        &TRACKS_OPTIONAL,
    )?)
}

fn tracks<S: Source>(mut table: Table<'_, S>) -> Result<Vec<TrackHistory>, ScoreError> {
    let mut groups = Groups::default();
    while let Some(line) = table.next_row()? {
        let t = table.number(0)?;
        let name = table.name(1)?;
        let confirmed = match table.optional(6).as_deref() {
            None => true,
            Some("confirmed") => true,
            Some("tentative" | "deleted") => false,
            Some(other) => {
                let msg = format!("'{other}' is not a status (tentative, confirmed or deleted)");
                return Err(table.field_error(6, msg));
            }
        };
        let row = TrackRow {
            t,
            confirmed,
            x: table.number(2)?,
            vx: table.number(3)?,
            y: table.number(4)?,
            vy: table.number(5)?,
        };
        let prev = groups.push(&name, t, line, row);
        if let Some((pt, pl)) = prev
            && t < pt
        {
            return Err(table.field_error(
                0,
                format!("time {t} is before track {name}'s previous row at {pt} (line {pl})"),
            ));
        }
    }
    groups
        .items
        .into_iter()
        .map(|(name, rows)| TrackHistory::new(name, rows))
        .collect()
}

fn open(path: &Path) -> Result<std::fs::File, ScoreError> {
    std::fs::File::open(path).map_err(|source| ScoreError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Rows grouped by name in order of first appearance, with each group's last time and
/// line.
struct Groups<T> {
    index: HashMap<String, usize>,
    last: Vec<(f64, u64)>,
    items: Vec<(String, Vec<T>)>,
}

impl<T> Default for Groups<T> {
    fn default() -> Self {
        Self {
            index: HashMap::new(),
            last: Vec::new(),
            items: Vec::new(),
        }
    }
}

impl<T> Groups<T> {
    /// Adds `item` to `name`'s group; returns the group's previous (time, line), if any.
    fn push(&mut self, name: &str, t: f64, line: u64, item: T) -> Option<(f64, u64)> {
        if let Some(&i) = self.index.get(name) {
            let prev = self.last[i];
            self.last[i] = (t, line);
            self.items[i].1.push(item);
            Some(prev)
        } else {
            let i = self.items.len();
            self.index.insert(name.to_string(), i);
            self.last.push((t, line));
            self.items.push((name.to_string(), vec![item]));
            None
        }
    }
}

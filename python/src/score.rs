//! Track scoring from Python (`score_tracks()`): `argus-score` on a tracks table and a
//! truth table (files, or the columns of a DataFrame / structured array / dict), returning the report `argus score` writes, as JSON text.

use std::path::Path;

use argus_score::{ScoreConfig, ScoreError, Scorer, read_tracks, read_tracks_columns};
use argus_score::{read_truth, read_truth_columns};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::{Kind, input, raise, rust_name};
use crate::track::Owned;

/// A scoring error as the package's exception: a file that cannot be read as
/// `ArgusOSError`, everything else (a malformed row, a bad parameter) as
/// `InvalidInputError`.
fn score_error(e: &ScoreError) -> PyErr {
    let kind = match e {
        ScoreError::Io { .. } => Kind::Io,
        _ => Kind::InvalidInput,
    };
    raise(kind, &rust_name("ScoreError", e), e.to_string())
}

/// One table: `("path", path)` or `("columns", names, columns, name)` (columns as
/// `track_columns` takes them), read by `argus_score`'s readers (their checks and errors,
/// `name:LINE: field 'f'`, row `i` being line `i + 2`).
enum Table {
    Path(std::path::PathBuf),
    Columns(Vec<String>, Vec<Owned>, String),
}

impl Table {
    fn from_py(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Self> {
        let (kind, value): (String, Bound<'_, PyAny>) = obj
            .get_item(0)
            .and_then(|k| Ok((k.extract()?, obj.get_item(1)?)))?;
        match kind.as_str() {
            "path" => Ok(Self::Path(value.extract()?)),
            "columns" => {
                let names: Vec<String> = value.extract()?;
                let columns: Vec<Bound<'_, PyAny>> = obj.get_item(2)?.extract()?;
                let columns: Vec<Owned> = columns
                    .iter()
                    .map(Owned::from_py)
                    .collect::<PyResult<_>>()?;
                Ok(Self::Columns(names, columns, obj.get_item(3)?.extract()?))
            }
            other => Err(input(format!(
                "argument '{what}': unknown table kind {other:?}"
            ))),
        }
    }
}

/// An optional float of `config` (`None` when absent or `None`), named in errors.
fn opt(config: &Bound<'_, PyDict>, key: &str) -> PyResult<Option<f64>> {
    match config.get_item(key)? {
        Some(v) if !v.is_none() => v
            .extract::<f64>()
            .map(Some)
            .map_err(|_| input(format!("argument '{key}': a number is needed, got {v}"))),
        _ => Ok(None),
    }
}

/// The scoring parameters from `config` (the keys of [`ScoreConfig`]; others rejected),
/// defaults for the absent ones.
fn config_from(config: &Bound<'_, PyDict>) -> PyResult<ScoreConfig> {
    const KEYS: [&str; 8] = [
        "step",
        "start",
        "end",
        "assign_cutoff",
        "max_track_age",
        "max_truth_gap",
        "gospa_cutoff",
        "gospa_order",
    ];
    for key in config.keys() {
        let key: String = key.extract()?;
        if !KEYS.contains(&key.as_str()) {
            return Err(input(format!(
                "unknown scoring parameter {key:?} (expected one of {})",
                KEYS.join(", ")
            )));
        }
    }
    let d = ScoreConfig::default();
    Ok(ScoreConfig {
        step: opt(config, "step")?.unwrap_or(d.step),
        start: opt(config, "start")?,
        end: opt(config, "end")?,
        assign_cutoff: opt(config, "assign_cutoff")?.unwrap_or(d.assign_cutoff),
        max_track_age: opt(config, "max_track_age")?.unwrap_or(d.max_track_age),
        max_truth_gap: opt(config, "max_truth_gap")?.unwrap_or(d.max_truth_gap),
        gospa_cutoff: opt(config, "gospa_cutoff")?.unwrap_or(d.gospa_cutoff),
        gospa_order: opt(config, "gospa_order")?.unwrap_or(d.gospa_order),
    })
}

/// Scores `tracks` against `truth` (each `("path", p)` or `("columns", names, columns,
/// name)`) with the
/// parameters in `config`; returns the report as JSON text (the content of `argus score
/// --out`). The GIL is released while scoring.
#[pyfunction]
pub(crate) fn score_json(
    py: Python<'_>,
    tracks: &Bound<'_, PyAny>,
    truth: &Bound<'_, PyAny>,
    config: &Bound<'_, PyDict>,
) -> PyResult<String> {
    let tracks = Table::from_py(tracks, "tracks")?;
    let truth = Table::from_py(truth, "truth")?;
    let config = config_from(config)?;
    py.detach(|| {
        let tracks = match &tracks {
            Table::Path(p) => read_tracks(Path::new(p))?,
            Table::Columns(names, c, name) => read_tracks_columns(
                names,
                &c.iter().map(Owned::column).collect::<Vec<_>>(),
                name,
            )?,
        };
        let truth = match &truth {
            Table::Path(p) => read_truth(Path::new(p))?,
            Table::Columns(names, c, name) => read_truth_columns(
                names,
                &c.iter().map(Owned::column).collect::<Vec<_>>(),
                name,
            )?,
        };
        Scorer::new(config)?.score(&tracks, &truth)
    })
    .map_err(|e| score_error(&e))
    .and_then(|score| {
        serde_json::to_string(&score)
            .map_err(|e| raise(Kind::Numerical, "serde_json::Error", e.to_string()))
    })
}

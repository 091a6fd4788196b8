//! `argus track` from Python: the command's own pipeline on a plot table given as columns
//! (used by `track()`), its multi-target tracker as a stream (used by `Tracker`), and a
//! configuration given as TOML text, a path or a dict. Plots and configuration are
//! checked here (`argus_io::plotfile::from_columns`, `argus_config::load_text`) and
//! handed to the runner by [`crate::track_run`]; the tracks come back as columns.

use std::path::{Path, PathBuf};

use argus_config::{ConfigError, Loaded};
use argus_filters::Lag;
use argus_io::plotfile::{self, Column, FilePlot};
use argus_io::rows::ColumnValues;
use argus_tracker::smooth::Smoothing;
use numpy::{IntoPyArray, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::errors::{Kind, input, raise, rust_name};
use crate::track_run::{self, Columns, PLOTS, io_error};

/// A configuration error as the package's exception (`ArgusOSError` for a file that
/// cannot be read, `InvalidInputError` otherwise).
fn config_error(e: &ConfigError) -> PyErr {
    let kind = match e {
        ConfigError::Io { .. } => Kind::Io,
        _ => Kind::InvalidInput,
    };
    raise(kind, &rust_name("ConfigError", e), e.to_string())
}

/// A configuration: the name of its file in errors (`config.toml` for text and dicts),
/// and the configuration loaded.
struct Config {
    name: PathBuf,
    loaded: Loaded,
}

/// The configuration given as `kind` `"text"` (TOML text), `"path"` (a file, read here)
/// or `"json"` (a dict as JSON text, turned into TOML).
fn config(kind: &str, value: &str) -> PyResult<Config> {
    let name = PathBuf::from(if kind == "path" { value } else { "config.toml" });
    let loaded = match kind {
        "path" => argus_config::load(&name),
        "text" => argus_config::load_text(value, &name),
        "json" => argus_config::load_text(&toml_from_json(value)?, &name),
        other => return Err(input(format!("argument 'config': unknown kind {other:?}"))),
    }
    .map_err(|e| config_error(&e))?;
    Ok(Config { name, loaded })
}

/// A table column's values, owned (from a float64 / int64 array or a list of str).
pub(crate) enum Owned {
    Float(Vec<f64>),
    Int(Vec<i64>),
    Text(Vec<String>),
}

impl Owned {
    pub(crate) fn from_py(obj: &Bound<'_, PyAny>) -> PyResult<Self> {
        if let Ok(a) = obj.extract::<PyReadonlyArray1<'_, f64>>() {
            return Ok(Self::Float(a.as_array().to_vec()));
        }
        if let Ok(a) = obj.extract::<PyReadonlyArray1<'_, i64>>() {
            return Ok(Self::Int(a.as_array().to_vec()));
        }
        obj.extract::<Vec<String>>().map(Self::Text).map_err(|_| {
            input(
                "argument 'plots': a column must be a 1-D float64 or int64 array or a list of str",
            )
        })
    }

    pub(crate) fn column(&self) -> Column<'_> {
        match self {
            Self::Float(v) => Column::Float(v),
            Self::Int(v) => Column::Int(v),
            Self::Text(v) => Column::Text(v),
        }
    }
}

/// The plots of the table with columns `names` / `columns`, checked as a plot file
/// (`plots:LINE: field 'f'` in errors).
fn plots(names: &[String], columns: &[Bound<'_, PyAny>]) -> PyResult<Vec<FilePlot>> {
    let owned: Vec<Owned> = columns
        .iter()
        .map(Owned::from_py)
        .collect::<PyResult<_>>()?;
    let cols: Vec<Column<'_>> = owned.iter().map(Owned::column).collect();
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    plotfile::from_columns(&names, &cols, Path::new(PLOTS)).map_err(|e| io_error(&e))
}

/// The tracks columns as a dict of numpy arrays (float64, int64) and lists of str.
fn columns_dict<'py>(py: Python<'py>, columns: Columns) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (name, values) in columns {
        match values {
            ColumnValues::F64(v) => d.set_item(name, v.into_pyarray(py))?,
            ColumnValues::I64(v) => d.set_item(name, v.into_pyarray(py))?,
            ColumnValues::Text(v) => d.set_item(name, PyList::new(py, v)?)?,
        }
    }
    Ok(d)
}

/// A JSON value as Python objects (through the `json` module).
fn py_json<'py>(py: Python<'py>, value: &serde_json::Value) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?
        .call_method1("loads", (value.to_string(),))
}

/// The smoothing flags: `smooth` is `--smooth`, `smooth_lag` `--smooth-lag N`,
/// `smooth_lag_seconds` `--smooth-lag-seconds S` (at most one).
fn smoothing(
    smooth: bool,
    smooth_lag: Option<usize>,
    smooth_lag_seconds: Option<f64>,
) -> PyResult<Option<Smoothing>> {
    match (smooth, smooth_lag, smooth_lag_seconds) {
        (false, None, None) => Ok(None),
        (true, None, None) => Ok(Some(Smoothing::Interval)),
        (false, Some(n), None) if n >= 1 => Ok(Some(Smoothing::Lag(Lag::Steps(n)))),
        (false, None, Some(s)) if s.is_finite() && s > 0.0 => {
            Ok(Some(Smoothing::Lag(Lag::Seconds(s))))
        }
        _ => Err(input(
            "argument 'smooth': True, a lag of N >= 1 steps (int) or S > 0 seconds (float), one at most",
        )),
    }
}

/// Runs `argus track` on the plot table (column `names`, `columns` of float64 / int64
/// arrays or lists of str) with the configuration (`config_kind` `"text"`, `"path"` or
/// `"json"`): returns the tracks columns (a dict) and the summary (multi-target jobs; a
/// dict without its file names). The GIL is released while tracking.
#[pyfunction]
#[pyo3(signature = (names, columns, config_kind, config_value, smooth=false, smooth_lag=None, smooth_lag_seconds=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn track_columns<'py>(
    py: Python<'py>,
    names: Vec<String>,
    columns: Vec<Bound<'py, PyAny>>,
    config_kind: &str,
    config_value: &str,
    smooth: bool,
    smooth_lag: Option<usize>,
    smooth_lag_seconds: Option<f64>,
) -> PyResult<(Bound<'py, PyDict>, Option<Bound<'py, PyAny>>)> {
    let smoothing = smoothing(smooth, smooth_lag, smooth_lag_seconds)?;
    // The configuration first, as `argus track` reads it before the plots.
    let cfg = config(config_kind, config_value)?;
    let plots = plots(&names, &columns)?;
    let (table, summary) =
        py.detach(|| track_run::run_plots(&cfg.loaded, &cfg.name, plots, smoothing))?;
    let summary = match summary {
        Some(mut doc) => {
            if let Some(m) = doc.as_object_mut() {
                for key in ["config", "plots_file", "tracks_file"] {
                    m.remove(key);
                }
            }
            Some(py_json(py, &doc)?)
        }
        None => None,
    };
    Ok((columns_dict(py, table)?, summary))
}

/// The columns of tracks CSV text (a file `argus track` wrote), as `track_columns`
/// returns them.
#[pyfunction]
pub(crate) fn tracks_text_columns<'py>(
    py: Python<'py>,
    text: &str,
) -> PyResult<Bound<'py, PyDict>> {
    columns_dict(py, argus_io::rows::text_columns(text))
}

/// TOML text of a configuration given as JSON text (from a Python dict).
#[pyfunction]
pub(crate) fn toml_from_json(json: &str) -> PyResult<String> {
    let value: serde_json::Value = serde_json::from_str(json)
        .map_err(|e| input(format!("argument 'config': not a JSON-like dict ({e})")))?;
    toml::to_string(&value).map_err(|e| {
        input(format!(
            "argument 'config': cannot be written as TOML ({e}); None values are not allowed"
        ))
    })
}

/// The multi-target tracker of an `argus track` configuration, fed plot tables.
#[pyclass(module = "argus_tracking._native")]
pub(crate) struct TrackerStream {
    inner: track_run::Stream,
}

#[pymethods]
impl TrackerStream {
    /// The tracker of the configuration (`kind` `"text"`, `"path"` or `"json"`).
    #[new]
    fn new(kind: &str, value: &str) -> PyResult<Self> {
        let cfg = config(kind, value)?;
        Ok(Self {
            inner: track_run::Stream::new(cfg.loaded, &cfg.name)?,
        })
    }

    /// Processes the plot table (`names`, `columns` as for `track_columns`); returns the
    /// tracks columns of the scans it held. On an error the tracker is unchanged. The GIL
    /// is released.
    fn process<'py>(
        &mut self,
        py: Python<'py>,
        names: Vec<String>,
        columns: Vec<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let plots = plots(&names, &columns)?;
        let inner = &mut self.inner;
        let table = py.detach(|| inner.process(&plots))?;
        columns_dict(py, table)
    }
}

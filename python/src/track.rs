//! `argus track` from Python: the command's own pipeline on files
//! (`argus_cli::track_files`, used by `track()`), its multi-target tracker as a stream
//! (`argus_cli::TrackStream`, used by `Tracker`), and a dict configuration turned into
//! the TOML text the command reads.

use std::path::{Path, PathBuf};

use argus_cli::{CliError, Smoothing, TrackStream};
use argus_filters::Lag;
use pyo3::prelude::*;

use crate::errors::{Kind, raise, rust_name};

/// A command error as the package's exception: I/O as `ArgusOSError`, a failed filter
/// step as `NumericalError`, everything else (configuration, plots) as
/// `InvalidInputError`.
fn cli_error(e: &CliError) -> PyErr {
    let kind = match e {
        CliError::Io { .. } => Kind::Io,
        CliError::Filter(_) | CliError::Imm(_) => Kind::Numerical,
        _ => Kind::InvalidInput,
    };
    raise(kind, &rust_name("CliError", e), e.to_string())
}

/// Runs `argus track` on the files: returns the number of rows and the summary's path
/// (multi-target jobs). `smooth` is `--smooth`, `smooth_lag` `--smooth-lag N`,
/// `smooth_lag_seconds` `--smooth-lag-seconds S` (at most one). The GIL is released.
#[pyfunction]
#[pyo3(signature = (config, plots, out, smooth=false, smooth_lag=None, smooth_lag_seconds=None))]
pub(crate) fn track_files(
    py: Python<'_>,
    config: PathBuf,
    plots: PathBuf,
    out: PathBuf,
    smooth: bool,
    smooth_lag: Option<usize>,
    smooth_lag_seconds: Option<f64>,
) -> PyResult<(usize, Option<PathBuf>)> {
    let smoothing = match (smooth, smooth_lag, smooth_lag_seconds) {
        (false, None, None) => None,
        (true, None, None) => Some(Smoothing::Interval),
        (false, Some(n), None) if n >= 1 => Some(Smoothing::Lag(Lag::Steps(n))),
        (false, None, Some(s)) if s.is_finite() && s > 0.0 => Some(Smoothing::Lag(Lag::Seconds(s))),
        _ => {
            return Err(crate::errors::input(
                "argument 'smooth': True, a lag of N >= 1 steps (int) or S > 0 seconds (float), one at most",
            ));
        }
    };
    py.detach(|| argus_cli::track_files(&config, &plots, &out, smoothing))
        .map_err(|e| cli_error(&e))
}

/// TOML text of a configuration given as JSON text (from a Python dict).
#[pyfunction]
pub(crate) fn toml_from_json(json: &str) -> PyResult<String> {
    let value: serde_json::Value = serde_json::from_str(json).map_err(|e| {
        crate::errors::input(format!("argument 'config': not a JSON-like dict ({e})"))
    })?;
    toml::to_string(&value).map_err(|e| {
        crate::errors::input(format!(
            "argument 'config': cannot be written as TOML ({e}); None values are not allowed"
        ))
    })
}

/// The multi-target tracker of an `argus track` configuration, fed plot file text.
#[pyclass(module = "argus_tracking._native")]
pub(crate) struct TrackerStream {
    inner: TrackStream,
}

#[pymethods]
impl TrackerStream {
    /// The tracker of the configuration file at `config`.
    #[new]
    fn new(config: PathBuf) -> PyResult<Self> {
        Ok(Self {
            inner: TrackStream::new(&config).map_err(|e| cli_error(&e))?,
        })
    }

    /// Processes plot file text (`name` in errors); returns the tracks CSV text of the
    /// scans it held. On an error the tracker is unchanged. The GIL is released.
    fn process(&mut self, py: Python<'_>, text: &str, name: &str) -> PyResult<String> {
        let inner = &mut self.inner;
        py.detach(|| inner.process(text, Path::new(name)))
            .map_err(|e| cli_error(&e))
    }
}

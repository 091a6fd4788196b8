//! The one place that calls `argus track`'s job ([`argus_io::track`]) for `track()` and
//! `Tracker`: the already-checked configuration and plots go in, the tracks table comes
//! back as columns. Nothing is written to a file and no CSV text is made.

use std::path::Path;

use argus_config::Loaded;
use argus_io::IoError;
use argus_io::plotfile::FilePlot;
use argus_io::rows::ColumnValues;
use argus_io::track::{self, Names, Smoothing, TrackStream};
use pyo3::prelude::*;

use crate::errors::{Kind, raise, rust_name};

/// The name of the plot table in errors.
pub(crate) const PLOTS: &str = "plots";

/// A tracks table as columns.
pub(crate) type Columns = Vec<(String, ColumnValues)>;

/// A job error as the package's exception: I/O as `ArgusOSError`, a failed filter step
/// as `NumericalError`, everything else (bad plots, configuration) as
/// `InvalidInputError`.
pub(crate) fn io_error(e: &IoError) -> PyErr {
    let kind = match e {
        IoError::Io { .. } => Kind::Io,
        IoError::Filter(_) | IoError::Imm(_) => Kind::Numerical,
        _ => Kind::InvalidInput,
    };
    raise(kind, &rust_name("IoError", e), e.to_string())
}

/// `argus track` on `plots` with the configuration `loaded` (named `config_name` in
/// errors): the tracks table's columns and the summary (multi-target jobs).
pub(crate) fn run_plots(
    loaded: &Loaded,
    config_name: &Path,
    plots: Vec<FilePlot>,
    smoothing: Option<Smoothing>,
) -> PyResult<(Columns, Option<serde_json::Value>)> {
    let names = Names {
        config: config_name,
        plots: Path::new(PLOTS),
        out: Path::new("tracks.csv"),
    };
    track::run_plots(loaded, names, plots, smoothing)
        .map(|(rows, summary)| (rows.columns(), summary))
        .map_err(|e| io_error(&e))
}

/// The multi-target tracker of a configuration, fed checked plots.
pub(crate) struct Stream {
    inner: TrackStream,
}

impl Stream {
    /// The tracker of `loaded` (named `config_name` in errors).
    pub(crate) fn new(loaded: Loaded, config_name: &Path) -> PyResult<Self> {
        let inner = TrackStream::new(loaded, config_name).map_err(|e| io_error(&e))?;
        Ok(Self { inner })
    }

    /// The rows of the scans in `plots`; on an error the tracker is unchanged.
    pub(crate) fn process(&mut self, plots: &[FilePlot]) -> PyResult<Columns> {
        self.inner
            .process(plots, Path::new(PLOTS))
            .map(|rows| rows.columns())
            .map_err(|e| io_error(&e))
    }
}

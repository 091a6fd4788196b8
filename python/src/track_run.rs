//! The one place that calls `argus track`'s job runner (for `track()` and `Tracker`).
//!
//! TODO(argus_io::track): today's runner is `argus_cli`'s, which works on files; these
//! functions hand it the already-checked plots and configuration in a private temporary
//! folder and read its tracks CSV back (error messages cleaned of the folder). Once
//! `argus_io::track` exists, replace the bodies (and drop `argus-cli` and `tempfile`
//! from python/Cargo.toml):
//!
//! - [`run_plots`]: `argus_io::track::run_plots(loaded, argus_io::track::Names { config:
//!   config_name, plots: Path::new(PLOTS), out: Path::new("tracks.csv") }, plots,
//!   smoothing).map(|(rows, summary)| (rows.columns(), summary)).map_err(|e|
//!   io_error(&e))`;
//! - [`Stream::new`]: `argus_io::track::TrackStream::new(loaded, config_name)` (drop
//!   `dir` / `config_name`);
//! - [`Stream::process`]: `self.inner.process(plots, Path::new(PLOTS)).map(|rows|
//!   rows.columns()).map_err(|e| io_error(&e))`.

use std::path::Path;

use argus_cli::{CliError, Smoothing, TrackStream};
use argus_config::Loaded;
use argus_io::plotfile::{self, FilePlot};
use argus_io::rows::{self, ColumnValues};
use argus_sim::{LabelledPlot, Origin};
use pyo3::prelude::*;

use crate::errors::{Kind, raise, rust_name};

/// The name of the plot table in errors.
pub(crate) const PLOTS: &str = "plots";

/// A tracks table as columns.
pub(crate) type Columns = Vec<(String, ColumnValues)>;

/// A runner error as the package's exception: I/O as `ArgusOSError`, a failed filter
/// step as `NumericalError`, everything else as `InvalidInputError`; `clean` maps the
/// message (the temporary folder's paths to the names the caller gave).
fn cli_error(e: &CliError, clean: &dyn Fn(String) -> String) -> PyErr {
    let kind = match e {
        CliError::Io { .. } => Kind::Io,
        CliError::Filter(_) | CliError::Imm(_) => Kind::Numerical,
        _ => Kind::InvalidInput,
    };
    raise(kind, &rust_name("CliError", e), clean(e.to_string()))
}

/// An I/O error of the temporary folder.
fn os_error(e: &std::io::Error) -> PyErr {
    raise(Kind::Io, "std::io::Error", e.to_string())
}

/// A private folder holding `config.toml` (the configuration's text).
struct Folder {
    dir: tempfile::TempDir,
    config: std::path::PathBuf,
}

impl Folder {
    fn new(config_text: &str) -> PyResult<Self> {
        let dir = tempfile::Builder::new()
            .prefix("argus-track-")
            .tempdir()
            .map_err(|e| os_error(&e))?;
        let config = dir.path().join("config.toml");
        std::fs::write(&config, config_text).map_err(|e| os_error(&e))?;
        Ok(Self { dir, config })
    }

    /// `msg` with the folder's configuration called `config_name` and its other files
    /// by their names.
    fn clean(prefix: &str, config: &str, config_name: &Path, msg: String) -> String {
        msg.replace(config, &config_name.display().to_string())
            .replace(prefix, "")
    }
}

/// The plot file text of `plots` (already checked; read back to the same values).
fn plot_text(plots: &[FilePlot]) -> String {
    let labelled: Vec<LabelledPlot> = plots
        .iter()
        .map(|p| LabelledPlot {
            plot: p.plot,
            origin: Origin::Clutter,
        })
        .collect();
    plotfile::write_text(&labelled).0
}

/// `argus track` on `plots` with the configuration `loaded` (its text `config_text`,
/// named `config_name` in errors): the tracks table's columns and the summary (multi-
/// target jobs).
pub(crate) fn run_plots(
    _loaded: &Loaded,
    config_text: &str,
    config_name: &Path,
    plots: &[FilePlot],
    smoothing: Option<Smoothing>,
) -> PyResult<(Columns, Option<serde_json::Value>)> {
    let folder = Folder::new(config_text)?;
    let plots_path = folder.dir.path().join(PLOTS);
    std::fs::write(&plots_path, plot_text(plots)).map_err(|e| os_error(&e))?;
    let out = folder.dir.path().join("tracks.csv");
    let prefix = format!(
        "{}{}",
        folder.dir.path().display(),
        std::path::MAIN_SEPARATOR
    );
    let config = folder.config.display().to_string();
    let clean = |m: String| Folder::clean(&prefix, &config, config_name, m);
    let (_, summary) = argus_cli::track_files(&folder.config, &plots_path, &out, smoothing)
        .map_err(|e| cli_error(&e, &clean))?;
    let text = std::fs::read_to_string(&out).map_err(|e| os_error(&e))?;
    let summary = match summary {
        Some(p) => {
            let text = std::fs::read_to_string(&p).map_err(|e| os_error(&e))?;
            Some(
                serde_json::from_str(&text)
                    .map_err(|e| raise(Kind::Io, "serde_json::Error", format!("summary: {e}")))?,
            )
        }
        None => None,
    };
    Ok((rows::text_columns(&text), summary))
}

/// The multi-target tracker of a configuration, fed checked plots.
pub(crate) struct Stream {
    inner: TrackStream,
    /// The temporary folder's path with a separator, and its configuration's path.
    prefix: String,
    config: String,
    config_name: std::path::PathBuf,
}

impl Stream {
    /// The tracker of `loaded` (text `config_text`, named `config_name` in errors).
    pub(crate) fn new(_loaded: Loaded, config_text: &str, config_name: &Path) -> PyResult<Self> {
        let folder = Folder::new(config_text)?;
        let prefix = format!(
            "{}{}",
            folder.dir.path().display(),
            std::path::MAIN_SEPARATOR
        );
        let config = folder.config.display().to_string();
        let clean = |m: String| Folder::clean(&prefix, &config, config_name, m);
        let inner = TrackStream::new(&folder.config).map_err(|e| cli_error(&e, &clean))?;
        Ok(Self {
            inner,
            prefix,
            config,
            config_name: config_name.to_path_buf(),
        })
    }

    /// The rows of the scans in `plots`; on an error the tracker is unchanged.
    pub(crate) fn process(&mut self, plots: &[FilePlot]) -> PyResult<Columns> {
        let clean = |m: String| Folder::clean(&self.prefix, &self.config, &self.config_name, m);
        self.inner
            .process(&plot_text(plots), Path::new(PLOTS))
            .map(|text| rows::text_columns(&text))
            .map_err(|e| cli_error(&e, &clean))
    }
}

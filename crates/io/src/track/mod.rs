//! The `argus track` job (see `docs/FORMATS.md`): a configured estimator, or the
//! multi-target tracker, over plots, giving the tracks CSV's rows and (multi-target) a
//! summary. The `argus` command ([`run_files`]) and the Python bindings ([`run_files`],
//! [`run_plots`], [`TrackStream`]) are each one call on it.
//!
//! One pipeline: the configuration is read and checked once by `argus_config`
//! ([`argus_config::load`]: the sensors, the estimator with every default filled in, the
//! `[tracker]` table mapped onto the tracker's configuration), the plot file read by
//! [`crate::plotfile`] or [`crate::source`] (ASTERIX for the configured sensors) as one
//! time-ordered stream of [`crate::event::Event`]s. The [`argus_config::Job`] is then one
//! target (`argus_tracker::single`'s engine over the plots, its errors mapped back to the
//! file's lines and keys) or the multi-target tracker (an `argus_tracker::Session`, each
//! event one of its inputs, its rows written as sectors conclude when going to a file);
//! both write their rows through [`crate::rows`].

mod multi;
mod multi_files;
mod multi_smooth;
mod names;
mod single;
mod smooth;
mod start;
mod stream;
mod tally;

use std::path::{Path, PathBuf};

pub use argus_tracker::smooth::Smoothing;
pub use stream::TrackStream;

use argus_config::{Job, Loaded, Sensor};
use argus_tracker::single::EstimatorSpec;

use crate::IoError;
use crate::event::Event;
use crate::output::write_atomic;
use crate::plotfile::{self, FilePlot};
use crate::rows::TrackRows;
use crate::source;

/// The paths of a run as they appear in error messages and in the summary (`config`,
/// `plots_file`, `tracks_file`).
#[derive(Debug, Clone, Copy)]
pub struct Names<'a> {
    /// The configuration.
    pub config: &'a Path,
    /// The plot file.
    pub plots: &'a Path,
    /// The tracks CSV.
    pub out: &'a Path,
}

/// Runs `argus track`: the configuration at `config` over the plot file `plots`
/// (CSV, or ASTERIX known by its content, as [`crate::source`] reads it),
/// the tracks CSV to `out` (the multi-target tracker also writes `<out>.summary.json`),
/// with the smoothed columns when `smoothing` is given. Returns the number of rows written
/// and the summary's path (multi-target only).
///
/// # Errors
/// [`IoError::Input`] for bad configuration or plots, [`IoError::Config`], filter
/// errors, I/O; [`IoError::Smooth`] for a track that cannot be smoothed.
pub fn run_files(
    config: &Path,
    plots: &Path,
    out: &Path,
    smoothing: Option<Smoothing>,
) -> Result<(usize, Option<PathBuf>), IoError> {
    let loaded = argus_config::load(config)?;
    let names = Names { config, plots, out };
    // `None` for CSV, which is then read as before (streamed for the tracker).
    let asterix = source::read(plots, config, &loaded.sensors)?;
    match &loaded.job {
        Job::Single { sensors, estimator } => {
            let plots = match &asterix {
                Some(a) => a.plots(),
                None => plotfile::read(plots)?,
            };
            let rows = single_rows(&loaded, names, sensors, estimator, plots, smoothing)?;
            let n = rows.rows();
            write_atomic(out, rows.into_text().as_bytes())?;
            Ok((n, None))
        }
        Job::Multi(m) => {
            let files = multi_files::Files::new(names, loaded.reference.as_ref(), smoothing);
            let grid = &loaded.grid_rotations;
            let (n, summary) = match asterix {
                Some(a) => multi::run_to_files(m, &files, grid, a.events.into_iter().map(Ok))?,
                None => {
                    let events = plotfile::PlotReader::open(plots)?.map(|p| p.map(Event::Plot));
                    multi::run_to_files(m, &files, grid, events)?
                }
            };
            Ok((n, Some(summary)))
        }
    }
}

/// `argus track` in memory: the configuration `loaded` over `plots` (in file order, as
/// [`plotfile`] reads them), `names` naming the files in errors and the summary. Returns
/// the tracks CSV's rows ([`TrackRows::into_text`] is the file [`run_files`] writes) and,
/// for the multi-target tracker, the summary JSON it writes beside it.
///
/// # Errors
/// As [`run_files`], but for reading and writing files.
pub fn run_plots(
    loaded: &Loaded,
    names: Names<'_>,
    plots: Vec<FilePlot>,
    smoothing: Option<Smoothing>,
) -> Result<(TrackRows, Option<serde_json::Value>), IoError> {
    match &loaded.job {
        Job::Single { sensors, estimator } => {
            let rows = single_rows(loaded, names, sensors, estimator, plots, smoothing)?;
            Ok((rows, None))
        }
        Job::Multi(m) => {
            let files = multi_files::Files::new(names, loaded.reference.as_ref(), smoothing);
            let grid = &loaded.grid_rotations;
            let events = plots.into_iter().map(|p| Ok(Event::Plot(p)));
            let (rows, (), summary) = multi::run(m, &files, grid, events, || Ok(()))?;
            let value = serde_json::to_value(&summary).map_err(|e| {
                let path = multi::summary_path(names.out);
                IoError::io(&path, std::io::Error::other(e.to_string()))
            })?;
            Ok((rows, Some(value)))
        }
    }
}

/// The single-target job's rows over `plots` (moved into the reference frame here).
fn single_rows(
    loaded: &Loaded,
    names: Names<'_>,
    sensors: &[Sensor],
    estimator: &EstimatorSpec,
    plots: Vec<FilePlot>,
    smoothing: Option<Smoothing>,
) -> Result<TrackRows, IoError> {
    let plots: Vec<_> = plots
        .into_iter()
        .map(|p| p.to_reference(&loaded.grid_rotations))
        .collect();
    let ctx = start::Ctx {
        config: names.config,
        plots_path: names.plots,
        sensors,
        reference: loaded.reference.as_ref(),
        smoothing,
    };
    single::run(&ctx, estimator, &plots)
}

//! `argus track`: a configured estimator, or the multi-target tracker, over a user's plot
//! file (see `docs/FORMATS.md`).
//!
//! One pipeline: the configuration file is read and checked once by `argus_config`
//! ([`argus_config::load`]: the sensors, the estimator with every default filled in, the
//! `[tracker]` table mapped onto the tracker's configuration), the plot file read by
//! `argus_io` (the plot CSV, or ASTERIX for the configured sensors). The
//! [`argus_config::Job`] is then one target ([`single`]: `argus_tracker::single`'s
//! engine, its errors mapped back to the file's lines and keys by [`start`]) or the
//! multi-target tracker ([`multi`], an `argus_tracker::Session`); both write their rows
//! through [`argus_io::rows`].

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

pub use smooth::Smoothing;
pub use stream::TrackStream;

use argus_config::Job;
use argus_io::output::write_atomic;
use argus_io::{plotfile, source};

use crate::error::CliError;

/// Runs `argus track`: the configuration at `config` over the plot file `plots_path`
/// (CSV, or ASTERIX known by its content, as [`argus_io::source`] reads it),
/// the tracks CSV to `out` (the multi-target tracker also writes `<out>.summary.json`),
/// with the smoothed columns when `smoothing` is given. Returns the number of rows written
/// and the summary's path (multi-target only).
///
/// # Errors
/// [`CliError::Input`] for bad configuration or plots, filter errors, I/O;
/// [`CliError::Smooth`] for a track that cannot be smoothed.
pub fn run(
    config: &Path,
    plots_path: &Path,
    out: &Path,
    smoothing: Option<Smoothing>,
) -> Result<(usize, Option<PathBuf>), CliError> {
    let loaded = argus_config::load(config)?;
    let reference = loaded.reference.as_ref();
    // `None` for CSV, which is then read as before (streamed for the tracker).
    let asterix = source::read(plots_path, config, &loaded.sensors)?;
    match &loaded.job {
        Job::Single { sensors, estimator } => {
            let plots = match &asterix {
                Some(a) => a.plots.clone(),
                None => plotfile::read(plots_path)?,
            };
            let plots: Vec<_> = plots
                .into_iter()
                .map(|p| p.to_reference(&loaded.grid_rotations))
                .collect();
            let ctx = start::Ctx {
                config,
                plots_path,
                sensors,
                reference,
                smoothing,
            };
            let rows = single::run(&ctx, estimator, &plots)?;
            let n = rows.rows();
            write_atomic(out, rows.into_text().as_bytes())?;
            Ok((n, None))
        }
        Job::Multi(m) => {
            let mut m = m.clone();
            let mut files = multi_files::Files {
                config,
                plots: plots_path,
                out,
                reference,
                smoothing,
                markers: &[],
            };
            let (n, summary) = match &asterix {
                Some(a) => {
                    multi::set_rotations(&mut m, &a.rotations, &loaded.grid_rotations);
                    files.markers = &a.markers;
                    let plots = a
                        .plots
                        .iter()
                        .map(|p| Ok(p.to_reference(&loaded.grid_rotations)));
                    multi::run(&m, &files, plots)?
                }
                None => {
                    let plots = plotfile::PlotReader::open(plots_path)?.map(|p| {
                        p.map(|p| p.to_reference(&loaded.grid_rotations))
                            .map_err(CliError::from)
                    });
                    multi::run(&m, &files, plots)?
                }
            };
            Ok((n, Some(summary)))
        }
    }
}

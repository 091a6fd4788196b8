//! `argus track`: a configured estimator, or the multi-target tracker, over a user's plot
//! file (see `docs/FORMATS.md`).
//!
//! One pipeline: the configuration file is parsed once ([`schema`]), its sensors and
//! estimator checked once with every default filled in ([`spec`]); with a `[tracker]`
//! table that is mapped onto the tracker's configuration ([`tracker_config`], whose
//! errors [`errors`] maps back to the file's keys). The [`job`] is then one target
//! ([`single`], [`single_imm`], started by the one two-point start of [`start`]) or the
//! multi-target tracker ([`multi`]); both write their rows through [`rows`].

mod errors;
mod job;
mod multi;
mod rows;
mod schema;
mod single;
mod single_imm;
mod spec;
mod start;
mod stream;
#[cfg(test)]
mod tests;
mod tracker_config;

use std::path::{Path, PathBuf};

use crate::error::CliError;
use crate::output::write_atomic;
use crate::plotfile;

pub use stream::TrackStream;

/// Runs `argus track`: the configuration at `config` over the plot file `plots_path`,
/// the tracks CSV to `out` (the multi-target tracker also writes `<out>.summary.json`).
/// Returns the number of rows written and the summary's path (multi-target only).
///
/// # Errors
/// [`CliError::Input`] for bad configuration or plots, filter errors, I/O.
pub fn run(
    config: &Path,
    plots_path: &Path,
    out: &Path,
) -> Result<(usize, Option<PathBuf>), CliError> {
    let job = job::load(config)?;
    let plots = plotfile::read(plots_path)?;
    match job {
        job::Job::Single { sensors, estimator } => {
            let ctx = start::Ctx {
                config,
                plots_path,
                sensors: &sensors,
            };
            let rows = single::run(&ctx, &estimator, &plots)?;
            let n = rows.rows();
            write_atomic(out, rows.into_text().as_bytes())?;
            Ok((n, None))
        }
        job::Job::Multi(m) => {
            let files = multi::Files {
                config,
                plots: plots_path,
                out,
            };
            let (n, summary) = multi::run(&m, &files, &plots)?;
            Ok((n, Some(summary)))
        }
    }
}

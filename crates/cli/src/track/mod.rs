//! `argus track`: the job of [`argus_io::track`] on files, its errors as the command's.

use std::path::{Path, PathBuf};

pub use argus_io::track::Smoothing;

use crate::error::CliError;

/// Runs `argus track` ([`argus_io::track::run_files`]): the configuration at `config`
/// over the plot file `plots`, the tracks CSV to `out` (the multi-target tracker also
/// writes `<out>.summary.json`), smoothed when `smoothing` is given. Returns the number
/// of rows written and the summary's path (multi-target only).
///
/// # Errors
/// [`CliError::Input`] for bad configuration or plots, filter errors, I/O;
/// [`CliError::File`] for a track that cannot be smoothed ([`argus_io::IoError::Smooth`]).
pub fn run(
    config: &Path,
    plots: &Path,
    out: &Path,
    smoothing: Option<Smoothing>,
) -> Result<(usize, Option<PathBuf>), CliError> {
    Ok(argus_io::track::run_files(config, plots, out, smoothing)?)
}

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
/// [`CliError::Smooth`] for a track that cannot be smoothed.
pub fn run(
    config: &Path,
    plots: &Path,
    out: &Path,
    smoothing: Option<Smoothing>,
) -> Result<(usize, Option<PathBuf>), CliError> {
    Ok(argus_io::track::run_files(config, plots, out, smoothing)?)
}

/// The multi-target tracker of an `argus track` configuration (one with a `[tracker]`
/// table), fed plot file text a batch at a time ([`argus_io::track::TrackStream`]).
#[derive(Debug, Clone)]
pub struct TrackStream(argus_io::track::TrackStream);

impl TrackStream {
    /// The tracker of the configuration at `config`.
    ///
    /// # Errors
    /// As `argus track` for the configuration; [`CliError::Input`] when it has no
    /// `[tracker]` table (a single-target configuration).
    pub fn new(config: &Path) -> Result<Self, CliError> {
        let loaded = argus_config::load(config)?;
        Ok(Self(argus_io::track::TrackStream::new(loaded, config)?))
    }

    /// Processes `text`, plot file text (header and rows), called `name` in errors: its
    /// plots grouped into scans by `(time, sensor)` in order, as `argus track` does.
    /// Returns the tracks CSV text (header and one row per track per scan). On an error
    /// the tracker is left as it was before the call.
    ///
    /// # Errors
    /// As `argus track` for the plots.
    pub fn process(&mut self, text: &str, name: &Path) -> Result<String, CliError> {
        Ok(self.0.process_text(text, name)?)
    }

    /// The stream of [`argus_io`], fed plots.
    pub fn inner(&mut self) -> &mut argus_io::track::TrackStream {
        &mut self.0
    }
}

//! The multi-target job as a stream, for the Python bindings' `Tracker`: the same
//! configuration, the same tracker and the same rows as [`super::multi`], scan by scan
//! as the caller hands plots in instead of over one file.

use std::path::{Path, PathBuf};

use crate::plotfile::{self, FilePlot};
use crate::rows::TrackRows;
use argus_config::{Job, Loaded, MultiTarget, Reference};
use argus_tracker::{Input, Session};

use super::multi;
use super::multi_files::{Files, tracker_plot};
use super::tally::Tally;
use crate::IoError;

/// The multi-target tracker of an `argus track` configuration (one with a `[tracker]`
/// table), fed plots (or plot file text) a batch at a time.
#[derive(Debug, Clone)]
pub struct TrackStream {
    job: MultiTarget,
    session: Session,
    config: PathBuf,
    reference: Option<Reference>,
    /// Geodetic sites' `(sensor, γ)` ([`FilePlot::to_reference`]).
    grid_rotations: Vec<(u32, f64)>,
}

impl TrackStream {
    /// The tracker of the configuration `loaded`, read from `config` (its name in errors).
    ///
    /// # Errors
    /// [`IoError::Tracker`] for a configuration the tracker refuses; [`IoError::Input`]
    /// when it has no `[tracker]` table (a single-target configuration).
    pub fn new(loaded: Loaded, config: &Path) -> Result<Self, IoError> {
        match loaded.job {
            Job::Multi(m) => Ok(Self {
                session: Session::new(m.config.clone())?,
                job: m,
                config: config.to_path_buf(),
                reference: loaded.reference,
                grid_rotations: loaded.grid_rotations,
            }),
            Job::Single { .. } => Err(IoError::input(
                config,
                None,
                Some("tracker"),
                "the multi-target tracker needs a [tracker] table (this configuration is a single-target job)",
            )),
        }
    }

    /// Processes `text`, plot file text (header and rows), called `name` in errors, as
    /// [`Self::process`] its plots; returns the tracks CSV text.
    ///
    /// # Errors
    /// As `argus track` for the plots.
    pub fn process_text(&mut self, text: &str, name: &Path) -> Result<String, IoError> {
        let plots = plotfile::read_text(text, name)?;
        Ok(self.process(&plots, name)?.into_text())
    }

    /// Processes `plots` (as [`plotfile`] reads them, in order; `name` is their file in
    /// errors), grouped into scans by `(time, sensor)` in order, as `argus track` does.
    /// Returns the tracks CSV's rows (one per track per scan). On an error the tracker is
    /// left as it was before the call.
    ///
    /// # Errors
    /// As `argus track` for the plots.
    pub fn process(&mut self, plots: &[FilePlot], name: &Path) -> Result<TrackRows, IoError> {
        let before = self.session.clone();
        let result = self.scans(plots, name);
        if result.is_err() {
            self.session = before;
        }
        result
    }

    fn scans(&mut self, plots: &[FilePlot], name: &Path) -> Result<TrackRows, IoError> {
        let files = Files {
            config: &self.config,
            plots: name,
            out: name,
            reference: self.reference.as_ref(),
            smoothing: None,
        };
        let mut out =
            TrackRows::with_reference(multi::columns(&self.job.config), self.reference.as_ref());
        let mut tally = Tally::new(&mut out, None);
        let mut outputs = Vec::new();
        for p in plots {
            let p = p.to_reference(&self.grid_rotations);
            let input = Input::Plot {
                plot: tracker_plot(&files, &p)?,
                tag: p.line,
            };
            multi::push(&mut self.session, &mut tally, &files, input, &mut outputs)?;
        }
        // The call's last plots are a whole scan; a rotating sensor's sector stays open
        // until a later call's plots (or none: the tracker holds it) pass its end.
        let end = Input::EndOfScan;
        multi::push(&mut self.session, &mut tally, &files, end, &mut outputs)?;
        Ok(out)
    }
}

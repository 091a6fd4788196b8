//! The multi-target job's files (for errors and the summary), and what it says of a plot
//! the tracker cannot take.

use std::path::Path;

use crate::plotfile::FilePlot;
use argus_config::Reference;
use argus_sensors::Measurement;
use argus_tracker::{Plot, SessionError, TrackerError};

use super::smooth::Smoothing;
use crate::IoError;

/// Where the run's inputs and outputs are, for errors and the summary.
pub(super) struct Files<'a> {
    /// The configuration.
    pub(super) config: &'a Path,
    /// The plot file.
    pub(super) plots: &'a Path,
    /// The tracks CSV to write.
    pub(super) out: &'a Path,
    /// The system reference point (`lat, lon` columns).
    pub(super) reference: Option<&'a Reference>,
    /// `--smooth` / `--smooth-lag` ([`super::multi_smooth`]).
    pub(super) smoothing: Option<Smoothing>,
}

impl<'a> Files<'a> {
    /// The files of `names`.
    pub(super) fn new(
        names: super::Names<'a>,
        reference: Option<&'a Reference>,
        smoothing: Option<Smoothing>,
    ) -> Self {
        Self {
            config: names.config,
            plots: names.plots,
            out: names.out,
            reference,
            smoothing,
        }
    }
}

/// The tracker's plot of a file plot: polar plots go in as they are (the tracker converts
/// them with its sensor's noise, or the EKF and multi-IMM use them directly), Cartesian
/// reports with their covariance.
pub(super) fn tracker_plot(files: &Files<'_>, p: &FilePlot) -> Result<Plot, IoError> {
    match p.measurement() {
        Measurement::Cartesian2(_) | Measurement::Polar(_) => Ok(p.plot),
        Measurement::Spherical(_) | Measurement::Cartesian3(_) => Err(IoError::input(
            files.plots,
            Some(p.line),
            None,
            "the multi-target tracker ([tracker]) tracks 2-D plots (polar or x, y); this plot is 3-D",
        )),
    }
}

/// A session's error: a [`TrackerError`] about a plot at that plot's line (its tag).
pub(super) fn plot_error(files: &Files<'_>, e: SessionError) -> IoError {
    let SessionError {
        error: e,
        tag: line,
    } = e;
    let field = match &e {
        TrackerError::TimeOrder { .. } => Some("t"),
        TrackerError::UnknownSensor { .. }
        | TrackerError::NoPolarNoise { .. }
        | TrackerError::NotPolar { .. } => Some("sensor"),
        TrackerError::NonPositiveRange { .. } | TrackerError::Conversion { .. } => Some("range"),
        TrackerError::NonFinite { .. }
        | TrackerError::PlotCovariance { .. }
        | TrackerError::MixedScan { .. } => None,
        _ => return IoError::Tracker(e),
    };
    IoError::input(files.plots, line, field, format!("tracker: {e}"))
}

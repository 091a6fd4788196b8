//! A [`super::Session`]'s error: the tracker's, and the tag of the plot it is about.

use crate::TrackerError;

/// What went wrong in [`super::Session::push`]: the tracker's error and, when it is about
/// a plot, that plot's tag ([`super::Input::Plot`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{error}")]
pub struct SessionError {
    /// The tracker's error (its `index`, if any, is the plot's in the group handed in).
    pub error: TrackerError,
    /// The tag of the plot the error is about; `None` for an error about a marker, a
    /// rotation or the configuration.
    pub tag: Option<u64>,
}

impl SessionError {
    /// `error` about the plots whose tags are `tags` (handed to the tracker together).
    pub(super) fn of(error: TrackerError, tags: &[u64]) -> Self {
        let tag = plot_index(&error).and_then(|i| tags.get(i).copied());
        Self { error, tag }
    }
}

impl From<TrackerError> for SessionError {
    fn from(error: TrackerError) -> Self {
        Self { error, tag: None }
    }
}

/// The index of the plot a tracker error names, if it names one.
fn plot_index(e: &TrackerError) -> Option<usize> {
    match e {
        TrackerError::TimeOrder { index, .. }
        | TrackerError::UnknownSensor { index, .. }
        | TrackerError::NonFinite { index, .. }
        | TrackerError::PlotCovariance { index, .. }
        | TrackerError::NonPositiveRange { index, .. }
        | TrackerError::NoPolarNoise { index, .. }
        | TrackerError::NotPolar { index, .. }
        | TrackerError::NotPlanar { index, .. }
        | TrackerError::Conversion { index, .. }
        | TrackerError::MixedScan { index, .. } => Some(*index),
        _ => None,
    }
}

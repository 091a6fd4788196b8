//! The smoothing of a single-target run (`imm`, `multi-imm`, `aircraft-imm` with
//! `--smooth` / `--smooth-lag`): its recorded forward pass smoothed once the plots are
//! done, and each row given its step's smoothed estimate (rows of one time are one step,
//! [`crate::smooth::steps`]).

use argus_imm::ForwardRecord;

use super::error::SingleError;
use crate::smooth::{self, Failure, ModeRecorder, Smoothing};

/// A run's smoothed steps, and the step of each row.
pub(super) struct SmoothedRun<S> {
    steps: Vec<S>,
    row_step: Vec<usize>,
}

impl<S> SmoothedRun<S> {
    /// The smoothed estimate of row `i` (its step's), if any.
    pub(super) fn at(&self, i: usize) -> Option<&S> {
        self.row_step.get(i).and_then(|&k| self.steps.get(k))
    }
}

/// With smoothing (`how`), the record `record` of `imm` smoothed, for the rows of times
/// `times`; `None` without.
///
/// # Errors
/// [`SingleError::Smoothing`] for a step that cannot be smoothed.
pub(super) fn smooth_run<T: ForwardRecord<M, 4, Estimate = E>, M, E>(
    record: Option<ModeRecorder<T, E>>,
    imm: &M,
    how: Option<Smoothing>,
    times: &[f64],
) -> Result<Option<SmoothedRun<T::Smoothed>>, SingleError> {
    let steps = match (record, how) {
        (Some(r), Some(how)) => r
            .smooth(imm, how)
            .map_err(|f: Failure| SingleError::Smoothing(f))?,
        _ => return Ok(None),
    };
    Ok(Some(SmoothedRun {
        steps,
        row_step: smooth::steps(times).row_step,
    }))
}

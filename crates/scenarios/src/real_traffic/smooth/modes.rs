//! The smoothing of a multiple-model track's rows over its recorded mode-conditioned
//! states, written once for the two-mode CV IMM (`argus_imm::ImmTrack`) and the aircraft
//! IMM (`argus_imm::AircraftTrack`) through their [`ForwardRecord`]: the forward record
//! rebuilt row by row, then the smoother's combined means put back into the rows (the
//! parent module's docs).

use argus_core_math::Vector;
use argus_imm::ForwardRecord;
use argus_score::TrackHistory;

use super::{smoothing_error, with_smoothed_states};
use crate::error::ScenarioError;

/// A track's rows smoothed over its recorded states `states` (`state` reads a row's
/// posterior; `what` names the model in errors): a history with the same rows and flags
/// and the smoothed combined states. Rows at the time of the row before (a deleted
/// track's last row) take that row's smoothed state.
///
/// # Errors
/// [`ScenarioError::Degenerate`] naming the track if the states and rows differ in
/// number, a row has no state or a step fails.
pub(super) fn smoothed_mode_track<T: ForwardRecord<M, 4>, M, S>(
    imm: &M,
    history: &TrackHistory,
    states: &[S],
    what: &str,
    state: impl Fn(&S) -> Option<T::Estimate>,
) -> Result<TrackHistory, ScenarioError> {
    let fail = |e: &dyn std::fmt::Display| smoothing_error(&format!("track {}", history.name()), e);
    let rows = history.rows();
    if states.len() != rows.len() {
        return Err(fail(&format!(
            "{} rows against {} {what} states",
            rows.len(),
            states.len()
        )));
    }
    let mut track: Option<T> = None;
    let mut step_of = Vec::with_capacity(rows.len());
    for (k, (r, s)) in rows.iter().zip(states).enumerate() {
        let est = state(s).ok_or_else(|| fail(&format!("row {k} has no {what} state")))?;
        match &mut track {
            None => {
                let mut t = T::start(imm, r.t, est).map_err(|e| fail(&e))?;
                t.reserve(rows.len());
                track = Some(t);
            }
            Some(t) => {
                if r.t > t.latest_time() {
                    t.push(imm, r.t, est).map_err(|e| fail(&e))?;
                }
            }
        }
        step_of.push(track.as_ref().map_or(0, |t| t.step_count() - 1));
    }
    let Some(track) = track else {
        return TrackHistory::new(history.name(), Vec::new()).map_err(ScenarioError::from);
    };
    let smoothed = track
        .smooth_steps(0, track.step_count() - 1)
        .map_err(|e| fail(&e))?;
    let means: Vec<Vector<4>> = smoothed.iter().map(|s| *T::combined(s).mean()).collect();
    with_smoothed_states(history, &step_of, |k| &means[k])
}

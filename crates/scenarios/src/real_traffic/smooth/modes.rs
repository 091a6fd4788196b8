//! The smoothing of a multiple-model track's rows over its recorded mode-conditioned
//! states, written once for the two-mode CV IMM ([`ImmTrack`]) and the aircraft IMM
//! ([`AircraftTrack`]): the forward record rebuilt row by row, then the smoother's
//! combined means put back into the rows (the parent module's docs).

use argus_core_math::Vector;
use argus_imm::{
    AircraftEkf, AircraftEstimate, AircraftTrack, ImmEstimate, ImmSmoothError, ImmTrack,
};
use argus_score::TrackHistory;

use super::{Imm2, smoothing_error, with_smoothed_states};
use crate::error::ScenarioError;

/// A multiple-model smoother's forward record that a track's rows are pushed onto.
pub(super) trait ModeTrack: Sized {
    /// The IMM the track was filtered by.
    type Imm;
    /// One row's recorded posterior.
    type Estimate;
    /// A record of `imm` starting at `time` with `estimate`, with room for `rows` steps.
    ///
    /// # Errors
    /// The record's error for a non-finite `time`.
    fn begin(
        imm: &Self::Imm,
        time: f64,
        estimate: Self::Estimate,
        rows: usize,
    ) -> Result<Self, ImmSmoothError>;
    /// The number of steps recorded and the latest one's time.
    fn last_step(&self) -> (usize, f64);
    /// Records `estimate`, the posterior of `imm` at `time` after the latest step.
    ///
    /// # Errors
    /// The record's error (time not after the latest step, a failed prediction).
    fn record(
        &mut self,
        imm: &Self::Imm,
        time: f64,
        estimate: Self::Estimate,
    ) -> Result<(), ImmSmoothError>;
    /// The smoothed combined `[x, vx, y, vy]` mean of every step.
    ///
    /// # Errors
    /// The smoother's error.
    fn smoothed_means(&self) -> Result<Vec<Vector<4>>, ImmSmoothError>;
}

impl ModeTrack for ImmTrack<4, 2> {
    type Imm = Imm2;
    type Estimate = ImmEstimate<4, 2>;

    fn begin(
        imm: &Imm2,
        time: f64,
        estimate: ImmEstimate<4, 2>,
        rows: usize,
    ) -> Result<Self, ImmSmoothError> {
        let mut t = ImmTrack::new(*imm.markov(), time, estimate)?;
        t.reserve(rows);
        Ok(t)
    }

    fn last_step(&self) -> (usize, f64) {
        let steps = self.steps();
        (steps.len(), steps[steps.len() - 1].time())
    }

    fn record(
        &mut self,
        imm: &Imm2,
        time: f64,
        estimate: ImmEstimate<4, 2>,
    ) -> Result<(), ImmSmoothError> {
        self.push(imm, time, estimate)
    }

    fn smoothed_means(&self) -> Result<Vec<Vector<4>>, ImmSmoothError> {
        Ok(self.smooth()?.iter().map(|s| *s.combined.mean()).collect())
    }
}

impl ModeTrack for AircraftTrack<2, 3> {
    type Imm = AircraftEkf<2, 3>;
    type Estimate = AircraftEstimate<2, 3>;

    fn begin(
        imm: &AircraftEkf<2, 3>,
        time: f64,
        estimate: AircraftEstimate<2, 3>,
        _rows: usize,
    ) -> Result<Self, ImmSmoothError> {
        AircraftTrack::new(*imm.markov(), time, estimate)
    }

    fn last_step(&self) -> (usize, f64) {
        let steps = self.steps();
        (steps.len(), steps[steps.len() - 1].time())
    }

    fn record(
        &mut self,
        imm: &AircraftEkf<2, 3>,
        time: f64,
        estimate: AircraftEstimate<2, 3>,
    ) -> Result<(), ImmSmoothError> {
        self.push(imm, time, estimate)
    }

    fn smoothed_means(&self) -> Result<Vec<Vector<4>>, ImmSmoothError> {
        Ok(self.smooth()?.iter().map(|s| *s.combined.mean()).collect())
    }
}

/// A track's rows smoothed over its recorded states `states` (`state` reads a row's
/// posterior; `what` names the model in errors): a history with the same rows and flags
/// and the smoothed combined states. Rows at the time of the row before (a deleted
/// track's last row) take that row's smoothed state.
///
/// # Errors
/// [`ScenarioError::Degenerate`] naming the track if the states and rows differ in
/// number, a row has no state or a step fails.
pub(super) fn smoothed_mode_track<T: ModeTrack, S>(
    imm: &T::Imm,
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
                track = Some(T::begin(imm, r.t, est, rows.len()).map_err(|e| fail(&e))?);
            }
            Some(t) => {
                if r.t > t.last_step().1 {
                    t.record(imm, r.t, est).map_err(|e| fail(&e))?;
                }
            }
        }
        step_of.push(track.as_ref().map_or(0, |t| t.last_step().0 - 1));
    }
    let Some(track) = track else {
        return TrackHistory::new(history.name(), Vec::new()).map_err(ScenarioError::from);
    };
    let means = track.smoothed_means().map_err(|e| fail(&e))?;
    with_smoothed_states(history, &step_of, |k| &means[k])
}

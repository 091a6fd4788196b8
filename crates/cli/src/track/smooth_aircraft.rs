//! `argus track --smooth` / `--smooth-lag` for the aircraft IMM (`aircraft-imm`): its
//! forward pass recorded one step per time ([`argus_imm::AircraftTrack`]) and smoothed by
//! `argus_imm`'s aircraft-IMM smoother ([`argus_imm::aircraft_smooth`]: Kim's pairwise
//! RTS form with backward-likelihood weights across the CV modes' 4 and the CT mode's 5
//! states), fixed interval or, by windows of the same backward pass, fixed lag — as
//! [`super::smooth::ImmRecorder`] does for the `imm` kind.
//!
//! The record is formed from the posteriors (each transition recomputed from the
//! posterior of the time before with the IMM's own filters and mixing maps), so a
//! tracker's track rows give the same record as the single-target run over the same
//! plots.

use argus_imm::{AircraftEkf, AircraftEstimate, AircraftSmoothed, AircraftTrack, PairWeights};

use super::smooth::{Failure, Smoothing, by_windows, imm_failure};

/// An aircraft-IMM forward pass being recorded for smoothing, one step per time: the
/// posterior of a time is recorded when the next time comes (plots of one instant are
/// applied in turn), so that the transitions start from the last posterior of each time.
pub(super) struct AircraftRecorder {
    track: Option<AircraftTrack<2, 3>>,
    pending: Option<(f64, AircraftEstimate<2, 3>)>,
    times: Vec<f64>,
}

impl AircraftRecorder {
    /// An empty record.
    pub(super) fn new() -> Self {
        Self {
            track: None,
            pending: None,
            times: Vec::new(),
        }
    }

    /// Records the posterior `est` at `time` (the row's).
    ///
    /// # Errors
    /// [`Failure`] when the transitions from the previous time cannot be formed.
    pub(super) fn record(
        &mut self,
        imm: &AircraftEkf<2, 3>,
        time: f64,
        est: AircraftEstimate<2, 3>,
    ) -> Result<(), Failure> {
        if let Some((t, _)) = &self.pending
            && t.total_cmp(&time).is_eq()
        {
            self.pending = Some((time, est));
            return Ok(());
        }
        self.flush(imm)?;
        self.pending = Some((time, est));
        Ok(())
    }

    fn flush(&mut self, imm: &AircraftEkf<2, 3>) -> Result<(), Failure> {
        let Some((t, est)) = self.pending.take() else {
            return Ok(());
        };
        self.times.push(t);
        let res = match &mut self.track {
            None => AircraftTrack::new(*imm.markov(), t, est).map(|tr| self.track = Some(tr)),
            Some(tr) => tr.push(imm, t, est),
        };
        res.map_err(|e| imm_failure(&e, 0, &self.times))
    }

    /// Smooths the record: one smoothed estimate per step (rows of one time share it).
    ///
    /// # Errors
    /// [`Failure`] at the failed step.
    pub(super) fn smooth(
        mut self,
        imm: &AircraftEkf<2, 3>,
        how: Smoothing,
    ) -> Result<Vec<AircraftSmoothed<2, 3>>, Failure> {
        self.flush(imm)?;
        let Some(track) = &self.track else {
            return Ok(Vec::new());
        };
        let times = &self.times;
        let steps = track.steps();
        by_windows(times, how, |j, k| {
            argus_imm::aircraft_smooth(track.markov(), PairWeights::default(), &steps[j..=k])
                .map_err(|e| imm_failure(&e, j, times))
        })
    }
}

//! The forward-pass record of a mode-switching estimator (the IMM, the aircraft IMM),
//! kept for smoothing one step per time: the posterior of a time is recorded when the
//! next time comes (plots of one instant are applied in turn), so that the transitions
//! start from the last posterior of each time, into `argus_imm`'s track of one estimator
//! ([`ForwardRecord`]: [`ImmRecorder`], [`AircraftRecorder`]).
//!
//! The IMM (`imm`, and the multi-IMM over its merged posteriors) is smoothed by
//! `argus_imm`'s IMM smoother ([`argus_imm::imm_smooth`]); the aircraft IMM by its
//! aircraft-IMM smoother ([`argus_imm::aircraft_smooth`]: Kim's pairwise RTS form with
//! backward-likelihood weights across the CV modes' 4 and the CT mode's 5 states); fixed
//! interval or, by windows of the same backward pass, fixed lag. The record is formed from
//! the posteriors (each transition recomputed from the posterior of the time before with
//! the IMM's own filters and mixing maps), so a tracker's track rows give the same record
//! as the single-target run over the same plots.

use argus_imm::{AircraftEstimate, AircraftTrack, ForwardRecord, ImmEstimate, ImmTrack};

use super::{Failure, Smoothing, by_windows, imm_failure};

/// An IMM forward pass with `R` modes being recorded for smoothing.
pub type ImmRecorder<const R: usize> = ModeRecorder<ImmTrack<4, R>, ImmEstimate<4, R>>;

/// An aircraft-IMM forward pass being recorded for smoothing.
pub type AircraftRecorder = ModeRecorder<AircraftTrack<2, 3>, AircraftEstimate<2, 3>>;

/// A forward pass being recorded for smoothing (module docs): the track `T` and the
/// posterior `E` of the latest time, held until the next time comes.
#[derive(Debug, Clone)]
pub struct ModeRecorder<T, E> {
    track: Option<T>,
    pending: Option<(f64, E)>,
    times: Vec<f64>,
}

impl<T, E> ModeRecorder<T, E> {
    /// An empty record.
    #[must_use]
    pub fn new() -> Self {
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
    pub fn record<M>(&mut self, imm: &M, time: f64, est: E) -> Result<(), Failure>
    where
        T: ForwardRecord<M, 4, Estimate = E>,
    {
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

    fn flush<M>(&mut self, imm: &M) -> Result<(), Failure>
    where
        T: ForwardRecord<M, 4, Estimate = E>,
    {
        let Some((t, est)) = self.pending.take() else {
            return Ok(());
        };
        self.times.push(t);
        let res = match &mut self.track {
            None => T::start(imm, t, est).map(|tr| self.track = Some(tr)),
            Some(tr) => tr.push(imm, t, est),
        };
        res.map_err(|e| imm_failure(&e, 0, &self.times))
    }

    /// Smooths the record: one smoothed estimate per step (rows of one time share it).
    ///
    /// # Errors
    /// [`Failure`] at the failed step.
    pub fn smooth<M>(mut self, imm: &M, how: Smoothing) -> Result<Vec<T::Smoothed>, Failure>
    where
        T: ForwardRecord<M, 4, Estimate = E>,
    {
        self.flush(imm)?;
        let Some(track) = &self.track else {
            return Ok(Vec::new());
        };
        let times = &self.times;
        by_windows(times, how, |j, k| {
            track
                .smooth_steps(j, k)
                .map_err(|e| imm_failure(&e, j, times))
        })
    }
}

impl<T, E> Default for ModeRecorder<T, E> {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::smooth::Smoothing;
    use argus_core_math::{Gaussian, Matrix, Vector};
    use argus_filters::Kf;
    use argus_imm::{Imm, MarkovMatrix};
    use argus_motion_models::Cv2D;
    use argus_sensors::CartesianPosition;

    #[test]
    fn the_imm_record_keeps_one_step_per_time() {
        let imm = Imm::new(
            [
                Kf::new(Cv2D::discrete(0.1).unwrap()),
                Kf::new(Cv2D::discrete(3.0).unwrap()),
            ],
            MarkovMatrix::new([[0.9, 0.1], [0.1, 0.9]]).unwrap(),
        )
        .unwrap();
        let pos = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 400.0).unwrap();
        let start = Gaussian::new(
            Vector::<4>::new(0.0, 10.0, 0.0, -5.0),
            Matrix::<4, 4>::identity() * 1e4,
        )
        .unwrap();
        let mut est = ImmEstimate::from_common(start, [0.5, 0.5]).unwrap();
        let mut rec = ImmRecorder::new();
        rec.record(&imm, 0.0, est).unwrap();
        let mut t = 0.0;
        // Plots at 2, 4, 4 (one instant twice), 7 s.
        for (tn, off) in [(2.0, 0.0), (4.0, 1.0), (4.0, 2.0), (7.0, 3.0)] {
            let z = Vector::<2>::new(10.0 * tn + off, -5.0 * tn);
            est = if tn > t {
                imm.step(&est, tn - t, &pos, &z).unwrap().estimate
            } else {
                imm.update(&est.into_prediction(), &pos, &z)
                    .unwrap()
                    .estimate
            };
            t = tn;
            rec.record(&imm, t, est).unwrap();
        }
        let last = est.combined().unwrap();
        let sm = rec.smooth(&imm, Smoothing::Interval).unwrap();
        // Four times, four steps; the last is the filter's (the second update at 4 s
        // is the step's estimate).
        assert_eq!(sm.len(), 4);
        assert_eq!(sm[3].combined, last);
    }
}

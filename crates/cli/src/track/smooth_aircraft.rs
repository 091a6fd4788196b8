//! `argus track --smooth` / `--smooth-lag` for the aircraft IMM (`aircraft-imm`): its
//! forward pass recorded one step per time ([`argus_imm::AircraftTrack`]) and smoothed by
//! `argus_imm`'s aircraft-IMM smoother ([`argus_imm::aircraft_smooth`]: Kim's pairwise
//! RTS form with backward-likelihood weights across the CV modes' 4 and the CT mode's 5
//! states), fixed interval or, by windows of the same backward pass, fixed lag — as
//! [`super::smooth_imm::ImmRecorder`] does for the `imm` kind.
//!
//! The record is formed from the posteriors (each transition recomputed from the
//! posterior of the time before with the IMM's own filters and mixing maps), so a
//! tracker's track rows give the same record as the single-target run over the same
//! plots.

use argus_core_math::Gaussian;
use argus_imm::{
    AircraftEkf, AircraftEstimate, AircraftSmoothed, AircraftTrack, ImmSmoothError, PairWeights,
};

use super::mode_record::{ModeRecorder, ModeTrack};

/// An aircraft-IMM forward pass being recorded for smoothing.
pub(super) type AircraftRecorder = ModeRecorder<AircraftTrack<2, 3>, AircraftEstimate<2, 3>>;

impl ModeTrack<AircraftEkf<2, 3>> for AircraftTrack<2, 3> {
    type Estimate = AircraftEstimate<2, 3>;
    type Smoothed = AircraftSmoothed<2, 3>;

    fn start(
        imm: &AircraftEkf<2, 3>,
        time: f64,
        est: Self::Estimate,
    ) -> Result<Self, ImmSmoothError> {
        Self::new(*imm.markov(), time, est)
    }

    fn push(
        &mut self,
        imm: &AircraftEkf<2, 3>,
        time: f64,
        est: Self::Estimate,
    ) -> Result<(), ImmSmoothError> {
        AircraftTrack::push(self, imm, time, est)
    }

    fn smooth_steps(&self, j: usize, k: usize) -> Result<Vec<Self::Smoothed>, ImmSmoothError> {
        argus_imm::aircraft_smooth(self.markov(), PairWeights::default(), &self.steps()[j..=k])
    }

    fn row(s: &Self::Smoothed) -> (Gaussian<4>, Vec<f64>) {
        (s.combined, s.mode_probabilities.to_vec())
    }
}

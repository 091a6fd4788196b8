//! [`crate::ModeTrack`] and [`crate::ForwardRecord`] for the aircraft IMM's record
//! ([`AircraftTrack`]), its combined estimate on `[x, vx, y, vy]`.

use argus_core_math::Gaussian;
use argus_filters::SmoothingFilter;

use super::{AircraftSmoothed, AircraftTrack};
use crate::aircraft::{AircraftEstimate, AircraftImm};
use crate::{ForwardRecord, ImmSmoothError, ModeTrack};

impl<const C: usize, const R: usize> ModeTrack<4> for AircraftTrack<C, R> {
    type Estimate = AircraftEstimate<C, R>;
    type Smoothed = AircraftSmoothed<C, R>;

    fn reserve(&mut self, additional: usize) {
        AircraftTrack::reserve(self, additional);
    }

    fn step_count(&self) -> usize {
        self.steps().len()
    }

    fn latest_time(&self) -> f64 {
        self.steps()[self.steps().len() - 1].time()
    }

    fn smooth_steps(
        &self,
        first: usize,
        last: usize,
    ) -> Result<Vec<AircraftSmoothed<C, R>>, ImmSmoothError> {
        self.smooth_window(first, last)
    }

    fn combined(smoothed: &AircraftSmoothed<C, R>) -> &Gaussian<4> {
        &smoothed.combined
    }

    fn mode_probabilities(smoothed: &AircraftSmoothed<C, R>) -> &[f64] {
        &smoothed.mode_probabilities
    }
}

impl<Fcv, Fct, const C: usize, const R: usize> ForwardRecord<AircraftImm<Fcv, Fct, C, R>, 4>
    for AircraftTrack<C, R>
where
    Fcv: SmoothingFilter<4>,
    Fct: SmoothingFilter<5>,
{
    fn start(
        imm: &AircraftImm<Fcv, Fct, C, R>,
        time: f64,
        estimate: AircraftEstimate<C, R>,
    ) -> Result<Self, ImmSmoothError> {
        Self::new(*imm.markov(), time, estimate)
    }

    fn push(
        &mut self,
        imm: &AircraftImm<Fcv, Fct, C, R>,
        time: f64,
        estimate: AircraftEstimate<C, R>,
    ) -> Result<(), ImmSmoothError> {
        AircraftTrack::push(self, imm, time, estimate)
    }
}

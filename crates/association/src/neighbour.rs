//! Nearest-neighbour and strongest-neighbour filters.

use argus_core_math::{Gaussian, Vector};
use argus_filters::MeasurementPrediction;
use argus_sensors::MeasurementModel;

use crate::associator::{Associator, Candidate, Outcome, for_each_gated};
use crate::error::AssociationError;
use crate::gate::Gate;

/// The nearest-neighbour (NN) filter: of the plots in the gate, the one with the
/// smallest normalised distance `D(z) = νᵀS⁻¹ν` updates the track as if it were the
/// target's; with no plot in the gate the prediction is kept.
///
/// Its covariance is the Kalman one, which ignores that the NN plot may be clutter,
/// so it is over-confident in clutter.
///
/// # References
/// Seed 002 §2.2, eq (13); Li, X. R. & Bar-Shalom, Y. (1996), "Tracking in clutter with
/// nearest neighbor filters: analysis and performance", IEEE TAES 32(3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NearestNeighbour {
    gate: Gate,
}

impl NearestNeighbour {
    /// The NN filter with validation gate `gate`.
    #[must_use]
    pub fn new(gate: Gate) -> Self {
        Self { gate }
    }
}

/// The strongest-neighbour (SN) filter: of the plots in the gate, the one with the
/// largest amplitude updates the track as if it were the target's. Over-confident
/// in clutter — the flaw that [`crate::Psn`] fixes.
///
/// # References
/// Seed 002 §2.4; Li, X. R. & Bar-Shalom, Y. (1998), "Tracking in clutter with
/// strongest neighbor measurements — Part I", IEEE TAC 43(11).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrongestNeighbour {
    gate: Gate,
}

impl StrongestNeighbour {
    /// The SN filter with validation gate `gate`.
    #[must_use]
    pub fn new(gate: Gate) -> Self {
        Self { gate }
    }
}

/// Updates with the selected plot (or keeps the prediction when none was gated).
fn single_plot_outcome<const N: usize, const M: usize>(
    predicted: &Gaussian<N>,
    mp: &MeasurementPrediction<N, M>,
    chosen: Option<(usize, Vector<M>, f64)>,
    gated: usize,
) -> Result<Outcome<N>, AssociationError> {
    match chosen {
        Some((index, residual, nis)) => Ok(Outcome {
            posterior: mp.update(predicted, &residual)?,
            gated,
            used: Some(index),
            miss_probability: 0.0,
            log_likelihood: mp.log_likelihood_from_nis(nis),
        }),
        None => Ok(Outcome {
            posterior: *predicted,
            gated,
            used: None,
            miss_probability: 1.0,
            log_likelihood: 0.0,
        }),
    }
}

impl Associator for NearestNeighbour {
    fn gate(&self) -> &Gate {
        &self.gate
    }

    /// `log_likelihood` is the Gaussian log-likelihood of the NN plot (0 when none).
    fn associate<const N: usize, const M: usize, Me: MeasurementModel<N, M>>(
        &self,
        predicted: &Gaussian<N>,
        mp: &MeasurementPrediction<N, M>,
        meas: &Me,
        plots: &[Candidate<M>],
    ) -> Result<Outcome<N>, AssociationError> {
        let mut best: Option<(usize, Vector<M>, f64)> = None;
        let gated = for_each_gated(&self.gate, mp, meas, plots, |i, innov, _| {
            if best.is_none_or(|(_, _, d)| innov.nis < d) {
                best = Some((i, innov.residual, innov.nis));
            }
            Ok(())
        })?;
        single_plot_outcome(predicted, mp, best, gated)
    }
}

impl Associator for StrongestNeighbour {
    fn gate(&self) -> &Gate {
        &self.gate
    }

    /// `log_likelihood` is the Gaussian log-likelihood of the SN plot (0 when none).
    ///
    /// # Errors
    /// Also [`AssociationError::MissingAmplitude`] / [`AssociationError::InvalidAmplitude`]
    /// for a gated plot without a finite amplitude.
    fn associate<const N: usize, const M: usize, Me: MeasurementModel<N, M>>(
        &self,
        predicted: &Gaussian<N>,
        mp: &MeasurementPrediction<N, M>,
        meas: &Me,
        plots: &[Candidate<M>],
    ) -> Result<Outcome<N>, AssociationError> {
        let mut best: Option<(usize, Vector<M>, f64, f64)> = None;
        let gated = for_each_gated(&self.gate, mp, meas, plots, |i, innov, c| {
            let a = c.amplitude.ok_or(AssociationError::MissingAmplitude {
                index: i,
                filter: "the strongest-neighbour filter",
            })?;
            if !a.is_finite() {
                return Err(AssociationError::InvalidAmplitude {
                    index: i,
                    value: a,
                    threshold: f64::NEG_INFINITY,
                });
            }
            if best.is_none_or(|(_, _, _, b)| a > b) {
                best = Some((i, innov.residual, innov.nis, a));
            }
            Ok(())
        })?;
        single_plot_outcome(predicted, mp, best.map(|(i, r, d, _)| (i, r, d)), gated)
    }
}

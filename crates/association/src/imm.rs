//! IMM with data association in clutter (IMM-PDA, IMM-PSN, …).

use argus_core_math::Gaussian;
use argus_filters::GaussianFilter;
use argus_imm::{ImmEstimate, ImmPrediction, log_sum_exp};
use argus_sensors::MeasurementModel;

use crate::associator::{Associator, Candidate};
use crate::error::AssociationError;

/// The update of an IMM with an association filter: each mode's prediction (from
/// [`argus_imm::Imm::predict`]) is associated and updated with `assoc` on its own
/// measurement prediction, and the mode probabilities are
/// `μ_j ∝ c̄_j Λ_j` with `Λ_j` the association filter's likelihood of the scan
/// ([`crate::Outcome::log_likelihood`]) — IMM-PDA when `assoc` is a [`crate::Pda`].
///
/// Returns the updated estimate and each mode's outcome log-likelihood.
///
/// # References
/// Bar-Shalom, Li & Kirubarajan (2001), §11.6.6 (IMM-PDAF); seed 002 issue 5.
///
/// # Errors
/// [`AssociationError::Filter`] for a failed measurement prediction (naming no mode:
/// the first failure is returned), association errors, [`AssociationError::NoLikelihood`]
/// when every mode's likelihood is zero; the prediction is never modified.
pub fn imm_associate<const N: usize, const M: usize, const R: usize, F, A, Me>(
    filters: &[F; R],
    assoc: &A,
    meas: &Me,
    pred: &ImmPrediction<N, R>,
    plots: &[Candidate<M>],
) -> Result<(ImmEstimate<N, R>, [f64; R]), AssociationError>
where
    F: GaussianFilter<N>,
    A: Associator,
    Me: MeasurementModel<N, M>,
{
    let mut modes: [Gaussian<N>; R] = *pred.modes();
    let mut ll = [f64::NEG_INFINITY; R];
    for ((f, g), l) in filters.iter().zip(modes.iter_mut()).zip(ll.iter_mut()) {
        let mp = f.predict_measurement(g, meas)?;
        let out = assoc.associate(g, &mp, meas, plots)?;
        *g = out.posterior;
        *l = out.log_likelihood;
    }
    let mut joint = *pred.log_predicted_probabilities();
    for (j, l) in joint.iter_mut().zip(ll.iter()) {
        *j += l;
    }
    let total = log_sum_exp(&joint);
    if !total.is_finite() {
        return Err(AssociationError::NoLikelihood);
    }
    let mu = joint.map(|v| (v - total).exp());
    Ok((ImmEstimate::new(modes, mu)?, ll))
}

//! The common interface of the data-association filters.

use argus_core_math::{Gaussian, Vector};
use argus_filters::{GaussianFilter, Innovation, MeasurementPrediction};
use argus_sensors::MeasurementModel;

use crate::error::AssociationError;
use crate::gate::Gate;

/// A plot offered to an association filter: its measurement and, if the radar
/// reports one, its normalised amplitude.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Candidate<const M: usize> {
    /// The measured value.
    pub z: Vector<M>,
    /// Normalised amplitude (needed by SN and PSN).
    pub amplitude: Option<f64>,
}

impl<const M: usize> Candidate<M> {
    /// A plot without amplitude.
    #[must_use]
    pub fn new(z: Vector<M>) -> Self {
        Self { z, amplitude: None }
    }

    /// A plot with amplitude `a`.
    #[must_use]
    pub fn with_amplitude(z: Vector<M>, a: f64) -> Self {
        Self {
            z,
            amplitude: Some(a),
        }
    }
}

/// The result of one association update.
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome<const N: usize> {
    /// The posterior estimate.
    pub posterior: Gaussian<N>,
    /// Number of plots inside the gate.
    pub gated: usize,
    /// Index (into the plots given) of the plot used, for single-plot filters.
    pub used: Option<usize>,
    /// Probability that no gated plot (PDA) or that the used plot is not the
    /// target's (PSN; 1 when nothing is gated); 0 for NN and SN with a plot.
    pub miss_probability: f64,
    /// `ln` of the likelihood of the plots given this filter's prediction, up to a
    /// factor common to every model fed the same plots (for IMM mode probabilities).
    /// `−∞` when the plots are impossible under the model (e.g. no clutter and no
    /// detection where `P_D = 1`).
    pub log_likelihood: f64,
}

/// A data-association filter: turns the predicted estimate, its measurement prediction
/// (from any [`GaussianFilter`]) and the plots of one scan into a posterior.
///
/// Implemented by [`crate::NearestNeighbour`], [`crate::StrongestNeighbour`],
/// [`crate::Psn`] and [`crate::Pda`]; the IMM-PDA calls it once per mode.
pub trait Associator {
    /// The validation gate.
    fn gate(&self) -> &Gate;

    /// Updates `predicted` with the plots `plots`, using the measurement prediction `mp`
    /// that the filter computed once for this step.
    ///
    /// # Errors
    /// [`AssociationError::DimensionMismatch`] when the gate is for another dimension;
    /// [`AssociationError::Filter`] for a non-finite plot or a non-PD posterior;
    /// amplitude errors for filters that need amplitudes. `predicted` is never modified.
    fn associate<const N: usize, const M: usize, Me: MeasurementModel<N, M>>(
        &self,
        predicted: &Gaussian<N>,
        mp: &MeasurementPrediction<N, M>,
        meas: &Me,
        plots: &[Candidate<M>],
    ) -> Result<Outcome<N>, AssociationError>;
}

/// One full step: predict `prior` over `dt` with `filter`, predict the measurement,
/// then associate and update with `assoc`.
///
/// # Errors
/// As [`GaussianFilter::predict`], [`GaussianFilter::predict_measurement`] and
/// [`Associator::associate`]; `prior` is never modified.
pub fn track_step<const N: usize, const M: usize, F, A, Me>(
    filter: &F,
    assoc: &A,
    meas: &Me,
    prior: &Gaussian<N>,
    dt: f64,
    plots: &[Candidate<M>],
) -> Result<Outcome<N>, AssociationError>
where
    F: GaussianFilter<N>,
    A: Associator,
    Me: MeasurementModel<N, M>,
{
    let predicted = filter.predict(prior, dt)?;
    let mp = filter.predict_measurement(&predicted, meas)?;
    assoc.associate(&predicted, &mp, meas, plots)
}

/// Calls `f(index, innovation, plot)` for every plot inside `gate`, validating every
/// plot (finite values) whether gated or not. Returns the number gated.
pub(crate) fn for_each_gated<const N: usize, const M: usize, Me, Fn>(
    gate: &Gate,
    mp: &MeasurementPrediction<N, M>,
    meas: &Me,
    plots: &[Candidate<M>],
    mut f: Fn,
) -> Result<usize, AssociationError>
where
    Me: MeasurementModel<N, M>,
    Fn: FnMut(usize, &Innovation<M>, &Candidate<M>) -> Result<(), AssociationError>,
{
    gate.check_dim::<M>()?;
    let mut count = 0;
    for (i, c) in plots.iter().enumerate() {
        let innov = mp.innovation(meas, &c.z)?;
        if gate.contains(innov.nis) {
            count += 1;
            f(i, &innov, c)?;
        }
    }
    Ok(count)
}

/// `x⁻ + K ν` with the covariance `cov`, checked.
pub(crate) fn gaussian_checked<const N: usize>(
    mean: Vector<N>,
    cov: &argus_core_math::Matrix<N, N>,
) -> Result<Gaussian<N>, AssociationError> {
    argus_core_math::check_finite_vector(&mean, "posterior mean")?;
    Ok(Gaussian::from_symmetrized(mean, cov)?)
}

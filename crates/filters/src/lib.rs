//! Kalman-type filters on stack matrices.
//!
//! Filters hold models, never track state: a [`Gaussian`] estimate goes in and a
//! new one comes out. Every filter implements [`GaussianFilter`]; a step
//! predicts, then computes the [`MeasurementPrediction`] once (predicted
//! measurement, innovation covariance `S` and its Cholesky factor, cross
//! covariance, gain) and reuses it for the gate test, the log-likelihood and the
//! update of any number of candidate plots.
//!
//! A failed step returns a typed [`FilterError`] and leaves the estimate passed
//! in untouched (it is borrowed, never mutated).

mod error;
mod prediction;

pub use error::{FilterError, check_dt};
pub use prediction::{CovarianceForm, Innovation, MeasurementPrediction};

use argus_core_math::{Gaussian, Vector};
use argus_sensors::MeasurementModel;

/// A Gaussian (Kalman-type) filter for an `N`-dimensional state.
pub trait GaussianFilter<const N: usize> {
    /// Predicts `prior` over `dt` seconds.
    ///
    /// # Errors
    /// [`FilterError::InvalidInterval`] when `dt` is not finite and positive; a
    /// non-finite or non-positive-definite result is reported, never returned.
    fn predict(&self, prior: &Gaussian<N>, dt: f64) -> Result<Gaussian<N>, FilterError>;

    /// Predicts the measurement of `meas` from the predicted state: `ẑ`, `S`, its
    /// factor, the cross covariance and the gain.
    ///
    /// # Errors
    /// [`FilterError::Math`] when `S` is not positive definite or a value is non-finite.
    fn predict_measurement<const M: usize, Me: MeasurementModel<N, M>>(
        &self,
        predicted: &Gaussian<N>,
        meas: &Me,
    ) -> Result<MeasurementPrediction<N, M>, FilterError>;

    /// Updates `predicted` with the plot `z`: the innovation is computed once and returned
    /// with the posterior.
    ///
    /// # Errors
    /// As [`GaussianFilter::predict_measurement`], and [`FilterError::Math`] for a non-finite `z`.
    fn update<const M: usize, Me: MeasurementModel<N, M>>(
        &self,
        predicted: &Gaussian<N>,
        meas: &Me,
        z: &Vector<M>,
    ) -> Result<(Gaussian<N>, Innovation<M>), FilterError> {
        let mp = self.predict_measurement(predicted, meas)?;
        let innov = mp.innovation(meas, z)?;
        let post = mp.update(predicted, &innov.residual)?;
        Ok((post, innov))
    }
}

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
//!
//! - [`Kf`]: linear Kalman filter, standard or Joseph covariance update.
//! - [`Ekf`]: extended Kalman filter; [`SecondOrderEkf`]: truncated second-order EKF.
//! - [`CdEkf`]: continuous–discrete EKF (RK4 moment equations, optional second order).
//! - [`Ukf`]: unscented Kalman filter (scaled unscented transform, allocation-free).
//! - [`two_point_cv1`], [`two_point_cv2`], [`two_point_cv3`]: two-point initiation.
//! - [`nees`], [`ChiSquareAverage`]: NEES/NIS consistency with chi-square bounds.
//! - [`RtsTrack`], [`rts_smooth`]: fixed-interval RTS smoothing (KF, EKF) and the unscented
//!   RTS smoother (UKF) from a recorded forward pass ([`SmoothingFilter`]);
//!   [`FixedLagSmoother`]: fixed-lag smoothing ([`Lag`] in steps or seconds); the
//!   equations and references are in [`smooth`].

mod cd_ekf;
mod consistency;
mod ekf;
mod error;
mod init;
mod kf;
mod linearized;
mod prediction;
mod second_order;
pub mod smooth;
mod ukf;

#[cfg(test)]
mod test_models;

pub use cd_ekf::{CdEkf, MAX_SUBSTEPS};
pub use consistency::{ChiSquareAverage, nees};
pub use ekf::{Ekf, SecondOrderEkf};
pub use error::{FilterError, check_dt};
pub use init::{two_point_cv1, two_point_cv2, two_point_cv3};
pub use kf::Kf;
pub use prediction::{CovarianceForm, Innovation, MeasurementPrediction};
pub use second_order::second_order_terms;
pub use smooth::{
    FixedLagSmoother, Lag, Lagged, RtsStep, RtsTrack, SmoothError, SmoothingFilter, Transition,
    rts_smooth, rts_smooth_into, rts_step, rts_step_across,
};
pub use ukf::{Ukf, UtParams};

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

    /// [`GaussianFilter::predict`] in place: `estimate` becomes the prediction, and is left
    /// unchanged on an error. The filters of this crate that can write their result
    /// straight into `estimate` do (no `Result` holding a whole Gaussian is copied out).
    ///
    /// # Errors
    /// As [`GaussianFilter::predict`].
    #[inline(always)]
    fn predict_in_place(&self, estimate: &mut Gaussian<N>, dt: f64) -> Result<(), FilterError> {
        *estimate = self.predict(estimate, dt)?;
        Ok(())
    }

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
    #[inline(always)]
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

    /// [`GaussianFilter::update`] in place: `estimate` (the prediction) becomes the
    /// posterior, and is left unchanged on an error; returns the innovation.
    ///
    /// # Errors
    /// As [`GaussianFilter::update`].
    #[inline(always)]
    fn update_in_place<const M: usize, Me: MeasurementModel<N, M>>(
        &self,
        estimate: &mut Gaussian<N>,
        meas: &Me,
        z: &Vector<M>,
    ) -> Result<Innovation<M>, FilterError> {
        let mp = self.predict_measurement(estimate, meas)?;
        let innov = mp.innovation(meas, z)?;
        mp.update_in_place(estimate, &innov.residual)?;
        Ok(innov)
    }

    /// One cycle in place, for a caller that keeps only the posterior (an IMM's mode): the
    /// prediction over `dt`, then the update with `z`; returns the innovation. On an error
    /// `estimate` is a valid Gaussian but unspecified (the prior or the prediction): callers
    /// work on a copy. The default is [`GaussianFilter::predict_in_place`] then
    /// [`GaussianFilter::update_in_place`]; [`Kf`] checks its intermediate prediction for
    /// finiteness only (see there), the posterior fully.
    ///
    /// # Errors
    /// As [`GaussianFilter::predict`] and [`GaussianFilter::update`].
    #[inline(always)]
    fn step_in_place<const M: usize, Me: MeasurementModel<N, M>>(
        &self,
        estimate: &mut Gaussian<N>,
        dt: f64,
        meas: &Me,
        z: &Vector<M>,
    ) -> Result<Innovation<M>, FilterError> {
        self.predict_in_place(estimate, dt)?;
        self.update_in_place(estimate, meas, z)
    }
}

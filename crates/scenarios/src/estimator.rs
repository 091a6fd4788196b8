//! Estimator wiring shared by the scenarios and the command's `argus track`: the Kalman
//! filter on the 2-D constant-velocity model (DWNA noise) with converted plots, the
//! unbiased polar conversion and one predict + update step.

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{GaussianFilter, Innovation, Kf};
use argus_motion_models::Cv2D;
use argus_sensors::{
    CartesianPosition, ConversionMethod, MeasurementModel, SensorError, convert_polar,
};

/// KF on the 2-D CV model `[x, vx, y, vy]`, `Q = σ² Γ Γᵀ` (seed 000).
pub type CvKf = Kf<Cv2D>;

/// A KF on a 2-D CV model with white-acceleration σ `sigma_a` (m/s²).
///
/// # Errors
/// The model's error for a negative or non-finite σ.
pub fn cv_kf(sigma_a: f64) -> Result<CvKf, argus_motion_models::MotionError> {
    Ok(Kf::new(Cv2D::discrete(sigma_a)?))
}

/// The unbiased converted measurement of a polar plot (relative to its sensor) and its
/// covariance (Mo Longbin et al. 1998; Bar-Shalom, Li & Kirubarajan 2001 §10.4.3).
///
/// # Errors
/// The sensor crate's error for a non-positive range or a bad σ.
pub fn unbiased(
    range: f64,
    azimuth: f64,
    sigma_r: f64,
    sigma_az: f64,
) -> Result<(Vector<2>, Matrix<2, 2>), SensorError> {
    let c = convert_polar(
        range,
        azimuth,
        sigma_r,
        sigma_az,
        ConversionMethod::Unbiased,
    )?;
    Ok((c.position, c.covariance))
}

/// Position measurement `(x, y)` of `[x, vx, y, vy]` with covariance `r`.
///
/// # Errors
/// The sensor crate's error for a covariance that is not SPD.
pub fn position(r: Matrix<2, 2>) -> Result<CartesianPosition<4, 2>, SensorError> {
    CartesianPosition::<4, 2>::cv(r)
}

/// Predicts over `dt` (skipped when `dt = 0`, plots of one instant) and updates with `z`.
///
/// # Errors
/// The filter's error.
pub fn step<const N: usize, const M: usize, F: GaussianFilter<N>, Me: MeasurementModel<N, M>>(
    filter: &F,
    est: &Gaussian<N>,
    dt: f64,
    meas: &Me,
    z: &Vector<M>,
) -> Result<(Gaussian<N>, Innovation<M>), argus_filters::FilterError> {
    let pred = if dt == 0.0 {
        *est
    } else {
        filter.predict(est, dt)?
    };
    filter.update(&pred, meas, z)
}

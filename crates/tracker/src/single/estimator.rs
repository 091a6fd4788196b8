//! The estimators the engine builds from the foundation crates: Kalman filters on the
//! 2-D and 3-D constant-velocity models (DWNA noise) with converted plots, EKFs on polar
//! and spherical plots, the unbiased conversions and one predict + update step. The 2-D
//! KF, the polar conversion, the position measurement and the step are public (the
//! scenarios' `argus_scenarios::estimator` re-exports them).

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{Ekf, FilterError, GaussianFilter, Innovation, Kf};
use argus_motion_models::{Cv2D, Cv3D, MotionError};
use argus_sensors::{
    CartesianPosition, ConversionMethod, MeasurementModel, Polar2D, RadarNoise, SensorError,
    Spherical3D, convert_polar, convert_spherical,
};

/// A KF on a 2-D CV model with white-acceleration σ `sigma_a` (m/s²).
///
/// # Errors
/// The model's error for a negative or non-finite σ.
pub fn cv_kf(sigma_a: f64) -> Result<Kf<Cv2D>, MotionError> {
    Ok(Kf::new(Cv2D::discrete(sigma_a)?))
}

/// An EKF on a 2-D CV model with white-acceleration σ `sigma_a` (m/s²).
pub(super) fn cv_ekf(sigma_a: f64) -> Result<Ekf<Cv2D>, MotionError> {
    Ok(Ekf::new(Cv2D::discrete(sigma_a)?))
}

/// A KF on a 3-D CV model `[x, vx, y, vy, z, vz]` (DWNA noise per axis).
pub(super) fn cv3_kf(sigma_a: f64) -> Result<Kf<Cv3D>, MotionError> {
    Ok(Kf::new(Cv3D::discrete(sigma_a)?))
}

/// An EKF on a 3-D CV model.
pub(super) fn cv3_ekf(sigma_a: f64) -> Result<Ekf<Cv3D>, MotionError> {
    Ok(Ekf::new(Cv3D::discrete(sigma_a)?))
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

/// The unbiased converted measurement of a spherical plot (relative to its sensor) and
/// its covariance: Mo Longbin et al.'s (1998) construction in three dimensions
/// (`argus_sensors::convert_spherical`).
pub(super) fn unbiased3(
    range: f64,
    azimuth: f64,
    elevation: f64,
    sigmas: [f64; 3],
) -> Result<(Vector<3>, Matrix<3, 3>), SensorError> {
    let c = convert_spherical(
        range,
        azimuth,
        elevation,
        sigmas,
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

/// Position measurement `(x, y, z)` of `[x, vx, y, vy, z, vz]` with covariance `r`.
pub(super) fn position3(r: Matrix<3, 3>) -> Result<CartesianPosition<6, 3>, SensorError> {
    CartesianPosition::<6, 3>::cv(r)
}

/// Spherical radar at `sensor` with constant σ (range m, azimuth and elevation rad).
pub(super) fn spherical(sensor: [f64; 3], sigmas: [f64; 3]) -> Result<Spherical3D<6>, SensorError> {
    Spherical3D::<6>::cv(
        sensor,
        RadarNoise::constant(sigmas[0], sigmas[1], sigmas[2])?,
    )
}

/// Polar radar at `sensor` with constant σ (range m, azimuth rad).
pub(super) fn polar(
    sensor: [f64; 2],
    sigma_r: f64,
    sigma_az: f64,
) -> Result<Polar2D<4>, SensorError> {
    Polar2D::<4>::cv(sensor, RadarNoise::constant(sigma_r, sigma_az, 0.0)?)
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
) -> Result<(Gaussian<N>, Innovation<M>), FilterError> {
    let pred = if dt == 0.0 {
        *est
    } else {
        filter.predict(est, dt)?
    };
    filter.update(&pred, meas, z)
}

//! The estimators the command builds from the foundation crates: Kalman filters on the
//! 2-D and 3-D constant-velocity models (DWNA noise) with converted plots, EKFs on polar
//! and spherical plots, the unbiased conversions and one predict + update step. The 2-D KF,
//! the polar conversion and the step are the scenarios' (`argus_scenarios::estimator`).

use argus_core_math::{Matrix, Vector};
use argus_filters::{Ekf, Kf};
use argus_motion_models::{Cv2D, Cv3D};
use argus_sensors::{
    CartesianPosition, ConversionMethod, Polar2D, RadarNoise, Spherical3D, convert_spherical,
};

use crate::error::CliError;

pub(crate) use argus_scenarios::estimator::{cv_kf, position, step, unbiased};

/// EKF on the 2-D CV model (for polar plots).
pub(crate) type CvEkf = Ekf<Cv2D>;

/// An EKF on a 2-D CV model with white-acceleration σ `sigma_a` (m/s²).
///
/// # Errors
/// The model's error for a negative or non-finite σ.
pub(crate) fn cv_ekf(sigma_a: f64) -> Result<CvEkf, CliError> {
    Ok(Ekf::new(Cv2D::discrete(sigma_a)?))
}

/// KF on the 3-D CV model `[x, vx, y, vy, z, vz]` (DWNA noise per axis).
pub(crate) type Cv3Kf = Kf<Cv3D>;
/// EKF on the same model (for spherical plots).
pub(crate) type Cv3Ekf = Ekf<Cv3D>;

/// A KF on a 3-D CV model with white-acceleration σ `sigma_a` (m/s²).
///
/// # Errors
/// As [`cv_kf`].
pub(crate) fn cv3_kf(sigma_a: f64) -> Result<Cv3Kf, CliError> {
    Ok(Kf::new(Cv3D::discrete(sigma_a)?))
}

/// An EKF on a 3-D CV model.
///
/// # Errors
/// As [`cv_kf`].
pub(crate) fn cv3_ekf(sigma_a: f64) -> Result<Cv3Ekf, CliError> {
    Ok(Ekf::new(Cv3D::discrete(sigma_a)?))
}

/// The unbiased converted measurement of a spherical plot (relative to its sensor) and
/// its covariance: Mo Longbin et al.'s (1998) construction in three dimensions
/// (`argus_sensors::convert_spherical`).
///
/// # Errors
/// The sensor crate's error for a non-positive range or a bad σ.
pub(crate) fn unbiased3(
    range: f64,
    azimuth: f64,
    elevation: f64,
    sigmas: [f64; 3],
) -> Result<(Vector<3>, Matrix<3, 3>), CliError> {
    let c = convert_spherical(
        range,
        azimuth,
        elevation,
        sigmas,
        ConversionMethod::Unbiased,
    )?;
    Ok((c.position, c.covariance))
}

/// Position measurement `(x, y, z)` of `[x, vx, y, vy, z, vz]` with covariance `r`.
///
/// # Errors
/// The sensor crate's error for a covariance that is not SPD.
pub(crate) fn position3(r: Matrix<3, 3>) -> Result<CartesianPosition<6, 3>, CliError> {
    Ok(CartesianPosition::<6, 3>::cv(r)?)
}

/// Spherical radar at `sensor` with constant σ (range m, azimuth and elevation rad).
///
/// # Errors
/// The sensor crate's error for bad values.
pub(crate) fn spherical(sensor: [f64; 3], sigmas: [f64; 3]) -> Result<Spherical3D<6>, CliError> {
    Ok(Spherical3D::<6>::cv(
        sensor,
        RadarNoise::constant(sigmas[0], sigmas[1], sigmas[2])?,
    )?)
}

/// Polar radar at `sensor` with constant σ (range m, azimuth rad).
///
/// # Errors
/// The sensor crate's error for bad values.
pub(crate) fn polar(sensor: [f64; 2], sigma_r: f64, sigma_az: f64) -> Result<Polar2D<4>, CliError> {
    Ok(Polar2D::<4>::cv(
        sensor,
        RadarNoise::constant(sigma_r, sigma_az, 0.0)?,
    )?)
}

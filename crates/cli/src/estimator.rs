//! The estimators the command builds from the foundation crates: Kalman filters on the
//! 2-D and 3-D constant-velocity models (DWNA noise) with converted plots, EKFs on polar
//! and spherical plots, the unbiased conversions, one predict + update step, and the IMM of
//! a configuration (fixed-rate CT and CV modes). The 2-D KF, the polar conversion and the
//! step are the scenarios' (`argus_scenarios::estimator`).

use argus_core_math::{Matrix, Vector};
use argus_filters::{Ekf, Kf};
use argus_imm::{Imm, ImmError, MarkovMatrix};
use argus_motion_models::{Cv2D, Cv3D, PlanarModel};
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

/// The largest number of motion models an `argus track` IMM may have (the mode count is a
/// compile-time size; 1 … 5 are built).
pub(crate) const MAX_MODELS: usize = 5;

/// A validated IMM description: one planar motion model per mode, the Markov matrix (rows
/// of `models.len()` entries) and the initial mode probabilities.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ImmSpec {
    /// The mode-matched models (CV or fixed-rate CT), each in a Kalman filter.
    pub(crate) models: Vec<PlanarModel>,
    /// `π_ij`, row by row.
    pub(crate) markov: Vec<Vec<f64>>,
    /// `μ₀`.
    pub(crate) initial: Vec<f64>,
}

/// The multi-IMM's parameters (seed 000 eqs (12)–(14), generalised).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct MultiSpec {
    /// Hypotheses per axis (`n` IMMs with one common scale, `n²` with `per_axis`).
    pub(crate) n: usize,
    /// Grid spacing `p`.
    pub(crate) p: f64,
    /// Per-step clip of the reference's relative change (`None`: unclipped).
    pub(crate) clip: Option<f64>,
    /// Range and azimuth variances on an independent `n × n` grid.
    pub(crate) per_axis: bool,
}

/// The IMM of `spec` with `R` modes (`R = spec.models.len()`), Kalman filters on converted
/// plots.
///
/// # Errors
/// [`CliError::Imm`] for an invalid Markov matrix or a mode count other than `R`.
pub(crate) fn build_imm<const R: usize>(
    spec: &ImmSpec,
) -> Result<Imm<Kf<PlanarModel>, 4, R>, CliError> {
    let filters: [Kf<PlanarModel>; R] = spec
        .models
        .iter()
        .map(|m| Kf::new(*m))
        .collect::<Vec<_>>()
        .try_into()
        .map_err(|_| ImmError::Empty {
            what: "IMM modes (count mismatch)",
        })?;
    let rows: [[f64; R]; R] = std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            spec.markov
                .get(i)
                .and_then(|r| r.get(j))
                .copied()
                .unwrap_or(f64::NAN)
        })
    });
    Ok(Imm::new(filters, MarkovMatrix::new(rows)?)?)
}

/// The initial mode probabilities of `spec` as an array.
pub(crate) fn initial_probabilities<const R: usize>(spec: &ImmSpec) -> [f64; R] {
    std::array::from_fn(|j| spec.initial.get(j).copied().unwrap_or(f64::NAN))
}

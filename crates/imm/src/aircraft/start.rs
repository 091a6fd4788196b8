//! Two-point start of the aircraft IMM with a turn-rate prior for the CT mode.

use argus_core_math::{Gaussian, Vector};
use argus_filters::{FilterError, two_point_cv2};

use super::estimate::AircraftEstimate;
use super::mixing::augmented;
use super::radar::AircraftRadar;
use crate::ImmError;
use crate::error::check_positive;

/// Two-point differencing from two plots `z1`, `z2` (`[r, θ]`, `dt` seconds apart) of
/// `radar`, at the time of `z2`.
///
/// Each plot is converted to a global position `zₖ` with covariance `Rₖ` by the unbiased
/// conversion (Mo et al. 1998); then `x = z₂`, `v = (z₂ − z₁)/T`, with
/// `P[p,p] = R₂`, `P[p,v] = R₂/T`, `P[v,v] = (R₁ + R₂)/T²` per axis pair
/// (Bar-Shalom, Li & Kirubarajan 2001, §5.5.3; [`two_point_cv2`]). Every CV mode starts
/// from it; the CT mode from it extended by a turn rate `ω ~ N(0, sigma_omega²)`,
/// independent of the kinematic part (two plots say nothing about the turn rate). The
/// mode probabilities start at `mu` (CV modes, then CT).
///
/// # Errors
/// [`ImmError::InvalidParameter`] for a bad plot or `sigma_omega` not finite and
/// positive; [`ImmError::InvalidInterval`] for `dt` not finite and positive;
/// [`ImmError::Sensor`] from the conversion; [`ImmError::Math`] for a covariance that is
/// not positive definite; [`ImmError::InvalidProbabilities`] for a bad `mu`.
pub fn two_point_start<const C: usize, const R: usize>(
    radar: &AircraftRadar,
    z1: &Vector<2>,
    z2: &Vector<2>,
    dt: f64,
    sigma_omega: f64,
    mu: [f64; R],
) -> Result<AircraftEstimate<C, R>, ImmError> {
    check_positive("start turn-rate sigma", sigma_omega)?;
    let (p1, r1) = radar.convert(z1)?;
    let (p2, r2) = radar.convert(z2)?;
    let cv = two_point_cv2(&p1, &r1, &p2, &r2, dt).map_err(|e| match e {
        FilterError::InvalidInterval { dt } => ImmError::InvalidInterval { dt },
        FilterError::Math(m) => ImmError::Math(m),
        other => ImmError::Filter {
            mode: 0,
            source: other,
        },
    })?;
    start_from_cv(&cv, sigma_omega, mu)
}

/// The start from a two-point CV estimate `cv` already made (e.g. by a tracker's
/// initiation from the same converted plots): every CV mode starts at `cv`, the CT mode
/// at `cv` extended by `ω ~ N(0, sigma_omega²)`, independent of the kinematic part; mode
/// probabilities `mu`. [`two_point_start`] is this after its own differencing.
///
/// # Errors
/// [`ImmError::InvalidParameter`] for `sigma_omega` not finite and positive;
/// [`ImmError::Math`] for a covariance that is not positive definite;
/// [`ImmError::InvalidProbabilities`] for a bad `mu`.
pub fn start_from_cv<const C: usize, const R: usize>(
    cv: &Gaussian<4>,
    sigma_omega: f64,
    mu: [f64; R],
) -> Result<AircraftEstimate<C, R>, ImmError> {
    check_positive("start turn-rate sigma", sigma_omega)?;
    let ct = augmented(cv, 0.0, sigma_omega * sigma_omega)?;
    AircraftEstimate::new([*cv; C], ct, mu)
}

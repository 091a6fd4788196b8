//! What a scan makes of the plots it is given ([`argus_sensors::Plot`]: 2-D Cartesian
//! or polar), and the configured sensors they come from.

use argus_core_math::{Matrix, Vector};
use argus_imm::{AircraftRadar, NoiseVariances, UnbiasedConversion};
use argus_sensors::{
    CartesianPosition, ConversionMethod, Measurement, Plot, Polar2D, RadarNoise, SensorId, Sigmas,
    convert_polar,
};

use crate::field::{ConfigField, SensorField};
use crate::{SensorConfig, TrackerError};

/// A checked plot of the scan: its global Cartesian position and covariance (converted
/// once for a polar plot), the linear measurement model, and the raw `(r, θ)` when polar.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ScanPoint {
    pub(crate) position: Vector<2>,
    pub(crate) covariance: Matrix<2, 2>,
    pub(crate) model: CartesianPosition<4, 2>,
    pub(crate) polar: Option<Vector<2>>,
}

/// A configured sensor with what its polar plots need, built once.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SensorModel {
    pub(crate) id: SensorId,
    pub(crate) position: Vector<2>,
    pub(crate) polar: Option<PolarModel>,
}

/// A polar sensor's models.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PolarModel {
    /// `(σ_r, σ_θ)`.
    pub(crate) sigmas: [f64; 2],
    /// The EKF's measurement model at the sensor.
    pub(crate) model: Polar2D<4>,
    /// The multi-IMM's conversion at the sensor.
    pub(crate) conversion: UnbiasedConversion<4>,
    /// The configured variances (the multi-IMM's starting reference).
    pub(crate) reference: NoiseVariances,
    /// `1/λ − 1`, `λ = e^{−σ_θ²/2}`: how far (relative to the range) the unbiased
    /// conversion moves a plot outwards.
    pub(crate) conversion_stretch: f64,
    /// The aircraft IMM's measurement models at the sensor (both state sizes).
    pub(crate) aircraft: AircraftRadar,
}

/// Whether an estimator takes Cartesian plots, and if not, its name for the error.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum CartesianPlots {
    /// Cartesian plots are used as they are.
    Accepted,
    /// Only polar plots: the estimator's name.
    Refused(&'static str),
}

impl SensorModel {
    pub(crate) fn new(cfg: &SensorConfig) -> Result<Self, TrackerError> {
        let position = Vector::<2>::new(cfg.position[0], cfg.position[1]);
        let polar = match cfg.polar_noise {
            None => None,
            Some(n) => {
                let bad = |reason| TrackerError::InvalidConfig {
                    field: ConfigField::Sensor(SensorField::PolarNoise),
                    value: n.sigma_azimuth,
                    reason,
                };
                let sig = Sigmas::polar(n.sigma_range, n.sigma_azimuth)
                    .map_err(|_| bad("not valid standard deviations"))?;
                let model = Polar2D::<4>::cv(cfg.position, RadarNoise::Constant(sig))
                    .map_err(|_| bad("the polar model rejected it"))?;
                let conversion = UnbiasedConversion::<4>::new(0, 2)
                    .and_then(|c| c.at(cfg.position))
                    .map_err(|_| bad("the conversion rejected it"))?;
                let reference = NoiseVariances::from_sigmas(n.sigma_range, n.sigma_azimuth)
                    .map_err(|_| bad("not valid standard deviations"))?;
                let aircraft = AircraftRadar::new(cfg.position, RadarNoise::Constant(sig))
                    .map_err(|_| bad("the aircraft IMM's polar model rejected it"))?;
                Some(PolarModel {
                    sigmas: [n.sigma_range, n.sigma_azimuth],
                    model,
                    conversion,
                    reference,
                    conversion_stretch: (0.5 * n.sigma_azimuth * n.sigma_azimuth).exp() - 1.0,
                    aircraft,
                })
            }
        };
        Ok(Self {
            id: cfg.id,
            position,
            polar,
        })
    }

    /// Checks one plot of this sensor (time and order already checked) and makes its scan
    /// point; `cartesian` says whether the estimator takes Cartesian plots.
    pub(crate) fn point(
        &self,
        index: usize,
        plot: &Plot,
        cartesian: CartesianPlots,
    ) -> Result<ScanPoint, TrackerError> {
        // The plot's values are finite and its covariance positive definite by
        // construction (argus_sensors::Plot); what is checked here is what the tracker
        // needs beyond that.
        let (time, sensor) = (plot.time(), plot.sensor());
        let (position, covariance, polar) = match plot.measurement() {
            Measurement::Cartesian2(c) => {
                if let CartesianPlots::Refused(estimator) = cartesian {
                    return Err(TrackerError::NotPolar {
                        index,
                        time,
                        sensor,
                        estimator,
                    });
                }
                (*c.position(), *c.covariance(), None)
            }
            Measurement::Polar(m) => {
                let (range, azimuth) = (m.range(), m.azimuth());
                if range <= 0.0 {
                    return Err(TrackerError::NonPositiveRange {
                        index,
                        time,
                        sensor,
                        range,
                    });
                }
                let Some(pm) = &self.polar else {
                    return Err(TrackerError::NoPolarNoise {
                        index,
                        time,
                        sensor,
                    });
                };
                let c = convert_polar(
                    range,
                    azimuth,
                    pm.sigmas[0],
                    pm.sigmas[1],
                    ConversionMethod::Unbiased,
                )
                .map_err(|source| TrackerError::Conversion {
                    index,
                    time,
                    sensor,
                    source,
                })?;
                (
                    c.position + self.position,
                    c.covariance,
                    Some(Vector::<2>::new(range, azimuth)),
                )
            }
            Measurement::Spherical(_) | Measurement::Cartesian3(_) => {
                return Err(TrackerError::NotPlanar {
                    index,
                    time,
                    sensor,
                });
            }
        };
        let model = CartesianPosition::<4, 2>::cv(covariance).map_err(|source| {
            TrackerError::PlotCovariance {
                index,
                time,
                sensor,
                source,
            }
        })?;
        Ok(ScanPoint {
            position,
            covariance,
            model,
            polar,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::innovation::polar_half;
    use argus_core_math::Gaussian;
    use argus_filters::{Ekf, GaussianFilter};
    use argus_motion_models::Cv2D;
    use rand::RngExt;

    #[test]
    fn the_ekf_query_box_holds_its_polar_gate_as_converted_plots() {
        // Claim of `polar_half`: every plot inside the EKF's gate νᵀ S⁻¹ ν ≤ γ, once
        // converted (unbiased) and placed at the sensor, lies in the square box of that
        // half-width around the predicted position. Checked on the gate's boundary (where
        // the extreme points are) for random predictions, with a large σ_θ = 0.03 rad so
        // that the curvature and the conversion's outward stretch matter.
        let gamma = 9.21; // χ²₂ at 0.99
        let cfg = SensorConfig::polar(SensorId(0), [1_000.0, -500.0], 50.0, 0.03);
        let sensor = SensorModel::new(&cfg).unwrap();
        let pm = sensor.polar.unwrap();
        let ekf = Ekf::new(Cv2D::discrete(2.0).unwrap());
        let mut rng = argus_sim::run_rng(90, 0);
        let mut checked = 0;
        for _ in 0..300 {
            let range = 2_000.0 + 48_000.0 * rng.random::<f64>();
            let bearing = std::f64::consts::TAU * rng.random::<f64>();
            let (sx, sy, rho) = (
                50.0 + 3_000.0 * rng.random::<f64>(),
                50.0 + 3_000.0 * rng.random::<f64>(),
                1.8 * rng.random::<f64>() - 0.9,
            );
            let mean = Vector::<4>::new(
                cfg.position[0] + range * bearing.cos(),
                0.0,
                cfg.position[1] + range * bearing.sin(),
                0.0,
            );
            let mut p = Matrix::<4, 4>::identity() * 100.0;
            p[(0, 0)] = sx * sx;
            p[(2, 2)] = sy * sy;
            p[(0, 2)] = rho * sx * sy;
            p[(2, 0)] = rho * sx * sy;
            let pred = Gaussian::new(mean, p).unwrap();
            let mp = ekf.predict_measurement(&pred, &pm.model).unwrap();
            let half = polar_half(&mp, gamma, pm.conversion_stretch);
            let s = mp.s();
            // Cholesky of the 2 × 2 S.
            let l00 = s[(0, 0)].sqrt();
            let l10 = s[(1, 0)] / l00;
            let l11 = (s[(1, 1)] - l10 * l10).sqrt();
            for k in 0..64 {
                let a = std::f64::consts::TAU * f64::from(k) / 64.0;
                let (u0, u1) = (gamma.sqrt() * a.cos(), gamma.sqrt() * a.sin());
                let z = mp.z_pred() + Vector::<2>::new(l00 * u0, l10 * u0 + l11 * u1);
                if z[0] <= 0.0 {
                    continue;
                }
                let plot = Plot::polar(0.0, SensorId(0), z[0], z[1]).unwrap();
                let point = sensor.point(0, &plot, CartesianPlots::Accepted).unwrap();
                let d = point.position - Vector::<2>::new(mean[0], mean[2]);
                assert!(
                    d[0].abs() <= half && d[1].abs() <= half,
                    "offset {d:?} outside ±{half} (range {range})"
                );
                checked += 1;
            }
        }
        assert!(checked > 15_000, "{checked}");
    }
}

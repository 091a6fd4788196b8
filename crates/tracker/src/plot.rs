//! Plots (Cartesian or polar), the sensors they come from, and what a scan makes of them.

use argus_core_math::{Matrix, Vector};
use argus_imm::{NoiseVariances, UnbiasedConversion};
use argus_sensors::{
    CartesianPosition, ConversionMethod, Polar2D, RadarNoise, Sigmas, convert_polar,
};

use crate::{SensorConfig, SensorId, TrackerError};

/// What a plot measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PlotMeasurement {
    /// A global position `(x, y)` (m) with its covariance (m²): finite, symmetric, positive
    /// definite (e.g. a plot converted by the caller).
    Cartesian {
        /// Position `(x, y)` (m).
        position: Vector<2>,
        /// Its covariance (m²).
        covariance: Matrix<2, 2>,
    },
    /// Range (m, positive) and azimuth (rad, counter-clockwise from +x) relative to the
    /// sensor's position, with the sensor's configured polar noise.
    Polar {
        /// Range `r` (m).
        range: f64,
        /// Azimuth `θ` (rad).
        azimuth: f64,
    },
}

/// One plot from one sensor at one time. Build it with [`Plot::cartesian`] or
/// [`Plot::polar`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plot {
    /// Time (s).
    pub time: f64,
    /// The sensor that made it.
    pub sensor: SensorId,
    /// What it measured.
    pub measurement: PlotMeasurement,
}

impl Plot {
    /// A Cartesian plot: global position `(x, y)` (m) and its covariance (m²).
    #[must_use]
    pub fn cartesian(
        time: f64,
        sensor: SensorId,
        position: Vector<2>,
        covariance: Matrix<2, 2>,
    ) -> Self {
        Self {
            time,
            sensor,
            measurement: PlotMeasurement::Cartesian {
                position,
                covariance,
            },
        }
    }

    /// A polar plot: range (m) and azimuth (rad, counter-clockwise from +x) from the
    /// sensor's position.
    #[must_use]
    pub fn polar(time: f64, sensor: SensorId, range: f64, azimuth: f64) -> Self {
        Self {
            time,
            sensor,
            measurement: PlotMeasurement::Polar { range, azimuth },
        }
    }
}

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
}

impl SensorModel {
    pub(crate) fn new(cfg: &SensorConfig) -> Result<Self, TrackerError> {
        let position = Vector::<2>::new(cfg.position[0], cfg.position[1]);
        let polar = match cfg.polar_noise {
            None => None,
            Some(n) => {
                let bad = |reason| TrackerError::InvalidConfig {
                    field: "sensors.polar_noise",
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
                Some(PolarModel {
                    sigmas: [n.sigma_range, n.sigma_azimuth],
                    model,
                    conversion,
                    reference,
                    conversion_stretch: (0.5 * n.sigma_azimuth * n.sigma_azimuth).exp() - 1.0,
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
    /// point; `cartesian_ok` is false for an estimator that needs polar plots.
    pub(crate) fn point(
        &self,
        index: usize,
        plot: &Plot,
        cartesian_ok: bool,
    ) -> Result<ScanPoint, TrackerError> {
        let non_finite = |what| TrackerError::NonFinite {
            index,
            sensor: plot.sensor,
            what,
        };
        let (position, covariance, polar) = match plot.measurement {
            PlotMeasurement::Cartesian {
                position,
                covariance,
            } => {
                if !position.iter().all(|v| v.is_finite()) {
                    return Err(non_finite("position"));
                }
                if !covariance.iter().all(|v| v.is_finite()) {
                    return Err(non_finite("covariance"));
                }
                if !cartesian_ok {
                    return Err(TrackerError::NotPolar {
                        index,
                        time: plot.time,
                        sensor: plot.sensor,
                    });
                }
                (position, covariance, None)
            }
            PlotMeasurement::Polar { range, azimuth } => {
                if !range.is_finite() {
                    return Err(non_finite("range"));
                }
                if !azimuth.is_finite() {
                    return Err(non_finite("azimuth"));
                }
                if range <= 0.0 {
                    return Err(TrackerError::NonPositiveRange {
                        index,
                        time: plot.time,
                        sensor: plot.sensor,
                        range,
                    });
                }
                let Some(pm) = &self.polar else {
                    return Err(TrackerError::NoPolarNoise {
                        index,
                        time: plot.time,
                        sensor: plot.sensor,
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
                    time: plot.time,
                    sensor: plot.sensor,
                    source,
                })?;
                (
                    c.position + self.position,
                    c.covariance,
                    Some(Vector::<2>::new(range, azimuth)),
                )
            }
        };
        let model = CartesianPosition::<4, 2>::cv(covariance).map_err(|source| {
            TrackerError::PlotCovariance {
                index,
                time: plot.time,
                sensor: plot.sensor,
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

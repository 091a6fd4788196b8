//! Sensor descriptions for plot generation: what a sensor measures, with which noise and
//! bias, when it looks, how it detects and what clutter it sees.

use argus_core_math::{Matrix, SpdFactor, Vector};
use argus_sensors::{
    CartesianPosition, MeasurementModel, Polar2D, RadarNoise, SensorId, Spherical3D,
};

use crate::error::{SimError, finite, non_negative, positive, probability};

/// What a sensor measures and its white-noise standard deviations.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum SensorKind {
    /// 2-D radar: range (m) and azimuth (rad, from +x counter-clockwise), relative to the
    /// sensor's position.
    Polar {
        /// Range noise σ (m).
        sigma_range: f64,
        /// Azimuth noise σ (rad).
        sigma_azimuth: f64,
    },
    /// 3-D radar: range, azimuth and elevation (rad, above the horizontal plane).
    Spherical {
        /// Range noise σ (m).
        sigma_range: f64,
        /// Azimuth noise σ (rad).
        sigma_azimuth: f64,
        /// Elevation noise σ (rad).
        sigma_elevation: f64,
    },
    /// A 2-D Cartesian position report `(x, y)` in global coordinates with its covariance.
    Cartesian2d {
        /// Report covariance (m²).
        cov: Matrix<2, 2>,
    },
    /// A 3-D Cartesian position report `(x, y, z)` in global coordinates with its covariance.
    Cartesian3d {
        /// Report covariance (m²).
        cov: Matrix<3, 3>,
    },
}

impl SensorKind {
    /// The measurement dimension (2 or 3).
    #[must_use]
    pub fn dim(&self) -> usize {
        match self {
            Self::Polar { .. } | Self::Cartesian2d { .. } => 2,
            Self::Spherical { .. } | Self::Cartesian3d { .. } => 3,
        }
    }
}

/// Systematic errors of a polar or spherical sensor (seed 004 eq (1)):
/// `r = (1 + ε_r) r_true + b_r + w_r`, `θ = (1 + ε_θ) θ_true + b_θ + w_θ`, and an
/// elevation offset `b_φ`. Ignored by Cartesian sensors. Zero by default.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Bias {
    /// Range offset `b_r` (m).
    pub range_offset: f64,
    /// Azimuth offset `b_θ` (rad).
    pub azimuth_offset: f64,
    /// Elevation offset (rad).
    pub elevation_offset: f64,
    /// Range scale error `ε_r` (dimensionless).
    pub range_scale: f64,
    /// Azimuth scale error `ε_θ` (dimensionless).
    pub azimuth_scale: f64,
}

/// When a sensor produces plots.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Schedule {
    /// Scans at `offset + k · period`, `k = 0, 1, …`: every target is observed at the
    /// scan time.
    Periodic {
        /// Scan period (s).
        period: f64,
        /// Time of scan 0 (s).
        offset: f64,
    },
    /// A beam rotating counter-clockwise at `2π / period` rad/s, at azimuth
    /// `azimuth_at_zero` at `t = 0` (seed 000's scenario): a target is observed when the
    /// beam crosses it, so its sampling interval varies around the period. Revolution `k`
    /// covers `[k · period, (k + 1) · period)`.
    RotatingBeam {
        /// Antenna period (s).
        period: f64,
        /// Beam azimuth at `t = 0` (rad).
        azimuth_at_zero: f64,
    },
}

impl Schedule {
    fn period(&self) -> f64 {
        match *self {
            Self::Periodic { period, .. } | Self::RotatingBeam { period, .. } => period,
        }
    }
}

/// How targets are detected.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Detection {
    /// Each target is detected with this probability; plots carry no amplitude.
    Probability(f64),
    /// Swerling I amplitudes with a detection threshold (Li & Bar-Shalom 1998
    /// convention, envelope normalised to the noise): clutter amplitude pdf
    /// `a exp(−a²/2)`, target amplitude pdf `a/(1+d) exp(−a²/(2(1+d)))` with `d` the
    /// mean SNR; a plot is declared when `a ≥ τ`. Hence `P_D = exp(−τ²/(2(1+d)))` and
    /// `P_FA = exp(−τ²/2)`; clutter plots carry amplitudes drawn above `τ`. The clutter
    /// density is set separately by [`Clutter`].
    Swerling1 {
        /// Mean signal-to-noise ratio of the target (dB).
        snr_db: f64,
        /// Detection threshold `τ` on the normalised amplitude.
        threshold: f64,
    },
}

impl Detection {
    /// The probability that a target is detected.
    #[must_use]
    pub fn probability(&self) -> f64 {
        match *self {
            Self::Probability(p) => p,
            Self::Swerling1 { snr_db, threshold } => {
                let d = 10f64.powf(snr_db / 10.0);
                (-threshold * threshold / (2.0 * (1.0 + d))).exp()
            }
        }
    }
}

/// Where clutter plots fall.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum ClutterRegion {
    /// Uniform over a box of measurement space (the first `dim` components of
    /// `lower`/`upper`: e.g. range and azimuth for a polar sensor, x and y for a
    /// Cartesian one); once per scan (per revolution for a rotating beam, each
    /// clutter plot then timed when the beam crosses its azimuth).
    Box {
        /// Lower corner.
        lower: [f64; 3],
        /// Upper corner.
        upper: [f64; 3],
    },
    /// Uniform over a box of half-widths `half_width` centred on each target's noise-free
    /// measurement, at that target's plot time (detected or not).
    Gate {
        /// Half-widths of the box in measurement space.
        half_width: [f64; 3],
    },
}

/// Poisson clutter: the number of clutter plots in a region of measurement-space volume
/// `V` is Poisson with mean `density · V`, positions uniform.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Clutter {
    /// Expected clutter plots per unit measurement-space volume (e.g. per m·rad for a
    /// polar sensor, per m² for a 2-D Cartesian one).
    pub density: f64,
    /// The region.
    pub region: ClutterRegion,
}

/// A sensor for plot generation. Built with [`SensorSpec::new`] and the `with_*`
/// methods, each of which validates its input.
#[derive(Debug, Clone, PartialEq)]
pub struct SensorSpec {
    pub(crate) id: SensorId,
    pub(crate) position: Vector<3>,
    pub(crate) kind: SensorKind,
    /// Cholesky factor of a Cartesian report covariance (identity otherwise).
    pub(crate) chol: Matrix<3, 3>,
    /// The sensor's measurement function `h`, read on the target position `(x, y, z)`.
    pub(crate) model: Model,
    pub(crate) bias: Bias,
    pub(crate) schedule: Schedule,
    pub(crate) detection: Detection,
    pub(crate) clutter: Option<Clutter>,
}

/// A sensor's measurement model from `argus-sensors`, on the target position
/// `(x, y, z)` as its state (global frame; the sensor's position is inside the model).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Model {
    Polar(Polar2D<3>),
    Spherical(Spherical3D<3>),
    Cartesian2(CartesianPosition<3, 2>),
    Cartesian3(CartesianPosition<3, 3>),
}

impl Model {
    /// The noise-free measurement `h(p)` of a target at `p`: `(range, azimuth[,
    /// elevation])` relative to the sensor or `(x, y[, z])`, zero-padded to three.
    pub(crate) fn h(&self, p: &Vector<3>) -> [f64; 3] {
        match self {
            Self::Polar(m) => {
                let z = m.predict(p);
                [z[0], z[1], 0.0]
            }
            Self::Spherical(m) => m.predict(p).into(),
            Self::Cartesian2(m) => {
                let z = m.predict(p);
                [z[0], z[1], 0.0]
            }
            Self::Cartesian3(m) => m.predict(p).into(),
        }
    }
}

impl SensorSpec {
    /// A sensor at `position` (m) that detects every target (`P_D = 1`), without bias or
    /// clutter.
    ///
    /// # Errors
    /// [`SimError::InvalidParameter`] for a non-finite position, a negative or non-finite
    /// σ, a covariance that is not symmetric positive definite, or a non-positive period.
    pub fn new(
        id: SensorId,
        position: Vector<3>,
        kind: SensorKind,
        schedule: Schedule,
    ) -> Result<Self, SimError> {
        for c in position.iter() {
            finite("sensor position", *c)?;
        }
        let mut chol = Matrix::<3, 3>::identity();
        let (px, py, pz) = (position[0], position[1], position[2]);
        let model = match kind {
            SensorKind::Polar {
                sigma_range,
                sigma_azimuth,
            } => {
                non_negative("range sigma", sigma_range)?;
                non_negative("azimuth sigma", sigma_azimuth)?;
                let noise = RadarNoise::constant(sigma_range, sigma_azimuth, 0.0)?;
                Model::Polar(Polar2D::new([0, 1], [px, py], noise)?)
            }
            SensorKind::Spherical {
                sigma_range,
                sigma_azimuth,
                sigma_elevation,
            } => {
                non_negative("range sigma", sigma_range)?;
                non_negative("azimuth sigma", sigma_azimuth)?;
                non_negative("elevation sigma", sigma_elevation)?;
                let noise = RadarNoise::constant(sigma_range, sigma_azimuth, sigma_elevation)?;
                Model::Spherical(Spherical3D::new([0, 1, 2], [px, py, pz], noise)?)
            }
            SensorKind::Cartesian2d { cov } => {
                let l = SpdFactor::new(&cov, "Cartesian report covariance")?.l();
                chol.fixed_view_mut::<2, 2>(0, 0).copy_from(&l);
                Model::Cartesian2(CartesianPosition::new([0, 1], cov)?)
            }
            SensorKind::Cartesian3d { cov } => {
                chol = SpdFactor::new(&cov, "Cartesian report covariance")?.l();
                Model::Cartesian3(CartesianPosition::new([0, 1, 2], cov)?)
            }
        };
        positive("scan period", schedule.period())?;
        match schedule {
            Schedule::Periodic { offset, .. } => {
                finite("scan offset", offset)?;
            }
            Schedule::RotatingBeam {
                azimuth_at_zero, ..
            } => {
                finite("beam azimuth at t = 0", azimuth_at_zero)?;
            }
        }
        Ok(Self {
            id,
            position,
            kind,
            chol,
            model,
            bias: Bias::default(),
            schedule,
            detection: Detection::Probability(1.0),
            clutter: None,
        })
    }

    /// Sets the systematic errors.
    ///
    /// # Errors
    /// [`SimError::InvalidParameter`] for a non-finite value.
    pub fn with_bias(mut self, bias: Bias) -> Result<Self, SimError> {
        finite("range offset", bias.range_offset)?;
        finite("azimuth offset", bias.azimuth_offset)?;
        finite("elevation offset", bias.elevation_offset)?;
        finite("range scale", bias.range_scale)?;
        finite("azimuth scale", bias.azimuth_scale)?;
        self.bias = bias;
        Ok(self)
    }

    /// Sets the detection model.
    ///
    /// # Errors
    /// [`SimError::InvalidParameter`] for a probability outside `[0, 1]`, a non-finite SNR
    /// or a negative threshold.
    pub fn with_detection(mut self, detection: Detection) -> Result<Self, SimError> {
        match detection {
            Detection::Probability(p) => {
                probability("detection probability", p)?;
            }
            Detection::Swerling1 { snr_db, threshold } => {
                finite("mean SNR (dB)", snr_db)?;
                non_negative("detection threshold", threshold)?;
            }
        }
        self.detection = detection;
        Ok(self)
    }

    /// Sets the clutter.
    ///
    /// # Errors
    /// [`SimError::InvalidParameter`] for a negative density, a box with `upper < lower`
    /// or a negative half-width.
    pub fn with_clutter(mut self, clutter: Clutter) -> Result<Self, SimError> {
        non_negative("clutter density", clutter.density)?;
        let dim = self.kind.dim();
        match clutter.region {
            ClutterRegion::Box { lower, upper } => {
                for (lo, hi) in lower.iter().zip(upper.iter()).take(dim) {
                    finite("clutter box corner", *lo)?;
                    non_negative("clutter box width", hi - lo)?;
                }
            }
            ClutterRegion::Gate { half_width } => {
                for h in half_width.iter().take(dim) {
                    non_negative("clutter gate half-width", *h)?;
                }
            }
        }
        self.clutter = Some(clutter);
        Ok(self)
    }

    /// The sensor's id.
    #[must_use]
    pub fn id(&self) -> SensorId {
        self.id
    }

    /// The sensor's position (m).
    #[must_use]
    pub fn position(&self) -> &Vector<3> {
        &self.position
    }

    /// What it measures.
    #[must_use]
    pub fn kind(&self) -> &SensorKind {
        &self.kind
    }

    /// Its bias.
    #[must_use]
    pub fn bias(&self) -> &Bias {
        &self.bias
    }

    /// Its schedule.
    #[must_use]
    pub fn schedule(&self) -> &Schedule {
        &self.schedule
    }

    /// Its detection model.
    #[must_use]
    pub fn detection(&self) -> &Detection {
        &self.detection
    }

    /// Its clutter, if any.
    #[must_use]
    pub fn clutter(&self) -> Option<&Clutter> {
        self.clutter.as_ref()
    }
}

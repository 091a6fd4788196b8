//! The plot vocabulary of the workspace: a plot is a time, the [`SensorId`] of the
//! sensor that made it, a [`Measurement`] and an optional amplitude.
//!
//! Every value is checked when it is built, so a [`Plot`] in hand is finite: ranges
//! are `≥ 0`, angles and times finite, Cartesian covariances symmetric positive
//! definite. Azimuths are not wrapped here (a producer that wants `(−π, π]` applies
//! [`crate::wrap_angle`]); residuals are wrapped by the measurement models.

use argus_core_math::{Matrix, SpdFactor, Vector, check_finite_vector};

use crate::SensorId;
use crate::error::{SensorError, finite, non_negative};

/// A 2-D radar measurement: range (m, `≥ 0`) and azimuth (rad, counter-clockwise from
/// +x) relative to the sensor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PolarMeasurement {
    range: f64,
    azimuth: f64,
}

impl PolarMeasurement {
    /// A polar measurement.
    ///
    /// # Errors
    /// [`SensorError::NonFinite`] for a NaN or infinite value, [`SensorError::Negative`]
    /// for a negative range.
    pub fn new(range: f64, azimuth: f64) -> Result<Self, SensorError> {
        Ok(Self {
            range: non_negative(range, "plot range")?,
            azimuth: finite(azimuth, "plot azimuth")?,
        })
    }

    /// Range (m).
    #[must_use]
    pub fn range(&self) -> f64 {
        self.range
    }

    /// Azimuth (rad).
    #[must_use]
    pub fn azimuth(&self) -> f64 {
        self.azimuth
    }

    /// `[range, azimuth]`, the layout of [`crate::Polar2D`]'s measurement.
    #[must_use]
    pub fn to_vector(&self) -> Vector<2> {
        Vector::<2>::new(self.range, self.azimuth)
    }
}

/// A 3-D radar measurement: range (m, `≥ 0`), azimuth (rad, counter-clockwise from +x)
/// and elevation (rad, above the x–y plane) relative to the sensor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphericalMeasurement {
    range: f64,
    azimuth: f64,
    elevation: f64,
}

impl SphericalMeasurement {
    /// A spherical measurement.
    ///
    /// # Errors
    /// [`SensorError::NonFinite`] for a NaN or infinite value, [`SensorError::Negative`]
    /// for a negative range.
    pub fn new(range: f64, azimuth: f64, elevation: f64) -> Result<Self, SensorError> {
        Ok(Self {
            range: non_negative(range, "plot range")?,
            azimuth: finite(azimuth, "plot azimuth")?,
            elevation: finite(elevation, "plot elevation")?,
        })
    }

    /// Range (m).
    #[must_use]
    pub fn range(&self) -> f64 {
        self.range
    }

    /// Azimuth (rad).
    #[must_use]
    pub fn azimuth(&self) -> f64 {
        self.azimuth
    }

    /// Elevation (rad).
    #[must_use]
    pub fn elevation(&self) -> f64 {
        self.elevation
    }

    /// `[range, azimuth, elevation]`, the layout of [`crate::Spherical3D`]'s measurement.
    #[must_use]
    pub fn to_vector(&self) -> Vector<3> {
        Vector::<3>::new(self.range, self.azimuth, self.elevation)
    }
}

/// A `D`-dimensional position (m) in a Cartesian frame with its covariance (m²): a
/// position report, or a radar measurement converted to Cartesian.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CartesianMeasurement<const D: usize> {
    position: Vector<D>,
    covariance: Matrix<D, D>,
}

impl<const D: usize> CartesianMeasurement<D> {
    /// A position and its covariance, kept as given (not symmetrised).
    ///
    /// # Errors
    /// [`SensorError::Math`] for a non-finite position or a covariance that is not
    /// finite, symmetric and positive definite.
    pub fn new(position: Vector<D>, covariance: Matrix<D, D>) -> Result<Self, SensorError> {
        check_finite_vector(&position, "plot position")?;
        SpdFactor::new(&covariance, "plot covariance")?;
        Ok(Self {
            position,
            covariance,
        })
    }

    /// The position (m).
    #[must_use]
    pub fn position(&self) -> &Vector<D> {
        &self.position
    }

    /// Its covariance (m²).
    #[must_use]
    pub fn covariance(&self) -> &Matrix<D, D> {
        &self.covariance
    }
}

/// What a plot measured, in the sensor's own coordinates (polar, spherical) or in a
/// Cartesian frame with its covariance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Measurement {
    /// Range and azimuth.
    Polar(PolarMeasurement),
    /// Range, azimuth and elevation.
    Spherical(SphericalMeasurement),
    /// A 2-D position `(x, y)` and its covariance.
    Cartesian2(CartesianMeasurement<2>),
    /// A 3-D position `(x, y, z)` and its covariance.
    Cartesian3(CartesianMeasurement<3>),
}

impl Measurement {
    /// The spatial dimension: 2 or 3.
    #[must_use]
    pub fn dim(&self) -> usize {
        match self {
            Self::Polar(_) | Self::Cartesian2(_) => 2,
            Self::Spherical(_) | Self::Cartesian3(_) => 3,
        }
    }

    /// The measured components (range, azimuth[, elevation] or x, y[, z]), zero-padded
    /// to three, and their count ([`Measurement::dim`]).
    #[must_use]
    pub fn components(&self) -> ([f64; 3], usize) {
        match self {
            Self::Polar(m) => ([m.range, m.azimuth, 0.0], 2),
            Self::Spherical(m) => ([m.range, m.azimuth, m.elevation], 3),
            Self::Cartesian2(m) => ([m.position[0], m.position[1], 0.0], 2),
            Self::Cartesian3(m) => ([m.position[0], m.position[1], m.position[2]], 3),
        }
    }
}

impl From<PolarMeasurement> for Measurement {
    fn from(m: PolarMeasurement) -> Self {
        Self::Polar(m)
    }
}

impl From<SphericalMeasurement> for Measurement {
    fn from(m: SphericalMeasurement) -> Self {
        Self::Spherical(m)
    }
}

impl From<CartesianMeasurement<2>> for Measurement {
    fn from(m: CartesianMeasurement<2>) -> Self {
        Self::Cartesian2(m)
    }
}

impl From<CartesianMeasurement<3>> for Measurement {
    fn from(m: CartesianMeasurement<3>) -> Self {
        Self::Cartesian3(m)
    }
}

/// One plot (detection report): when, from which sensor, what it measured, and its
/// normalised amplitude when the sensor reports one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plot {
    time: f64,
    sensor: SensorId,
    measurement: Measurement,
    amplitude: Option<f64>,
}

impl Plot {
    /// A plot without amplitude at `time` (s).
    ///
    /// # Errors
    /// [`SensorError::NonFinite`] for a NaN or infinite time.
    pub fn new(
        time: f64,
        sensor: SensorId,
        measurement: impl Into<Measurement>,
    ) -> Result<Self, SensorError> {
        Ok(Self {
            time: finite(time, "plot time")?,
            sensor,
            measurement: measurement.into(),
            amplitude: None,
        })
    }

    /// A polar plot: range (m) and azimuth (rad) from the sensor.
    ///
    /// # Errors
    /// As [`Plot::new`] and [`PolarMeasurement::new`].
    pub fn polar(
        time: f64,
        sensor: SensorId,
        range: f64,
        azimuth: f64,
    ) -> Result<Self, SensorError> {
        Self::new(time, sensor, PolarMeasurement::new(range, azimuth)?)
    }

    /// A 2-D Cartesian plot: position (m) and its covariance (m²).
    ///
    /// # Errors
    /// As [`Plot::new`] and [`CartesianMeasurement::new`].
    pub fn cartesian(
        time: f64,
        sensor: SensorId,
        position: Vector<2>,
        covariance: Matrix<2, 2>,
    ) -> Result<Self, SensorError> {
        Self::new(
            time,
            sensor,
            CartesianMeasurement::new(position, covariance)?,
        )
    }

    /// The same plot with an amplitude (or none).
    ///
    /// # Errors
    /// [`SensorError::NonFinite`] for a NaN or infinite amplitude.
    pub fn with_amplitude(self, amplitude: Option<f64>) -> Result<Self, SensorError> {
        if let Some(a) = amplitude {
            finite(a, "plot amplitude")?;
        }
        Ok(Self { amplitude, ..self })
    }

    /// Time (s).
    #[must_use]
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The sensor that made it.
    #[must_use]
    pub fn sensor(&self) -> SensorId {
        self.sensor
    }

    /// What it measured.
    #[must_use]
    pub fn measurement(&self) -> &Measurement {
        &self.measurement
    }

    /// Its normalised amplitude, when the sensor reports one.
    #[must_use]
    pub fn amplitude(&self) -> Option<f64> {
        self.amplitude
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use argus_core_math::MathError;

    #[test]
    fn constructors_reject_what_a_plot_cannot_be() {
        assert!(matches!(
            PolarMeasurement::new(-1.0, 0.0),
            Err(SensorError::Negative {
                what: "plot range",
                ..
            })
        ));
        // A range of zero is a plot on the sensor: allowed here (a filter may refuse it).
        assert!(PolarMeasurement::new(0.0, 0.0).is_ok());
        assert!(matches!(
            SphericalMeasurement::new(1.0, 0.0, f64::NAN),
            Err(SensorError::NonFinite {
                what: "plot elevation",
                ..
            })
        ));
        assert!(matches!(
            Plot::polar(f64::INFINITY, SensorId(0), 1.0, 0.0),
            Err(SensorError::NonFinite {
                what: "plot time",
                ..
            })
        ));
        // [[1, 2], [2, 1]] has eigenvalues 3 and −1.
        let not_pd = Matrix::<2, 2>::new(1.0, 2.0, 2.0, 1.0);
        assert!(matches!(
            CartesianMeasurement::new(Vector::<2>::zeros(), not_pd),
            Err(SensorError::Math(MathError::NotPositiveDefinite { .. }))
        ));
        let asym = Matrix::<2, 2>::new(1.0, 0.5, 0.0, 1.0);
        assert!(CartesianMeasurement::new(Vector::<2>::zeros(), asym).is_err());
        let p = Plot::polar(1.0, SensorId(2), 10.0, 0.1).unwrap();
        assert!(p.with_amplitude(Some(f64::NAN)).is_err());
        assert_eq!(p.with_amplitude(Some(2.5)).unwrap().amplitude(), Some(2.5));
    }

    #[test]
    fn components_follow_the_layout() {
        let m = Measurement::from(SphericalMeasurement::new(5.0, 0.1, 0.2).unwrap());
        assert_eq!(m.components(), ([5.0, 0.1, 0.2], 3));
        let c = CartesianMeasurement::new(Vector::<2>::new(1.0, 2.0), Matrix::<2, 2>::identity())
            .unwrap();
        assert_eq!(Measurement::from(c).components(), ([1.0, 2.0, 0.0], 2));
        assert_eq!(Measurement::from(c).dim(), 2);
    }
}

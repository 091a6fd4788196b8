//! A 2-D radar seen by both state sizes of the aircraft IMM.

use argus_core_math::Vector;
use argus_sensors::{ConversionMethod, MeasurementModel, Polar2D, RadarNoise, convert_polar};

use crate::ImmError;

/// A (range, azimuth) radar for the aircraft IMM: the same [`Polar2D`] for the CV modes'
/// `[x, vx, y, vy]` and the CT mode's `[x, vx, y, vy, ω]` (positions at indices 0 and 2
/// in both). Plots are `z = [r, θ]` relative to the radar, θ counter-clockwise from +x
/// (Argus's convention; radar azimuths go through `argus_sensors::radar_to_math_azimuth`).
///
/// The filters update in (range, azimuth) directly (EKF, `H` at the prediction): the
/// noise is the radar's own `diag(σr², σθ²)`, with no conversion covariance evaluated at
/// a noisy plot, and the mode likelihoods are those of the plot the radar reported. At the
/// seed-000 radar (σθ = 0.08°, 20–150 km) the linearisation error is negligible: the
/// second-order term `½ tr(Hᵢ P)` is about `σ_pos²/r` ≤ 0.1 m for a predicted position
/// spread of ~100 m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AircraftRadar {
    cv: Polar2D<4>,
    ct: Polar2D<5>,
}

impl AircraftRadar {
    /// A radar at `sensor = [x, y]` (m) with noise `noise`.
    ///
    /// # Errors
    /// [`ImmError::Sensor`] for a non-finite sensor position.
    pub fn new(sensor: [f64; 2], noise: RadarNoise) -> Result<Self, ImmError> {
        Ok(Self {
            cv: Polar2D::new([0, 2], sensor, noise)?,
            ct: Polar2D::new([0, 2], sensor, noise)?,
        })
    }

    /// The measurement model of the CV modes.
    #[must_use]
    pub fn cv(&self) -> &Polar2D<4> {
        &self.cv
    }

    /// The measurement model of the CT mode.
    #[must_use]
    pub fn ct(&self) -> &Polar2D<5> {
        &self.ct
    }

    /// Checks a plot `[r, θ]`: finite, with a positive range.
    ///
    /// # Errors
    /// [`ImmError::InvalidParameter`] naming the bad component.
    pub fn check_plot(z: &Vector<2>) -> Result<(), ImmError> {
        if !(z[0].is_finite() && z[0] > 0.0) {
            return Err(ImmError::InvalidParameter {
                what: "plot range",
                value: z[0],
                reason: "must be finite and positive",
            });
        }
        if !z[1].is_finite() {
            return Err(ImmError::InvalidParameter {
                what: "plot azimuth",
                value: z[1],
                reason: "must be finite",
            });
        }
        Ok(())
    }

    /// The plot as a global Cartesian position with its covariance, by the unbiased
    /// conversion (Mo et al. 1998) with the radar's standard deviations at that range:
    /// for the two-point start only.
    ///
    /// # Errors
    /// As [`AircraftRadar::check_plot`]; [`ImmError::Sensor`] from the conversion.
    pub fn convert(
        &self,
        z: &Vector<2>,
    ) -> Result<(Vector<2>, argus_core_math::Matrix<2, 2>), ImmError> {
        Self::check_plot(z)?;
        let s = self.cv.noise_model().sigmas_at_range(z[0]);
        let c = convert_polar(
            z[0],
            z[1],
            s.range(),
            s.azimuth(),
            ConversionMethod::Unbiased,
        )?;
        Ok((c.position + self.cv.sensor(), c.covariance))
    }

    /// The noise-free plot of a kinematic state `[x, vx, y, vy]`.
    #[must_use]
    pub fn predict(&self, x: &Vector<4>) -> Vector<2> {
        self.cv.predict(x)
    }
}

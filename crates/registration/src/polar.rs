//! The biased 2-D polar radar of seed 004 and its linearised Cartesian form
//! `z = H X + B C β + w` (eqs (1)–(6)), in the form registration needs: each plot is
//! converted once to Cartesian with its noise `R` and bias Jacobian `B C`, evaluated
//! at a chosen [`Linearization`] point.

use argus_core_math::{Matrix, Vector, check_finite_matrix, check_finite_vector, symmetrize};
use argus_sensors::{
    CartesianMeasurement, ConversionMethod, MeasurementModel, Polar2D, PolarBias, PolarMeasurement,
    RadarNoise, Sigmas, bias_regressor, convert_polar,
};

use crate::error::{RegistrationError, finite, positive};

/// Where `B`, `C` and `R` of eqs (3), (4), (6) are evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Linearization {
    /// At the measured plot, as seed 004 does. The plot's own noise then enters the
    /// regressor `B C`, which biases every least-squares bias estimator (SPEC §004).
    AtPlot,
    /// At the sensor's own local track predicted to the plot time (falls back to the plot
    /// while no track exists). The default: the regressor is then independent of the
    /// plot's noise.
    #[default]
    AtPrediction,
}

/// A 2-D polar radar as registration uses it: an [`argus_sensors::Polar2D`] (position
/// and noise model) whose plots are converted to Cartesian with `R` and `B C` evaluated at
/// a chosen [`Linearization`] point. The measurement function, the bias model
/// ([`PolarBias`]), the bias regressor `B C` ([`argus_sensors::bias_regressor`]) and the
/// linearised conversion ([`argus_sensors::convert_polar`]) all come from `argus-sensors`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PolarSensor {
    radar: Polar2D<4>,
}

/// A plot converted to Cartesian: the position `z` (m, global frame) with its noise
/// covariance `R` (eq (6)) — the vocabulary's [`CartesianMeasurement`] — and the bias
/// Jacobian `B C` (eqs (3), (4)) that maps the sensor's bias into it, at time `time`.
///
/// Not an [`argus_sensors::Plot`]: it is what registration makes of a raw polar plot,
/// linearised at a chosen point, and it carries `B C`, which no raw plot has (its sensor
/// is the registrar's index, not a `SensorId`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConvertedPlot {
    time: f64,
    measurement: CartesianMeasurement<2>,
    bias_jacobian: Matrix<2, 4>,
}

impl ConvertedPlot {
    /// A converted plot from its parts (for plots linearised elsewhere).
    ///
    /// # Errors
    /// [`RegistrationError::NonFinite`] / [`RegistrationError::Math`] for a non-finite
    /// time or `B C`, [`RegistrationError::Sensor`] for a non-finite position or a noise
    /// covariance that is not symmetric positive definite.
    pub fn new(
        time: f64,
        z: Vector<2>,
        noise: Matrix<2, 2>,
        bias_jacobian: Matrix<2, 4>,
    ) -> Result<Self, RegistrationError> {
        finite("plot time", time)?;
        check_finite_matrix(&bias_jacobian, "bias Jacobian B C")?;
        Ok(Self {
            time,
            measurement: CartesianMeasurement::new(z, noise)?,
            bias_jacobian,
        })
    }

    /// The plot time (s).
    #[must_use]
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The Cartesian position `z^m` (m).
    #[must_use]
    pub fn z(&self) -> &Vector<2> {
        self.measurement.position()
    }

    /// The converted noise covariance `R^m = B diag(σr², σθ²) Bᵀ`.
    #[must_use]
    pub fn noise(&self) -> &Matrix<2, 2> {
        self.measurement.covariance()
    }

    /// The position and its noise covariance as the vocabulary's Cartesian measurement.
    #[must_use]
    pub fn measurement(&self) -> &CartesianMeasurement<2> {
        &self.measurement
    }

    /// The bias Jacobian `B C`.
    #[must_use]
    pub fn bias_jacobian(&self) -> &Matrix<2, 4> {
        &self.bias_jacobian
    }
}

impl PolarSensor {
    /// A sensor at `position` (m) with constant range noise σ (m) and azimuth noise σ (rad).
    ///
    /// # Errors
    /// [`RegistrationError::NonFinite`] or [`RegistrationError::InvalidParameter`] for a
    /// non-finite position or a non-positive σ.
    pub fn new(
        position: Vector<2>,
        sigma_range: f64,
        sigma_azimuth: f64,
    ) -> Result<Self, RegistrationError> {
        finite("sensor x", position[0])?;
        finite("sensor y", position[1])?;
        let sigmas = Sigmas::polar(
            positive("range noise sigma", sigma_range)?,
            positive("azimuth noise sigma", sigma_azimuth)?,
        )?;
        Ok(Self::from_radar(Polar2D::cv(
            [position[0], position[1]],
            RadarNoise::Constant(sigmas),
        )?))
    }

    /// A sensor from a polar radar model for the `[x, vx, y, vy]` layout (constant or
    /// SNR-driven noise, evaluated at the linearisation point's range).
    #[must_use]
    pub fn from_radar(radar: Polar2D<4>) -> Self {
        Self { radar }
    }

    /// The radar model.
    #[must_use]
    pub fn radar(&self) -> &Polar2D<4> {
        &self.radar
    }

    /// The sensor position (m).
    #[must_use]
    pub fn position(&self) -> &Vector<2> {
        self.radar.sensor()
    }

    /// Range and azimuth of a global position relative to the sensor (azimuth in (−π, π]),
    /// by [`Polar2D`]'s measurement function.
    ///
    /// # Errors
    /// [`RegistrationError::Sensor`] for a non-finite position.
    pub fn polar_of(&self, p: &Vector<2>) -> Result<PolarMeasurement, RegistrationError> {
        let z = self.radar.predict(&Vector::<4>::new(p[0], 0.0, p[1], 0.0));
        Ok(PolarMeasurement::new(z[0], z[1])?)
    }

    /// The noise standard deviations at `range`.
    #[must_use]
    pub fn sigmas(&self, range: f64) -> Sigmas {
        self.radar.noise_model().sigmas_at_range(range)
    }

    /// The biased noisy plot of a target at global position `p`, eq (1):
    /// `r = (1+ε_r) r_true + b_r + σr n_r`, `θ = (1+ε_θ) θ_true + b_θ + σθ n_θ`
    /// ([`PolarBias::apply`], then the noise), where `(n_r, n_θ)` are standard normal draws
    /// supplied by the caller.
    ///
    /// # Errors
    /// [`RegistrationError::Sensor`] for a non-finite position, or a noisy range below
    /// zero (noise larger than the range: no radar reports it).
    pub fn biased_plot(
        &self,
        p: &Vector<2>,
        bias: &PolarBias,
        n_r: f64,
        n_theta: f64,
    ) -> Result<PolarMeasurement, RegistrationError> {
        let t = self.polar_of(p)?;
        let (r, a) = bias.apply(t.range(), t.azimuth())?;
        let s = self.sigmas(t.range());
        Ok(PolarMeasurement::new(
            r + s.range() * n_r,
            a + s.azimuth() * n_theta,
        )?)
    }

    /// Converts a polar plot taken at `time`: `z` is the plot in Cartesian, and `R`, `B C`
    /// are evaluated at the plot (`at = None`, seed 004's choice) or at the global
    /// position `at` (the local track's prediction; see [`Linearization`]):
    /// `R = B diag(σr², σθ²) Bᵀ` (eq (6), the linearised [`convert_polar`]) and
    /// `B C` = [`bias_regressor`] (eqs (3), (4)).
    ///
    /// # Errors
    /// [`RegistrationError::NonFinite`] for a non-finite point,
    /// [`RegistrationError::InvalidParameter`] for a zero range,
    /// [`RegistrationError::Sensor`] for a linearisation point on the sensor and
    /// [`RegistrationError::Math`] when `R` is singular.
    pub fn convert(
        &self,
        time: f64,
        plot: &PolarMeasurement,
        at: Option<&Vector<2>>,
    ) -> Result<ConvertedPlot, RegistrationError> {
        positive("plot range", plot.range())?;
        let s = |r: f64| self.sigmas(r);
        let at_plot = {
            let sp = s(plot.range());
            convert_polar(
                plot.range(),
                plot.azimuth(),
                sp.range(),
                sp.azimuth(),
                ConversionMethod::Linearized,
            )?
        };
        let (lin, noise) = match at {
            None => (*plot, at_plot.covariance),
            Some(p) => {
                check_finite_vector(p, "linearisation point")?;
                let lin = self.polar_of(p)?;
                let sl = s(lin.range());
                let c = convert_polar(
                    lin.range(),
                    lin.azimuth(),
                    sl.range(),
                    sl.azimuth(),
                    ConversionMethod::Linearized,
                )?;
                (lin, c.covariance)
            }
        };
        ConvertedPlot::new(
            time,
            self.position() + at_plot.position,
            symmetrize(&noise),
            bias_regressor(lin.range(), lin.azimuth()),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bias_jacobian_matches_central_differences() {
        // Eq (2): z(β) = p_s + (1+ε_r) r + b_r at (1+ε_θ) θ + b_θ; ∂z/∂β at β = 0 is B C.
        let r = 12_000.0;
        let th = 0.7;
        let z = |b: &Vector<4>| {
            let rr = (1.0 + b[2]) * r + b[0];
            let tt = (1.0 + b[3]) * th + b[1];
            Vector::<2>::new(rr * tt.cos(), rr * tt.sin())
        };
        let bc = bias_regressor(r, th);
        let steps = [1e-3, 1e-7, 1e-8, 1e-7];
        for k in 0..4 {
            let mut e = Vector::<4>::zeros();
            e[k] = steps[k];
            let d = (z(&e) - z(&(-e))) / (2.0 * steps[k]);
            for i in 0..2 {
                // Central difference error O(h²·|∂³z|): relative 1e-6 is ample.
                assert!(
                    (d[i] - bc[(i, k)]).abs() < 1e-6 * (1.0 + bc[(i, k)].abs()),
                    "{k} {i}"
                );
            }
        }
    }

    #[test]
    fn constructors_reject_bad_input() {
        assert!(PolarSensor::new(Vector::<2>::new(f64::NAN, 0.0), 1.0, 1.0).is_err());
        assert!(matches!(
            PolarSensor::new(Vector::<2>::zeros(), 0.0, 1.0),
            Err(RegistrationError::InvalidParameter {
                what: "range noise sigma",
                ..
            })
        ));
        let s = PolarSensor::new(Vector::<2>::zeros(), 10.0, 1e-3).unwrap();
        // A negative or non-finite plot cannot be built; a zero range cannot be converted.
        assert!(PolarMeasurement::new(-1.0, 0.0).is_err());
        assert!(PolarMeasurement::new(1.0, f64::NAN).is_err());
        let zero = PolarMeasurement::new(0.0, 0.3).unwrap();
        assert!(matches!(
            s.convert(0.0, &zero, None),
            Err(RegistrationError::InvalidParameter {
                what: "plot range",
                ..
            })
        ));
        let not_pd = Matrix::<2, 2>::new(1.0, 2.0, 2.0, 1.0);
        assert!(
            ConvertedPlot::new(0.0, Vector::<2>::zeros(), not_pd, Matrix::<2, 4>::zeros()).is_err()
        );
    }

    #[test]
    fn converted_noise_has_polar_eigenvalues() {
        // B diag(σr², σθ²) Bᵀ is a rotation of diag(σr², r² σθ²): eigenvalues σr², (r σθ)²,
        // here at the linearisation point (r = 20 km, θ = 1.1 rad), not at the plot.
        let s = PolarSensor::new(Vector::<2>::zeros(), 10.0, 1e-3).unwrap();
        let plot = PolarMeasurement::new(5_000.0, 0.3).unwrap();
        let at = Vector::<2>::new(20_000.0 * 1.1_f64.cos(), 20_000.0 * 1.1_f64.sin());
        let c = s.convert(0.0, &plot, Some(&at)).unwrap();
        let r = c.noise();
        assert!((r.trace() - (100.0 + 400.0)).abs() < 1e-9);
        assert!((r.determinant() - 100.0 * 400.0).abs() < 1e-6);
        // The position is the plot's (5 km at 0.3 rad), the regressor the point's.
        assert!(
            (c.z() - Vector::<2>::new(5_000.0 * 0.3_f64.cos(), 5_000.0 * 0.3_f64.sin())).norm()
                < 1e-9
        );
        assert!((c.bias_jacobian() - bias_regressor(20_000.0, 1.1)).amax() < 1e-9);
    }
}

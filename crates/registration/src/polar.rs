//! The biased 2-D polar radar of seed 004 and its linearised Cartesian form
//! `z = H X + B C β + w` (eqs (1)–(6)), in the form registration needs: each plot is
//! converted once to Cartesian with its noise `R` and bias Jacobian `B C`, evaluated
//! at a chosen [`Linearization`] point.

use argus_core_math::{Matrix, SpdFactor, Vector, check_finite_matrix, check_finite_vector};

use crate::error::{RegistrationError, finite, positive};

/// A sensor's bias `β = [b_r, b_θ, ε_r, ε_θ]`: range offset (m), azimuth offset (rad),
/// range scale and azimuth scale (both dimensionless).
///
/// # References
/// Seed 004 eq (1) and the text after eq (4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SensorBias(Vector<4>);

impl SensorBias {
    /// A bias from its four components.
    ///
    /// # Errors
    /// [`RegistrationError::NonFinite`] naming the component.
    pub fn new(
        range_offset: f64,
        azimuth_offset: f64,
        range_scale: f64,
        azimuth_scale: f64,
    ) -> Result<Self, RegistrationError> {
        Ok(Self(Vector::<4>::new(
            finite("range offset bias", range_offset)?,
            finite("azimuth offset bias", azimuth_offset)?,
            finite("range scale bias", range_scale)?,
            finite("azimuth scale bias", azimuth_scale)?,
        )))
    }

    /// No bias.
    #[must_use]
    pub fn zero() -> Self {
        Self(Vector::<4>::zeros())
    }

    /// The vector `[b_r, b_θ, ε_r, ε_θ]`.
    #[must_use]
    pub fn vector(&self) -> &Vector<4> {
        &self.0
    }
}

/// A plot in the sensor's polar frame: range (m) and azimuth (rad, from +x
/// counter-clockwise), relative to the sensor's position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PolarPlot {
    /// Range (m).
    pub range: f64,
    /// Azimuth (rad).
    pub azimuth: f64,
}

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

/// A 2-D polar radar at a known position with white range and azimuth noise.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PolarSensor {
    position: Vector<2>,
    sigma_range: f64,
    sigma_azimuth: f64,
}

/// A plot converted to Cartesian: the position `z` (m, global frame), its noise
/// covariance `R` (eq (6)) and the bias Jacobian `B C` (eqs (3), (4)) that maps the
/// sensor's bias into it, at time `time`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConvertedPlot {
    time: f64,
    z: Vector<2>,
    noise: Matrix<2, 2>,
    bias_jacobian: Matrix<2, 4>,
}

impl ConvertedPlot {
    /// A converted plot from its parts (for plots linearised elsewhere).
    ///
    /// # Errors
    /// [`RegistrationError::NonFinite`] / [`RegistrationError::Math`] for non-finite
    /// values or a noise covariance that is not symmetric positive definite.
    pub fn new(
        time: f64,
        z: Vector<2>,
        noise: Matrix<2, 2>,
        bias_jacobian: Matrix<2, 4>,
    ) -> Result<Self, RegistrationError> {
        finite("plot time", time)?;
        check_finite_vector(&z, "plot position")?;
        check_finite_matrix(&bias_jacobian, "bias Jacobian B C")?;
        SpdFactor::new(&noise, "plot noise covariance R")?;
        Ok(Self {
            time,
            z,
            noise,
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
        &self.z
    }

    /// The converted noise covariance `R^m = B diag(σr², σθ²) Bᵀ`.
    #[must_use]
    pub fn noise(&self) -> &Matrix<2, 2> {
        &self.noise
    }

    /// The bias Jacobian `B C`.
    #[must_use]
    pub fn bias_jacobian(&self) -> &Matrix<2, 4> {
        &self.bias_jacobian
    }
}

impl PolarSensor {
    /// A sensor at `position` (m) with range noise σ (m) and azimuth noise σ (rad).
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
        Ok(Self {
            position,
            sigma_range: positive("range noise sigma", sigma_range)?,
            sigma_azimuth: positive("azimuth noise sigma", sigma_azimuth)?,
        })
    }

    /// The sensor position (m).
    #[must_use]
    pub fn position(&self) -> &Vector<2> {
        &self.position
    }

    /// Range and azimuth of a global position relative to the sensor (azimuth in (−π, π]).
    #[must_use]
    pub fn polar_of(&self, p: &Vector<2>) -> PolarPlot {
        let d = p - self.position;
        PolarPlot {
            range: d.norm(),
            azimuth: d[1].atan2(d[0]),
        }
    }

    /// The biased noisy plot of a target at global position `p`, eq (1):
    /// `r = (1+ε_r) r_true + b_r + σr n_r`, `θ = (1+ε_θ) θ_true + b_θ + σθ n_θ`, where
    /// `(n_r, n_θ)` are standard normal draws supplied by the caller.
    #[must_use]
    pub fn biased_plot(
        &self,
        p: &Vector<2>,
        bias: &SensorBias,
        n_r: f64,
        n_theta: f64,
    ) -> PolarPlot {
        let t = self.polar_of(p);
        let b = bias.vector();
        PolarPlot {
            range: (1.0 + b[2]) * t.range + b[0] + self.sigma_range * n_r,
            azimuth: (1.0 + b[3]) * t.azimuth + b[1] + self.sigma_azimuth * n_theta,
        }
    }

    /// The global Cartesian position of a polar plot.
    #[must_use]
    pub fn to_cartesian(&self, plot: &PolarPlot) -> Vector<2> {
        self.position
            + Vector::<2>::new(
                plot.range * plot.azimuth.cos(),
                plot.range * plot.azimuth.sin(),
            )
    }

    /// The bias Jacobian `B C` at range `r` and azimuth `θ`, eqs (3)–(4):
    /// `B = [[cos θ, −r sin θ], [sin θ, r cos θ]]`, `C = [[1, 0, r, 0], [0, 1, 0, θ]]`.
    #[must_use]
    pub fn bias_jacobian(range: f64, azimuth: f64) -> Matrix<2, 4> {
        let (s, c) = azimuth.sin_cos();
        let b = Matrix::<2, 2>::new(c, -range * s, s, range * c);
        let cm = Matrix::<2, 4>::new(1.0, 0.0, range, 0.0, 0.0, 1.0, 0.0, azimuth);
        b * cm
    }

    /// The converted noise covariance `B diag(σr², σθ²) Bᵀ` at `(r, θ)`, eq (6).
    #[must_use]
    pub fn converted_noise(&self, range: f64, azimuth: f64) -> Matrix<2, 2> {
        let (s, c) = azimuth.sin_cos();
        let b = Matrix::<2, 2>::new(c, -range * s, s, range * c);
        let d = Matrix::<2, 2>::new(
            self.sigma_range.powi(2),
            0.0,
            0.0,
            self.sigma_azimuth.powi(2),
        );
        argus_core_math::symmetrize(&(b * d * b.transpose()))
    }

    /// Converts a polar plot taken at `time`: `z` is the plot in Cartesian, and `R`, `B C`
    /// are evaluated at the plot (`at = None`, seed 004's choice) or at the global
    /// position `at` (the local track's prediction; see [`Linearization`]).
    ///
    /// # Errors
    /// [`RegistrationError::NonFinite`] for a non-finite plot or point,
    /// [`RegistrationError::InvalidParameter`] for a non-positive range, and
    /// [`RegistrationError::Math`] when `R` is singular (linearisation point on the sensor).
    pub fn convert(
        &self,
        time: f64,
        plot: &PolarPlot,
        at: Option<&Vector<2>>,
    ) -> Result<ConvertedPlot, RegistrationError> {
        finite("plot range", plot.range)?;
        finite("plot azimuth", plot.azimuth)?;
        positive("plot range", plot.range)?;
        let lin = match at {
            None => *plot,
            Some(p) => {
                check_finite_vector(p, "linearisation point")?;
                self.polar_of(p)
            }
        };
        ConvertedPlot::new(
            time,
            self.to_cartesian(plot),
            self.converted_noise(lin.range, lin.azimuth),
            Self::bias_jacobian(lin.range, lin.azimuth),
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
        let bc = PolarSensor::bias_jacobian(r, th);
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
        assert!(SensorBias::new(1.0, f64::INFINITY, 0.0, 0.0).is_err());
        let s = PolarSensor::new(Vector::<2>::zeros(), 10.0, 1e-3).unwrap();
        let bad = PolarPlot {
            range: -1.0,
            azimuth: 0.0,
        };
        assert!(s.convert(0.0, &bad, None).is_err());
        let nan = PolarPlot {
            range: 1.0,
            azimuth: f64::NAN,
        };
        assert!(matches!(
            s.convert(0.0, &nan, None),
            Err(RegistrationError::NonFinite {
                what: "plot azimuth",
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
        // B diag(σr², σθ²) Bᵀ is a rotation of diag(σr², r² σθ²): eigenvalues σr², (r σθ)².
        let s = PolarSensor::new(Vector::<2>::zeros(), 10.0, 1e-3).unwrap();
        let r = s.converted_noise(20_000.0, 1.1);
        let tr = r.trace();
        let det = r.determinant();
        assert!((tr - (100.0 + 400.0)).abs() < 1e-9);
        assert!((det - 100.0 * 400.0).abs() < 1e-6);
    }
}

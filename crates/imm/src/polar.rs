//! Polar plots' measurement-noise variances (the plots are [`argus_sensors::PolarMeasurement`]s), and the unbiased conversion to a
//! Cartesian position measurement that the multi-IMM applies with each IMM's own `R`.

use argus_core_math::{Matrix, Vector};
use argus_sensors::{
    ConversionMethod, LinearMeasurementModel, MeasurementModel, PolarMeasurement, convert_polar,
};

use crate::ImmError;
use crate::error::check_positive;

/// Range and azimuth measurement-noise variances `(σr², σθ²)` in m² and rad².
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NoiseVariances {
    range: f64,
    azimuth: f64,
}

impl NoiseVariances {
    /// Variances `σr²` (m²) and `σθ²` (rad²).
    ///
    /// # Errors
    /// [`ImmError::InvalidParameter`] unless both are finite and positive.
    pub fn new(range: f64, azimuth: f64) -> Result<Self, ImmError> {
        for (what, v) in [("range variance", range), ("azimuth variance", azimuth)] {
            check_positive(what, v)?;
        }
        Ok(Self { range, azimuth })
    }

    /// From standard deviations `σr` (m) and `σθ` (rad).
    ///
    /// # Errors
    /// As [`NoiseVariances::new`].
    pub fn from_sigmas(sigma_range: f64, sigma_azimuth: f64) -> Result<Self, ImmError> {
        Self::new(sigma_range * sigma_range, sigma_azimuth * sigma_azimuth)
    }

    /// `σr²`, m².
    #[must_use]
    pub fn range(&self) -> f64 {
        self.range
    }

    /// `σθ²`, rad².
    #[must_use]
    pub fn azimuth(&self) -> f64 {
        self.azimuth
    }

    /// Both variances scaled: `(a σr², b σθ²)`. Internal: factors are validated positive.
    pub(crate) fn scaled(&self, a: f64, b: f64) -> Self {
        Self {
            range: self.range * a,
            azimuth: self.azimuth * b,
        }
    }

    /// The variances as `[σr², σθ²]`.
    #[must_use]
    pub fn as_array(&self) -> [f64; 2] {
        [self.range, self.azimuth]
    }
}

/// The unbiased conversion of a polar plot to Cartesian position, with the
/// measurement-conditioned covariance: [`argus_sensors::convert_polar`] with
/// [`ConversionMethod::Unbiased`], for variances instead of standard deviations.
///
/// With `λ = e^{−σθ²/2}`, `λ' = e^{−2σθ²}`:
/// `x = r cos θ / λ`, `y = r sin θ / λ`, and
/// `R₁₁ = (λ⁻² − 2) r² cos²θ + ½ (r² + σr²)(1 + λ' cos 2θ)`,
/// `R₂₂ = (λ⁻² − 2) r² sin²θ + ½ (r² + σr²)(1 − λ' cos 2θ)`,
/// `R₁₂ = (λ⁻² − 2) r² cos θ sin θ + ½ (r² + σr²) λ' sin 2θ`.
///
/// # References
/// Mo Longbin, Song Xiaoquan, Zhou Yiyu, Sun Zhong Kang & Y. Bar-Shalom, "Unbiased converted
/// measurements for tracking", IEEE TAES 34(3), 1998; Bar-Shalom, Li & Kirubarajan (2001)
/// §10.4.3. Seed 000 §3.1 uses it ("covariance of the unbiased conversion").
///
/// # Errors
/// [`ImmError::Sensor`] for a zero range; [`ImmError::Math`] if the covariance is not
/// positive definite.
pub fn unbiased_conversion(
    plot: &PolarMeasurement,
    var: &NoiseVariances,
) -> Result<(Vector<2>, Matrix<2, 2>), ImmError> {
    let c = convert_polar(
        plot.range(),
        plot.azimuth(),
        var.range.sqrt(),
        var.azimuth.sqrt(),
        ConversionMethod::Unbiased,
    )?;
    // Positive definite: for a symmetric 2 × 2 matrix (finite, as `convert_polar` checked)
    // the two Cholesky pivots are R₁₁ and det R / R₁₁, so both tests are the factorisation's.
    let r = &c.covariance;
    let (r11, r12, r22) = (r[(0, 0)], r[(1, 0)], r[(1, 1)]);
    if !(r11 > 0.0 && r11 * r22 - r12 * r12 > 0.0) {
        return Err(argus_core_math::MathError::NotPositiveDefinite {
            what: "converted measurement covariance",
        }
        .into());
    }
    Ok((c.position, c.covariance))
}

/// A Cartesian position measurement `z = H x + w`, `w ~ N(0, R)`, of an `N`-state whose
/// x and y positions are at indices `px`, `py` (`[x, vx, y, vy]`: 0 and 2), with a fixed `R`
/// (here: the covariance of a converted plot).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PositionMeasurement<const N: usize> {
    h: Matrix<2, N>,
    r: Matrix<2, 2>,
}

impl<const N: usize> PositionMeasurement<N> {
    /// A position measurement with noise covariance `r`.
    ///
    /// # Errors
    /// [`ImmError::InvalidParameter`] for an index `≥ N` or `px == py`; [`ImmError::Math`]
    /// when `r` is not finite, symmetric and positive definite.
    pub fn new(px: usize, py: usize, r: Matrix<2, 2>) -> Result<Self, ImmError> {
        let h = position_selector::<N>(px, py)?;
        argus_core_math::SpdFactor::new(&r, "measurement noise R")?;
        Ok(Self { h, r })
    }
}

/// The `2 × N` matrix picking positions `px`, `py`.
pub(crate) fn position_selector<const N: usize>(
    px: usize,
    py: usize,
) -> Result<Matrix<2, N>, ImmError> {
    if px >= N || py >= N || px == py {
        return Err(ImmError::InvalidParameter {
            what: "position indices",
            value: px.max(py) as f64,
            reason: "must be distinct and smaller than the state size",
        });
    }
    let mut h = Matrix::<2, N>::zeros();
    h[(0, px)] = 1.0;
    h[(1, py)] = 1.0;
    Ok(h)
}

impl<const N: usize> MeasurementModel<N, 2> for PositionMeasurement<N> {
    fn predict(&self, x: &Vector<N>) -> Vector<2> {
        self.h * x
    }
    fn jacobian(&self, _x: &Vector<N>) -> Matrix<2, N> {
        self.h
    }
    fn noise(&self, _x: &Vector<N>) -> Matrix<2, 2> {
        self.r
    }
}

impl<const N: usize> LinearMeasurementModel<N, 2> for PositionMeasurement<N> {
    fn matrix(&self) -> Matrix<2, N> {
        self.h
    }
}

/// How a polar plot becomes a measurement for a filter that assumes noise variances `var`.
/// The multi-IMM calls it once per noise hypothesis, so each IMM uses its own `R`.
pub trait PlotConversion<const N: usize, const M: usize> {
    /// The measurement model the filters use.
    type Measurement: MeasurementModel<N, M>;

    /// The measurement model and the converted plot for noise variances `var`.
    ///
    /// # Errors
    /// [`ImmError`] when the conversion is undefined for this plot.
    fn convert(
        &self,
        plot: &PolarMeasurement,
        var: &NoiseVariances,
    ) -> Result<(Self::Measurement, Vector<M>), ImmError>;

    /// The target position `(x, y)` relative to the radar, for polar residuals.
    fn position(&self, x: &Vector<N>) -> Vector<2>;

    /// The `2 × 2` covariance of the position in a state covariance `P`.
    fn position_cov(&self, p: &Matrix<N, N>) -> Matrix<2, 2>;
}

/// [`unbiased_conversion`] to a [`PositionMeasurement`] (seed 000 §3.1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnbiasedConversion<const N: usize> {
    h: Matrix<2, N>,
    origin: Vector<2>,
}

impl<const N: usize> UnbiasedConversion<N> {
    /// For a state with positions at indices `px`, `py`.
    ///
    /// # Errors
    /// [`ImmError::InvalidParameter`] for an index `≥ N` or `px == py`.
    pub fn new(px: usize, py: usize) -> Result<Self, ImmError> {
        Ok(Self {
            h: position_selector::<N>(px, py)?,
            origin: Vector::<2>::zeros(),
        })
    }

    /// The same conversion for a radar at `origin` (`[x, y]`, m): plots are relative to
    /// it, converted positions are global.
    ///
    /// # Errors
    /// [`ImmError::InvalidParameter`] for a non-finite coordinate.
    pub fn at(mut self, origin: [f64; 2]) -> Result<Self, ImmError> {
        for v in origin {
            if !v.is_finite() {
                return Err(ImmError::InvalidParameter {
                    what: "radar position",
                    value: v,
                    reason: "must be finite",
                });
            }
        }
        self.origin = Vector::<2>::new(origin[0], origin[1]);
        Ok(self)
    }
}

impl<const N: usize> PlotConversion<N, 2> for UnbiasedConversion<N> {
    type Measurement = PositionMeasurement<N>;

    fn convert(
        &self,
        plot: &PolarMeasurement,
        var: &NoiseVariances,
    ) -> Result<(PositionMeasurement<N>, Vector<2>), ImmError> {
        let (z, r) = unbiased_conversion(plot, var)?;
        Ok((PositionMeasurement { h: self.h, r }, z + self.origin))
    }

    fn position(&self, x: &Vector<N>) -> Vector<2> {
        self.h * x - self.origin
    }

    fn position_cov(&self, p: &Matrix<N, N>) -> Matrix<2, 2> {
        self.h * p * self.h.transpose()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_distr::{Distribution, Normal};

    #[test]
    fn unbiased_conversion_is_unbiased_and_its_covariance_matches_monte_carlo() {
        // Large azimuth noise (0.1 rad) makes the plain conversion's bias visible:
        // E[r cos θ] = λ r cos θ₀. The unbiased conversion removes it (Longbin et al. 1998).
        let (r0, th0, sr, st) = (10_000.0_f64, 0.7_f64, 50.0, 0.1);
        let var = NoiseVariances::from_sigmas(sr, st).unwrap();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let nr = Normal::new(0.0, sr).unwrap();
        let nt = Normal::new(0.0, st).unwrap();
        let n = 200_000;
        let mut mean = Vector::<2>::zeros();
        let mut zs = Vec::with_capacity(n);
        let mut rsum = Matrix::<2, 2>::zeros();
        for _ in 0..n {
            let plot =
                PolarMeasurement::new(r0 + nr.sample(&mut rng), th0 + nt.sample(&mut rng)).unwrap();
            let (z, r) = unbiased_conversion(&plot, &var).unwrap();
            mean += z;
            rsum += r;
            zs.push(z);
        }
        mean /= n as f64;
        let truth = Vector::<2>::new(r0 * th0.cos(), r0 * th0.sin());
        // Standard error of the mean ≈ sqrt(R/n) ≈ 1000/447 ≈ 2.3 m per axis; allow 4σ ≈ 10 m.
        // The plain conversion's bias would be (1 − λ) r ≈ 50 m here.
        assert!((mean - truth).norm() < 10.0, "{mean} vs {truth}");
        let mut cov = Matrix::<2, 2>::zeros();
        for z in &zs {
            let d = z - truth;
            cov += d * d.transpose();
        }
        cov /= n as f64;
        let avg_r = rsum / n as f64;
        // Derived here: E[R^a] − Cov = ½ r² (1 − λ')² [[cos 2θ, sin 2θ], [sin 2θ, −cos 2θ]]
        // + O(σr² σθ²) (take expectations of the formula: E[cos 2θ_m] = λ' cos 2θ). With
        // σθ = 0.1 rad that is ≈ 1.9e4 m² on the off-diagonal; at seed 000's 0.08° it is
        // ≈ 1e-3 m². Sampling sd of an entry ≈ 5e5·sqrt(2/n) ≈ 1.6e3 m²: allow 5e3 (≈ 3σ).
        let lp = (-2.0 * st * st).exp();
        let k = 0.5 * r0 * r0 * (1.0 - lp).powi(2);
        let (s2, c2) = (2.0 * th0).sin_cos();
        let bias = Matrix::<2, 2>::new(c2, s2, s2, -c2) * k;
        assert!((avg_r - cov - bias).amax() < 5e3, "{cov} vs {avg_r}");
        assert!(
            (avg_r - cov).amax() > 1.5e4,
            "the bias term is real at this σθ"
        );
    }

    #[test]
    fn bad_plots_and_variances_are_rejected() {
        assert!(PolarMeasurement::new(-1.0, 0.0).is_err());
        assert!(PolarMeasurement::new(1.0, f64::NAN).is_err());
        assert!(NoiseVariances::new(0.0, 1.0).is_err());
        assert!(NoiseVariances::new(1.0, f64::INFINITY).is_err());
        assert!(UnbiasedConversion::<4>::new(0, 4).is_err());
        assert!(UnbiasedConversion::<4>::new(2, 2).is_err());
        assert!(
            PositionMeasurement::<4>::new(0, 2, Matrix::<2, 2>::new(1.0, 2.0, 2.0, 1.0)).is_err()
        );
    }
}

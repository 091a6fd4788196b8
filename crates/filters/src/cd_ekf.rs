//! The continuous–discrete extended Kalman filter.

use argus_core_math::{Gaussian, Matrix, Vector, check_finite_matrix, symmetrize};
use argus_motion_models::ContinuousModel;
use argus_sensors::MeasurementModel;

use crate::ekf::second_order_measurement;
use crate::linearized::{checked_gaussian, first_order_measurement};
use crate::second_order::second_order_terms;
use crate::{CovarianceForm, FilterError, GaussianFilter, MeasurementPrediction, check_dt};

/// Largest number of RK4 substeps per prediction accepted by [`CdEkf::new`].
pub const MAX_SUBSTEPS: usize = 100_000;

/// The continuous–discrete EKF: between plots the mean and covariance follow
///
/// `dx̂/dt = a(x̂)` (plus `½ Σᵢ eᵢ tr(Aᵢ P)` with the drift correction),
/// `dP/dt = A P + P Aᵀ + Q_c`, `A = ∂a/∂x(x̂)`, `Aᵢ = ∂²aᵢ/∂x²(x̂)`,
///
/// integrated jointly by classical fourth-order Runge–Kutta with a fixed number of
/// equal substeps; at a plot the update is the EKF's (first order) or, when
/// enabled, the truncated second-order one (see [`crate::SecondOrderEkf`]).
///
/// With the drift correction and the second-order update this is the truncated
/// second-order filter of seed 001 (its `Ṗ` is the EKF's: the Gaussian fourth-moment
/// terms vanish for a state-independent `Q_c`).
///
/// # References
/// Seed 001 eqs (2-1)–(2-6); Gelb (1974), *Applied Optimal Estimation*, Table 6.1-1
/// (EKF) and Table 6.1-2 (truncated second-order filter); Jazwinski (1970) §9.3.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CdEkf<Mo> {
    model: Mo,
    substeps: usize,
    drift_correction: bool,
    second_order_update: bool,
    form: CovarianceForm,
}

impl<Mo> CdEkf<Mo> {
    /// A continuous–discrete EKF on `model`, integrating each prediction with
    /// `substeps` RK4 steps; first order (no drift correction, EKF update), Joseph form.
    ///
    /// # Errors
    /// [`FilterError::InvalidParameter`] when `substeps` is 0 or above [`MAX_SUBSTEPS`].
    pub fn new(model: Mo, substeps: usize) -> Result<Self, FilterError> {
        if substeps == 0 || substeps > MAX_SUBSTEPS {
            return Err(FilterError::InvalidParameter {
                what: "substeps",
                value: substeps as f64,
                reason: "must be between 1 and MAX_SUBSTEPS = 100000",
            });
        }
        Ok(Self {
            model,
            substeps,
            drift_correction: false,
            second_order_update: false,
            form: CovarianceForm::default(),
        })
    }

    /// Turns the second-order drift correction `½ Σᵢ eᵢ tr(Aᵢ P)` on or off.
    #[must_use]
    pub fn with_drift_correction(mut self, on: bool) -> Self {
        self.drift_correction = on;
        self
    }

    /// Turns the truncated second-order measurement update on or off (it needs the
    /// measurement model's Hessians).
    #[must_use]
    pub fn with_second_order_update(mut self, on: bool) -> Self {
        self.second_order_update = on;
        self
    }

    /// Sets the covariance update form.
    #[must_use]
    pub fn with_form(mut self, form: CovarianceForm) -> Self {
        self.form = form;
        self
    }

    /// The continuous-time model.
    #[must_use]
    pub fn model(&self) -> &Mo {
        &self.model
    }

    /// The number of RK4 substeps per prediction.
    #[must_use]
    pub fn substeps(&self) -> usize {
        self.substeps
    }

    /// Whether the second-order drift correction is on.
    #[must_use]
    pub fn drift_correction(&self) -> bool {
        self.drift_correction
    }

    /// Whether the second-order measurement update is on.
    #[must_use]
    pub fn second_order_update(&self) -> bool {
        self.second_order_update
    }
}

impl<Mo> CdEkf<Mo> {
    /// The right-hand side of the moment equations at `(x, P)`.
    #[allow(non_snake_case)]
    fn rates<const N: usize>(
        &self,
        x: &Vector<N>,
        P: &Matrix<N, N>,
        Qc: &Matrix<N, N>,
    ) -> (Vector<N>, Matrix<N, N>)
    where
        Mo: ContinuousModel<N>,
    {
        let A = self.model.drift_jacobian(x);
        let mut dx = self.model.drift(x);
        if self.drift_correction {
            let hess = self.model.drift_hessians(x);
            dx += second_order_terms(&hess, P).0;
        }
        let AP = A * P;
        (dx, AP + AP.transpose() + Qc)
    }
}

impl<const N: usize, Mo: ContinuousModel<N>> GaussianFilter<N> for CdEkf<Mo> {
    /// Integrates the moment equations over `dt` (see the type's docs).
    ///
    /// # Errors
    /// [`FilterError::InvalidInterval`] for a bad `dt`; [`FilterError::Math`] when
    /// `Q_c` or the result is non-finite or `P⁻` is not positive definite.
    #[allow(non_snake_case)]
    fn predict(&self, prior: &Gaussian<N>, dt: f64) -> Result<Gaussian<N>, FilterError> {
        check_dt(dt)?;
        let Qc = self.model.diffusion();
        check_finite_matrix(&Qc, "diffusion Q_c")?;
        let h = dt / self.substeps as f64;
        let mut x = *prior.mean();
        let mut P = *prior.cov();
        for _ in 0..self.substeps {
            let (k1x, k1p) = self.rates(&x, &P, &Qc);
            let (k2x, k2p) = self.rates(&(x + k1x * (0.5 * h)), &(P + k1p * (0.5 * h)), &Qc);
            let (k3x, k3p) = self.rates(&(x + k2x * (0.5 * h)), &(P + k2p * (0.5 * h)), &Qc);
            let (k4x, k4p) = self.rates(&(x + k3x * h), &(P + k3p * h), &Qc);
            x += (k1x + (k2x + k3x) * 2.0 + k4x) * (h / 6.0);
            P = symmetrize(&(P + (k1p + (k2p + k3p) * 2.0 + k4p) * (h / 6.0)));
        }
        checked_gaussian(x, P, "predicted mean", "predicted covariance")
    }

    /// The EKF's measurement prediction, or the truncated second-order one when enabled.
    ///
    /// # Errors
    /// [`FilterError::HessiansUnavailable`] (second-order update without measurement
    /// Hessians); [`FilterError::Math`] when a value is non-finite or `S` is not
    /// positive definite.
    fn predict_measurement<const M: usize, Me: MeasurementModel<N, M>>(
        &self,
        predicted: &Gaussian<N>,
        meas: &Me,
    ) -> Result<MeasurementPrediction<N, M>, FilterError> {
        if self.second_order_update {
            second_order_measurement(predicted, meas, self.form)
        } else {
            first_order_measurement(predicted, meas, self.form)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_models::{ContinuousCv1, Decay, Pos1, SquareRate};
    use argus_core_math::{MathError, Matrix, Vector};

    fn prior() -> Gaussian<2> {
        Gaussian::new(
            Vector::<2>::new(10.0, 3.0),
            Matrix::<2, 2>::new(4.0, 1.0, 1.0, 2.0),
        )
        .unwrap()
    }

    #[test]
    fn linear_cv_matches_the_exact_discretisation() {
        // For ẋ = v, v̇ = w (spectral density q) the exact discrete model is
        // F = [[1, T], [0, 1]], Q = q [[T³/3, T²/2], [T²/2, T]] (Bar-Shalom et al.
        // 2001 eq 6.2.2-12). The moment ODE has a cubic solution in t, which RK4
        // integrates exactly: tolerance is round-off, for any substep count.
        let (q, t) = (0.7, 2.5);
        for n in [1, 3, 50] {
            let f = CdEkf::new(ContinuousCv1 { q }, n).unwrap();
            let pred = f.predict(&prior(), t).unwrap();
            let fm = Matrix::<2, 2>::new(1.0, t, 0.0, 1.0);
            let qm = Matrix::<2, 2>::new(t.powi(3) / 3.0, t * t / 2.0, t * t / 2.0, t) * q;
            let p = fm * prior().cov() * fm.transpose() + qm;
            assert!((pred.mean() - fm * prior().mean()).amax() < 1e-12);
            assert!((pred.cov() - p).amax() < 1e-12, "{n}: {}", pred.cov() - p);
        }
    }

    #[test]
    fn drift_correction_gives_the_exact_mean_of_a_quadratic_drift() {
        // ẋ₁ = x₂², ẋ₂ = 0: x₁(T) = x₁ + T x₂², so E[x₁(T)] = x̂₁ + T (x̂₂² + P₂₂);
        // P₂₂ stays constant, so the corrected mean ODE is exact (RK4 on a linear
        // solution). Without the correction the mean misses T P₂₂.
        let t = 1.5;
        let corrected = CdEkf::new(SquareRate, 4)
            .unwrap()
            .with_drift_correction(true)
            .predict(&prior(), t)
            .unwrap();
        let plain = CdEkf::new(SquareRate, 4)
            .unwrap()
            .predict(&prior(), t)
            .unwrap();
        let exact = 10.0 + t * (9.0 + 2.0);
        assert!((corrected.mean()[0] - exact).abs() < 1e-12);
        assert!((plain.mean()[0] - (10.0 + t * 9.0)).abs() < 1e-12);
    }

    #[test]
    fn rk4_converges_with_fourth_order_on_exponential_decay() {
        // ẋ = −k x, Q_c = q I: x(T) = e^{−kT} x₀, P(T) = e^{−2kT} P₀ + q (1 − e^{−2kT}) / (2k)
        // I (scalar linear ODEs). RK4's global error is O(h⁴): doubling the substeps
        // divides it by ≈ 16 once h·2k ≪ 1 (h·2k = 0.0375 → 0.019 here).
        let (k, q, t): (f64, f64, f64) = (0.8, 0.5, 3.0);
        let exact_p11 = (-2.0 * k * t).exp() * 4.0 + q * (1.0 - (-2.0 * k * t).exp()) / (2.0 * k);
        let err = |n: usize| {
            let f = CdEkf::new(Decay { k, q }, n).unwrap();
            (f.predict(&prior(), t).unwrap().cov()[(0, 0)] - exact_p11).abs()
        };
        // Measured: err(n)/err(2n) = 20.7, 18.1, 17.0, 16.5, 16.25 for n = 8 … 128 (the
        // excess over 16 halves with h, as the next error term predicts).
        let ratio = err(128) / err(256);
        assert!((15.5..16.5).contains(&ratio), "error ratio {ratio}");
        assert!(err(256) < 1e-9, "{}", err(256));
        let mean = CdEkf::new(Decay { k, q }, 256)
            .unwrap()
            .predict(&prior(), t)
            .unwrap();
        // RK4's global error on ẏ = −ky: ≈ kT (kh)⁴ / 120 relative = 1.5e-10 (h = T/256).
        let rel = (mean.mean()[0] / (10.0 * (-k * t).exp()) - 1.0).abs();
        assert!(rel < 3e-10, "{rel:e}");
    }

    #[test]
    fn rejects_bad_parameters_and_intervals() {
        for n in [0, MAX_SUBSTEPS + 1] {
            assert!(matches!(
                CdEkf::new(ContinuousCv1 { q: 1.0 }, n),
                Err(FilterError::InvalidParameter {
                    what: "substeps",
                    ..
                })
            ));
        }
        let f = CdEkf::new(ContinuousCv1 { q: 1.0 }, 10).unwrap();
        for dt in [0.0, -1.0, f64::NAN] {
            assert!(matches!(
                f.predict(&prior(), dt),
                Err(FilterError::InvalidInterval { .. })
            ));
        }
        let g = CdEkf::new(ContinuousCv1 { q: f64::NAN }, 10).unwrap();
        assert_eq!(
            g.predict(&prior(), 1.0).unwrap_err(),
            FilterError::Math(MathError::NonFinite {
                what: "diffusion Q_c"
            })
        );
        let so = CdEkf::new(ContinuousCv1 { q: 1.0 }, 10)
            .unwrap()
            .with_second_order_update(true);
        assert_eq!(
            so.predict_measurement(&prior(), &Pos1 { r: 1.0 })
                .unwrap_err(),
            FilterError::HessiansUnavailable {
                what: "measurement model"
            }
        );
    }
}

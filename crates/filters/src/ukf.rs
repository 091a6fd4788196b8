//! The unscented Kalman filter (scaled unscented transform).

use argus_core_math::{Gaussian, Matrix, Vector, check_finite_matrix, check_finite_vector};
use argus_motion_models::MotionModel;
use argus_sensors::MeasurementModel;

use crate::linearized::checked_gaussian;
use crate::{CovarianceForm, FilterError, GaussianFilter, MeasurementPrediction, check_dt};

/// Parameters of the scaled unscented transform.
///
/// `λ = α² (N + κ) − N`; sigma points `x̂` and `x̂ ± √(N + λ) Lⱼ` (`P = L Lᵀ`); weights
/// `W₀ᵐ = λ / (N + λ)`, `W₀ᶜ = W₀ᵐ + 1 − α² + β`, `Wᵢ = 1 / (2 (N + λ))`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UtParams {
    /// Spread of the sigma points, `0 < α ≤ 1`.
    pub alpha: f64,
    /// Prior-knowledge weight on the centre point's covariance, `β ≥ 0` (2 is optimal for Gaussians).
    pub beta: f64,
    /// Secondary scaling, with `N + κ > 0`.
    pub kappa: f64,
}

impl Default for UtParams {
    /// `α = 1, β = 2, κ = 0`: `λ = 0`, all weights non-negative
    /// (`W₀ᵐ = 0`, `W₀ᶜ = 2`, `Wᵢ = 1/(2N)`), sigma points at `±√N` standard deviations.
    fn default() -> Self {
        Self {
            alpha: 1.0,
            beta: 2.0,
            kappa: 0.0,
        }
    }
}

/// The unscented Kalman filter with the scaled unscented transform.
///
/// Prediction propagates the `2N + 1` sigma points of the prior through `f` and
/// adds `Q(x̂, dt)`; the measurement prediction passes the sigma points of the
/// predicted estimate through `h` and adds `R(x⁻)`. Measurement sigma points are
/// taken relative to the centre point through [`MeasurementModel::residual`], so an
/// azimuth near ±π averages correctly. The moments are accumulated on the fly
/// (no sigma-point storage, no heap): with `dᵢ = g(χᵢ) − g(χ₀)`,
/// `m = Σᵢ Wᵢ dᵢ`, the mean is `g(χ₀) + m` and the covariance
/// `Σᵢ Wᵢ dᵢ dᵢᵀ + (β − α²) m mᵀ` (algebraically equal to the textbook form, since
/// `Σᵢ Wᵢ (χᵢ − x̂) = 0` and `W₀ᶜ − W₀ᵐ = 1 − α² + β`). The UKF has no measurement
/// Jacobian, so the update uses `P = P⁻ − K S Kᵀ` whatever the [`CovarianceForm`].
///
/// # References
/// Julier & Uhlmann (2004), "Unscented filtering and nonlinear estimation", Proc.
/// IEEE 92(3); Julier (2002), "The scaled unscented transformation", ACC; Wan & van
/// der Merwe (2000), "The unscented Kalman filter for nonlinear estimation", eqs (15)–(16).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ukf<const N: usize, Mo> {
    model: Mo,
    params: UtParams,
    /// `√(N + λ)`.
    scale: f64,
    /// `Wᵢ`, `i ≥ 1`.
    weight: f64,
    /// `β − α²`.
    centre_extra: f64,
}

impl<const N: usize, Mo> Ukf<N, Mo> {
    /// A UKF on `model` with the scaled unscented transform `params`.
    ///
    /// # Errors
    /// [`FilterError::InvalidParameter`] when `α ∉ (0, 1]`, `β < 0`, `κ` is not
    /// finite or `N + κ ≤ 0` (any of them NaN included).
    pub fn new(model: Mo, params: UtParams) -> Result<Self, FilterError> {
        let UtParams { alpha, beta, kappa } = params;
        if !(alpha.is_finite() && alpha > 0.0 && alpha <= 1.0) {
            return Err(FilterError::InvalidParameter {
                what: "UKF alpha",
                value: alpha,
                reason: "must lie in (0, 1]",
            });
        }
        if !(beta.is_finite() && beta >= 0.0) {
            return Err(FilterError::InvalidParameter {
                what: "UKF beta",
                value: beta,
                reason: "must be finite and non-negative",
            });
        }
        let n = N as f64;
        if !(kappa.is_finite() && n + kappa > 0.0) {
            return Err(FilterError::InvalidParameter {
                what: "UKF kappa",
                value: kappa,
                reason: "must be finite with N + kappa > 0",
            });
        }
        let n_plus_lambda = alpha * alpha * (n + kappa);
        Ok(Self {
            model,
            params,
            scale: n_plus_lambda.sqrt(),
            weight: 0.5 / n_plus_lambda,
            centre_extra: beta - alpha * alpha,
        })
    }

    /// A UKF on `model` with the default parameters ([`UtParams::default`]).
    ///
    /// # Errors
    /// [`FilterError::InvalidParameter`] only for `N = 0` (no sigma points).
    pub fn with_defaults(model: Mo) -> Result<Self, FilterError> {
        Self::new(model, UtParams::default())
    }

    /// The motion model.
    #[must_use]
    pub fn model(&self) -> &Mo {
        &self.model
    }

    /// The unscented-transform parameters.
    #[must_use]
    pub fn params(&self) -> UtParams {
        self.params
    }

    /// The sigma-point weights `(W₀ᵐ, W₀ᶜ, Wᵢ)`.
    #[must_use]
    pub fn weights(&self) -> (f64, f64, f64) {
        let w0m = 1.0 - 2.0 * N as f64 * self.weight;
        (
            w0m,
            w0m + 1.0 - self.params.alpha.powi(2) + self.params.beta,
            self.weight,
        )
    }

    /// Visits the `2N` off-centre sigma offsets `±√(N+λ) Lⱼ` of `g`.
    fn for_each_offset(
        &self,
        g: &Gaussian<N>,
        mut visit: impl FnMut(&Vector<N>),
    ) -> Result<(), FilterError> {
        let l = g.factor()?.l() * self.scale;
        for col in l.column_iter() {
            let s: Vector<N> = col.into_owned();
            visit(&s);
            visit(&(-s));
        }
        Ok(())
    }
}

impl<const N: usize, Mo: MotionModel<N>> Ukf<N, Mo> {
    /// The unscented prediction, and with `CROSS` the cross covariance of the prior and
    /// the prediction, `C = Σᵢ Wᵢ sᵢ dᵢᵀ` (Särkkä 2008 eq (14): the centre point's term
    /// is zero and `Σᵢ Wᵢ sᵢ = 0`, so the propagated mean drops out); zero without it.
    #[allow(non_snake_case)]
    #[inline]
    pub(crate) fn unscented_predict<const CROSS: bool>(
        &self,
        prior: &Gaussian<N>,
        dt: f64,
    ) -> Result<(Gaussian<N>, Matrix<N, N>), FilterError> {
        check_dt(dt)?;
        let x = prior.mean();
        let y0 = self.model.propagate(x, dt);
        check_finite_vector(&y0, "propagated sigma point")?;
        let mut m = Vector::<N>::zeros();
        let mut S2 = Matrix::<N, N>::zeros();
        let mut C = Matrix::<N, N>::zeros();
        let w = self.weight;
        self.for_each_offset(prior, |s| {
            let d = self.model.propagate(&(x + s), dt) - y0;
            m.axpy(w, &d, 1.0);
            S2.ger(w, &d, &d, 1.0);
            if CROSS {
                C.ger(w, s, &d, 1.0);
            }
        })?;
        check_finite_vector(&m, "propagated sigma point")?;
        let Q = self.model.process_noise(x, dt);
        check_finite_matrix(&Q, "process noise Q")?;
        let cov = S2 + m * m.transpose() * self.centre_extra + Q;
        let g = checked_gaussian(y0 + m, cov, "predicted mean", "predicted covariance")?;
        Ok((g, C))
    }
}

impl<const N: usize, Mo: MotionModel<N>> GaussianFilter<N> for Ukf<N, Mo> {
    /// Unscented prediction: sigma points of the prior through `f`, plus `Q(x̂, dt)`.
    ///
    /// # Errors
    /// [`FilterError::InvalidInterval`] for a bad `dt`; [`FilterError::Math`] when a
    /// propagated point or `Q` is non-finite or `P⁻` is not positive definite (possible
    /// with a negative `W₀ᶜ`).
    fn predict(&self, prior: &Gaussian<N>, dt: f64) -> Result<Gaussian<N>, FilterError> {
        Ok(self.unscented_predict::<false>(prior, dt)?.0)
    }

    /// Unscented measurement prediction: `ẑ`, `S = P_zz + R(x⁻)`, `P_xz`; measurement
    /// sigma points taken relative to the centre through `meas.residual`.
    ///
    /// # Errors
    /// [`FilterError::Math`] when a value is non-finite or `S` is not positive definite.
    #[allow(non_snake_case)]
    fn predict_measurement<const M: usize, Me: MeasurementModel<N, M>>(
        &self,
        predicted: &Gaussian<N>,
        meas: &Me,
    ) -> Result<MeasurementPrediction<N, M>, FilterError> {
        let x = predicted.mean();
        let z0 = meas.predict(x);
        check_finite_vector(&z0, "predicted measurement")?;
        let mut m = Vector::<M>::zeros();
        let mut Szz = Matrix::<M, M>::zeros();
        let mut Pxz = Matrix::<N, M>::zeros();
        let w = self.weight;
        self.for_each_offset(predicted, |s| {
            let d = meas.residual(&meas.predict(&(x + s)), &z0);
            m.axpy(w, &d, 1.0);
            Szz.ger(w, &d, &d, 1.0);
            Pxz.ger(w, s, &d, 1.0);
        })?;
        let R = meas.noise(x);
        check_finite_matrix(&R, "measurement noise R")?;
        let S = Szz + m * m.transpose() * self.centre_extra + R;
        MeasurementPrediction::new(z0 + m, S, Pxz, None, R, CovarianceForm::Standard)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_models::{Cv2, Polar2, Pos2, Quadratic, QuadraticMotion};
    use crate::{Ekf, Kf};
    use argus_core_math::MathError;

    fn prior4() -> Gaussian<4> {
        #[rustfmt::skip]
        let p = Matrix::<4, 4>::new(
            400.0, 20.0, 10.0, 0.0,
            20.0, 25.0, 0.0, 1.0,
            10.0, 0.0, 300.0, 15.0,
            0.0, 1.0, 15.0, 16.0,
        );
        Gaussian::new(Vector::<4>::new(1000.0, -5.0, 2000.0, 8.0), p).unwrap()
    }

    fn param_sets() -> [UtParams; 3] {
        [
            UtParams::default(),
            UtParams {
                alpha: 0.5,
                beta: 2.0,
                kappa: 1.0,
            },
            UtParams {
                alpha: 1e-3,
                beta: 2.0,
                kappa: 0.0,
            },
        ]
    }

    #[test]
    fn reduces_to_kf_on_a_linear_model() {
        // The unscented transform of a linear map is exact: UKF = KF (to round-off;
        // 1e-9 relative), for any valid parameters, including a negative W₀.
        let meas = Pos2 {
            r: Matrix::<2, 2>::new(50.0, 5.0, 5.0, 40.0),
        };
        let kf = Kf::with_form(Cv2 { q: 0.5 }, CovarianceForm::Standard);
        for params in param_sets() {
            let ukf = Ukf::new(Cv2 { q: 0.5 }, params).unwrap();
            let (mut a, mut b) = (prior4(), prior4());
            for k in 0..20 {
                let z = Vector::<2>::new(1000.0 - 5.0 * k as f64, 2000.0 + 8.0 * k as f64 + 3.0);
                a = kf
                    .update(&kf.predict(&a, 1.5).unwrap(), &meas, &z)
                    .unwrap()
                    .0;
                b = ukf
                    .update(&ukf.predict(&b, 1.5).unwrap(), &meas, &z)
                    .unwrap()
                    .0;
            }
            assert!(
                (a.mean() - b.mean()).amax() < 1e-9 * a.mean().amax(),
                "{params:?}"
            );
            assert!(
                (a.cov() - b.cov()).amax() < 1e-9 * a.cov().amax(),
                "{params:?}"
            );
        }
    }

    #[test]
    fn mean_of_a_quadratic_is_exact() {
        // The UT captures E[g(x)] exactly up to second order: for h = xᵀAx,
        // E[h] = x̂ᵀAx̂ + tr(AP) (round-off tolerance), whatever α, β, κ.
        let a = Matrix::<2, 2>::new(0.5, 0.2, 0.2, -1.0);
        let meas = Quadratic { a, r: 0.3 };
        let pred = Gaussian::new(
            Vector::<2>::new(1.5, -0.7),
            Matrix::<2, 2>::new(0.8, 0.3, 0.3, 0.5),
        )
        .unwrap();
        let expect = (pred.mean().transpose() * a * pred.mean())[0] + (a * pred.cov()).trace();
        for params in param_sets() {
            let ukf = Ukf::new(QuadraticMotion { q: 0.0 }, params).unwrap();
            let mp = ukf.predict_measurement(&pred, &meas).unwrap();
            assert!(
                (mp.z_pred()[0] - expect).abs() < 1e-9,
                "{params:?}: {}",
                mp.z_pred()[0]
            );
        }
    }

    #[test]
    fn weights_sum_to_one() {
        // Σ Wᵐ = 1 and W₀ᶜ − W₀ᵐ = 1 − α² + β (Wan & van der Merwe 2000, eq 15).
        for params in param_sets() {
            let ukf = Ukf::<4, _>::new(Cv2 { q: 0.5 }, params).unwrap();
            let (w0m, w0c, wi) = ukf.weights();
            assert!((w0m + 8.0 * wi - 1.0).abs() < 1e-9);
            assert!((w0c - w0m - (1.0 - params.alpha.powi(2) + params.beta)).abs() < 1e-9);
        }
    }

    #[test]
    fn azimuth_near_pi_is_averaged_through_the_residual() {
        // A target behind the radar, straddling the ±π cut: sigma points' azimuths
        // fall on both sides. The predicted azimuth must stay near π (a naive average
        // lands near 0); it agrees with the EKF's h(x̂) up to the second-order bias,
        // which here is ≈ 0 by symmetry (y = 0).
        let p = Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(100.0, 1.0, 2500.0, 1.0));
        let pred = Gaussian::new(Vector::<4>::new(-1000.0, 0.0, 0.0, 0.0), p).unwrap();
        let polar = Polar2 {
            sigma_r: 5.0,
            sigma_az: 1e-3,
        };
        let ukf = Ukf::with_defaults(Cv2 { q: 1.0 }).unwrap();
        let mp = ukf.predict_measurement(&pred, &polar).unwrap();
        let ekf = Ekf::new(Cv2 { q: 1.0 })
            .predict_measurement(&pred, &polar)
            .unwrap();
        let d = polar.residual(mp.z_pred(), ekf.z_pred());
        assert!(
            d[1].abs() < 1e-9,
            "azimuth {} vs {}",
            mp.z_pred()[1],
            ekf.z_pred()[1]
        );
        // Azimuth spread ≈ σ_y / r = 0.05 rad: S₂₂ ≈ 0.0025 + R, not ~π².
        assert!((mp.s()[(1, 1)] - ekf.s()[(1, 1)]).abs() < 0.1 * ekf.s()[(1, 1)]);
    }

    #[test]
    fn rejects_bad_parameters() {
        let bad = [
            (0.0, 2.0, 0.0, "UKF alpha"),
            (1.5, 2.0, 0.0, "UKF alpha"),
            (f64::NAN, 2.0, 0.0, "UKF alpha"),
            (1.0, -1.0, 0.0, "UKF beta"),
            (1.0, f64::NAN, 0.0, "UKF beta"),
            (1.0, 2.0, -4.0, "UKF kappa"),
            (1.0, 2.0, f64::INFINITY, "UKF kappa"),
            (1.0, 2.0, f64::NAN, "UKF kappa"),
        ];
        for (alpha, beta, kappa, name) in bad {
            let r = Ukf::<4, _>::new(Cv2 { q: 1.0 }, UtParams { alpha, beta, kappa });
            assert!(
                matches!(r, Err(FilterError::InvalidParameter { what, .. }) if what == name),
                "{alpha} {beta} {kappa}"
            );
        }
    }

    #[test]
    fn rejects_bad_steps() {
        let ukf = Ukf::with_defaults(Cv2 { q: 1.0 }).unwrap();
        for dt in [0.0, -2.0, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                ukf.predict(&prior4(), dt),
                Err(FilterError::InvalidInterval { .. })
            ));
        }
        let polar = Polar2 {
            sigma_r: 10.0,
            sigma_az: 0.01,
        };
        assert_eq!(
            ukf.update(&prior4(), &polar, &Vector::<2>::new(1.0, f64::NAN))
                .unwrap_err(),
            FilterError::Math(MathError::NonFinite {
                what: "measurement"
            })
        );
        let bad = Pos2 {
            r: -Matrix::<2, 2>::new(400.0, 10.0, 10.0, 300.0),
        };
        assert_eq!(
            ukf.predict_measurement(&prior4(), &bad).unwrap_err(),
            FilterError::Math(MathError::NotPositiveDefinite {
                what: "innovation covariance S"
            })
        );
        let nan_q = Ukf::with_defaults(Cv2 { q: f64::NAN }).unwrap();
        assert_eq!(
            nan_q.predict(&prior4(), 1.0).unwrap_err(),
            FilterError::Math(MathError::NonFinite {
                what: "process noise Q"
            })
        );
    }
}

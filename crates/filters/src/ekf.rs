//! The extended Kalman filter and the truncated second-order EKF.

use argus_core_math::{Gaussian, check_finite_matrix, check_finite_vector};
use argus_motion_models::MotionModel;
use argus_sensors::MeasurementModel;

use crate::linearized::{
    checked_gaussian, first_order_measurement, linearized_predict, linearized_predict_in_place,
};
use crate::second_order::second_order_terms;
use crate::{CovarianceForm, FilterError, GaussianFilter, MeasurementPrediction, check_dt};

/// The extended Kalman filter: Jacobians at the prior mean (prediction) and at
/// the predicted mean (update).
///
/// `x⁻ = f(x̂, dt)`, `P⁻ = F P Fᵀ + Q` with `F = ∂f/∂x(x̂)`; `ẑ = h(x⁻)`,
/// `S = H P⁻ Hᵀ + R` with `H = ∂h/∂x(x⁻)`; `K = P⁻ Hᵀ S⁻¹`; covariance update in
/// the chosen [`CovarianceForm`] (Joseph by default).
///
/// # References
/// Seed 002 eqs (14)–(25); seed 001 eqs (2-3), (2-6); Bar-Shalom, Li &
/// Kirubarajan (2001) §10.3.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ekf<Mo> {
    model: Mo,
    form: CovarianceForm,
}

impl<Mo> Ekf<Mo> {
    /// An EKF on `model` with the Joseph-form covariance update.
    #[must_use]
    pub fn new(model: Mo) -> Self {
        Self::with_form(model, CovarianceForm::default())
    }

    /// An EKF on `model` with the given covariance update form.
    #[must_use]
    pub fn with_form(model: Mo, form: CovarianceForm) -> Self {
        Self { model, form }
    }

    /// The motion model.
    #[must_use]
    pub fn model(&self) -> &Mo {
        &self.model
    }

    /// The covariance update form.
    #[must_use]
    pub fn form(&self) -> CovarianceForm {
        self.form
    }
}

impl<const N: usize, Mo: MotionModel<N>> GaussianFilter<N> for Ekf<Mo> {
    /// `x⁻ = f(x̂, dt)`, `P⁻ = F P Fᵀ + Q(x̂, dt)`, `F = ∂f/∂x(x̂, dt)`.
    ///
    /// # Errors
    /// [`FilterError::InvalidInterval`] for a bad `dt`; [`FilterError::Math`] for a
    /// non-finite value or a `P⁻` that is not positive definite.
    #[allow(non_snake_case)]
    #[inline(always)]
    fn predict(&self, prior: &Gaussian<N>, dt: f64) -> Result<Gaussian<N>, FilterError> {
        linearized_predict(&self.model, prior, dt)
    }

    /// [`GaussianFilter::predict`] written straight into `estimate`.
    #[inline(always)]
    fn predict_in_place(&self, estimate: &mut Gaussian<N>, dt: f64) -> Result<(), FilterError> {
        linearized_predict_in_place(&self.model, estimate, dt)
    }

    /// `ẑ = h(x⁻)`, `H = ∂h/∂x(x⁻)`, `S = H P⁻ Hᵀ + R`, `P_xz = P⁻ Hᵀ`.
    ///
    /// # Errors
    /// [`FilterError::Math`] when a value is non-finite or `S` is not positive definite.
    #[inline(always)]
    fn predict_measurement<const M: usize, Me: MeasurementModel<N, M>>(
        &self,
        predicted: &Gaussian<N>,
        meas: &Me,
    ) -> Result<MeasurementPrediction<N, M>, FilterError> {
        first_order_measurement(predicted, meas, self.form)
    }
}

/// The truncated second-order (Gaussian) EKF: the EKF plus the Hessian terms.
///
/// Prediction, with `Fᵢ = ∂²fᵢ/∂x²` at `x̂`:
/// `x⁻ = f(x̂) + ½ Σᵢ eᵢ tr(Fᵢ P)`, `P⁻ = F P Fᵀ + ½ Σᵢⱼ eᵢ eⱼᵀ tr(Fᵢ P Fⱼ P) + Q`.
/// Measurement, with `Hᵢ = ∂²hᵢ/∂x²` at `x⁻`:
/// `ẑ = h(x⁻) + ½ Σᵢ eᵢ tr(Hᵢ P⁻)`, `S = H P⁻ Hᵀ + ½ Σᵢⱼ eᵢ eⱼᵀ tr(Hᵢ P⁻ Hⱼ P⁻) + R`,
/// `P_xz = P⁻ Hᵀ`. The Joseph form treats the second-order term as part of the
/// measurement noise (`R + ½ Σ …`), so it equals the standard form at the optimal gain.
/// Both moments are exact for a quadratic `f` or `h`.
///
/// # References
/// Bar-Shalom, Li & Kirubarajan (2001) §10.3.2–10.3.3 (eqs 10.3.2-4, 10.3.2-6,
/// 10.3.3-2, 10.3.3-4); Gelb (1974) Table 6.1-2; seed 001 (truncated second-order filter).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SecondOrderEkf<Mo> {
    model: Mo,
    form: CovarianceForm,
}

impl<Mo> SecondOrderEkf<Mo> {
    /// A second-order EKF on `model` with the Joseph-form covariance update.
    #[must_use]
    pub fn new(model: Mo) -> Self {
        Self::with_form(model, CovarianceForm::default())
    }

    /// A second-order EKF on `model` with the given covariance update form.
    #[must_use]
    pub fn with_form(model: Mo, form: CovarianceForm) -> Self {
        Self { model, form }
    }

    /// The motion model.
    #[must_use]
    pub fn model(&self) -> &Mo {
        &self.model
    }

    /// The covariance update form.
    #[must_use]
    pub fn form(&self) -> CovarianceForm {
        self.form
    }
}

impl<const N: usize, Mo: MotionModel<N>> GaussianFilter<N> for SecondOrderEkf<Mo> {
    /// Second-order prediction (see the type's docs).
    ///
    /// # Errors
    /// [`FilterError::InvalidInterval`] for a bad `dt`;
    /// [`FilterError::HessiansUnavailable`] when the motion model has no Hessians;
    /// [`FilterError::Math`] for a non-finite value or a `P⁻` that is not positive definite.
    #[allow(non_snake_case)]
    fn predict(&self, prior: &Gaussian<N>, dt: f64) -> Result<Gaussian<N>, FilterError> {
        check_dt(dt)?;
        let x = prior.mean();
        let P = prior.cov();
        let hess = self
            .model
            .hessians(x, dt)
            .ok_or(FilterError::HessiansUnavailable {
                what: "motion model",
            })?;
        for h in &hess {
            check_finite_matrix(h, "motion-model Hessian")?;
        }
        let (dmean, dcov) = second_order_terms(&hess, P);
        let F = self.model.jacobian(x, dt);
        let Q = self.model.process_noise(x, dt);
        check_finite_matrix(&F, "transition matrix F")?;
        check_finite_matrix(&Q, "process noise Q")?;
        let cov = F * P * F.transpose() + dcov + Q;
        checked_gaussian(
            self.model.propagate(x, dt) + dmean,
            cov,
            "predicted mean",
            "predicted covariance",
        )
    }

    /// Second-order measurement prediction (see the type's docs).
    ///
    /// # Errors
    /// [`FilterError::HessiansUnavailable`] when the measurement model has no Hessians;
    /// [`FilterError::Math`] when a value is non-finite or `S` is not positive definite.
    #[allow(non_snake_case)]
    fn predict_measurement<const M: usize, Me: MeasurementModel<N, M>>(
        &self,
        predicted: &Gaussian<N>,
        meas: &Me,
    ) -> Result<MeasurementPrediction<N, M>, FilterError> {
        second_order_measurement(predicted, meas, self.form)
    }
}

/// The truncated second-order measurement prediction at `predicted` (see
/// [`SecondOrderEkf`]); shared with the continuous–discrete filter.
#[allow(non_snake_case)]
pub(crate) fn second_order_measurement<const N: usize, const M: usize, Me>(
    predicted: &Gaussian<N>,
    meas: &Me,
    form: CovarianceForm,
) -> Result<MeasurementPrediction<N, M>, FilterError>
where
    Me: MeasurementModel<N, M>,
{
    let x = predicted.mean();
    let P = predicted.cov();
    let hess = meas.hessians(x).ok_or(FilterError::HessiansUnavailable {
        what: "measurement model",
    })?;
    for h in &hess {
        check_finite_matrix(h, "measurement Hessian")?;
    }
    let (dz, dS) = second_order_terms(&hess, P);
    let z_pred = meas.predict(x) + dz;
    check_finite_vector(&z_pred, "predicted measurement")?;
    let H = meas.jacobian(x);
    let R = meas.noise(x);
    check_finite_matrix(&H, "measurement Jacobian H")?;
    check_finite_matrix(&R, "measurement noise R")?;
    let PHt = P * H.transpose();
    let R_eff = R + dS;
    let S = H * PHt + R_eff;
    MeasurementPrediction::new(z_pred, S, PHt, Some(H), R_eff, form)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Kf;
    use crate::test_models::{
        Cv1Dwna, Cv2, Polar2, Pos2, Quadratic, QuadraticMotion, gauss_hermite_moments,
    };
    use argus_core_math::{MathError, Matrix, Vector};

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

    /// `predict_in_place` / `update_in_place` against `predict` / `update` for one filter:
    /// the same numbers bit for bit (the same arithmetic), and the estimate untouched when
    /// the step fails (time going backwards, a NaN plot).
    fn check_in_place<F: GaussianFilter<4>>(f: &F) {
        let polar = Polar2 {
            sigma_r: 30.0,
            sigma_az: 0.002,
        };
        let z = Vector::<2>::new(2250.0, 1.1);
        let prior = prior4();
        let pred = f.predict(&prior, 2.0).unwrap();
        let (post, innov) = f.update(&pred, &polar, &z).unwrap();
        let mut g = prior;
        f.predict_in_place(&mut g, 2.0).unwrap();
        assert_eq!(g, pred);
        let innov_in_place = f.update_in_place(&mut g, &polar, &z).unwrap();
        assert_eq!(g, post);
        assert_eq!(innov_in_place, innov);
        let mut h = prior;
        assert!(f.predict_in_place(&mut h, -1.0).is_err());
        assert!(
            f.update_in_place(&mut h, &polar, &Vector::<2>::new(f64::NAN, 1.0))
                .is_err()
        );
        assert_eq!(h, prior);
    }

    #[test]
    fn in_place_steps_equal_the_returning_ones() {
        for form in [CovarianceForm::Joseph, CovarianceForm::Standard] {
            check_in_place(&Kf::with_form(Cv2 { q: 0.5 }, form));
            check_in_place(&Ekf::with_form(Cv2 { q: 0.5 }, form));
        }
        // The trait's default in-place methods (no override).
        check_in_place(&crate::Ukf::new(Cv2 { q: 0.5 }, crate::UtParams::default()).unwrap());
    }

    #[test]
    fn ekf_reduces_to_kf_on_a_linear_model() {
        // Identity: with linear f and h the EKF equations are the KF's.
        let meas = Pos2 {
            r: Matrix::<2, 2>::new(50.0, 5.0, 5.0, 40.0),
        };
        let kf = Kf::new(Cv2 { q: 0.5 });
        let ekf = Ekf::new(Cv2 { q: 0.5 });
        let so = SecondOrderEkf::new(Cv2 { q: 0.5 });
        let (mut a, mut b, mut c) = (prior4(), prior4(), prior4());
        for k in 0..20 {
            let z = Vector::<2>::new(1000.0 - 5.0 * k as f64, 2000.0 + 8.0 * k as f64 + 3.0);
            a = kf
                .update(&kf.predict(&a, 1.5).unwrap(), &meas, &z)
                .unwrap()
                .0;
            b = ekf
                .update(&ekf.predict(&b, 1.5).unwrap(), &meas, &z)
                .unwrap()
                .0;
            c = so
                .update(&so.predict(&c, 1.5).unwrap(), &meas, &z)
                .unwrap()
                .0;
        }
        // Tolerance 1e-9 relative: round-off only.
        assert!((a.mean() - b.mean()).amax() < 1e-9 * a.mean().amax());
        assert!((a.cov() - b.cov()).amax() < 1e-9 * a.cov().amax());
        assert!((a.mean() - c.mean()).amax() < 1e-9 * a.mean().amax());
        assert!((a.cov() - c.cov()).amax() < 1e-9 * a.cov().amax());
    }

    #[test]
    fn second_order_measurement_is_exact_for_a_quadratic() {
        // E[xᵀAx] = x̂ᵀAx̂ + tr(AP) (= h(x̂) + ½ tr(H P), H = 2A) and
        // Var[xᵀAx] = 4x̂ᵀAPAx̂ + 2tr(APAP) for Gaussian x; checked against exact
        // Gauss–Hermite quadrature. Tolerance: round-off.
        let a = Matrix::<2, 2>::new(0.5, 0.2, 0.2, -1.0);
        let meas = Quadratic { a, r: 0.3 };
        let pred = Gaussian::new(
            Vector::<2>::new(1.5, -0.7),
            Matrix::<2, 2>::new(0.8, 0.3, 0.3, 0.5),
        )
        .unwrap();
        let f = SecondOrderEkf::new(QuadraticMotion { q: 0.0 });
        let mp = f.predict_measurement(&pred, &meas).unwrap();
        let (m, c) = gauss_hermite_moments(|x| meas.predict(x), pred.mean(), pred.cov());
        let x = pred.mean();
        let p = pred.cov();
        let expect_mean = (x.transpose() * a * x)[0] + (a * p).trace();
        assert!((mp.z_pred()[0] - expect_mean).abs() < 1e-12);
        assert!((mp.z_pred()[0] - m[0]).abs() < 1e-12);
        let expect_var = 4.0 * (x.transpose() * a * p * a * x)[0] + 2.0 * (a * p * a * p).trace();
        assert!((mp.s()[(0, 0)] - (expect_var + 0.3)).abs() < 1e-12);
        assert!((mp.s()[(0, 0)] - (c[(0, 0)] + 0.3)).abs() < 1e-12);
        // The first-order EKF misses the bias tr(AP).
        let e = Ekf::new(QuadraticMotion { q: 0.0 })
            .predict_measurement(&pred, &meas)
            .unwrap();
        assert!((mp.z_pred()[0] - e.z_pred()[0] - (a * p).trace()).abs() < 1e-12);
    }

    #[test]
    fn second_order_prediction_is_exact_for_quadratic_dynamics() {
        // Exact moments of f(x) for a quadratic f (Gauss–Hermite quadrature), plus Q.
        let model = QuadraticMotion { q: 0.01 };
        let prior = Gaussian::new(
            Vector::<2>::new(0.4, 1.2),
            Matrix::<2, 2>::new(0.2, -0.05, -0.05, 0.1),
        )
        .unwrap();
        let dt = 0.5;
        let pred = SecondOrderEkf::new(QuadraticMotion { q: 0.01 })
            .predict(&prior, dt)
            .unwrap();
        let (m, c) = gauss_hermite_moments(|x| model.propagate(x, dt), prior.mean(), prior.cov());
        assert!((pred.mean() - m).amax() < 1e-12);
        assert!((pred.cov() - (c + Matrix::<2, 2>::identity() * 0.01)).amax() < 1e-12);
    }

    #[test]
    fn second_order_needs_hessians() {
        let prior = Gaussian::new(Vector::<2>::zeros(), Matrix::<2, 2>::identity()).unwrap();
        let f = SecondOrderEkf::new(Cv1Dwna { sigma_v: 1.0 });
        assert_eq!(
            f.predict(&prior, 1.0).unwrap_err(),
            FilterError::HessiansUnavailable {
                what: "motion model"
            }
        );
        let g = SecondOrderEkf::new(Cv2 { q: 1.0 });
        let polar = Polar2 {
            sigma_r: 10.0,
            sigma_az: 0.01,
        };
        assert_eq!(
            g.predict_measurement(&prior4(), &polar).unwrap_err(),
            FilterError::HessiansUnavailable {
                what: "measurement model"
            }
        );
    }

    #[test]
    fn ekf_rejects_bad_inputs() {
        let ekf = Ekf::new(Cv2 { q: 1.0 });
        let so = SecondOrderEkf::new(Cv2 { q: 1.0 });
        for dt in [0.0, -0.1, f64::NAN, f64::NEG_INFINITY] {
            assert!(matches!(
                ekf.predict(&prior4(), dt),
                Err(FilterError::InvalidInterval { .. })
            ));
            assert!(matches!(
                so.predict(&prior4(), dt),
                Err(FilterError::InvalidInterval { .. })
            ));
        }
        let polar = Polar2 {
            sigma_r: 10.0,
            sigma_az: 0.01,
        };
        let z = Vector::<2>::new(f64::NAN, 0.1);
        assert_eq!(
            ekf.update(&prior4(), &polar, &z).unwrap_err(),
            FilterError::Math(MathError::NonFinite {
                what: "measurement"
            })
        );
        // A polar Jacobian at the sensor's own position is non-finite (0/0).
        let at_origin = Gaussian::new(Vector::<4>::zeros(), Matrix::<4, 4>::identity()).unwrap();
        assert_eq!(
            ekf.predict_measurement(&at_origin, &polar).unwrap_err(),
            FilterError::Math(MathError::NonFinite {
                what: "measurement Jacobian H"
            })
        );
        // A Joseph or standard update whose S is singular: R = −H P Hᵀ.
        let bad = Pos2 {
            r: -Matrix::<2, 2>::new(400.0, 10.0, 10.0, 300.0),
        };
        assert_eq!(
            ekf.predict_measurement(&prior4(), &bad).unwrap_err(),
            FilterError::Math(MathError::NotPositiveDefinite {
                what: "innovation covariance S"
            })
        );
    }
}

//! The linear Kalman filter.

use argus_core_math::{Gaussian, Vector};
use argus_motion_models::LinearMotionModel;
use argus_sensors::MeasurementModel;

use crate::linearized::{
    first_order_measurement, linearized_predict, linearized_predict_in_place,
    linearized_step_in_place,
};
use crate::{CovarianceForm, FilterError, GaussianFilter, Innovation, MeasurementPrediction};

/// The Kalman filter on a linear motion model.
///
/// Prediction `x⁻ = F x`, `P⁻ = F P Fᵀ + Q` (with `F = F(dt)`, `Q = Q(x̂, dt)`);
/// measurement prediction `ẑ = h(x⁻)`, `S = H P⁻ Hᵀ + R`, `K = P⁻ Hᵀ S⁻¹` with
/// `H = ∂h/∂x`; update `x = x⁻ + K ν` and `P` in the chosen [`CovarianceForm`]
/// (Joseph by default). With a linear measurement (`h(x) = H x`) this is the
/// exact Kalman filter; a nonlinear sensor is linearised at `x⁻` (use [`crate::Ekf`]
/// to say so in the type).
///
/// # References
/// Seed 002 eqs (1)–(10); seed 000 eq (4) (corrected: `P = P⁻ − K S Kᵀ`);
/// Bar-Shalom, Li & Kirubarajan (2001) §5.2.
///
/// # Example
/// ```
/// use argus_core_math::{Gaussian, Matrix, Vector};
/// use argus_filters::{GaussianFilter, Kf};
/// use argus_motion_models::{LinearMotionModel, MotionModel};
/// use argus_sensors::MeasurementModel;
///
/// /// A 1-D random walk `x(t + dt) = x(t) + w`, `Var w = q dt`.
/// struct Walk(f64);
/// impl MotionModel<1> for Walk {
///     fn propagate(&self, x: &Vector<1>, _dt: f64) -> Vector<1> { *x }
///     fn jacobian(&self, _x: &Vector<1>, _dt: f64) -> Matrix<1, 1> { Matrix::identity() }
///     fn process_noise(&self, _x: &Vector<1>, dt: f64) -> Matrix<1, 1> {
///         Matrix::<1, 1>::new(self.0 * dt)
///     }
/// }
/// impl LinearMotionModel<1> for Walk {
///     fn transition(&self, _dt: f64) -> Matrix<1, 1> { Matrix::identity() }
/// }
/// /// Direct observation with variance 1.
/// struct Direct;
/// impl MeasurementModel<1, 1> for Direct {
///     fn predict(&self, x: &Vector<1>) -> Vector<1> { *x }
///     fn jacobian(&self, _x: &Vector<1>) -> Matrix<1, 1> { Matrix::identity() }
///     fn noise(&self, _x: &Vector<1>) -> Matrix<1, 1> { Matrix::identity() }
/// }
///
/// let kf = Kf::new(Walk(1.0));
/// let prior = Gaussian::new(Vector::<1>::new(0.0), Matrix::<1, 1>::new(1.0))?;
/// let pred = kf.predict(&prior, 1.0)?; // P⁻ = 1 + 1 = 2
/// let (post, innov) = kf.update(&pred, &Direct, &Vector::<1>::new(3.0))?;
/// // K = 2 / (2 + 1) = 2/3: x = 2, P = 2/3, NIS = 9 / 3 = 3.
/// assert!((post.mean()[0] - 2.0).abs() < 1e-12);
/// assert!((post.cov()[(0, 0)] - 2.0 / 3.0).abs() < 1e-12);
/// assert!((innov.nis - 3.0).abs() < 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kf<Mo> {
    model: Mo,
    form: CovarianceForm,
}

impl<Mo> Kf<Mo> {
    /// A Kalman filter on `model` with the Joseph-form covariance update.
    #[must_use]
    pub fn new(model: Mo) -> Self {
        Self::with_form(model, CovarianceForm::default())
    }

    /// A Kalman filter on `model` with the given covariance update form.
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

impl<const N: usize, Mo: LinearMotionModel<N>> GaussianFilter<N> for Kf<Mo> {
    /// `x⁻ = F(dt) x`, `P⁻ = F P Fᵀ + Q(x̂, dt)`.
    ///
    /// # Errors
    /// [`FilterError::InvalidInterval`] for `dt` not finite and positive;
    /// [`FilterError::Math`] when `F`, `Q` or the result is non-finite or `P⁻` is
    /// not positive definite.
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

    /// The prediction `x⁻, P⁻` and the update of one cycle, with `P⁻` never stored as a
    /// [`Gaussian`]: it is checked for finiteness only (a non-finite `P⁻` or `Q` is named as
    /// by [`GaussianFilter::predict`]), not for definiteness. That is safe: `P⁻ = F P Fᵀ + Q`
    /// is positive definite by construction for the positive-definite prior `P` (a checked
    /// `Gaussian`) and a positive semi-definite `Q`, and whatever round-off or a bad model
    /// does to it still meets two checks before anything is kept: `S = H P⁻ Hᵀ + R` is
    /// factored (not positive definite: an error), and the posterior, the only result, is
    /// checked for finiteness and definiteness as by [`GaussianFilter::update`]. Saves one
    /// definiteness test per cycle (~65 instructions of `N = 4`); the values are those of
    /// `predict_in_place` then `update_in_place`, bit for bit. `estimate` is left unchanged
    /// on an error.
    #[inline(always)]
    fn step_in_place<const M: usize, Me: MeasurementModel<N, M>>(
        &self,
        estimate: &mut Gaussian<N>,
        dt: f64,
        meas: &Me,
        z: &Vector<M>,
    ) -> Result<Innovation<M>, FilterError> {
        linearized_step_in_place(&self.model, self.form, estimate, dt, meas, z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_models::{Cv1Dwna, Cv2, Pos1, Pos2};
    use argus_core_math::{MathError, Matrix, Vector};

    fn kalata(lambda: f64) -> (f64, f64) {
        let root = (lambda * lambda + 8.0 * lambda).sqrt();
        let alpha = -(lambda * lambda + 8.0 * lambda - (lambda + 4.0) * root) / 8.0;
        let beta = (lambda * lambda + 4.0 * lambda - lambda * root) / 4.0;
        (alpha, beta)
    }

    #[test]
    fn converges_to_kalata_alpha_beta_gains() {
        // Kalata (1984); Bar-Shalom, Li & Kirubarajan (2001) §6.5: the steady-state
        // gain of the 1-D CV filter with DWNA noise is [α, β/T] with
        // λ = σ_v T² / σ_w. The covariance recursion does not depend on the plots.
        for &(lambda, t) in &[(0.05, 1.0), (0.3, 2.0), (1.0, 0.5), (3.0, 1.0), (10.0, 5.0)] {
            let sigma_w = 2.0;
            let sigma_v = lambda * sigma_w / (t * t);
            for form in [CovarianceForm::Joseph, CovarianceForm::Standard] {
                let kf = Kf::with_form(Cv1Dwna { sigma_v }, form);
                let meas = Pos1 {
                    r: sigma_w * sigma_w,
                };
                let mut est =
                    Gaussian::new(Vector::<2>::zeros(), Matrix::<2, 2>::identity() * 1e4).unwrap();
                let mut gain = Matrix::<2, 1>::zeros();
                for _ in 0..3000 {
                    let pred = kf.predict(&est, t).unwrap();
                    let mp = kf.predict_measurement(&pred, &meas).unwrap();
                    gain = *mp.gain();
                    est = mp.update(&pred, &Vector::<1>::zeros()).unwrap();
                }
                let (alpha, beta) = kalata(lambda);
                // Tolerance: round-off of a converged recursion (derived values are exact).
                assert!(
                    (gain[0] - alpha).abs() < 1e-9,
                    "λ={lambda}: α {} vs {alpha}",
                    gain[0]
                );
                assert!(
                    (gain[1] - beta / t).abs() < 1e-9 / t,
                    "λ={lambda}: β/T {} vs {}",
                    gain[1],
                    beta / t
                );
            }
        }
    }

    #[test]
    fn joseph_equals_standard_at_optimal_gain() {
        // Identity: at K = P Hᵀ S⁻¹ both forms give P − K S Kᵀ.
        let prior = Gaussian::new(
            Vector::<4>::new(100.0, 5.0, -50.0, 2.0),
            Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(400.0, 25.0, 300.0, 16.0)),
        )
        .unwrap();
        let meas = Pos2 {
            r: Matrix::<2, 2>::new(100.0, 30.0, 30.0, 60.0),
        };
        let z = Vector::<2>::new(120.0, -40.0);
        let a = Kf::with_form(Cv2 { q: 1.0 }, CovarianceForm::Joseph);
        let b = Kf::with_form(Cv2 { q: 1.0 }, CovarianceForm::Standard);
        let (pa, _) = a
            .update(&a.predict(&prior, 2.0).unwrap(), &meas, &z)
            .unwrap();
        let (pb, _) = b
            .update(&b.predict(&prior, 2.0).unwrap(), &meas, &z)
            .unwrap();
        assert!((pa.cov() - pb.cov()).amax() < 1e-9 * pa.cov().amax());
        assert!((pa.mean() - pb.mean()).amax() < 1e-9);
    }

    #[test]
    fn one_step_matches_hand_computation() {
        // 1-D CV, T = 1, σ_v = 1: Q = [[1/4, 1/2], [1/2, 1]]; P₀ = I:
        // P⁻ = F P Fᵀ + Q = [[2.25, 1.5], [1.5, 2]]; with r = 1: S = 3.25,
        // K = [2.25, 1.5]/3.25; z = 1 from x⁻ = 0: x = K.
        let kf = Kf::new(Cv1Dwna { sigma_v: 1.0 });
        let prior = Gaussian::new(Vector::<2>::zeros(), Matrix::<2, 2>::identity()).unwrap();
        let pred = kf.predict(&prior, 1.0).unwrap();
        assert!((pred.cov() - Matrix::<2, 2>::new(2.25, 1.5, 1.5, 2.0)).amax() < 1e-14);
        let (post, innov) = kf
            .update(&pred, &Pos1 { r: 1.0 }, &Vector::<1>::new(1.0))
            .unwrap();
        assert!((post.mean() - Vector::<2>::new(2.25, 1.5) / 3.25).amax() < 1e-14);
        assert!((innov.nis - 1.0 / 3.25).abs() < 1e-14);
        // ln N(1; 0, 3.25) = −½ (1/3.25 + ln(2π · 3.25)), computed on demand.
        let ll = -0.5 * (1.0 / 3.25 + (2.0 * std::f64::consts::PI * 3.25).ln());
        assert!((innov.log_likelihood() - ll).abs() < 1e-14);
        let p11 = 2.25 - 2.25 * 2.25 / 3.25;
        assert!((post.cov()[(0, 0)] - p11).abs() < 1e-12);
    }

    #[test]
    fn rejects_bad_interval_and_plot() {
        let kf = Kf::new(Cv1Dwna { sigma_v: 1.0 });
        let prior = Gaussian::new(Vector::<2>::zeros(), Matrix::<2, 2>::identity()).unwrap();
        for dt in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                kf.predict(&prior, dt),
                Err(FilterError::InvalidInterval { .. })
            ));
        }
        let z = Vector::<1>::new(f64::NAN);
        assert_eq!(
            kf.update(&prior, &Pos1 { r: 1.0 }, &z).unwrap_err(),
            FilterError::Math(MathError::NonFinite {
                what: "measurement"
            })
        );
    }

    #[test]
    fn non_pd_noise_making_s_singular_is_reported() {
        // R = −H P Hᵀ makes S = 0.
        let kf = Kf::new(Cv1Dwna { sigma_v: 1.0 });
        let prior = Gaussian::new(Vector::<2>::zeros(), Matrix::<2, 2>::identity() * 2.0).unwrap();
        let err = kf
            .predict_measurement(&prior, &Pos1 { r: -2.0 })
            .unwrap_err();
        assert_eq!(
            err,
            FilterError::Math(MathError::NotPositiveDefinite {
                what: "innovation covariance S"
            })
        );
        let err = kf
            .predict_measurement(&prior, &Pos1 { r: f64::NAN })
            .unwrap_err();
        assert_eq!(
            err,
            FilterError::Math(MathError::NonFinite {
                what: "measurement noise R"
            })
        );
    }

    #[test]
    fn non_finite_or_indefinite_process_noise_is_reported() {
        let prior = Gaussian::new(Vector::<2>::zeros(), Matrix::<2, 2>::identity()).unwrap();
        let err = Kf::new(Cv1Dwna { sigma_v: f64::NAN })
            .predict(&prior, 1.0)
            .unwrap_err();
        assert_eq!(
            err,
            FilterError::Math(MathError::NonFinite {
                what: "process noise Q"
            })
        );
        // An overflowing step: F P Fᵀ is infinite.
        let err = Kf::new(Cv1Dwna { sigma_v: 1.0 })
            .predict(&prior, 1e300)
            .unwrap_err();
        assert!(
            matches!(err, FilterError::Math(MathError::NonFinite { .. })),
            "{err:?}"
        );
    }

    #[test]
    fn fused_step_equals_predict_then_update() {
        // `step_in_place` skips only the definiteness test of the intermediate prediction:
        // the posterior and innovation must be those of the two stages, bit for bit.
        let prior = Gaussian::new(
            Vector::<4>::new(100.0, 5.0, -50.0, 2.0),
            Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(400.0, 25.0, 300.0, 16.0)),
        )
        .unwrap();
        let meas = argus_sensors::CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::new(
            100.0, 30.0, 30.0, 60.0,
        ))
        .unwrap();
        let z = Vector::<2>::new(120.0, -40.0);
        for form in [CovarianceForm::Joseph, CovarianceForm::Standard] {
            let kf = Kf::with_form(Cv2 { q: 1.0 }, form);
            let (mut a, mut b) = (prior, prior);
            for _ in 0..5 {
                kf.predict_in_place(&mut a, 2.0).unwrap();
                let ia = kf.update_in_place(&mut a, &meas, &z).unwrap();
                let ib = kf.step_in_place(&mut b, 2.0, &meas, &z).unwrap();
                assert_eq!(a, b);
                assert_eq!(ia, ib);
            }
        }
        // Errors: the same kinds and names as the two stages, the estimate untouched.
        let mut e = prior;
        let bad_q = Kf::new(Cv2 { q: f64::NAN });
        assert_eq!(
            bad_q.step_in_place(&mut e, 1.0, &meas, &z).unwrap_err(),
            bad_q.predict(&prior, 1.0).unwrap_err()
        );
        let kf = Kf::new(Cv2 { q: 1.0 });
        assert!(matches!(
            kf.step_in_place(&mut e, -1.0, &meas, &z),
            Err(FilterError::InvalidInterval { .. })
        ));
        assert_eq!(
            kf.step_in_place(&mut e, 1.0, &meas, &Vector::<2>::new(f64::NAN, 0.0))
                .unwrap_err(),
            FilterError::Math(MathError::NonFinite {
                what: "measurement"
            })
        );
        assert_eq!(e, prior);
    }

    #[test]
    fn out_of_range_selection_is_ignored() {
        // A model declaring an index ≥ N must not be gathered with (no panic): the filter
        // takes the general `P Hᵀ` path, so the result equals the plain model's.
        struct BadSelection(Pos2);
        impl MeasurementModel<4, 2> for BadSelection {
            fn predict(&self, x: &Vector<4>) -> Vector<2> {
                self.0.predict(x)
            }
            fn jacobian(&self, x: &Vector<4>) -> Matrix<2, 4> {
                self.0.jacobian(x)
            }
            fn noise(&self, x: &Vector<4>) -> Matrix<2, 2> {
                self.0.noise(x)
            }
            fn selection(&self) -> Option<[usize; 2]> {
                Some([0, 9])
            }
        }
        let r = Matrix::<2, 2>::new(2.0, 0.1, 0.1, 3.0);
        let prior = Gaussian::new(
            Vector::<4>::new(1.0, 0.5, -2.0, 0.1),
            Matrix::<4, 4>::identity() * 4.0,
        )
        .unwrap();
        let z = Vector::<2>::new(1.5, -1.0);
        let kf = Kf::new(Cv2 { q: 0.5 });
        let (a, _) = kf.update(&prior, &Pos2 { r }, &z).unwrap();
        let (b, _) = kf.update(&prior, &BadSelection(Pos2 { r }), &z).unwrap();
        assert_eq!(a, b);
    }

    proptest::proptest! {
        #[test]
        fn selection_path_equals_general_path(
            a in proptest::array::uniform16(-3.0f64..3.0),
            r in proptest::array::uniform3(0.1f64..2.0),
            z in proptest::array::uniform2(-5.0f64..5.0),
        ) {
            // `CartesianPosition` declares its selection (gathers in S, P Hᵀ and the Joseph
            // update); `Pos2` is the same H and R through the general products. Both forms
            // must agree to round-off (entries of order 10², tolerance 1e-12 relative).
            let m = Matrix::<4, 4>::from_row_slice(&a);
            let prior = Gaussian::from_lower_triangle(
                Vector::<4>::new(1.0, -2.0, 0.5, 3.0),
                m * m.transpose() + Matrix::<4, 4>::identity(),
            )
            .unwrap();
            let rm = Matrix::<2, 2>::new(r[0], 0.3 * r[1].min(r[0]), 0.3 * r[1].min(r[0]), r[1] + r[2]);
            let general = Pos2 { r: rm };
            let selected = argus_sensors::CartesianPosition::<4, 2>::cv(rm).unwrap();
            let z = Vector::<2>::new(z[0], z[1]);
            for form in [CovarianceForm::Joseph, CovarianceForm::Standard] {
                let kf = Kf::with_form(Cv2 { q: 0.5 }, form);
                let pred = kf.predict(&prior, 1.5).unwrap();
                let (pa, ia) = kf.update(&pred, &general, &z).unwrap();
                let (pb, ib) = kf.update(&pred, &selected, &z).unwrap();
                let tol = 1e-12 * (1.0 + pred.cov().amax());
                proptest::prop_assert!((pa.cov() - pb.cov()).amax() < tol);
                proptest::prop_assert!((pa.mean() - pb.mean()).amax() < tol);
                proptest::prop_assert!((ia.log_likelihood() - ib.log_likelihood()).abs() < 1e-12 * (1.0 + ia.log_likelihood().abs()));
            }
        }
    }
}

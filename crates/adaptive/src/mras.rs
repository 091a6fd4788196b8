//! Recursive estimation of an unknown persistent input, started at a maneuver
//! detection: the discrete-time form of the paper's stochastic MRAS estimator.
//!
//! # Continuous form (seed 001, section 4)
//! `dû/dt = L Bᵀ W (dx̂/dt − F x̂ − B û)` (eq 4-4), `dL/dt = −L Bᵀ W B L` (eq 4-5), with the
//! off-line solution `û(t) = [I + L(0) ∫ Bᵀ W B]⁻¹ [û(0) + L(0) ∫ Bᵀ W (…)]`,
//! `L(t) = [I + L(0) ∫ Bᵀ W B]⁻¹ L(0)` (eqs 4-6, 4-7): a least-squares estimate of a
//! constant `u` whose limit `L(0) → ∞` is the maximum-likelihood estimate. (The
//! weight `W` is garbled in print; the innovation-covariance weighting below is the
//! one that makes the limit the ML estimate.)
//!
//! # Discrete form used here
//! The regressor of the innovation on a constant input error `δu` that started at
//! the estimator's start is the GLRT signature of a persistent input (see [`crate::glrt`]):
//! `r(m) = G(m) δu + r₁(m)`, with `D`, `F` advanced as in eqs 3-3, 3-4. Recursive
//! least squares on it, with gain `L`:
//!
//! - `L(m)⁻¹ = L(m−1)⁻¹ + Gᵀ S⁻¹ G` (eq 4-5 integrated over one step),
//! - `δû(m) = δû(m−1) + L(m) Gᵀ S⁻¹ (r − G δû(m−1))` (eq 4-4 over one step),
//!
//! which equals the closed form `δû = (L(0)⁻¹ + C)⁻¹ (L(0)⁻¹ δû(0) + d)` with the GLRT's
//! `C`, `d` accumulated from the start (eqs 4-6, 4-7). It is kept in that information
//! form, so `L(0) = ∞` (no prior, `L(0)⁻¹ = 0`) is exact: the estimate is then the ML
//! estimate `C⁻¹ d`, available once `C` is positive definite.
//!
//! The estimated state of the compensated filter is `x̄ + [D − F] δû` with covariance
//! `P̄ + [D − F] L [D − F]ᵀ`, where `x̄`, `P̄` are the filter's own (Friedland's separate
//! bias form; seed 001 ref. 18).
//!
//! # References
//! - Lee & Kim (1987), seed 001, eqs 4-3 to 4-7.
//! - B. Friedland, "Treatment of bias in recursive filtering", IEEE TAC 14(4), 1969.

use argus_core_math::{Matrix, SpdFactor, Vector, symmetrize};

use crate::error::AdaptiveError;
use crate::glrt::{Detection, StepLinearization};

/// The recursive input estimator (MRAS, discrete form). `N` state, `P` input.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mras<const N: usize, const P: usize> {
    deviation: Matrix<N, P>,
    response: Matrix<N, P>,
    started: bool,
    /// `L(0)⁻¹ δû(0) + d`.
    b: Vector<P>,
    /// `L(m)⁻¹ = L(0)⁻¹ + C`.
    info: Matrix<P, P>,
    estimate: Option<(Vector<P>, Matrix<P, P>)>,
    steps: usize,
}

impl<const N: usize, const P: usize> Mras<N, P> {
    /// Starts with `L(0) = ∞` (no prior): the estimate is the ML one.
    #[must_use]
    pub fn new_ml() -> Self {
        Self {
            deviation: Matrix::zeros(),
            response: Matrix::zeros(),
            started: false,
            b: Vector::zeros(),
            info: Matrix::zeros(),
            estimate: None,
            steps: 0,
        }
    }

    /// Starts from the initial guess `δû(0)` with gain `L(0)` (its covariance).
    ///
    /// # Errors
    /// [`AdaptiveError::Math`] when `L(0)` is not finite, symmetric and positive definite
    /// or `δû(0)` is not finite.
    pub fn with_prior(u0: Vector<P>, l0: &Matrix<P, P>) -> Result<Self, AdaptiveError> {
        argus_core_math::check_finite_vector(&u0, "MRAS initial input u(0)")?;
        let f = SpdFactor::new(l0, "MRAS initial gain L(0)")?;
        let info = f.inverse();
        Ok(Self {
            b: info * u0,
            info,
            estimate: Some((u0, *l0)),
            ..Self::new_ml()
        })
    }

    /// Starts from the initial guess `δû(0)` given its information `L(0)⁻¹`, which may be
    /// singular (no prior information in some directions).
    ///
    /// # Errors
    /// [`AdaptiveError::Math`] when a value is non-finite.
    pub fn with_prior_information(
        u0: Vector<P>,
        info0: &Matrix<P, P>,
    ) -> Result<Self, AdaptiveError> {
        argus_core_math::check_finite_vector(&u0, "MRAS initial input u(0)")?;
        argus_core_math::check_finite_matrix(info0, "MRAS initial information L(0)^-1")?;
        let info = symmetrize(info0);
        let estimate = SpdFactor::new_symmetric(&info, "MRAS information")
            .ok()
            .map(|f| (u0, f.inverse()));
        Ok(Self {
            b: info * u0,
            info,
            estimate,
            ..Self::new_ml()
        })
    }

    /// Starts right after a GLRT detection whose estimate was applied to the filter:
    /// the remaining input error `δu = u − û` starts with prior `δû(0) = 0`,
    /// `L(0) = C⁻¹` and, since the corrected state still errs by `[D − F] δu`, with that
    /// sensitivity as the initial deviation (and no filter response yet). The
    /// compensated covariance then equals eq 3-12 at the detection step.
    #[must_use]
    pub fn after_detection(det: &Detection<N, P>) -> Self {
        Self {
            deviation: det.sensitivity,
            response: Matrix::zeros(),
            started: true,
            b: Vector::zeros(),
            info: symmetrize(&det.information),
            estimate: Some((Vector::zeros(), det.input_cov)),
            steps: 0,
        }
    }

    /// The current estimate `δû(m)` and its gain/covariance `L(m)`, once identifiable.
    #[must_use]
    pub fn estimate(&self) -> Option<(Vector<P>, Matrix<P, P>)> {
        self.estimate
    }

    /// `D − F`: maps the input error to the state error of the uncompensated filter.
    #[must_use]
    pub fn sensitivity(&self) -> Matrix<N, P> {
        self.deviation - self.response
    }

    /// Steps processed since the start.
    #[must_use]
    pub fn steps(&self) -> usize {
        self.steps
    }

    /// The predicted innovation contribution `G δû(m−1)` of the current estimate for
    /// the step described by `lin` (zero before the estimate exists).
    #[must_use]
    pub fn predicted_innovation<const M: usize>(
        &self,
        lin: &StepLinearization<'_, N, M, P>,
    ) -> Vector<M> {
        let (g, _, _) = self.signature(lin);
        self.estimate.map_or(Vector::zeros(), |(u, _)| g * u)
    }

    #[allow(clippy::type_complexity)]
    fn signature<const M: usize>(
        &self,
        lin: &StepLinearization<'_, N, M, P>,
    ) -> (Matrix<M, P>, Matrix<N, P>, Matrix<N, P>) {
        let (dev, phi_f) = if self.started {
            (
                lin.phi * self.deviation + lin.gamma,
                lin.phi * self.response,
            )
        } else {
            (*lin.gamma, Matrix::zeros())
        };
        (lin.h * (dev - phi_f), dev, phi_f)
    }

    /// Processes one filter step, returning the updated estimator (`self` is unchanged).
    ///
    /// # Errors
    /// [`AdaptiveError::Math`] when a step quantity or the result is non-finite.
    pub fn step<const M: usize>(
        &self,
        lin: &StepLinearization<'_, N, M, P>,
    ) -> Result<Self, AdaptiveError> {
        lin.validate()?;
        let (g, dev, phi_f) = self.signature(lin);
        let sinv_g = lin.s_factor.solve_matrix(&g);
        let info = symmetrize(&(self.info + g.transpose() * sinv_g));
        let b = self.b + sinv_g.transpose() * lin.residual;
        let estimate = match SpdFactor::new_symmetric(&info, "MRAS information") {
            Ok(f) => {
                let u = f.solve_vector(&b);
                argus_core_math::check_finite_vector(&u, "MRAS input estimate")?;
                Some((u, f.inverse()))
            }
            Err(_) => None,
        };
        Ok(Self {
            deviation: dev,
            response: phi_f + lin.gain * g,
            started: true,
            b,
            info,
            estimate,
            steps: self.steps + 1,
        })
    }
}

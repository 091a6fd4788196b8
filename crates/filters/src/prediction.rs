//! The measurement prediction computed once per step and the innovation of one plot.

use argus_core_math::{
    Gaussian, Matrix, SpdFactor, Vector, check_finite_matrix, check_finite_vector,
    joseph_update_from_innovation, kernels, log_det_of_pivots, unit_ball_volume,
};
use argus_sensors::MeasurementModel;

use crate::FilterError;

/// How the posterior covariance is computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CovarianceForm {
    /// `P = P⁻ − K S Kᵀ` (seed 000 eq (4), corrected).
    Standard,
    /// `P = (I − K H) P⁻ (I − K H)ᵀ + K R Kᵀ`, robust to round-off. Falls back to
    /// the standard form for filters without a measurement Jacobian (UKF).
    #[default]
    Joseph,
}

/// Everything about the predicted measurement that does not depend on the plot:
/// computed once, then used for gating, likelihoods and updates.
#[derive(Debug, Clone)]
pub struct MeasurementPrediction<const N: usize, const M: usize> {
    z_pred: Vector<M>,
    s: Matrix<M, M>,
    s_factor: SpdFactor<M>,
    cross: Matrix<N, M>,
    gain: Matrix<N, M>,
    jacobian: Option<Matrix<M, N>>,
    noise: Matrix<M, M>,
    form: CovarianceForm,
}

/// The innovation of one plot against a [`MeasurementPrediction`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Innovation<const M: usize> {
    /// The residual `ν = z − ẑ` (angles wrapped).
    pub residual: Vector<M>,
    /// The normalised innovation squared `νᵀ S⁻¹ ν`.
    pub nis: f64,
    /// The pivots of `S = L D Lᵀ`, for the likelihood's normaliser (computed on demand).
    s_pivots: [f64; M],
}

impl<const M: usize> Innovation<M> {
    /// The Gaussian log-likelihood `ln N(ν; 0, S) = −½ (NIS + ln|S| + M ln 2π)`, computed when
    /// asked (one logarithm): a filter step that does not need it does not pay for it.
    #[must_use]
    #[inline]
    pub fn log_likelihood(&self) -> f64 {
        log_normal::<M>(self.nis, log_det_of_pivots(&self.s_pivots))
    }
}

/// `ln N(ν; 0, S) = −½ (d² + ln|S| + M ln 2π)` from `d² = νᵀS⁻¹ν` and `ln|S|`.
#[inline]
fn log_normal<const M: usize>(nis: f64, log_det_s: f64) -> f64 {
    -0.5 * (nis + log_det_s + M as f64 * (2.0 * std::f64::consts::PI).ln())
}

impl<const N: usize, const M: usize> MeasurementPrediction<N, M> {
    /// Assembles a prediction from `ẑ`, `S`, the cross covariance `P_xz`, the
    /// measurement Jacobian (when the filter has one, for the Joseph form) and `R`.
    /// The gain `K = P_xz S⁻¹` is computed here. With a Jacobian and the Joseph form,
    /// `P_xz` must be `P⁻ Hᵀ` of the covariance later passed to [`Self::update`] /
    /// [`Self::posterior_cov`]: the Joseph update reuses it
    /// ([`argus_core_math::joseph_update_from_innovation`]).
    ///
    /// # Errors
    /// [`FilterError::Math`] when a value is non-finite or `S` is not positive definite.
    #[inline(always)]
    pub fn new(
        z_pred: Vector<M>,
        s: Matrix<M, M>,
        cross: Matrix<N, M>,
        jacobian: Option<Matrix<M, N>>,
        noise: Matrix<M, M>,
        form: CovarianceForm,
    ) -> Result<Self, FilterError> {
        check_finite_vector(&z_pred, "predicted measurement")?;
        // `S` is read as its lower triangle (mirrored), as the factorisation reads it.
        let mut s = s;
        kernels::mirror_lower(&mut s);
        let s_factor = SpdFactor::new_symmetric(&s, "innovation covariance S")?;
        let gain = s_factor.solve_right(&cross);
        // A non-finite `P_xz` (or an overflow of the division) shows in the gain.
        check_finite_matrix(&gain, "gain")?;
        Ok(Self {
            z_pred,
            s,
            s_factor,
            cross,
            gain,
            jacobian,
            noise,
            form,
        })
    }

    /// The predicted measurement `ẑ`.
    #[must_use]
    pub fn z_pred(&self) -> &Vector<M> {
        &self.z_pred
    }

    /// The innovation covariance `S`.
    #[must_use]
    pub fn s(&self) -> &Matrix<M, M> {
        &self.s
    }

    /// The Cholesky factor of `S`.
    #[must_use]
    pub fn s_factor(&self) -> &SpdFactor<M> {
        &self.s_factor
    }

    /// The cross covariance `P_xz` (`P Hᵀ` for a linearised filter).
    #[must_use]
    pub fn cross(&self) -> &Matrix<N, M> {
        &self.cross
    }

    /// The gain `K = P_xz S⁻¹`.
    #[must_use]
    pub fn gain(&self) -> &Matrix<N, M> {
        &self.gain
    }

    /// The measurement Jacobian used, if the filter has one.
    #[must_use]
    pub fn jacobian(&self) -> Option<&Matrix<M, N>> {
        self.jacobian.as_ref()
    }

    /// The measurement-noise covariance `R` used.
    #[must_use]
    pub fn noise(&self) -> &Matrix<M, M> {
        &self.noise
    }

    /// `ln |S|`.
    #[must_use]
    pub fn log_det_s(&self) -> f64 {
        self.s_factor.log_det()
    }

    /// The normalised innovation squared `νᵀ S⁻¹ ν` of a residual.
    #[must_use]
    #[inline]
    pub fn nis(&self, residual: &Vector<M>) -> f64 {
        self.s_factor.mahalanobis_sq(residual)
    }

    /// `ln N(ν; 0, S)` from the squared distance `d² = νᵀS⁻¹ν`: `−½(d² + ln|S| + M ln 2π)`.
    #[must_use]
    #[inline]
    pub fn log_likelihood_from_nis(&self, nis: f64) -> f64 {
        log_normal::<M>(nis, self.log_det_s())
    }

    /// The volume of the gate `νᵀ S⁻¹ ν ≤ γ`: `c_M γ^{M/2} |S|^{1/2}`.
    #[must_use]
    pub fn gate_volume(&self, gamma: f64) -> f64 {
        unit_ball_volume(M) * gamma.powf(M as f64 / 2.0) * (0.5 * self.log_det_s()).exp()
    }

    /// The innovation of plot `z` (residual through `meas`, wrapping angles).
    ///
    /// # Errors
    /// [`FilterError::Math`] when `z` is not finite.
    #[inline]
    pub fn innovation<Me: MeasurementModel<N, M>>(
        &self,
        meas: &Me,
        z: &Vector<M>,
    ) -> Result<Innovation<M>, FilterError> {
        let residual = meas.residual(z, &self.z_pred);
        // A non-finite plot gives a non-finite residual; only then is the plot examined.
        if let Err(e) = check_finite_vector(&residual, "residual") {
            check_finite_vector(z, "measurement")?;
            return Err(e.into());
        }
        let nis = self.nis(&residual);
        Ok(Innovation {
            residual,
            nis,
            s_pivots: self.s_factor.pivots(),
        })
    }

    /// The posterior after a Kalman update with `residual`: `x = x⁻ + K ν`, and the
    /// covariance in this prediction's [`CovarianceForm`].
    ///
    /// # Errors
    /// [`FilterError::Math`] when the posterior is non-finite or not positive definite.
    #[inline(always)]
    pub fn update(
        &self,
        predicted: &Gaussian<N>,
        residual: &Vector<M>,
    ) -> Result<Gaussian<N>, FilterError> {
        let (mean, cov) = self.posterior_moments(predicted.mean(), predicted.cov(), residual)?;
        crate::linearized::checked_gaussian(mean, cov, "posterior mean", "posterior covariance")
    }

    /// [`MeasurementPrediction::update`] in place: `estimate` (the prediction this was
    /// computed from) becomes the posterior, and is left unchanged on an error.
    ///
    /// # Errors
    /// As [`MeasurementPrediction::update`].
    #[inline(always)]
    pub fn update_in_place(
        &self,
        estimate: &mut Gaussian<N>,
        residual: &Vector<M>,
    ) -> Result<(), FilterError> {
        let (mean, cov) = self.posterior_moments(estimate.mean(), estimate.cov(), residual)?;
        crate::linearized::assign_checked(
            estimate,
            mean,
            cov,
            "posterior mean",
            "posterior covariance",
        )
    }

    /// `x = x⁻ + K ν` and the posterior covariance (its lower triangle is what counts) from
    /// the predicted mean and covariance this was computed from; not checked (the caller
    /// builds a checked Gaussian from them).
    #[inline(always)]
    pub(crate) fn posterior_moments(
        &self,
        predicted_mean: &Vector<N>,
        predicted_cov: &Matrix<N, N>,
        residual: &Vector<M>,
    ) -> Result<(Vector<N>, Matrix<N, N>), FilterError> {
        check_finite_vector(residual, "residual")?;
        let mean = predicted_mean + kernels::mul(&self.gain, residual);
        Ok((mean, self.posterior_cov(predicted_cov)))
    }

    /// The posterior covariance of an update with a plot (independent of the residual).
    #[must_use]
    #[inline]
    pub fn posterior_cov(&self, prior_cov: &Matrix<N, N>) -> Matrix<N, N> {
        match (self.form, self.jacobian.as_ref()) {
            (CovarianceForm::Joseph, Some(_)) => {
                // The Joseph form from `P_xz` and `S` (no `H` product needed).
                joseph_update_from_innovation(prior_cov, &self.gain, &self.cross, &self.s)
            }
            _ => {
                // `P − K S Kᵀ` as `P − K P_xzᵀ` (`K S = P_xz` for the gain formed in `new`),
                // lower triangle computed and mirrored.
                let mut out = *prior_cov;
                kernels::sub_mul_transpose_lower(&mut out, &self.gain, &self.cross);
                kernels::mirror_lower(&mut out);
                out
            }
        }
    }
}

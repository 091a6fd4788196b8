//! The RTS backward pass, and the KF's and EKF's predictions with their cross covariance.

use argus_core_math::{
    Gaussian, MathError, Matrix, SpdFactor, Vector, check_finite_matrix, kernels,
};
use argus_motion_models::{LinearMotionModel, MotionModel};

use super::{RtsStep, SmoothError, SmoothingFilter, Transition};
use crate::linearized::checked_gaussian;
use crate::{Ekf, FilterError, Kf, check_dt};

/// The linearised prediction with its cross covariance, `F` formed once:
/// `C = P Fᵀ`, `P⁻ = F C + Q`, `x⁻ = f(x̂, dt)`.
#[allow(non_snake_case)]
#[inline]
fn linearized_transition<const N: usize, Mo: MotionModel<N>>(
    model: &Mo,
    F: &Matrix<N, N>,
    prior: &Gaussian<N>,
    dt: f64,
) -> Result<Transition<N>, FilterError> {
    let x = prior.mean();
    check_finite_matrix(F, "transition matrix F")?;
    let Q = model.process_noise(x, dt);
    check_finite_matrix(&Q, "process noise Q")?;
    let cross = kernels::mul_transpose(prior.cov(), F);
    // `F (P Fᵀ)` is symmetric in exact arithmetic; its lower triangle is kept.
    let cov = kernels::mul(F, &cross) + Q;
    let predicted = checked_gaussian(
        model.propagate(x, dt),
        cov,
        "predicted mean",
        "predicted covariance",
    )?;
    Ok(Transition { predicted, cross })
}

impl<const N: usize, Mo: LinearMotionModel<N>> SmoothingFilter<N> for Kf<Mo> {
    /// `x⁻ = F x̂`, `C = P Fᵀ`, `P⁻ = F C + Q` with `F = F(dt)`.
    ///
    /// # Errors
    /// As [`crate::GaussianFilter::predict`]; a non-finite `F` is named.
    fn predict_with_cross(
        &self,
        prior: &Gaussian<N>,
        dt: f64,
    ) -> Result<Transition<N>, FilterError> {
        check_dt(dt)?;
        linearized_transition(self.model(), &self.model().transition(dt), prior, dt)
    }
}

impl<const N: usize, Mo: MotionModel<N>> SmoothingFilter<N> for Ekf<Mo> {
    /// `x⁻ = f(x̂, dt)`, `C = P Fᵀ`, `P⁻ = F C + Q` with `F = ∂f/∂x(x̂, dt)`.
    ///
    /// # Errors
    /// As [`crate::GaussianFilter::predict`]; a non-finite `F` is named.
    fn predict_with_cross(
        &self,
        prior: &Gaussian<N>,
        dt: f64,
    ) -> Result<Transition<N>, FilterError> {
        check_dt(dt)?;
        let jac = self.model().jacobian(prior.mean(), dt);
        linearized_transition(self.model(), &jac, prior, dt)
    }
}

/// One backward step: from the filtered estimate at `k`, the transition into `k + 1`
/// and the smoothed estimate at `k + 1`, the smoothed estimate at `k`:
/// `G = C (P⁻)⁻¹`, `x̂ˢ = x̂ + G (x̂ˢₖ₊₁ − x̂⁻)`, `Pˢ = P + G (Pˢₖ₊₁ − P⁻) Gᵀ`
/// (Rauch, Tung & Striebel 1965; Särkkä 2008 eqs (15)–(17)).
///
/// # Errors
/// [`MathError::NotPositiveDefinite`] naming the predicted covariance (not factorable)
/// or the smoothed covariance; [`MathError::NonFinite`] for a non-finite gain or result.
#[inline]
pub fn rts_step<const N: usize>(
    filtered: &Gaussian<N>,
    transition: &Transition<N>,
    next_smoothed: &Gaussian<N>,
) -> Result<Gaussian<N>, MathError> {
    rts_step_across(
        filtered,
        transition.predicted(),
        transition.cross(),
        next_smoothed,
    )
}

/// [`rts_step`] between states of different sizes: `filtered` (size `NI`) at `k`, its
/// prediction `predicted` into a state of size `NJ` at `k + 1` with the cross covariance
/// `cross` = Cov(xₖ, xₖ₊₁) (`NI × NJ`), and `next_smoothed` in that state:
/// `G = C (P⁻)⁻¹` (`NI × NJ`), `x̂ˢ = x̂ + G (x̂ˢₖ₊₁ − x̂⁻)`, `Pˢ = P + G (Pˢₖ₊₁ − P⁻) Gᵀ`
/// (the same equations; used by IMM smoothers whose modes have unequal state sizes).
///
/// # Errors
/// As [`rts_step`].
#[allow(non_snake_case)]
#[inline]
pub fn rts_step_across<const NI: usize, const NJ: usize>(
    filtered: &Gaussian<NI>,
    predicted: &Gaussian<NJ>,
    cross: &Matrix<NI, NJ>,
    next_smoothed: &Gaussian<NJ>,
) -> Result<Gaussian<NI>, MathError> {
    let factor = SpdFactor::new_symmetric(predicted.cov(), "predicted covariance")?;
    let G = factor.solve_right(cross);
    check_finite_matrix(&G, "smoother gain")?;
    let dx: Vector<NJ> = next_smoothed.mean() - predicted.mean();
    let mean = filtered.mean() + kernels::mul(&G, &dx);
    let dP = next_smoothed.cov() - predicted.cov();
    let cov = filtered.cov() + kernels::congruence(&G, &dP);
    Gaussian::from_lower_triangle(mean, cov).map_err(|e| match e {
        MathError::NotPositiveDefinite { .. } => MathError::NotPositiveDefinite {
            what: "smoothed covariance",
        },
        MathError::NonFinite { .. } => MathError::NonFinite {
            what: "smoothed estimate",
        },
        other => other,
    })
}

/// Checks a recorded sequence before anything is smoothed: times finite and strictly
/// increasing, a transition into every step after the first. `base` is the number of the
/// first step (for the error).
pub(crate) fn validate<const N: usize>(
    steps: &[RtsStep<N>],
    base: usize,
) -> Result<(), SmoothError> {
    let first = steps.first().ok_or(SmoothError::Empty)?;
    if !first.time().is_finite() {
        return Err(SmoothError::TimeNotIncreasing {
            step: base,
            prev: f64::NEG_INFINITY,
            now: first.time(),
        });
    }
    for (k, pair) in steps.windows(2).enumerate() {
        let (prev, now) = (pair[0].time(), pair[1].time());
        let step = base + k + 1;
        if !(now > prev && now.is_finite()) {
            return Err(SmoothError::TimeNotIncreasing { step, prev, now });
        }
        if pair[1].transition().is_none() {
            return Err(SmoothError::MissingTransition { step });
        }
    }
    Ok(())
}

/// The backward pass over a validated sequence into `out` (same length).
pub(crate) fn backward<const N: usize>(
    steps: &[RtsStep<N>],
    base: usize,
    out: &mut [Gaussian<N>],
) -> Result<(), SmoothError> {
    let n = steps.len();
    let (Some(last), Some(slot)) = (steps.last(), out.last_mut()) else {
        return Err(SmoothError::Empty);
    };
    *slot = *last.filtered();
    for k in (0..n - 1).rev() {
        let step = base + k;
        let tr = steps[k + 1]
            .transition()
            .ok_or(SmoothError::MissingTransition { step: step + 1 })?;
        out[k] = rts_step(steps[k].filtered(), tr, &out[k + 1])
            .map_err(|source| SmoothError::Backward { step, source })?;
    }
    Ok(())
}

/// Fixed-interval RTS smoothing of a recorded sequence into `out` (one entry per step),
/// allocating nothing. The sequence is checked whole before the backward pass starts.
///
/// # Errors
/// [`SmoothError::LengthMismatch`] when `out` is not as long as `steps`;
/// [`SmoothError::Empty`], [`SmoothError::TimeNotIncreasing`],
/// [`SmoothError::MissingTransition`] for a bad sequence; [`SmoothError::Backward`] for a
/// numerical failure (then `out` holds no meaningful result).
pub fn rts_smooth_into<const N: usize>(
    steps: &[RtsStep<N>],
    out: &mut [Gaussian<N>],
) -> Result<(), SmoothError> {
    if out.len() != steps.len() {
        return Err(SmoothError::LengthMismatch {
            what: "smoothed output",
            expected: steps.len(),
            found: out.len(),
        });
    }
    validate(steps, 0)?;
    backward(steps, 0, out)
}

/// Fixed-interval RTS smoothing of a recorded sequence: one smoothed estimate per step.
///
/// # Errors
/// As [`rts_smooth_into`].
pub fn rts_smooth<const N: usize>(steps: &[RtsStep<N>]) -> Result<Vec<Gaussian<N>>, SmoothError> {
    validate(steps, 0)?;
    let mut out: Vec<Gaussian<N>> = steps.iter().map(|s| *s.filtered()).collect();
    backward(steps, 0, &mut out)?;
    Ok(out)
}

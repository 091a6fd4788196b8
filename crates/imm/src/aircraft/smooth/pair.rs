//! One mode pair's transition across unequal state sizes, and its RTS step.

use argus_core_math::{Gaussian, MathError, Matrix, SpdFactor, kernels};
use argus_filters::{Transition, rts_step_across};

/// Mode `i`'s filtered estimate (size `NI`) brought into mode `j`'s state (size `NJ`) by
/// the forward pass's mixing map and predicted through model `j`: the prediction
/// `x̂ⁱʲₖ₊₁|ₖ, Pⁱʲₖ₊₁|ₖ` and the cross covariance `Cⁱʲ = Cov(xⁱₖ, xₖ₊₁ | Z₁:ₖ)` (`NI × NJ`),
/// a [`Transition`] across state sizes.
pub type PairTransition<const NI: usize, const NJ: usize> = Transition<NI, NJ>;

/// The pair's RTS step (module docs, eqs (4)–(5)): `G = Cⁱʲ (Pⁱʲₖ₊₁|ₖ)⁻¹` (`NI × NJ`),
/// `x̂ⁱʲ = x̂ⁱₖ + G (x̃ − x̂ⁱʲₖ₊₁|ₖ)`, `Pⁱʲ = Pⁱₖ + G (P̃ − Pⁱʲₖ₊₁|ₖ) Gᵀ`, with the target
/// `N(x̃, P̃)` in mode `j`'s state and the result in mode `i`'s.
///
/// # Errors
/// [`MathError::NotPositiveDefinite`] naming the predicted or the smoothed covariance;
/// [`MathError::NonFinite`] for a non-finite gain or result.
pub(super) fn pair_rts<const NI: usize, const NJ: usize>(
    filtered: &Gaussian<NI>,
    tr: &PairTransition<NI, NJ>,
    target: &Gaussian<NJ>,
) -> Result<Gaussian<NI>, MathError> {
    rts_step_across(filtered, tr.predicted(), tr.cross(), target)
}

/// The cross covariance of the full CT state with a prediction made from its kinematic
/// marginal (module docs, CT → CV): rows 0–3 are the marginal's cross covariance `C₄`,
/// row 4 (the turn rate) is `P_ω4 P₄₄⁻¹ C₄` — for a Gaussian, `E[ω | x₄]` is linear in
/// `x₄`, so `Cov(ω, g(x₄)) = P_ω4 P₄₄⁻¹ Cov(x₄, g(x₄))` for any `g` (for a linear model
/// `g(x₄) = F x₄ + w` it is `P_ω4 Fᵀ`).
///
/// # Errors
/// [`MathError::NotPositiveDefinite`] if the kinematic block cannot be factored.
pub(super) fn ct_to_cv_cross(
    ct: &Gaussian<5>,
    marginal_cross: &Matrix<4, 4>,
) -> Result<Matrix<5, 4>, MathError> {
    let p44: Matrix<4, 4> = ct.cov().fixed_view::<4, 4>(0, 0).into_owned();
    let p_w4: Matrix<1, 4> = ct.cov().fixed_view::<1, 4>(4, 0).into_owned();
    let f = SpdFactor::new_symmetric(&p44, "CT kinematic covariance")?;
    let reg = f.solve_right(&p_w4);
    let row = kernels::mul(&reg, marginal_cross);
    let mut out = Matrix::<5, 4>::zeros();
    out.fixed_view_mut::<4, 4>(0, 0).copy_from(marginal_cross);
    out.fixed_view_mut::<1, 4>(4, 0).copy_from(&row);
    Ok(out)
}

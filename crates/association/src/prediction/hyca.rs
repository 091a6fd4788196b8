//! The scalars of the NN filter's HYCA recursion in clutter.

use argus_core_math::chi2_cdf;

use crate::error::{AssociationError, check_non_negative, check_prob_open_closed};
use crate::gate::Gate;
use crate::quadrature::{gamma_half, integrate};

/// Quadrature panels (16 nodes each) over the gate radius `r = √q ∈ [0, √γ]`.
pub(super) const R_PANELS: usize = 8;

/// The scalars `(c_T, c_F)` of the NN filter's HYCA recursion,
/// `P̄(k|k) = P̄(k|k−1) − [c_T − c_F] W̄ S̄ W̄ᵀ`, with `β = λ c_n |S̄|^{1/2}`:
///
/// ```text
/// c_F = (β/2) ∫₀^γ q^{n/2} e^{−β q^{n/2}} [1 − P_D P(χ²_n ≤ q)] dq
/// c_T = P_D / (2^{n/2+1} Γ(n/2+1)) ∫₀^γ q^{n/2} e^{−β q^{n/2} − q/2} dq
/// ```
///
/// `c_T` is `E[(q/n) 1{M_T}]` (target plot nearest at normalised distance `q`), `c_F`
/// is `E[(q/n) 1{M_F}]` (a clutter plot nearest; `β (n/2) q^{n/2−1} e^{−βq^{n/2}}` is the
/// density of the nearest clutter plot's distance).
///
/// Seed 002's Fig. 2 prints the exponent of `q` and the upper limits as `γ/2`; they are
/// `n/2` and `γ` (re-derived above, and by the closed form for `n = 2` in the tests).
///
/// # References
/// Li, X. R. & Bar-Shalom, Y. (1996), "Tracking in clutter with nearest neighbor
/// filters: analysis and performance", IEEE TAES 32(3); seed 002 §2.2, Fig. 2 (corrected).
///
/// # Errors
/// [`AssociationError::InvalidParameter`] for `β < 0`, `P_D ∉ (0, 1]`; chi-square
/// errors for `n ∉` the supported range.
pub fn hyca_factors(gate: &Gate, beta: f64, p_d: f64) -> Result<(f64, f64), AssociationError> {
    check_non_negative(beta, "HYCA β = λ c_n |S|^{1/2}")?;
    check_prob_open_closed(p_d, "detection probability")?;
    let n = gate.dim();
    let nf = n as f64;
    let rmax = gate.gamma().sqrt();
    let norm = 2.0 * p_d / (nf * 2f64.powf(nf / 2.0) * gamma_half(n));
    let c_t = integrate(0.0, rmax, R_PANELS, |r| {
        norm * r.powi(n as i32 + 1) * (-0.5 * r * r - beta * r.powi(n as i32)).exp()
    });
    let mut err = None;
    let c_f = integrate(0.0, rmax, R_PANELS, |r| {
        let q = r * r;
        let g = if n == 2 {
            -(-0.5 * q).exp_m1()
        } else {
            chi2_cdf(q, nf).unwrap_or_else(|e| {
                err = Some(e);
                0.0
            })
        };
        beta * r.powi(n as i32 + 1) * (-beta * r.powi(n as i32)).exp() * (1.0 - p_d * g)
    });
    if let Some(e) = err {
        return Err(e.into());
    }
    Ok((c_t, c_f))
}

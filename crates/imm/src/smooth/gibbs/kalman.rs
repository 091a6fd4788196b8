//! The stack-matrix Kalman pieces a sweep runs thousands of times: predict, update with the
//! plot's log-likelihood, the backward information step, the integral of a Gaussian against
//! the backward information, and the RTS step. No allocation; a failure is `None` and the
//! caller names the step.

use argus_core_math::{Matrix, Vector, kernels};

use super::problem::StepModel;

/// A Gaussian's moments in the sweep's buffers (not validated: the sweep's own output).
#[derive(Debug, Clone, Copy)]
pub(super) struct Moments<const N: usize> {
    pub(super) x: Vector<N>,
    pub(super) p: Matrix<N, N>,
}

/// The backward information `βₖ(x) ∝ exp(−½ xᵀ Ω x + ηᵀ x)`.
#[derive(Debug, Clone, Copy)]
pub(super) struct Info<const N: usize> {
    pub(super) omega: Matrix<N, N>,
    pub(super) eta: Vector<N>,
}

impl<const N: usize> Info<N> {
    /// `β = 1` (after the last plot).
    pub(super) fn flat() -> Self {
        Self {
            omega: Matrix::zeros(),
            eta: Vector::zeros(),
        }
    }
}

const LN_2PI: f64 = 1.837_877_066_409_345_5;

/// `F x, F P Fᵀ + Q` of mode `j`.
pub(super) fn predict<const N: usize, const D: usize, const R: usize>(
    g: &Moments<N>,
    s: &StepModel<N, D, R>,
    j: usize,
) -> Moments<N> {
    let mut p = kernels::congruence(&s.f[j], &g.p);
    p += s.q[j];
    Moments {
        x: kernels::mul(&s.f[j], &g.x),
        p,
    }
}

/// The Kalman update with the step's plot, and `ln N(z; H x, H P Hᵀ + R)`. With `S = L Lᵀ`
/// (Cholesky), `W = L⁻¹ H P` and `e = L⁻¹ ν`: `x + Wᵀ e`, `P − Wᵀ W`, and the
/// log-likelihood `−½ (D ln 2π + 2 Σ ln Lᵢᵢ + eᵀ e)`. `None` if `S` is not positive
/// definite.
pub(super) fn update<const N: usize, const D: usize, const R: usize>(
    g: &Moments<N>,
    s: &StepModel<N, D, R>,
) -> Option<(Moments<N>, f64)> {
    let hp: Matrix<D, N> = kernels::mul(&s.h, &g.p);
    let sm: Matrix<D, D> = kernels::mul_transpose(&hp, &s.h) + s.r;
    let chol = sm.cholesky()?;
    let l = chol.l();
    let nu = s.z - kernels::mul(&s.h, &g.x);
    let w = l.solve_lower_triangular(&hp)?;
    let e = l.solve_lower_triangular(&nu)?;
    let x = g.x + w.tr_mul(&e);
    let mut p = g.p;
    kernels::sub_mul_transpose_lower(&mut p, &w.transpose(), &w.transpose());
    kernels::mirror_lower(&mut p);
    let log_det: f64 = (0..D).map(|i| l[(i, i)].ln()).sum();
    let ll = -0.5 * (D as f64 * LN_2PI + 2.0 * log_det + e.norm_squared());
    ll.is_finite().then_some((Moments { x, p }, ll))
}

/// `ln ∫ N(x; μ, P) exp(−½ xᵀ Ω x + ηᵀ x) dx = −½ ln |I + P Ω| − ½ μᵀ Ω μ + ηᵀ μ
/// + ½ bᵀ (I + P Ω)⁻¹ P b`, `b = η − Ω μ`, in symmetric form: with `P = L Lᵀ` and
/// `M = I + Lᵀ Ω L = K Kᵀ` (both Cholesky), `|I + P Ω| = |M|` and `(I + P Ω)⁻¹ P =
/// L M⁻¹ Lᵀ`, so the last term is `½ ‖K⁻¹ Lᵀ b‖²`. `None` if `P` or `M` is not positive
/// definite.
pub(super) fn log_integral<const N: usize>(g: &Moments<N>, b: &Info<N>) -> Option<f64> {
    let l = g.p.cholesky()?.unpack();
    let mut m = Matrix::<N, N>::identity() + kernels::congruence(&l.transpose(), &b.omega);
    kernels::mirror_lower(&mut m);
    let k = m.cholesky()?.unpack();
    let om_mu = kernels::mul(&b.omega, &g.x);
    let r = b.eta - om_mu;
    let c = k.solve_lower_triangular(&l.tr_mul(&r))?;
    let log_det: f64 = (0..N).map(|i| k[(i, i)].ln()).sum();
    let v = -log_det - 0.5 * g.x.dot(&om_mu) + b.eta.dot(&g.x) + 0.5 * c.norm_squared();
    v.is_finite().then_some(v)
}

/// `βₖ` from `βₖ₊₁` through the plot at `k + 1` and the transition of mode `j` into it:
/// `Ω' = Ωₖ₊₁ + Hᵀ R⁻¹ H`, `η' = ηₖ₊₁ + Hᵀ R⁻¹ z`, `A = (I + Q Ω')⁻¹`, `Ωₖ = Fᵀ Ω' A F`,
/// `ηₖ = Fᵀ Aᵀ η'` (Woodbury; no `Q⁻¹`). `None` if `I + Q Ω'` is singular.
pub(super) fn backward<const N: usize, const D: usize, const R: usize>(
    next: &Info<N>,
    s: &StepModel<N, D, R>,
    j: usize,
) -> Option<Info<N>> {
    let om = next.omega + s.info;
    let et = next.eta + s.info_z;
    let a = (Matrix::<N, N>::identity() + kernels::mul(&s.q[j], &om)).try_inverse()?;
    let f = &s.f[j];
    let omega = f.tr_mul(&kernels::mul(&kernels::mul(&om, &a), f));
    let omega = 0.5 * (omega + omega.transpose());
    let eta = f.tr_mul(&a.tr_mul(&et));
    Some(Info { omega, eta })
}

/// The RTS step: `G = Pₖ Fᵀ (Pₖ₊₁|ₖ)⁻¹`, `xₖ + G (xˢₖ₊₁ − x̂ₖ₊₁|ₖ)`, `Pₖ + G (Pˢₖ₊₁ −
/// Pₖ₊₁|ₖ) Gᵀ`. `None` if the prediction's covariance is not positive definite.
pub(super) fn rts<const N: usize>(
    filtered: &Moments<N>,
    f: &Matrix<N, N>,
    pred: &Moments<N>,
    next: &Moments<N>,
) -> Option<Moments<N>> {
    let chol = pred.p.cholesky()?;
    // G = (P⁻¹ F Pₖ)ᵀ with P the (symmetric) prediction covariance.
    let g = chol.solve(&kernels::mul(f, &filtered.p)).transpose();
    let x = filtered.x + kernels::mul(&g, &(next.x - pred.x));
    let p = filtered.p + kernels::congruence(&g, &(next.p - pred.p));
    Some(Moments { x, p })
}

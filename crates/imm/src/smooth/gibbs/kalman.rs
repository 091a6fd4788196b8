//! The stack-matrix Kalman pieces a sweep runs thousands of times: predict, update with the
//! plot's log-likelihood, the backward information step, the integral of a Gaussian against
//! the backward information, and the RTS step. No allocation; a failure is `None` and the
//! caller names the step.

use argus_core_math::{Matrix, Vector, kernels};

use super::step_model::StepModel;

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

/// The lower Cholesky factor `L` of a symmetric `A = L Lᵀ` (only the lower triangle of `A`
/// is read) and `Π Lᵢᵢ`; `None` unless `A` is positive definite. Written out for the
/// sweep's 2×2 and 4×4 matrices: the generic factorisation was a quarter of a sweep.
fn cholesky<const N: usize>(a: &Matrix<N, N>) -> Option<(Matrix<N, N>, f64)> {
    let mut l = Matrix::<N, N>::zeros();
    let mut prod = 1.0;
    for j in 0..N {
        let mut d = a[(j, j)];
        for k in 0..j {
            d -= l[(j, k)] * l[(j, k)];
        }
        if !(d > 0.0 && d.is_finite()) {
            return None;
        }
        let ljj = d.sqrt();
        prod *= ljj;
        l[(j, j)] = ljj;
        let inv = 1.0 / ljj;
        for i in j + 1..N {
            let mut s = a[(i, j)];
            for k in 0..j {
                s -= l[(i, k)] * l[(j, k)];
            }
            l[(i, j)] = s * inv;
        }
    }
    Some((l, prod))
}

/// `L⁻ᵀ B` for a lower-triangular `L` of nonzero diagonal (back substitution on `Lᵀ`).
fn back<const N: usize, const C: usize>(l: &Matrix<N, N>, b: &Matrix<N, C>) -> Matrix<N, C> {
    let mut x = *b;
    for c in 0..C {
        for i in (0..N).rev() {
            let mut s = x[(i, c)];
            for k in i + 1..N {
                s -= l[(k, i)] * x[(k, c)];
            }
            x[(i, c)] = s / l[(i, i)];
        }
    }
    x
}

/// `L⁻¹ B` for a lower-triangular `L` of nonzero diagonal (forward substitution).
fn forward<const N: usize, const C: usize>(l: &Matrix<N, N>, b: &Matrix<N, C>) -> Matrix<N, C> {
    let mut x = *b;
    for c in 0..C {
        for i in 0..N {
            let mut s = x[(i, c)];
            for k in 0..i {
                s -= l[(i, k)] * x[(k, c)];
            }
            x[(i, c)] = s / l[(i, i)];
        }
    }
    x
}

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
    let (l, diag) = cholesky(&sm)?;
    let nu = s.z - kernels::mul(&s.h, &g.x);
    let w = forward(&l, &hp);
    let e = forward(&l, &nu);
    let x = g.x + w.tr_mul(&e);
    let mut p = g.p;
    kernels::sub_mul_transpose_lower(&mut p, &w.transpose(), &w.transpose());
    kernels::mirror_lower(&mut p);
    let ll = -0.5 * (D as f64 * LN_2PI + 2.0 * diag.ln() + e.norm_squared());
    ll.is_finite().then_some((Moments { x, p }, ll))
}

/// `ln ∫ N(x; μ, P) exp(−½ xᵀ Ω x + ηᵀ x) dx =
/// −½ ln |I + P Ω| − ½ μᵀ Ω μ + ηᵀ μ + ½ bᵀ (I + P Ω)⁻¹ P b`, `b = η − Ω μ`, in symmetric form: with `P = L Lᵀ` and
/// `M = I + Lᵀ Ω L = K Kᵀ` (both Cholesky), `|I + P Ω| = |M|` and `(I + P Ω)⁻¹ P =
/// L M⁻¹ Lᵀ`, so the last term is `½ ‖K⁻¹ Lᵀ b‖²`. `None` if `P` or `M` is not positive
/// definite.
pub(super) fn log_integral<const N: usize>(g: &Moments<N>, b: &Info<N>) -> Option<f64> {
    let (l, _) = cholesky(&g.p)?;
    let m = Matrix::<N, N>::identity() + kernels::congruence(&l.transpose(), &b.omega);
    let (k, diag) = cholesky(&m)?;
    let om_mu = kernels::mul(&b.omega, &g.x);
    let r = b.eta - om_mu;
    let c = forward(&k, &l.tr_mul(&r));
    let v = -diag.ln() - 0.5 * g.x.dot(&om_mu) + b.eta.dot(&g.x) + 0.5 * c.norm_squared();
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
    // G = (P⁻¹ F Pₖ)ᵀ with P = L Lᵀ the prediction covariance.
    let (l, _) = cholesky(&pred.p)?;
    let y = forward(&l, &kernels::mul(f, &filtered.p));
    let g = back(&l, &y).transpose();
    let x = filtered.x + kernels::mul(&g, &(next.x - pred.x));
    let p = filtered.p + kernels::congruence(&g, &(next.p - pred.p));
    Some(Moments { x, p })
}

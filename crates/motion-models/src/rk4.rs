//! Fixed-step classical Runge–Kutta integration on stack types (private helper).

use argus_core_math::{Matrix, Vector};

/// A state that RK4 can advance: `self + h k`.
pub(crate) trait OdeState: Copy {
    /// `self + h · k`.
    fn axpy(&self, h: f64, k: &Self) -> Self;
}

impl<const N: usize> OdeState for Vector<N> {
    fn axpy(&self, h: f64, k: &Self) -> Self {
        self + k * h
    }
}

/// The number of substeps for an interval `dt` with substeps no longer than `max_step`:
/// `⌈|dt| / max_step⌉`, at least 1 and at most [`MAX_SUBSTEPS`] (a NaN `dt` gives 1, and
/// the NaN propagates to the result, where the filter reports it).
pub(crate) fn substep_count(dt: f64, max_step: f64) -> usize {
    let n = (dt.abs() / max_step).ceil();
    if n >= MAX_SUBSTEPS_F64 {
        MAX_SUBSTEPS
    } else if n >= 1.0 {
        // Exact: 1 ≤ n < 2⁵³, an integer-valued float.
        n as usize
    } else {
        1
    }
}

/// Upper bound on the substeps of one call (bounds the work for an absurd `dt`).
pub(crate) const MAX_SUBSTEPS: usize = 1_000_000;
const MAX_SUBSTEPS_F64: f64 = 1_000_000.0;

/// Integrates `ṡ = f(s)` from `s0` over `dt` with `n` equal classical RK4 steps.
///
/// # References
/// Butcher (2016), *Numerical Methods for Ordinary Differential Equations*, §23 (the
/// classical fourth-order method).
pub(crate) fn rk4<S: OdeState>(s0: S, dt: f64, n: usize, f: impl Fn(&S) -> S) -> S {
    let n = n.max(1);
    // n ≤ MAX_SUBSTEPS < 2⁵³: the conversion is exact.
    #[allow(clippy::cast_precision_loss)]
    let h = dt / n as f64;
    let mut s = s0;
    for _ in 0..n {
        let k1 = f(&s);
        let k2 = f(&s.axpy(0.5 * h, &k1));
        let k3 = f(&s.axpy(0.5 * h, &k2));
        let k4 = f(&s.axpy(h, &k3));
        s = s
            .axpy(h / 6.0, &k1)
            .axpy(h / 3.0, &k2)
            .axpy(h / 3.0, &k3)
            .axpy(h / 6.0, &k4);
    }
    s
}

/// A state with its sensitivity (transition) matrix: `(x, Φ)`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct WithMatrix<const N: usize> {
    pub(crate) x: Vector<N>,
    pub(crate) m: Matrix<N, N>,
}

impl<const N: usize> OdeState for WithMatrix<N> {
    fn axpy(&self, h: f64, k: &Self) -> Self {
        Self {
            x: self.x + k.x * h,
            m: self.m + k.m * h,
        }
    }
}

/// A state with its transition matrix and the second-order sensitivities
/// `∂²xᵢ(t)/∂x(0)²`, one matrix per component.
#[derive(Debug, Clone, Copy)]
pub(crate) struct WithHessians<const N: usize> {
    pub(crate) x: Vector<N>,
    pub(crate) phi: Matrix<N, N>,
    pub(crate) hess: [Matrix<N, N>; N],
}

impl<const N: usize> OdeState for WithHessians<N> {
    fn axpy(&self, h: f64, k: &Self) -> Self {
        let mut hess = self.hess;
        for (a, b) in hess.iter_mut().zip(k.hess.iter()) {
            *a += b * h;
        }
        Self {
            x: self.x + k.x * h,
            phi: self.phi + k.phi * h,
            hess,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn substep_count_rounds_up() {
        assert_eq!(substep_count(1.0, 0.1), 10);
        assert_eq!(substep_count(1.05, 0.1), 11);
        assert_eq!(substep_count(0.0, 0.1), 1);
        assert_eq!(substep_count(-0.25, 0.1), 3);
        assert_eq!(substep_count(f64::NAN, 0.1), 1);
        assert_eq!(substep_count(1e300, 0.1), MAX_SUBSTEPS);
    }

    #[test]
    fn exponential_decay_fourth_order() {
        // ẋ = −x from 1 over 1 s, exact e⁻¹. One RK4 step multiplies by
        // R(h) = 1 − h + h²/2 − h³/6 + h⁴/24 = e⁻ʰ (1 + h⁵/120 + h⁶/144 + O(h⁷)) (series of
        // eʰ R(h)), so after n = 1/h steps the error is e⁻¹ h⁴ (1/120 + h/144) to leading
        // order: 3.32e-7 for h = 0.1, and the halving ratio is
        // 16 (1/120 + h/144) / (1/120 + h/288) = 16.64 (not exactly 16: the h⁵ term).
        let f = |x: &Vector<1>| -x;
        let exact = (-1.0_f64).exp();
        let e10 = rk4(Vector::<1>::new(1.0), 1.0, 10, f)[0] - exact;
        let e20 = rk4(Vector::<1>::new(1.0), 1.0, 20, f)[0] - exact;
        let predicted = exact * 1e-4 * (1.0 / 120.0 + 0.1 / 144.0);
        assert!(
            (e10 - predicted).abs() < 0.02 * predicted,
            "{e10:e} vs {predicted:e}"
        );
        let h = 0.1;
        let ratio_pred = 16.0 * (1.0 / 120.0 + h / 144.0) / (1.0 / 120.0 + h / 288.0);
        let ratio = e10 / e20;
        assert!((ratio - ratio_pred).abs() < 0.1, "{ratio} vs {ratio_pred}");
    }
}

//! Cholesky-based algebra on small stack matrices.

use crate::{MathError, Matrix, Vector};

/// Relative tolerance used to decide whether a matrix is symmetric.
pub(crate) const SYMMETRY_TOL: f64 = 1e-9;

/// Checks that every entry of `v` is finite.
///
/// # Errors
/// [`MathError::NonFinite`] naming `what`.
#[inline]
pub fn check_finite_vector<const N: usize>(
    v: &Vector<N>,
    what: &'static str,
) -> Result<(), MathError> {
    if all_finite(v.as_slice()) {
        Ok(())
    } else {
        Err(MathError::NonFinite { what })
    }
}

/// Checks that every entry of `m` is finite.
///
/// # Errors
/// [`MathError::NonFinite`] naming `what`.
#[inline]
pub fn check_finite_matrix<const R: usize, const C: usize>(
    m: &Matrix<R, C>,
    what: &'static str,
) -> Result<(), MathError> {
    if all_finite(m.as_slice()) {
        Ok(())
    } else {
        Err(MathError::NonFinite { what })
    }
}

/// Whether every value is finite. Fast path: NaN and ±∞ propagate through a sum, so a
/// finite sum proves every term finite (one vectorisable pass, no branch per entry);
/// only a non-finite sum (or an overflow of huge finite terms) takes the exact check.
#[inline]
pub(crate) fn all_finite(values: &[f64]) -> bool {
    values.iter().sum::<f64>().is_finite() || values.iter().all(|x| x.is_finite())
}

/// Returns `(A + Aᵀ) / 2`.
#[must_use]
#[inline]
pub fn symmetrize<const N: usize>(a: &Matrix<N, N>) -> Matrix<N, N> {
    (a + a.transpose()) * 0.5
}

/// Largest relative asymmetry `max |A - Aᵀ| / max |A|` (0 for the zero matrix).
pub(crate) fn asymmetry<const N: usize>(a: &Matrix<N, N>) -> f64 {
    let scale = a.amax();
    if scale == 0.0 {
        return 0.0;
    }
    (a - a.transpose()).amax() / scale
}

/// Whether the symmetric matrix `a` is positive definite, reading its lower triangle.
///
/// Positive definite exactly when every leading principal minor is positive (Sylvester's
/// criterion), equivalently every pivot `dⱼ` of `A = L D Lᵀ` (Golub & Van Loan 2013,
/// §4.2). The fast path computes the minors by Bareiss's fraction-free elimination
/// (Bareiss 1968): each step multiplies by the new pivot and by the reciprocal of the
/// previous one, which is ready a step ahead, so no division waits on the step before it
/// (the pivot chain of `LDLᵀ` costs one division latency per row). The minors scale as
/// `scale^k`; when one is not a positive finite number (a non-definite matrix, a NaN or
/// ±∞ in the lower triangle, or an overflow or underflow of the minors), the `LDLᵀ`
/// pivots decide. It is the cheap check for a covariance that is stored but not solved
/// with (a filter's output); use [`SpdFactor`] when the factor is needed.
#[must_use]
#[inline]
pub fn is_positive_definite<const N: usize>(a: &Matrix<N, N>) -> bool {
    bareiss_minors_positive(a) || ldl_pivots_positive(a)
}

/// The fast path of [`is_positive_definite`]: the leading principal minors by Bareiss's
/// elimination on a copy of the lower triangle (`m[j][i]` is entry (i, j)); `true` when
/// all are positive and finite. No early exit: fixed trip counts unroll for small `N`.
#[inline]
pub(crate) fn bareiss_minors_positive<const N: usize>(a: &Matrix<N, N>) -> bool {
    let mut m = a.data.0;
    let mut pivots = PivotTest::new();
    // After step j, m[c][r] (c, r > j) is the minor of rows 0..=j, r and columns 0..=j, c
    // (Bareiss: (d_j m − m_jc m_jr) / d_{j−1}, with d_{−1} = 1).
    let mut inv_prev = 1.0;
    for j in 0..N {
        let d = m[j][j];
        pivots.add(d);
        for c in j + 1..N {
            for r in c..N {
                m[c][r] = (d * m[c][r] - m[j][c] * m[j][r]) * inv_prev;
            }
        }
        inv_prev = 1.0 / d;
    }
    pivots.passed()
}

/// The exact path of [`is_positive_definite`]: every `LDLᵀ` pivot positive and finite (the
/// factorisation of [`SpdFactor`], whose factor is discarded; only reached when the fast
/// path fails).
#[inline(never)]
fn ldl_pivots_positive<const N: usize>(a: &Matrix<N, N>) -> bool {
    SpdFactor::new_symmetric(a, "matrix").is_ok()
}

/// The running test of a factorisation's pivots: all positive and finite, as the smallest
/// positive and the sum finite (a NaN or ±∞ pivot makes the sum non-finite): two float
/// operations per pivot and one test at the end, no branch per pivot.
#[derive(Clone, Copy)]
struct PivotTest {
    smallest: f64,
    sum: f64,
}

impl PivotTest {
    #[inline]
    fn new() -> Self {
        Self {
            smallest: f64::INFINITY,
            sum: 0.0,
        }
    }

    #[inline]
    fn add(&mut self, d: f64) {
        self.smallest = self.smallest.min(d);
        self.sum += d;
    }

    #[inline]
    fn passed(self) -> bool {
        self.smallest > 0.0 && self.sum.is_finite()
    }
}

/// The factorisation `A = L D Lᵀ` (`L` unit lower triangular, `D` diagonal and positive) of
/// a symmetric positive-definite matrix, with the solves and determinants built on it.
///
/// Construction checks finiteness and symmetry, then positive definiteness (a pivot that
/// is not positive and finite fails it). The factor is computed here on the stack arrays
/// (Golub & Van Loan 2013, §4.1.2) with the reciprocals of the pivots kept, so the solves
/// multiply instead of dividing; no square roots are taken (the Cholesky factor
/// `L D^{1/2}` is formed only when [`SpdFactor::l`] asks for it), which keeps one
/// division, and no square root, per row on the factorisation's critical path.
#[derive(Debug, Clone, Copy)]
pub struct SpdFactor<const N: usize> {
    /// The strictly lower part of the unit `L`, column-major (`l[j][i]` is `L(i, j)`);
    /// the diagonal and the upper triangle are zero.
    l: [[f64; N]; N],
    /// The pivots `D`.
    d: [f64; N],
    /// `1 / D`.
    inv_d: [f64; N],
}

impl<const N: usize> SpdFactor<N> {
    /// Factors the symmetric positive-definite matrix `a`.
    ///
    /// # Errors
    /// [`MathError::NonFinite`], [`MathError::NotSymmetric`] or
    /// [`MathError::NotPositiveDefinite`], each naming `what`.
    pub fn new(a: &Matrix<N, N>, what: &'static str) -> Result<Self, MathError> {
        check_finite_matrix(a, what)?;
        let asym = asymmetry(a);
        if asym > SYMMETRY_TOL {
            return Err(MathError::NotSymmetric {
                what,
                asymmetry: asym,
            });
        }
        Self::new_symmetric(a, what)
    }

    /// Factors `a`, reading only its lower triangle (no symmetry check).
    /// Use it where `a` is symmetric by construction.
    ///
    /// # Errors
    /// [`MathError::NonFinite`] or [`MathError::NotPositiveDefinite`], naming `what`.
    #[inline]
    pub fn new_symmetric(a: &Matrix<N, N>, what: &'static str) -> Result<Self, MathError> {
        // Every entry of the lower triangle reaches a pivot `d_i` (through `L(i, j)`), so a
        // NaN or ±∞ anywhere in it makes some pivot fail the test: one check covers
        // non-finite input and indefiniteness; only then is `a` examined to name the cause.
        let a = &a.data.0;
        let mut l = [[0.0; N]; N];
        // `w[j][i] = L(i, j) d_j`, the unscaled column, reused by later columns.
        let mut w = [[0.0; N]; N];
        let mut d = [0.0; N];
        let mut inv_d = [0.0; N];
        let mut pivots = PivotTest::new();
        for j in 0..N {
            let mut dj = a[j][j];
            for k in 0..j {
                dj -= l[k][j] * w[k][j];
            }
            pivots.add(dj);
            let inv = 1.0 / dj;
            d[j] = dj;
            inv_d[j] = inv;
            for i in j + 1..N {
                let mut s = a[j][i];
                for k in 0..j {
                    s -= l[k][i] * w[k][j];
                }
                w[j][i] = s;
                l[j][i] = s * inv;
            }
        }
        if pivots.passed() {
            Ok(Self { l, d, inv_d })
        } else {
            let full = Matrix::<N, N>::from_data(nalgebra::ArrayStorage(*a));
            Err(check_finite_matrix(&full, what)
                .err()
                .unwrap_or(MathError::NotPositiveDefinite { what }))
        }
    }

    /// The lower-triangular Cholesky factor `L D^{1/2}` (`A = (L D^{1/2})(L D^{1/2})ᵀ`).
    #[must_use]
    pub fn l(&self) -> Matrix<N, N> {
        Matrix::<N, N>::from_fn(|i, j| {
            let root = self.d[j].sqrt();
            match i.cmp(&j) {
                std::cmp::Ordering::Equal => root,
                std::cmp::Ordering::Greater => self.l[j][i] * root,
                std::cmp::Ordering::Less => 0.0,
            }
        })
    }

    /// Solves `A x = b`.
    #[must_use]
    #[inline]
    pub fn solve_vector(&self, b: &Vector<N>) -> Vector<N> {
        self.solve_matrix(b)
    }

    /// Solves `A X = B` for a matrix right-hand side.
    #[must_use]
    #[inline]
    pub fn solve_matrix<const C: usize>(&self, b: &Matrix<N, C>) -> Matrix<N, C> {
        // `L y = b` forward, `y /= D`, `Lᵀ x = y` backward, on the stack arrays
        // (column-major: `l[j][i]` is L(i, j)); fixed trip counts unroll for small `N`.
        let l = &self.l;
        let mut x = *b;
        for col in &mut x.data.0 {
            for i in 0..N {
                let mut s = col[i];
                for k in 0..i {
                    s -= l[k][i] * col[k];
                }
                col[i] = s;
            }
            for (c, &inv) in col.iter_mut().zip(&self.inv_d) {
                *c *= inv;
            }
            for i in (0..N).rev() {
                let mut s = col[i];
                for k in i + 1..N {
                    s -= l[i][k] * col[k];
                }
                col[i] = s;
            }
        }
        x
    }

    /// Solves `X A = B` for `X` (a right division, `X = B A⁻¹`), as a filter's gain
    /// `K = P Hᵀ S⁻¹`: column operations on `B` (`V Lᵀ = B` forward, `Y = V D⁻¹`, then
    /// `X L = Y` backward), so no transposes are formed.
    #[must_use]
    #[inline]
    pub fn solve_right<const R: usize>(&self, b: &Matrix<R, N>) -> Matrix<R, N> {
        let l = &self.l;
        let mut x = b.data.0;
        // V Lᵀ = B: column i of V is B_i − Σ_{k<i} L(i, k) V_k; then Y_i = V_i / d_i.
        for i in 0..N {
            let mut col = x[i];
            for (k, vk) in x.iter().enumerate().take(i) {
                let lik = l[k][i];
                for (c, &v) in col.iter_mut().zip(vk) {
                    *c -= lik * v;
                }
            }
            x[i] = col;
        }
        for (col, &inv) in x.iter_mut().zip(&self.inv_d) {
            for c in col {
                *c *= inv;
            }
        }
        // X L = Y: column i of X is Y_i − Σ_{k>i} L(k, i) X_k.
        for i in (0..N).rev() {
            let mut col = x[i];
            for (k, xk) in x.iter().enumerate().skip(i + 1) {
                let lki = l[i][k];
                for (c, &v) in col.iter_mut().zip(xk) {
                    *c -= lki * v;
                }
            }
            x[i] = col;
        }
        Matrix::<R, N>::from_data(nalgebra::ArrayStorage(x))
    }

    /// The inverse `A⁻¹` (symmetrised).
    #[must_use]
    pub fn inverse(&self) -> Matrix<N, N> {
        symmetrize(&self.solve_matrix(&Matrix::<N, N>::identity()))
    }

    /// `ln |A| = Σ ln dᵢ` (no overflow or underflow of the determinant).
    #[must_use]
    #[inline]
    pub fn log_det(&self) -> f64 {
        log_det_of_pivots(&self.d)
    }

    /// The pivots `D` of `A = L D Lᵀ` (their product is `|A|`).
    #[must_use]
    #[inline]
    pub fn pivots(&self) -> [f64; N] {
        self.d
    }

    /// The squared Mahalanobis distance `vᵀ A⁻¹ v = Σ wᵢ² / dᵢ` with `L w = v`.
    #[must_use]
    #[inline]
    pub fn mahalanobis_sq(&self, v: &Vector<N>) -> f64 {
        let l = &self.l;
        let mut w = v.data.0[0];
        let mut sum = 0.0;
        for i in 0..N {
            let mut s = w[i];
            for k in 0..i {
                s -= l[k][i] * w[k];
            }
            w[i] = s;
            sum += s * s * self.inv_d[i];
        }
        sum
    }

    /// The Gaussian log-density `ln N(v; 0, A) = −½ (vᵀA⁻¹v + ln|A| + N ln 2π)`.
    #[must_use]
    pub fn log_density(&self, v: &Vector<N>) -> f64 {
        -0.5 * (self.mahalanobis_sq(v)
            + self.log_det()
            + N as f64 * (2.0 * std::f64::consts::PI).ln())
    }
}

/// `ln Π dᵢ` of positive pivots (a determinant's logarithm, [`SpdFactor::pivots`]): one
/// logarithm of the product when that is a normal float, otherwise (under- or overflow) the
/// sum of logarithms.
#[must_use]
#[inline]
pub fn log_det_of_pivots<const N: usize>(d: &[f64; N]) -> f64 {
    let product: f64 = d.iter().product();
    if product.is_normal() {
        product.ln()
    } else {
        d.iter().map(|d| d.ln()).sum::<f64>()
    }
}

/// Gaussian log-likelihood of a residual `r` with covariance `s`:
/// `−½ (rᵀS⁻¹r + ln|2πS|)`.
///
/// Note `|2πS|^{−½}`: the normaliser carries the square root (seed 000 eqs (5), (9)
/// misprint it). Work in logs: likelihoods of many models are compared and multiplied.
///
/// # Errors
/// As [`SpdFactor::new`] for `s`, and [`MathError::NonFinite`] for `r`.
pub fn log_likelihood<const M: usize>(r: &Vector<M>, s: &Matrix<M, M>) -> Result<f64, MathError> {
    check_finite_vector(r, "residual")?;
    let f = SpdFactor::new(s, "innovation covariance")?;
    Ok(f.log_density(r))
}

/// Joseph-form covariance update `(I − K H) P (I − K H)ᵀ + K R Kᵀ`, symmetrised.
///
/// Valid for any gain `K` (not only the optimal one). Computed as
/// [`joseph_update_from_innovation`] with `P Hᵀ` and `S = H P Hᵀ + R` formed here.
#[must_use]
#[allow(non_snake_case)]
#[inline]
pub fn joseph_update<const N: usize, const M: usize>(
    P: &Matrix<N, N>,
    K: &Matrix<N, M>,
    H: &Matrix<M, N>,
    R: &Matrix<M, M>,
) -> Matrix<N, N> {
    joseph_update_from_cross(P, K, H, &crate::kernels::mul_transpose(P, H), R)
}

/// The Joseph-form update `(I − K H) P (I − K H)ᵀ + K R Kᵀ` given the cross covariance
/// `P Hᵀ` a filter has already formed; as [`joseph_update_from_innovation`] with
/// `S = H (P Hᵀ) + R`.
#[must_use]
#[allow(non_snake_case)]
#[inline]
pub fn joseph_update_from_cross<const N: usize, const M: usize>(
    P: &Matrix<N, N>,
    K: &Matrix<N, M>,
    H: &Matrix<M, N>,
    PHt: &Matrix<N, M>,
    R: &Matrix<M, M>,
) -> Matrix<N, N> {
    let mut S = crate::kernels::mul(H, PHt) + R;
    crate::kernels::mirror_lower(&mut S);
    joseph_update_from_innovation(P, K, PHt, &S)
}

/// The Joseph-form update from the cross covariance `P_xz = P Hᵀ` and the innovation
/// covariance `S = H P Hᵀ + R` (symmetric), for any gain `K`:
/// `(I − K H) P (I − K H)ᵀ + K R Kᵀ = P − K P_xzᵀ − P_xz Kᵀ + K S Kᵀ
///  = P − K P_xzᵀ − C Kᵀ` with `C = P_xz − K S`.
///
/// `C` is the gain's error (zero at `K = P_xz S⁻¹`), so a perturbed gain moves the result
/// only at second order (`δK S δKᵀ`), the property the Joseph form is used for; the result
/// is symmetric, and its lower triangle is computed and mirrored. For `N = 4`, `M = 2`
/// that is 56 multiply-adds (`H` is not needed). Tested against the literal definition.
#[must_use]
#[allow(non_snake_case)]
#[inline]
pub fn joseph_update_from_innovation<const N: usize, const M: usize>(
    P: &Matrix<N, N>,
    K: &Matrix<N, M>,
    PHt: &Matrix<N, M>,
    S: &Matrix<M, M>,
) -> Matrix<N, N> {
    use crate::kernels::{mirror_lower, mul, sub_mul_transpose_lower};
    let C = PHt - mul(K, S);
    let mut out = *P;
    sub_mul_transpose_lower(&mut out, K, PHt);
    sub_mul_transpose_lower(&mut out, &C, K);
    mirror_lower(&mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Cholesky;
    use proptest::prelude::*;

    fn spd3(seed: [f64; 9]) -> Matrix<3, 3> {
        let a = Matrix::<3, 3>::from_row_slice(&seed);
        a * a.transpose() + Matrix::<3, 3>::identity() * 0.5
    }

    #[test]
    fn rejects_nan_asymmetric_and_indefinite() {
        let mut a = Matrix::<2, 2>::identity();
        a[(0, 1)] = f64::NAN;
        assert!(matches!(
            SpdFactor::new(&a, "A"),
            Err(MathError::NonFinite { what: "A" })
        ));
        let b = Matrix::<2, 2>::new(1.0, 0.5, 0.0, 1.0);
        assert!(matches!(
            SpdFactor::new(&b, "B"),
            Err(MathError::NotSymmetric { .. })
        ));
        let c = Matrix::<2, 2>::new(1.0, 2.0, 2.0, 1.0); // eigenvalues 3, −1
        assert!(matches!(
            SpdFactor::new(&c, "C"),
            Err(MathError::NotPositiveDefinite { .. })
        ));
        let z = Matrix::<2, 2>::zeros();
        assert!(SpdFactor::new(&z, "Z").is_err());
    }

    #[test]
    fn finite_check_is_exact_on_overflowing_sums() {
        // Two huge finite values overflow their sum; the exact fallback still says finite.
        assert!(all_finite(&[f64::MAX, f64::MAX, 1.0]));
        assert!(!all_finite(&[1.0, f64::NAN]));
        assert!(!all_finite(&[f64::INFINITY, f64::NEG_INFINITY]));
        assert!(!all_finite(&[1.0, f64::INFINITY]));
    }

    #[test]
    fn log_det_survives_extreme_scales() {
        // diag(1e-200, 1e-200, 1e-200): the determinant underflows, its log is 3 ln 1e-200.
        let tiny = Matrix::<3, 3>::identity() * 1e-200;
        let f = SpdFactor::new(&tiny, "tiny").unwrap();
        assert!((f.log_det() - 3.0 * 1e-200f64.ln()).abs() < 1e-9);
        let huge = Matrix::<3, 3>::identity() * 1e200;
        let f = SpdFactor::new(&huge, "huge").unwrap();
        assert!((f.log_det() - 3.0 * 1e200f64.ln()).abs() < 1e-9);
        // A NaN off the diagonal is named non-finite, not "not positive definite".
        let mut nan = Matrix::<2, 2>::identity();
        nan[(1, 0)] = f64::NAN;
        nan[(0, 1)] = f64::NAN;
        assert!(matches!(
            SpdFactor::new_symmetric(&nan, "N"),
            Err(MathError::NonFinite { what: "N" })
        ));
    }

    #[test]
    fn log_likelihood_matches_closed_form_1d() {
        // N(r; 0, s) = exp(-r²/2s)/sqrt(2πs): closed form.
        let s = 4.0;
        let r = 1.5;
        let expect = -0.5 * r * r / s - 0.5 * (2.0 * std::f64::consts::PI * s).ln();
        let got = log_likelihood(&Vector::<1>::new(r), &Matrix::<1, 1>::new(s)).unwrap();
        assert!((got - expect).abs() < 1e-14);
    }

    #[test]
    fn log_likelihood_does_not_underflow() {
        // A residual of 100 sigma: the density underflows to 0 in linear space,
        // the log stays finite (−5000 − ½ ln 2π).
        let got = log_likelihood(&Vector::<1>::new(100.0), &Matrix::<1, 1>::new(1.0)).unwrap();
        assert!(got.is_finite());
        assert!((got - (-5000.0 - 0.5 * (2.0 * std::f64::consts::PI).ln())).abs() < 1e-9);
    }

    #[test]
    fn positive_definite_test_agrees_on_edge_cases() {
        // Hand-checked: eigenvalues of [[1, 2], [2, 1]] are 3 and −1; of [[2, 1], [1, 2]] 3 and 1.
        assert!(!is_positive_definite(&Matrix::<2, 2>::new(
            1.0, 2.0, 2.0, 1.0
        )));
        assert!(is_positive_definite(&Matrix::<2, 2>::new(
            2.0, 1.0, 1.0, 2.0
        )));
        // Semi-definite (a zero eigenvalue) is not definite.
        assert!(!is_positive_definite(&Matrix::<2, 2>::new(
            1.0, 1.0, 1.0, 1.0
        )));
        assert!(!is_positive_definite(&Matrix::<3, 3>::zeros()));
        // Non-finite entries of the lower triangle, on or off the diagonal, fail.
        for (i, j) in [(0, 0), (1, 0), (2, 0), (2, 1), (2, 2)] {
            for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                let mut m = Matrix::<3, 3>::identity();
                m[(i, j)] = bad;
                m[(j, i)] = bad;
                assert!(!is_positive_definite(&m), "({i}, {j}) = {bad}");
            }
        }
    }

    #[test]
    fn positive_definite_test_survives_extreme_scales() {
        // The fast path's minors overflow (1e200⁴) or underflow (1e-200⁴); the LDLᵀ
        // pivots decide, and both matrices are definite.
        let big = Matrix::<4, 4>::identity() * 1e200;
        assert!(!bareiss_minors_positive(&big));
        assert!(is_positive_definite(&big));
        let tiny = Matrix::<4, 4>::identity() * 1e-200;
        assert!(!bareiss_minors_positive(&tiny));
        assert!(is_positive_definite(&tiny));
        assert!(!is_positive_definite(
            &(Matrix::<4, 4>::identity() * -1e200)
        ));
    }

    proptest! {
        #[test]
        fn bareiss_minors_are_the_leading_principal_minors(seed in proptest::array::uniform16(-3.0f64..3.0)) {
            // The fast path decides exactly as the determinants of the leading blocks do
            // (away from zero), and as the LDLᵀ pivots.
            let g = Matrix::<4, 4>::from_row_slice(&seed);
            let m = symmetrize(&(g + g.transpose()));
            let minors: Vec<f64> = (1..=4).map(|k| m.view((0, 0), (k, k)).determinant()).collect();
            prop_assume!(minors.iter().all(|d| d.abs() > 1e-6));
            let all_positive = minors.iter().all(|&d| d > 0.0);
            prop_assert_eq!(bareiss_minors_positive(&m), all_positive);
            prop_assert_eq!(ldl_pivots_positive(&m), all_positive);
            let spd = m * m.transpose() + Matrix::<4, 4>::identity();
            prop_assert!(bareiss_minors_positive(&symmetrize(&spd)));
        }

        #[test]
        fn positive_definite_test_agrees_with_cholesky(seed in proptest::array::uniform9(-3.0f64..3.0), shift in -4.0f64..1.0) {
            // A A^T + shift I is definite exactly when shift exceeds −λ_min(A Aᵀ); the
            // test and nalgebra's Cholesky must agree away from the boundary.
            let a = Matrix::<3, 3>::from_row_slice(&seed);
            let m = symmetrize(&(a * a.transpose() + Matrix::<3, 3>::identity() * shift));
            let lambda_min = m.symmetric_eigenvalues().min();
            prop_assume!(lambda_min.abs() > 1e-9 * (1.0 + m.amax()));
            prop_assert_eq!(is_positive_definite(&m), lambda_min > 0.0);
            prop_assert_eq!(is_positive_definite(&m), Cholesky::new(m).is_some());
        }

        #[test]
        fn solve_inverse_logdet_agree_with_nalgebra(seed in proptest::array::uniform9(-3.0f64..3.0)) {
            let a = spd3(seed);
            let f = SpdFactor::new(&symmetrize(&a), "A").unwrap();
            let b = Vector::<3>::new(1.0, -2.0, 0.5);
            let x = f.solve_vector(&b);
            prop_assert!(((a * x) - b).amax() < 1e-8 * (1.0 + a.amax()));
            let inv = f.inverse();
            prop_assert!((a * inv - Matrix::<3, 3>::identity()).amax() < 1e-8 * (1.0 + a.amax()));
            prop_assert!((f.log_det() - a.determinant().ln()).abs() < 1e-9 * (1.0 + a.determinant().ln().abs()));
            let m = f.mahalanobis_sq(&b);
            prop_assert!((m - b.dot(&x)).abs() < 1e-8 * (1.0 + m));
            // The hand-written substitutions against nalgebra's Cholesky solve.
            let rhs = Matrix::<3, 2>::new(1.0, -2.0, 0.5, 3.0, -1.0, 2.0);
            let ours = f.solve_matrix(&rhs);
            let theirs = Cholesky::new(symmetrize(&a)).unwrap().solve(&rhs);
            prop_assert!((ours - theirs).amax() < 1e-10 * (1.0 + theirs.amax()));
            // The Cholesky factor it reports reproduces A, and agrees with nalgebra's.
            let ll = f.l();
            prop_assert!((ll * ll.transpose() - a).amax() < 1e-9 * (1.0 + a.amax()));
            prop_assert!((ll - Cholesky::new(symmetrize(&a)).unwrap().l()).amax() < 1e-9 * (1.0 + a.amax()));
            // The right division X A = B against the transposed left solve.
            let right = f.solve_right(&rhs.transpose());
            prop_assert!((right - theirs.transpose()).amax() < 1e-10 * (1.0 + theirs.amax()));
        }

        #[test]
        fn joseph_equals_standard_at_optimal_gain(seed in proptest::array::uniform9(-3.0f64..3.0)) {
            // Property: at K = P Hᵀ S⁻¹ the Joseph form equals P − K S Kᵀ.
            let p = symmetrize(&spd3(seed));
            let h = Matrix::<2, 3>::new(1.0, 0.0, 0.5, 0.0, 1.0, -0.25);
            let r = Matrix::<2, 2>::new(0.7, 0.1, 0.1, 0.9);
            let s = h * p * h.transpose() + r;
            let sf = SpdFactor::new(&symmetrize(&s), "S").unwrap();
            let k = sf.solve_matrix(&(h * p)).transpose();
            let standard = p - k * s * k.transpose();
            let joseph = joseph_update(&p, &k, &h, &r);
            prop_assert!((standard - joseph).amax() < 1e-9 * (1.0 + p.amax()));
        }

        #[test]
        fn joseph_equals_its_definition_for_any_gain(
            seed in proptest::array::uniform9(-3.0f64..3.0),
            kv in proptest::array::uniform6(-2.0f64..2.0),
        ) {
            // Definition (I − KH) P (I − KH)ᵀ + K R Kᵀ, formed literally, for an arbitrary
            // (sub-optimal) gain; tolerance: round-off of products of entries ≲ 10² in size.
            let p = symmetrize(&spd3(seed));
            let h = Matrix::<2, 3>::new(1.0, 0.0, 0.5, 0.0, 1.0, -0.25);
            let r = Matrix::<2, 2>::new(0.7, 0.1, 0.1, 0.9);
            let k = Matrix::<3, 2>::from_row_slice(&kv);
            let a = Matrix::<3, 3>::identity() - k * h;
            let literal = a * p * a.transpose() + k * r * k.transpose();
            let joseph = joseph_update(&p, &k, &h, &r);
            prop_assert!((literal - joseph).amax() < 1e-11 * (1.0 + literal.amax()));
            prop_assert_eq!(joseph, joseph.transpose());
        }
    }
}

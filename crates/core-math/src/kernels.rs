//! Small dense products written as plain loops over nalgebra's stack storage.
//!
//! nalgebra's `*` on fixed-size matrices goes through its general `gemm` and is not
//! inlined for the 2–6-dimensional sizes of per-track filtering; these loops have
//! compile-time bounds, so the compiler unrolls and vectorises them in place. They compute
//! the same sums as `*` (the order of the terms may differ in the last bit). The per-step
//! instruction counts are in `docs/STATUS.md` (measured with
//! `crates/filters/examples/step_timing.rs <filter> <steps>` under callgrind).

use crate::Matrix;

/// `A B`.
#[inline]
#[must_use]
pub fn mul<const R: usize, const K: usize, const C: usize>(
    a: &Matrix<R, K>,
    b: &Matrix<K, C>,
) -> Matrix<R, C> {
    let a = &a.data.0;
    let b = &b.data.0;
    let mut out = Matrix::<R, C>::zeros();
    for (o, bj) in out.data.0.iter_mut().zip(b) {
        // Column j of the product, accumulated in registers: Σ_k a_k b_kj.
        let mut col = [0.0; R];
        for (ak, &bkj) in a.iter().zip(bj) {
            for (c, &aik) in col.iter_mut().zip(ak) {
                *c += aik * bkj;
            }
        }
        *o = col;
    }
    out
}

/// `A Bᵀ`.
#[inline]
#[must_use]
pub fn mul_transpose<const R: usize, const K: usize, const C: usize>(
    a: &Matrix<R, K>,
    b: &Matrix<C, K>,
) -> Matrix<R, C> {
    let a = &a.data.0;
    let b = &b.data.0;
    let mut out = Matrix::<R, C>::zeros();
    for (j, o) in out.data.0.iter_mut().enumerate() {
        // Column j: Σ_k a_k b_jk.
        let mut col = [0.0; R];
        for (ak, bk) in a.iter().zip(b) {
            let bjk = bk[j];
            for (c, &aik) in col.iter_mut().zip(ak) {
                *c += aik * bjk;
            }
        }
        *o = col;
    }
    out
}

/// Copies the lower triangle onto the upper one: `m` becomes exactly symmetric (for a
/// product that is symmetric in exact arithmetic but not under round-off).
#[inline]
pub fn mirror_lower<const N: usize>(m: &mut Matrix<N, N>) {
    let src = *m;
    mirror_lower_into(&src, m);
}

/// The symmetric matrix whose lower triangle is that of `src`, written into `dst` (the
/// strict upper triangle of `src` is not read).
///
/// Every entry of `dst` is written, column by column, rather than only the upper triangle
/// one entry at a time: entries stored one by one and read back in pairs by the next copy
/// of the matrix cannot be forwarded from the store buffer, and that stall cost more than
/// the arithmetic of a filter step's last stage (measured on the IMM step, session 5).
#[inline(always)]
pub fn mirror_lower_into<const N: usize>(src: &Matrix<N, N>, dst: &mut Matrix<N, N>) {
    let o = &src.data.0;
    for (c, col) in dst.data.0.iter_mut().enumerate() {
        for (r, v) in col.iter_mut().enumerate() {
            *v = if r >= c { o[c][r] } else { o[r][c] };
        }
    }
}

/// Subtracts `A Bᵀ` from the lower triangle (diagonal included) of `m`, in place; the
/// strict upper triangle is not touched. For updates of a symmetric matrix by terms whose
/// sum is symmetric: apply each, then [`mirror_lower`].
#[inline]
pub fn sub_mul_transpose_lower<const N: usize, const K: usize>(
    m: &mut Matrix<N, N>,
    a: &Matrix<N, K>,
    b: &Matrix<N, K>,
) {
    let o = &mut m.data.0;
    let a = &a.data.0;
    let b = &b.data.0;
    for j in 0..N {
        for k in 0..K {
            let bjk = b[k][j];
            for i in j..N {
                o[j][i] -= a[k][i] * bjk;
            }
        }
    }
}

/// The congruence `A P Aᵀ` of a symmetric `P`, made exactly symmetric by mirroring the
/// lower triangle of `(A P) Aᵀ`.
#[inline]
#[must_use]
pub fn congruence<const R: usize, const N: usize>(
    a: &Matrix<R, N>,
    p: &Matrix<N, N>,
) -> Matrix<R, R> {
    let mut out = mul_transpose(&mul(a, p), a);
    mirror_lower(&mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn products_equal_nalgebra(v in proptest::collection::vec(-10.0f64..10.0, 42)) {
            // Reference: nalgebra's own products; tolerance: a few ulps of the largest term.
            let a = Matrix::<3, 4>::from_column_slice(&v[0..12]);
            let b = Matrix::<4, 2>::from_column_slice(&v[12..20]);
            let c = Matrix::<2, 4>::from_column_slice(&v[20..28]);
            let p = Matrix::<4, 4>::from_column_slice(&v[26..42]);
            let p = p + p.transpose();
            let tol = 1e-12 * 1e4;
            prop_assert!((mul(&a, &b) - a * b).amax() < tol);
            prop_assert!((mul_transpose(&a, &c) - a * c.transpose()).amax() < tol);
            let mut lower = p;
            // Lower triangle of P − b (cᵀ)ᵀ; the upper triangle untouched.
            sub_mul_transpose_lower(&mut lower, &b, &c.transpose());
            let full = p - b * c;
            for j in 0..4 {
                for i in 0..4 {
                    let want = if i >= j { full[(i, j)] } else { p[(i, j)] };
                    prop_assert!((lower[(i, j)] - want).abs() < tol);
                }
            }
            let g = congruence(&a, &p);
            prop_assert!((g - a * p * a.transpose()).amax() < tol);
            prop_assert_eq!(g, g.transpose());
        }
    }

    #[test]
    fn mirrors_copy_the_lower_triangle_exactly() {
        // Both mirrors: the lower triangle (diagonal included) kept bit for bit, the upper
        // one its transpose, whatever the upper triangle held before.
        let m = Matrix::<4, 4>::from_fn(|r, c| (10 * r + c) as f64 + 0.25);
        let mut a = m;
        mirror_lower(&mut a);
        let mut b = Matrix::<4, 4>::from_element(f64::NAN);
        mirror_lower_into(&m, &mut b);
        for c in 0..4 {
            for r in 0..4 {
                let want = if r >= c { m[(r, c)] } else { m[(c, r)] };
                assert_eq!(a[(r, c)].to_bits(), want.to_bits());
                assert_eq!(b[(r, c)].to_bits(), want.to_bits());
            }
        }
    }
}

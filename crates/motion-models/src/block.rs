//! Block-diagonal assembly of per-axis matrices (private helper).

use argus_core_math::Matrix;

/// Repeats the `B × B` block `b` along the diagonal of an `N × N` matrix
/// (`N / B` copies; the callers use `N` a multiple of `B`).
pub(crate) fn block_diag<const N: usize, const B: usize>(b: &Matrix<B, B>) -> Matrix<N, N> {
    let mut m = Matrix::<N, N>::zeros();
    let mut k = 0;
    while k + B <= N {
        m.fixed_view_mut::<B, B>(k, k).copy_from(b);
        k += B;
    }
    m
}

/// Implements [`crate::MotionModel`] and [`crate::LinearMotionModel`] for a model that is
/// the same per-axis block on every axis: `$name` has an `axis_transition(dt)` and an
/// `axis_noise(dt)` returning `B × B` blocks.
/// `F x` for `F = diag(A, A, …)` (`N / B` blocks), block by block.
#[inline]
pub(crate) fn block_mul_vec<const N: usize, const B: usize>(
    a: &Matrix<B, B>,
    x: &argus_core_math::Vector<N>,
) -> argus_core_math::Vector<N> {
    let mut out = *x;
    let mut k = 0;
    while k + B <= N {
        let xb: argus_core_math::Vector<B> = x.fixed_rows::<B>(k).into_owned();
        out.fixed_rows_mut::<B>(k)
            .copy_from(&argus_core_math::kernels::mul(a, &xb));
        k += B;
    }
    out
}

/// `F P Fᵀ` for `F = diag(A, A, …)` (`N / B` blocks): block `(i, j)` of the result is
/// `A P_ij Aᵀ`. Only the blocks on and below the diagonal are computed; the rest is
/// their mirror, so the result is exactly symmetric. Components past the last whole
/// block (none for the models here) keep `F = I`.
#[inline]
pub(crate) fn block_congruence<const N: usize, const B: usize>(
    a: &Matrix<B, B>,
    p: &Matrix<N, N>,
) -> Matrix<N, N> {
    use argus_core_math::kernels::{congruence, mul, mul_transpose};
    let mut out = *p;
    let blocks = N / B;
    for j in 0..blocks {
        let diag: Matrix<B, B> = p.fixed_view::<B, B>(j * B, j * B).into_owned();
        out.fixed_view_mut::<B, B>(j * B, j * B)
            .copy_from(&congruence(a, &diag));
        for i in j + 1..blocks {
            let off: Matrix<B, B> = p.fixed_view::<B, B>(i * B, j * B).into_owned();
            let m = mul_transpose(&mul(a, &off), a);
            out.fixed_view_mut::<B, B>(i * B, j * B).copy_from(&m);
            out.fixed_view_mut::<B, B>(j * B, i * B)
                .copy_from(&m.transpose());
        }
    }
    out
}

macro_rules! impl_block_model {
    ($name:ident, $n:literal, $b:literal) => {
        impl $crate::MotionModel<$n> for $name {
            fn propagate(
                &self,
                x: &argus_core_math::Vector<$n>,
                dt: f64,
            ) -> argus_core_math::Vector<$n> {
                $crate::block::block_mul_vec::<$n, $b>(&Self::axis_transition(dt), x)
            }

            #[inline]
            fn propagate_covariance(
                &self,
                _x: &argus_core_math::Vector<$n>,
                p: &argus_core_math::Matrix<$n, $n>,
                dt: f64,
            ) -> argus_core_math::Matrix<$n, $n> {
                $crate::block::block_congruence::<$n, $b>(&Self::axis_transition(dt), p)
            }

            fn jacobian(
                &self,
                _x: &argus_core_math::Vector<$n>,
                dt: f64,
            ) -> argus_core_math::Matrix<$n, $n> {
                $crate::LinearMotionModel::<$n>::transition(self, dt)
            }

            fn process_noise(
                &self,
                _x: &argus_core_math::Vector<$n>,
                dt: f64,
            ) -> argus_core_math::Matrix<$n, $n> {
                $crate::block::block_diag::<$n, $b>(&self.axis_noise(dt))
            }

            /// A linear model's Hessians are all zero.
            fn hessians(
                &self,
                _x: &argus_core_math::Vector<$n>,
                _dt: f64,
            ) -> Option<[argus_core_math::Matrix<$n, $n>; $n]> {
                Some([argus_core_math::Matrix::<$n, $n>::zeros(); $n])
            }
        }

        impl $crate::LinearMotionModel<$n> for $name {
            fn transition(&self, dt: f64) -> argus_core_math::Matrix<$n, $n> {
                $crate::block::block_diag::<$n, $b>(&Self::axis_transition(dt))
            }
        }
    };
}
pub(crate) use impl_block_model;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn block_diag_places_copies() {
        let b = Matrix::<2, 2>::new(1.0, 2.0, 3.0, 4.0);
        let m = block_diag::<6, 2>(&b);
        assert_eq!(m.fixed_view::<2, 2>(4, 4).into_owned(), b);
        assert_eq!(
            m.fixed_view::<2, 2>(0, 2).into_owned(),
            Matrix::<2, 2>::zeros()
        );
        // Sum of all entries: three copies of 1+2+3+4.
        assert!((m.sum() - 30.0).abs() < 1e-15);
    }

    fn check_structured<const N: usize, const B: usize>(a: &Matrix<B, B>, seed: &[f64]) {
        let g = Matrix::<N, N>::from_fn(|i, j| seed[(i * N + j) % seed.len()] + (i as f64));
        let p = g * g.transpose() + Matrix::<N, N>::identity();
        let x = argus_core_math::Vector::<N>::from_fn(|i, _| seed[i % seed.len()]);
        let f = block_diag::<N, B>(a);
        let full = f * p * f.transpose();
        let fast = block_congruence::<N, B>(a, &p);
        // Tolerance: the same sums in another order, relative round-off of the products.
        assert!((fast - full).amax() <= 1e-12 * full.amax());
        assert_eq!(fast, fast.transpose());
        assert!((block_mul_vec::<N, B>(a, &x) - f * x).amax() <= 1e-12 * (f * x).amax());
    }

    proptest::proptest! {
        #[test]
        fn structured_products_equal_full_products(
            dt in 0.01f64..20.0,
            seed in proptest::collection::vec(-3.0f64..3.0, 7),
        ) {
            let cv = crate::cv_axis_transition(dt);
            check_structured::<2, 2>(&cv, &seed);
            check_structured::<4, 2>(&cv, &seed);
            check_structured::<6, 2>(&cv, &seed);
            let ca = crate::ca_axis_transition(dt);
            check_structured::<6, 3>(&ca, &seed);
            check_structured::<9, 3>(&ca, &seed);
        }
    }
}

//! Block-diagonal assembly of per-axis matrices (private helper).

use argus_core_math::Matrix;

/// Repeats the `B × B` block `b` along the diagonal of an `N × N` matrix
/// (`N / B` copies; the callers use `N` a multiple of `B`).
#[inline]
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
/// `A P_ij Aᵀ`, computed by `blk` (the model's closed form, or the two products), plus the
/// per-axis `noise` on the diagonal blocks when given (`F P Fᵀ + Q`). Only the
/// blocks on and below the diagonal are computed; diagonal blocks are mirrored from their
/// lower triangle and the upper blocks are the transposes of the lower ones, so the result
/// is exactly symmetric. Components past the last whole block (none for the models here)
/// keep `F = I`.
#[inline]
pub(crate) fn block_congruence_with<const N: usize, const B: usize>(
    p: &Matrix<N, N>,
    blk: impl Fn(&Matrix<B, B>) -> Matrix<B, B>,
    noise: Option<&Matrix<B, B>>,
) -> Matrix<N, N> {
    // Column-major stack arrays: `p[c][r]` is entry (r, c).
    let src = &p.data.0;
    let mut out = *p;
    let blocks = N / B;
    for j in 0..blocks {
        for i in j..blocks {
            // Block (i, j): rows i·B.., columns j·B...
            let m = Matrix::<B, B>::from_fn(|r, c| src[j * B + c][i * B + r]);
            let mut r = blk(&m);
            if i == j {
                if let Some(q) = noise {
                    r += q;
                }
                argus_core_math::kernels::mirror_lower(&mut r);
            }
            let o = &mut out.data.0;
            for c in 0..B {
                for rr in 0..B {
                    o[j * B + c][i * B + rr] = r[(rr, c)];
                    o[i * B + rr][j * B + c] = r[(rr, c)];
                }
            }
        }
    }
    out
}

/// `A M Aᵀ` by two products (a block of [`block_congruence_with`] for a general `A`).
#[inline]
pub(crate) fn block_product<const B: usize>(a: &Matrix<B, B>, m: &Matrix<B, B>) -> Matrix<B, B> {
    use argus_core_math::kernels::{mul, mul_transpose};
    mul_transpose(&mul(a, m), a)
}

macro_rules! impl_block_model {
    ($name:ident, $n:literal, $b:literal) => {
        impl $crate::MotionModel<$n> for $name {
            #[inline]
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
                $crate::block::block_congruence_with::<$n, $b>(
                    p,
                    |m| Self::axis_congruence(dt, m),
                    None,
                )
            }

            #[inline]
            fn predict_moments(
                &self,
                x: &argus_core_math::Vector<$n>,
                p: &argus_core_math::Matrix<$n, $n>,
                dt: f64,
            ) -> (argus_core_math::Vector<$n>, argus_core_math::Matrix<$n, $n>) {
                let q = self.axis_noise(dt);
                (
                    $crate::MotionModel::<$n>::propagate(self, x, dt),
                    $crate::block::block_congruence_with::<$n, $b>(
                        p,
                        |m| Self::axis_congruence(dt, m),
                        Some(&q),
                    ),
                )
            }

            fn jacobian(
                &self,
                _x: &argus_core_math::Vector<$n>,
                dt: f64,
            ) -> argus_core_math::Matrix<$n, $n> {
                $crate::LinearMotionModel::<$n>::transition(self, dt)
            }

            #[inline]
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

    fn check_structured<const N: usize, M: crate::LinearMotionModel<N>>(
        model: &M,
        dt: f64,
        seed: &[f64],
    ) {
        let g = Matrix::<N, N>::from_fn(|i, j| seed[(i * N + j) % seed.len()] + (i as f64));
        let p = g * g.transpose() + Matrix::<N, N>::identity();
        let x = argus_core_math::Vector::<N>::from_fn(|i, _| seed[i % seed.len()]);
        let f = model.transition(dt);
        let full = f * p * f.transpose();
        let fast = model.propagate_covariance(&x, &p, dt);
        // Tolerance: the same sums in another order, relative round-off of the products.
        assert!((fast - full).amax() <= 1e-12 * full.amax());
        assert_eq!(fast, fast.transpose());
        assert!((model.propagate(&x, dt) - f * x).amax() <= 1e-12 * (f * x).amax());
        let q = model.process_noise(&x, dt);
        let (mean, moments) = model.predict_moments(&x, &p, dt);
        assert!((moments - (full + q)).amax() <= 1e-12 * (full + q).amax());
        assert_eq!(moments, moments.transpose());
        assert_eq!(mean, model.propagate(&x, dt));
    }

    proptest::proptest! {
        #[test]
        fn structured_products_equal_full_products(
            dt in 0.01f64..20.0,
            seed in proptest::collection::vec(-3.0f64..3.0, 7),
        ) {
            // The CV models' closed-form blocks and the CA models' block products against
            // the literal F P Fᵀ and F x.
            check_structured(&crate::Cv1D::discrete(0.5).unwrap(), dt, &seed);
            check_structured(&crate::Cv2D::discrete(0.5).unwrap(), dt, &seed);
            check_structured(&crate::Cv3D::discrete(0.5).unwrap(), dt, &seed);
            check_structured(&crate::Ca1D::discrete(0.5).unwrap(), dt, &seed);
            check_structured(&crate::Ca2D::discrete(0.5).unwrap(), dt, &seed);
            check_structured(&crate::Ca3D::discrete(0.5).unwrap(), dt, &seed);
        }
    }
}

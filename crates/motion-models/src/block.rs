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
macro_rules! impl_block_model {
    ($name:ident, $n:literal, $b:literal) => {
        impl $crate::MotionModel<$n> for $name {
            fn propagate(
                &self,
                x: &argus_core_math::Vector<$n>,
                dt: f64,
            ) -> argus_core_math::Vector<$n> {
                $crate::LinearMotionModel::<$n>::transition(self, dt) * x
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
}

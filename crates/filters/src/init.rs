//! Two-point-differencing track initiation for constant-velocity states.

use argus_core_math::{Gaussian, Matrix, SpdFactor, Vector, check_finite_vector};

use crate::linearized::checked_gaussian;
use crate::{FilterError, check_dt};

/// Two-point differencing in `D` axes into the interleaved state of size `N = 2D`.
/// Only instantiated with `(1, 2)`, `(2, 4)`, `(3, 6)`, so every index is in range.
#[allow(non_snake_case)]
fn two_point<const D: usize, const N: usize>(
    z1: &Vector<D>,
    R1: &Matrix<D, D>,
    z2: &Vector<D>,
    R2: &Matrix<D, D>,
    dt: f64,
) -> Result<Gaussian<N>, FilterError> {
    check_dt(dt)?;
    check_finite_vector(z1, "first plot")?;
    check_finite_vector(z2, "second plot")?;
    SpdFactor::new(R1, "first plot covariance")?;
    SpdFactor::new(R2, "second plot covariance")?;
    let mut mean = Vector::<N>::zeros();
    let mut cov = Matrix::<N, N>::zeros();
    for a in 0..D {
        mean[2 * a] = z2[a];
        mean[2 * a + 1] = (z2[a] - z1[a]) / dt;
        for b in 0..D {
            cov[(2 * a, 2 * b)] = R2[(a, b)];
            cov[(2 * a, 2 * b + 1)] = R2[(a, b)] / dt;
            cov[(2 * a + 1, 2 * b)] = R2[(a, b)] / dt;
            cov[(2 * a + 1, 2 * b + 1)] = (R1[(a, b)] + R2[(a, b)]) / (dt * dt);
        }
    }
    checked_gaussian(mean, cov, "initial mean", "initial covariance")
}

/// Two-point differencing for a 1-D constant-velocity state `[x, vx]` at the time
/// of the second plot: `x = z₂`, `v = (z₂ − z₁)/T`, covariance
/// `[[R₂, R₂/T], [R₂/T, (R₁ + R₂)/T²]]` (`[[R, R/T], [R/T, 2R/T²]]` for equal noise).
///
/// # References
/// Bar-Shalom, Li & Kirubarajan (2001) §5.5.3 (two-point differencing); seed 000
/// (two-point initialisation); seed 004 eq (10).
///
/// # Errors
/// [`FilterError::InvalidInterval`] when `dt` (time from the first to the second
/// plot) is not finite and positive; [`FilterError::Math`] for a non-finite plot or a
/// covariance that is non-finite, asymmetric or not positive definite.
pub fn two_point_cv1(
    z1: f64,
    r1: f64,
    z2: f64,
    r2: f64,
    dt: f64,
) -> Result<Gaussian<2>, FilterError> {
    two_point::<1, 2>(
        &Vector::<1>::new(z1),
        &Matrix::<1, 1>::new(r1),
        &Vector::<1>::new(z2),
        &Matrix::<1, 1>::new(r2),
        dt,
    )
}

/// Two-point differencing for a 2-D constant-velocity state `[x, vx, y, vy]` from
/// two Cartesian position plots `z₁`, `z₂` (taken `dt` apart) with covariances
/// `R₁`, `R₂` (full 2×2, e.g. of converted polar plots). Per axis pair `(a, b)`:
/// `P[pₐ,p_b] = R₂[a,b]`, `P[pₐ,v_b] = R₂[a,b]/T`, `P[vₐ,v_b] = (R₁ + R₂)[a,b]/T²`.
///
/// # References
/// Bar-Shalom, Li & Kirubarajan (2001) §5.5.3; seed 000; seed 004 eq (10).
///
/// # Errors
/// As [`two_point_cv1`].
#[allow(non_snake_case)]
pub fn two_point_cv2(
    z1: &Vector<2>,
    R1: &Matrix<2, 2>,
    z2: &Vector<2>,
    R2: &Matrix<2, 2>,
    dt: f64,
) -> Result<Gaussian<4>, FilterError> {
    two_point::<2, 4>(z1, R1, z2, R2, dt)
}

/// Two-point differencing for a 3-D constant-velocity state `[x, vx, y, vy, z, vz]`
/// (see [`two_point_cv2`]).
///
/// # References
/// Bar-Shalom, Li & Kirubarajan (2001) §5.5.3.
///
/// # Errors
/// As [`two_point_cv1`].
#[allow(non_snake_case)]
pub fn two_point_cv3(
    z1: &Vector<3>,
    R1: &Matrix<3, 3>,
    z2: &Vector<3>,
    R2: &Matrix<3, 3>,
    dt: f64,
) -> Result<Gaussian<6>, FilterError> {
    two_point::<3, 6>(z1, R1, z2, R2, dt)
}

#[cfg(test)]
mod tests {
    use super::*;
    use argus_core_math::MathError;

    #[test]
    fn one_dimensional_textbook_form() {
        // Bar-Shalom et al. (2001) §5.5.3: [[R, R/T], [R/T, 2R/T²]] for equal R.
        let (r, t) = (9.0, 2.0);
        let g = two_point_cv1(10.0, r, 16.0, r, t).unwrap();
        assert!((g.mean() - Vector::<2>::new(16.0, 3.0)).amax() < 1e-15);
        let p = Matrix::<2, 2>::new(r, r / t, r / t, 2.0 * r / (t * t));
        assert!((g.cov() - p).amax() < 1e-15);
    }

    #[test]
    fn matches_the_linear_map_of_both_plots() {
        // x = A [z₁; z₂] with A = [[0, I], [−I/T, I/T]] per axis, so
        // P = A diag(R₁, R₂) Aᵀ — computed here in the axis-major layout, then interleaved.
        let t = 0.5;
        let z1 = Vector::<3>::new(1.0, 2.0, 3.0);
        let z2 = Vector::<3>::new(2.0, 1.0, 4.0);
        let r1 = Matrix::<3, 3>::new(4.0, 1.0, 0.5, 1.0, 3.0, 0.2, 0.5, 0.2, 2.0);
        let r2 = Matrix::<3, 3>::new(5.0, -1.0, 0.0, -1.0, 6.0, 0.3, 0.0, 0.3, 1.0);
        let g = two_point_cv3(&z1, &r1, &z2, &r2, t).unwrap();
        let mut a = nalgebra::SMatrix::<f64, 6, 6>::zeros();
        let mut big_r = nalgebra::SMatrix::<f64, 6, 6>::zeros();
        for i in 0..3 {
            a[(2 * i, 3 + i)] = 1.0;
            a[(2 * i + 1, i)] = -1.0 / t;
            a[(2 * i + 1, 3 + i)] = 1.0 / t;
        }
        big_r.fixed_view_mut::<3, 3>(0, 0).copy_from(&r1);
        big_r.fixed_view_mut::<3, 3>(3, 3).copy_from(&r2);
        let mut zz = nalgebra::SVector::<f64, 6>::zeros();
        zz.fixed_rows_mut::<3>(0).copy_from(&z1);
        zz.fixed_rows_mut::<3>(3).copy_from(&z2);
        assert!((g.mean() - a * zz).amax() < 1e-14);
        assert!((g.cov() - a * big_r * a.transpose()).amax() < 1e-12);
    }

    #[test]
    fn two_dimensional_layout() {
        let r = Matrix::<2, 2>::new(100.0, 20.0, 20.0, 50.0);
        let g = two_point_cv2(
            &Vector::<2>::new(0.0, 0.0),
            &r,
            &Vector::<2>::new(50.0, -10.0),
            &r,
            5.0,
        )
        .unwrap();
        assert!((g.mean() - Vector::<4>::new(50.0, 10.0, -10.0, -2.0)).amax() < 1e-14);
        // Cross-axis terms: P[x, vy] = R₂[x, y]/T = 4, P[vx, vy] = 2·20/25 = 1.6.
        assert!((g.cov()[(0, 3)] - 4.0).abs() < 1e-14);
        assert!((g.cov()[(1, 3)] - 1.6).abs() < 1e-14);
    }

    #[test]
    fn rejects_bad_inputs() {
        let r = Matrix::<2, 2>::identity();
        let z = Vector::<2>::zeros();
        for dt in [0.0, -1.0, f64::NAN] {
            assert!(matches!(
                two_point_cv2(&z, &r, &z, &r, dt),
                Err(FilterError::InvalidInterval { .. })
            ));
        }
        assert_eq!(
            two_point_cv2(&Vector::<2>::new(f64::NAN, 0.0), &r, &z, &r, 1.0).unwrap_err(),
            FilterError::Math(MathError::NonFinite { what: "first plot" })
        );
        assert_eq!(
            two_point_cv1(0.0, 1.0, f64::INFINITY, 1.0, 1.0).unwrap_err(),
            FilterError::Math(MathError::NonFinite {
                what: "second plot"
            })
        );
        assert_eq!(
            two_point_cv1(0.0, -1.0, 1.0, 1.0, 1.0).unwrap_err(),
            FilterError::Math(MathError::NotPositiveDefinite {
                what: "first plot covariance"
            })
        );
        let asym = Matrix::<2, 2>::new(1.0, 0.5, 0.0, 1.0);
        assert!(matches!(
            two_point_cv2(&z, &r, &z, &asym, 1.0),
            Err(FilterError::Math(MathError::NotSymmetric {
                what: "second plot covariance",
                ..
            }))
        ));
        let nan3 = Matrix::<3, 3>::identity() * f64::NAN;
        let z3 = Vector::<3>::zeros();
        assert!(matches!(
            two_point_cv3(&z3, &nan3, &z3, &Matrix::<3, 3>::identity(), 1.0),
            Err(FilterError::Math(MathError::NonFinite { .. }))
        ));
    }
}

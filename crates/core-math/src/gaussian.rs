//! A validated Gaussian density with stack-allocated mean and covariance.

use crate::linalg::{
    SYMMETRY_TOL, all_finite, asymmetry, check_finite_matrix, check_finite_vector,
    is_positive_definite, symmetrize,
};
use crate::{MathError, Matrix, SpdFactor, Vector};

/// A Gaussian `N(mean, cov)` in `N` dimensions.
///
/// The fields are private: every `Gaussian` was checked on construction to have
/// a finite mean and a finite, symmetric, positive-definite covariance (stored
/// exactly symmetric). Filters take one in and hand a new one out.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gaussian<const N: usize> {
    mean: Vector<N>,
    cov: Matrix<N, N>,
}

impl<const N: usize> Gaussian<N> {
    /// Builds a Gaussian, checking the mean and covariance.
    ///
    /// # Errors
    /// [`MathError::NonFinite`] for a NaN or infinite entry, [`MathError::NotSymmetric`]
    /// when `cov` is asymmetric beyond a relative 1e-9, [`MathError::NotPositiveDefinite`]
    /// when its Cholesky factorisation fails.
    #[inline]
    pub fn new(mean: Vector<N>, cov: Matrix<N, N>) -> Result<Self, MathError> {
        check_finite_vector(&mean, "mean")?;
        check_finite_matrix(&cov, "covariance")?;
        let asym = asymmetry(&cov);
        if asym > SYMMETRY_TOL {
            return Err(MathError::NotSymmetric {
                what: "covariance",
                asymmetry: asym,
            });
        }
        let cov = symmetrize(&cov);
        if !is_positive_definite(&cov) {
            return Err(MathError::NotPositiveDefinite { what: "covariance" });
        }
        Ok(Self { mean, cov })
    }

    /// Builds a Gaussian from a covariance that may carry round-off asymmetry
    /// (it is symmetrised first), as a filter's output does.
    ///
    /// # Errors
    /// [`MathError::NonFinite`] or [`MathError::NotPositiveDefinite`].
    #[inline]
    pub fn from_symmetrized(mean: Vector<N>, cov: &Matrix<N, N>) -> Result<Self, MathError> {
        check_finite_vector(&mean, "mean")?;
        let cov = symmetrize(cov);
        // The LDLᵀ pivot test fails on non-finite entries too; only then is the cause named.
        if !is_positive_definite(&cov) {
            return Err(if all_finite(cov.as_slice()) {
                MathError::NotPositiveDefinite { what: "covariance" }
            } else {
                MathError::NonFinite { what: "covariance" }
            });
        }
        Ok(Self { mean, cov })
    }

    /// Builds a Gaussian whose covariance is the lower triangle of `cov`, mirrored (the
    /// strict upper triangle is not read): for a filter's output, which is symmetric by
    /// construction and computed as its lower triangle (or mirrored already), this skips
    /// the averaging of [`Gaussian::from_symmetrized`].
    ///
    /// # Errors
    /// [`MathError::NonFinite`] or [`MathError::NotPositiveDefinite`].
    #[inline(always)]
    pub fn from_lower_triangle(mean: Vector<N>, mut cov: Matrix<N, N>) -> Result<Self, MathError> {
        check_finite_vector(&mean, "mean")?;
        crate::kernels::mirror_lower(&mut cov);
        // The LDLᵀ pivot test reads the lower triangle and fails on non-finite entries too;
        // only then is the cause named.
        if !is_positive_definite(&cov) {
            return Err(if all_finite(cov.as_slice()) {
                MathError::NotPositiveDefinite { what: "covariance" }
            } else {
                MathError::NonFinite { what: "covariance" }
            });
        }
        Ok(Self { mean, cov })
    }

    /// The mean.
    #[must_use]
    pub fn mean(&self) -> &Vector<N> {
        &self.mean
    }

    /// The covariance.
    #[must_use]
    pub fn cov(&self) -> &Matrix<N, N> {
        &self.cov
    }

    /// Splits into `(mean, covariance)`.
    #[must_use]
    pub fn into_parts(self) -> (Vector<N>, Matrix<N, N>) {
        (self.mean, self.cov)
    }

    /// The Cholesky factor of the covariance.
    ///
    /// # Errors
    /// Never for a constructed `Gaussian` in exact arithmetic; kept fallible rather than panicking.
    pub fn factor(&self) -> Result<SpdFactor<N>, MathError> {
        SpdFactor::new_symmetric(&self.cov, "covariance")
    }

    /// Squared Mahalanobis distance `(x − μ)ᵀ P⁻¹ (x − μ)`; for the true state
    /// this is the NEES. Returns `+∞` if the covariance cannot be factored.
    #[must_use]
    pub fn mahalanobis_sq(&self, x: &Vector<N>) -> f64 {
        self.factor()
            .map_or(f64::INFINITY, |f| f.mahalanobis_sq(&(x - self.mean)))
    }

    /// Log-density at `x`. Returns `−∞` if the covariance cannot be factored.
    #[must_use]
    pub fn log_pdf(&self, x: &Vector<N>) -> f64 {
        self.factor()
            .map_or(f64::NEG_INFINITY, |f| f.log_density(&(x - self.mean)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constructor_rejects_bad_input() {
        let m = Vector::<2>::new(0.0, 0.0);
        assert!(matches!(
            Gaussian::new(Vector::<2>::new(f64::NAN, 0.0), Matrix::<2, 2>::identity()),
            Err(MathError::NonFinite { what: "mean" })
        ));
        assert!(matches!(
            Gaussian::new(m, Matrix::<2, 2>::new(1.0, f64::INFINITY, 0.0, 1.0)),
            Err(MathError::NonFinite { what: "covariance" })
        ));
        assert!(matches!(
            Gaussian::new(m, Matrix::<2, 2>::new(1.0, 0.3, 0.0, 1.0)),
            Err(MathError::NotSymmetric { .. })
        ));
        assert!(matches!(
            Gaussian::new(m, Matrix::<2, 2>::new(-1.0, 0.0, 0.0, 1.0)),
            Err(MathError::NotPositiveDefinite { .. })
        ));
    }

    #[test]
    fn stores_exactly_symmetric_covariance() {
        let c = Matrix::<2, 2>::new(2.0, 0.5 + 1e-12, 0.5, 1.0);
        let g = Gaussian::new(Vector::<2>::zeros(), c).unwrap();
        assert_eq!(g.cov()[(0, 1)].to_bits(), g.cov()[(1, 0)].to_bits());
    }

    #[test]
    fn lower_triangle_constructor_mirrors_and_checks() {
        // The strict upper triangle is ignored (here a wrong 9.0); the result is symmetric.
        let c = Matrix::<2, 2>::new(2.0, 9.0, 0.5, 1.0);
        let g = Gaussian::from_lower_triangle(Vector::<2>::zeros(), c).unwrap();
        assert_eq!(*g.cov(), Matrix::<2, 2>::new(2.0, 0.5, 0.5, 1.0));
        // det = 1 − 4 < 0 in the lower triangle: indefinite.
        let bad = Matrix::<2, 2>::new(1.0, 0.0, 2.0, 1.0);
        assert!(matches!(
            Gaussian::from_lower_triangle(Vector::<2>::zeros(), bad),
            Err(MathError::NotPositiveDefinite { .. })
        ));
        let nan = Matrix::<2, 2>::new(1.0, 0.0, f64::NAN, 1.0);
        assert!(matches!(
            Gaussian::from_lower_triangle(Vector::<2>::zeros(), nan),
            Err(MathError::NonFinite { .. })
        ));
        assert!(matches!(
            Gaussian::from_lower_triangle(Vector::<2>::new(f64::NAN, 0.0), c),
            Err(MathError::NonFinite { what: "mean" })
        ));
    }

    #[test]
    fn log_pdf_of_standard_normal_at_mean() {
        // ln N(0; 0, I₂) = −ln 2π.
        let g = Gaussian::new(Vector::<2>::zeros(), Matrix::<2, 2>::identity()).unwrap();
        assert!(
            (g.log_pdf(&Vector::<2>::zeros()) + (2.0 * std::f64::consts::PI).ln()).abs() < 1e-14
        );
    }
}

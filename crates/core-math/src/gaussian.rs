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
        // The average is exactly symmetric; its lower triangle is the whole of it.
        Self::from_lower_triangle(mean, symmetrize(cov))
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
        // The definiteness test reads the lower triangle and fails on non-finite entries
        // too; only then is the cause named.
        if !is_positive_definite(&cov) {
            return Err(if all_finite(cov.as_slice()) {
                MathError::NotPositiveDefinite { what: "covariance" }
            } else {
                MathError::NonFinite { what: "covariance" }
            });
        }
        Ok(Self { mean, cov })
    }

    /// The moment-matched Gaussian of the mixture `Σ wₘ N(xₘ, Pₘ)`:
    /// `x = Σ wₘ xₘ`, `P = Σ wₘ [Pₘ + (xₘ − x)(xₘ − x)ᵀ]` (the spread-of-means term; Bar-Shalom,
    /// Li & Kirubarajan 2001, §1.4.16). Parts with a weight that is not positive are skipped.
    ///
    /// `P` is a positive combination of positive-definite matrices (every part is a
    /// constructed `Gaussian`) plus positive semi-definite spread terms, so it is positive
    /// definite by construction: only finiteness is checked (of the weights and the result),
    /// not definiteness. The per-entry arithmetic is `Σ wₘ (Pₘ + dₘ dₘᵀ)` with whole
    /// columns, so the result is exactly symmetric.
    ///
    /// # Errors
    /// [`MathError::OutOfDomain`] when no weight is positive or a weight is not finite;
    /// [`MathError::NonFinite`] when the result is not finite (an overflow).
    #[inline]
    pub fn mixture<const K: usize>(
        weights: &[f64; K],
        parts: &[Self; K],
    ) -> Result<Self, MathError> {
        if !all_finite(weights) || !weights.iter().any(|&w| w > 0.0) {
            return Err(MathError::OutOfDomain {
                what: "mixture weights",
                value: weights.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                domain: "finite, at least one positive",
            });
        }
        let mut mean = [0.0; N];
        for (&w, g) in weights.iter().zip(parts) {
            if w > 0.0 {
                for (m, x) in mean.iter_mut().zip(g.mean.iter()) {
                    *m += x * w;
                }
            }
        }
        let mut cov = Matrix::<N, N>::zeros();
        let c = &mut cov.data.0;
        for (&w, g) in weights.iter().zip(parts) {
            if w > 0.0 {
                let mut d = [0.0; N];
                for ((d, x), m) in d.iter_mut().zip(g.mean.iter()).zip(&mean) {
                    *d = x - m;
                }
                // Column-major: p[b][a] is entry (a, b); d[a] d[b] = d[b] d[a], so the
                // entries above the diagonal equal their mirrors.
                for ((cb, pb), db) in c.iter_mut().zip(&g.cov.data.0).zip(&d) {
                    for ((cab, pab), da) in cb.iter_mut().zip(pb).zip(&d) {
                        *cab += (pab + da * db) * w;
                    }
                }
            }
        }
        let mean = Vector::<N>::from(mean);
        check_finite_vector(&mean, "mixture mean")?;
        check_finite_matrix(&cov, "mixture covariance")?;
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

    proptest::proptest! {
        #[test]
        fn mixture_moments_match_their_definition(
            seed in proptest::array::uniform12(-3.0f64..3.0),
            w in proptest::array::uniform3(0.0f64..1.0),
        ) {
            // Three parts with random means and SPD covariances; against the nalgebra
            // expression of the definition. The result must also pass the full PD test.
            let parts: [Gaussian<2>; 3] = std::array::from_fn(|m| {
                let a = Matrix::<2, 2>::new(seed[4 * m], seed[4 * m + 1], seed[4 * m + 2], seed[4 * m + 3]);
                Gaussian::new(
                    Vector::<2>::new(seed[m], -seed[m + 4]),
                    symmetrize(&(a * a.transpose() + Matrix::<2, 2>::identity() * 0.1)),
                )
                .unwrap()
            });
            proptest::prop_assume!(w.iter().sum::<f64>() > 1e-3);
            let total: f64 = w.iter().sum();
            let w = w.map(|x| x / total);
            let g = Gaussian::mixture(&w, &parts).unwrap();
            let mean: Vector<2> = parts.iter().zip(&w).map(|(p, &wm)| p.mean() * wm).sum();
            let cov: Matrix<2, 2> = parts
                .iter()
                .zip(&w)
                .map(|(p, &wm)| (p.cov() + (p.mean() - mean) * (p.mean() - mean).transpose()) * wm)
                .sum();
            proptest::prop_assert!((g.mean() - mean).amax() < 1e-12);
            proptest::prop_assert!((g.cov() - cov).amax() < 1e-12 * (1.0 + cov.amax()));
            proptest::prop_assert_eq!(*g.cov(), g.cov().transpose());
            proptest::prop_assert!(is_positive_definite(g.cov()));
        }
    }

    #[test]
    fn mixture_rejects_bad_weights() {
        let g = Gaussian::new(Vector::<2>::zeros(), Matrix::<2, 2>::identity()).unwrap();
        assert!(Gaussian::mixture(&[0.0, 0.0], &[g, g]).is_err());
        assert!(Gaussian::mixture(&[f64::NAN, 1.0], &[g, g]).is_err());
        let one = Gaussian::mixture(&[0.0, 1.0], &[g, g]).unwrap();
        assert_eq!(one, g);
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

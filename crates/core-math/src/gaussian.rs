//! A validated Gaussian density with stack-allocated mean and covariance.

use crate::linalg::{
    SYMMETRY_TOL, all_finite, asymmetry, bareiss_minors_positive, check_finite_matrix,
    check_finite_vector, is_positive_definite, symmetrize,
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
        check_lower_triangle(&mean, &cov)?;
        crate::kernels::mirror_lower(&mut cov);
        Ok(Self { mean, cov })
    }

    /// [`Gaussian::from_lower_triangle`] into `self`, which is left unchanged on an error:
    /// for a filter stage that replaces its estimate in place (no `Result` holding a whole
    /// Gaussian is built and copied out).
    ///
    /// # Errors
    /// As [`Gaussian::from_lower_triangle`].
    #[inline(always)]
    pub fn assign_lower_triangle(
        &mut self,
        mean: Vector<N>,
        cov: Matrix<N, N>,
    ) -> Result<(), MathError> {
        check_lower_triangle(&mean, &cov)?;
        // Mirrored straight into the estimate (no mirrored copy to be copied in).
        self.mean = mean;
        crate::kernels::mirror_lower_into(&cov, &mut self.cov);
        Ok(())
    }

    /// [`Gaussian::mixture`] into `self`, which is left unchanged on an error.
    ///
    /// # Errors
    /// As [`Gaussian::mixture`].
    #[inline(always)]
    pub fn assign_mixture<const K: usize>(
        &mut self,
        weights: &[f64; K],
        parts: &[Self; K],
    ) -> Result<(), MathError> {
        let (mean, cov) = mixture_moments(weights, parts)?;
        self.mean = mean;
        self.cov = cov;
        Ok(())
    }

    /// The moment-matched Gaussian of the mixture `Σ wₘ N(xₘ, Pₘ)`:
    /// `x = Σ wₘ xₘ`, `P = Σ wₘ [Pₘ + (xₘ − x)(xₘ − x)ᵀ]` (the spread-of-means term; Bar-Shalom,
    /// Li & Kirubarajan 2001, §1.4.16). Parts with a weight that is not positive are skipped.
    ///
    /// `P` is a positive combination of positive-definite matrices (every part is a
    /// constructed `Gaussian`) plus positive semi-definite spread terms, so it is positive
    /// definite by construction: only finiteness is checked (of the weights and the result),
    /// not definiteness. The lower triangle is computed entry by entry as
    /// `Σ wₘ (Pₘ + dₘ dₘᵀ)` and mirrored, so the result is exactly symmetric.
    ///
    /// # Errors
    /// [`MathError::OutOfDomain`] when no weight is positive or a weight is not finite;
    /// [`MathError::NonFinite`] when the result is not finite (an overflow).
    #[inline(always)]
    pub fn mixture<const K: usize>(
        weights: &[f64; K],
        parts: &[Self; K],
    ) -> Result<Self, MathError> {
        let (mean, cov) = mixture_moments(weights, parts)?;
        Ok(Self { mean, cov })
    }

    /// [`Gaussian::mixture`] of a number of parts known at run time (e.g. a PDA update's
    /// prediction and per-plot posteriors), with the same arithmetic.
    ///
    /// # Errors
    /// As [`Gaussian::mixture`], and [`MathError::OutOfDomain`] when `weights` and `parts`
    /// differ in length.
    pub fn mixture_of(weights: &[f64], parts: &[Self]) -> Result<Self, MathError> {
        if weights.len() != parts.len() {
            return Err(MathError::OutOfDomain {
                what: "mixture weights",
                #[allow(clippy::cast_precision_loss)]
                value: weights.len() as f64,
                domain: "one per part",
            });
        }
        let (mean, cov) = mixture_moments(weights, parts)?;
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

/// The checks of [`Gaussian::from_lower_triangle`] on `mean` and the lower triangle of
/// `cov` (the upper one is not read). The fast definiteness test (the minors) fails on
/// non-finite entries too; the callers mirror afterwards. (Mirrored before the test, the
/// upper triangle's entries were stored one by one and the copy into the result read them
/// back in pairs: a store-forwarding stall on every filter step.)
#[inline(always)]
fn check_lower_triangle<const N: usize>(
    mean: &Vector<N>,
    cov: &Matrix<N, N>,
) -> Result<(), MathError> {
    check_finite_vector(mean, "mean")?;
    if bareiss_minors_positive(cov) {
        Ok(())
    } else {
        check_lower_triangle_exact(cov)
    }
}

/// The rare path of [`check_lower_triangle`]: the minors were not all positive finite
/// numbers (an indefinite or non-finite matrix, or minors out of `f64`'s range); the exact
/// test decides and names the cause.
#[cold]
#[inline(never)]
fn check_lower_triangle_exact<const N: usize>(cov: &Matrix<N, N>) -> Result<(), MathError> {
    let mut full = *cov;
    crate::kernels::mirror_lower(&mut full);
    if is_positive_definite(&full) {
        Ok(())
    } else if all_finite(full.as_slice()) {
        Err(MathError::NotPositiveDefinite { what: "covariance" })
    } else {
        Err(MathError::NonFinite { what: "covariance" })
    }
}

/// The moments of [`Gaussian::mixture`] and [`Gaussian::mixture_of`] (one weight per part;
/// inlined, so a fixed-size caller's loops have constant bounds).
#[inline(always)]
fn mixture_moments<const N: usize>(
    weights: &[f64],
    parts: &[Gaussian<N>],
) -> Result<(Vector<N>, Matrix<N, N>), MathError> {
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
            // Column-major: p[b][a] is entry (a, b). The lower triangle (a ≥ b) only:
            // every part is symmetric and d[a] d[b] = d[b] d[a], so the entries above
            // the diagonal are the mirrors.
            let p = &g.cov.data.0;
            for b in 0..N {
                for a in b..N {
                    c[b][a] += (p[b][a] + d[a] * d[b]) * w;
                }
            }
        }
    }
    let mean = Vector::<N>::from(mean);
    check_finite_vector(&mean, "mixture mean")?;
    // The upper triangle is still zero: this checks the lower one. Mirrored last.
    check_finite_matrix(&cov, "mixture covariance")?;
    crate::kernels::mirror_lower(&mut cov);
    Ok((mean, cov))
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
    fn mixture_of_equals_mixture_bit_for_bit_and_checks_lengths() {
        // Same arithmetic through the slice entry: exact equality.
        let a = Gaussian::new(
            Vector::<2>::new(1.0, -2.0),
            Matrix::<2, 2>::new(2.0, 0.3, 0.3, 1.0),
        )
        .unwrap();
        let b = Gaussian::new(
            Vector::<2>::new(-0.5, 4.0),
            Matrix::<2, 2>::new(1.0, -0.2, -0.2, 3.0),
        )
        .unwrap();
        let w = [0.3, 0.7];
        assert_eq!(
            Gaussian::mixture_of(&w, &[a, b]).unwrap(),
            Gaussian::mixture(&w, &[a, b]).unwrap()
        );
        assert!(Gaussian::mixture_of(&w, &[a]).is_err());
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
    fn in_place_assignments_equal_the_constructors_and_keep_the_estimate_on_errors() {
        // `assign_lower_triangle` and `assign_mixture` write what `from_lower_triangle` and
        // `mixture` return, bit for bit (same arithmetic), and leave the target untouched
        // when they fail.
        let start = Gaussian::new(
            Vector::<3>::new(1.0, -2.0, 0.5),
            Matrix::<3, 3>::new(4.0, 1.0, 0.5, 1.0, 3.0, -0.2, 0.5, -0.2, 2.0),
        )
        .unwrap();
        // Lower triangle of an SPD matrix, with a wrong upper triangle that must be ignored.
        let lower = Matrix::<3, 3>::new(5.0, 9.0, 9.0, 0.3, 2.0, 9.0, -0.4, 0.1, 1.5);
        let mean = Vector::<3>::new(0.1, 0.2, 0.3);
        let mut g = start;
        g.assign_lower_triangle(mean, lower).unwrap();
        assert_eq!(g, Gaussian::from_lower_triangle(mean, lower).unwrap());
        assert_eq!(*g.cov(), g.cov().transpose());
        let mut h = start;
        let indefinite = Matrix::<3, 3>::new(1.0, 0.0, 0.0, 2.0, 1.0, 0.0, 0.0, 0.0, 1.0);
        assert!(matches!(
            h.assign_lower_triangle(mean, indefinite),
            Err(MathError::NotPositiveDefinite { .. })
        ));
        let mut nan = lower;
        nan[(2, 1)] = f64::NAN;
        assert!(matches!(
            h.assign_lower_triangle(mean, nan),
            Err(MathError::NonFinite { .. })
        ));
        assert!(matches!(
            h.assign_lower_triangle(Vector::<3>::new(f64::INFINITY, 0.0, 0.0), lower),
            Err(MathError::NonFinite { what: "mean" })
        ));
        assert_eq!(h, start);

        let parts = [
            start,
            g,
            Gaussian::from_lower_triangle(-mean, lower * 2.0).unwrap(),
        ];
        let w = [0.5, 0.3, 0.2];
        let mut m = start;
        m.assign_mixture(&w, &parts).unwrap();
        assert_eq!(m, Gaussian::mixture(&w, &parts).unwrap());
        let mut k = start;
        assert!(k.assign_mixture(&[0.0, 0.0, 0.0], &parts).is_err());
        assert_eq!(k, start);
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

//! NEES and NIS consistency statistics with chi-square acceptance intervals.

use argus_core_math::{
    ChiSquareInterval, Gaussian, MathError, Vector, anees_interval, check_finite_vector,
};

use crate::FilterError;

/// The normalised estimation error squared `(x − x̂)ᵀ P⁻¹ (x − x̂)` of an estimate
/// against the true state; chi-square with `N` degrees of freedom for a consistent filter.
///
/// # References
/// Bar-Shalom, Li & Kirubarajan (2001) §5.4.2, eq (5.4.2-1).
///
/// # Errors
/// [`FilterError::Math`] when `truth` is not finite.
pub fn nees<const N: usize>(estimate: &Gaussian<N>, truth: &Vector<N>) -> Result<f64, FilterError> {
    check_finite_vector(truth, "true state")?;
    let f = estimate.factor()?;
    Ok(f.mahalanobis_sq(&(truth - estimate.mean())))
}

/// An average of chi-square statistics of one dimension — NEES over Monte Carlo
/// runs (ANEES) or NIS (ANIS) — with its two-sided chi-square acceptance interval.
///
/// For `n` independent samples, `n · average` is chi-square with `dim · n` degrees of
/// freedom. Samples taken at successive times of one run are correlated: the
/// interval is then only indicative.
///
/// # References
/// Bar-Shalom, Li & Kirubarajan (2001) §5.4.2 (eqs 5.4.2-2, 5.4.2-6).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChiSquareAverage {
    dim: usize,
    count: usize,
    sum: f64,
}

impl ChiSquareAverage {
    /// An empty average of `dim`-degree-of-freedom statistics.
    ///
    /// # Errors
    /// [`FilterError::InvalidParameter`] for `dim = 0`.
    pub fn new(dim: usize) -> Result<Self, FilterError> {
        if dim == 0 {
            return Err(FilterError::InvalidParameter {
                what: "chi-square dimension",
                value: 0.0,
                reason: "must be at least 1",
            });
        }
        Ok(Self {
            dim,
            count: 0,
            sum: 0.0,
        })
    }

    /// Adds one sample (a NEES or NIS value).
    ///
    /// # Errors
    /// [`FilterError::Math`] when `value` is not finite or is negative; the average is
    /// then unchanged.
    pub fn push(&mut self, value: f64) -> Result<(), FilterError> {
        if !value.is_finite() {
            return Err(MathError::NonFinite {
                what: "chi-square sample",
            }
            .into());
        }
        if value < 0.0 {
            return Err(MathError::OutOfDomain {
                what: "chi-square sample",
                value,
                domain: "[0, ∞)",
            }
            .into());
        }
        self.sum += value;
        self.count += 1;
        Ok(())
    }

    /// The degrees of freedom of one sample.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// The number of samples.
    #[must_use]
    pub fn count(&self) -> usize {
        self.count
    }

    /// The average, `None` before the first sample.
    #[must_use]
    pub fn mean(&self) -> Option<f64> {
        (self.count > 0).then(|| self.sum / self.count as f64)
    }

    /// The two-sided `confidence` interval of the average for the current count.
    ///
    /// # Errors
    /// [`FilterError::Math`] when `confidence ∉ (0, 1)` or there is no sample yet.
    pub fn interval(&self, confidence: f64) -> Result<ChiSquareInterval, FilterError> {
        Ok(anees_interval(self.dim, self.count, confidence)?)
    }

    /// Whether the average lies inside its `confidence` interval.
    ///
    /// # Errors
    /// As [`ChiSquareAverage::interval`].
    pub fn is_consistent(&self, confidence: f64) -> Result<bool, FilterError> {
        let iv = self.interval(confidence)?;
        Ok(self.mean().is_some_and(|m| iv.contains(m)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use argus_core_math::Matrix;

    #[test]
    fn nees_by_hand() {
        // P = diag(4, 1), error (2, 1): 2²/4 + 1²/1 = 2.
        let g = Gaussian::new(
            Vector::<2>::new(1.0, 1.0),
            Matrix::<2, 2>::from_diagonal(&Vector::<2>::new(4.0, 1.0)),
        )
        .unwrap();
        assert!((nees(&g, &Vector::<2>::new(3.0, 2.0)).unwrap() - 2.0).abs() < 1e-14);
        assert_eq!(
            nees(&g, &Vector::<2>::new(f64::NAN, 2.0)).unwrap_err(),
            FilterError::Math(MathError::NonFinite { what: "true state" })
        );
    }

    #[test]
    fn average_and_interval() {
        // Bar-Shalom et al. (2001) §5.4.2: n = 2, 50 runs, 95 %: [74.222, 129.561]/50.
        let mut s = ChiSquareAverage::new(2).unwrap();
        assert_eq!(s.mean(), None);
        assert!(s.interval(0.95).is_err());
        for k in 0..50 {
            s.push(if k % 2 == 0 { 1.5 } else { 2.5 }).unwrap();
        }
        assert_eq!(s.count(), 50);
        assert!((s.mean().unwrap() - 2.0).abs() < 1e-14);
        let iv = s.interval(0.95).unwrap();
        assert!((iv.lower - 74.222 / 50.0).abs() < 1e-4);
        assert!((iv.upper - 129.561 / 50.0).abs() < 1e-4);
        assert!(s.is_consistent(0.95).unwrap());
        assert!(s.push(f64::NAN).is_err());
        assert!(s.push(-1.0).is_err());
        assert_eq!(s.count(), 50);
        assert!(matches!(
            ChiSquareAverage::new(0),
            Err(FilterError::InvalidParameter { .. })
        ));
        assert!(s.interval(1.0).is_err());
    }
}

//! Run-time-sized algebra through [`faer`]: stacked multisensor systems and
//! batch least squares, where the size is known only at run time or is large.
//!
//! Per-track algebra stays on nalgebra's stack types; `benches/` compares the two
//! on 4×4, 8×8 and 64×64 Cholesky solves (see `docs/BENCHMARKS.md`).

use faer::linalg::solvers::{DenseSolveCore, Llt, Solve};
use faer::{Mat, MatRef, Side};

use crate::MathError;

/// The Cholesky factor of a run-time-sized symmetric positive-definite matrix.
#[derive(Debug)]
pub struct DynSpdFactor {
    llt: Llt<f64>,
    dim: usize,
}

impl DynSpdFactor {
    /// Factors the symmetric positive-definite matrix `a` (lower triangle read).
    ///
    /// # Errors
    /// [`MathError::DimensionMismatch`] when `a` is not square, [`MathError::NonFinite`],
    /// [`MathError::NotPositiveDefinite`]; each names `what`.
    pub fn new(a: MatRef<'_, f64>, what: &'static str) -> Result<Self, MathError> {
        if a.nrows() != a.ncols() {
            return Err(MathError::DimensionMismatch {
                what,
                expected: a.nrows(),
                got: a.ncols(),
            });
        }
        for j in 0..a.ncols() {
            for i in 0..a.nrows() {
                if !a[(i, j)].is_finite() {
                    return Err(MathError::NonFinite { what });
                }
            }
        }
        let llt = a
            .llt(Side::Lower)
            .map_err(|_| MathError::NotPositiveDefinite { what })?;
        Ok(Self {
            llt,
            dim: a.nrows(),
        })
    }

    /// The dimension of the factored matrix.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Solves `A X = B`.
    ///
    /// # Errors
    /// [`MathError::DimensionMismatch`] when `B` has the wrong number of rows.
    pub fn solve(&self, b: MatRef<'_, f64>) -> Result<Mat<f64>, MathError> {
        if b.nrows() != self.dim {
            return Err(MathError::DimensionMismatch {
                what: "right-hand side",
                expected: self.dim,
                got: b.nrows(),
            });
        }
        Ok(self.llt.solve(b))
    }

    /// The inverse `A⁻¹`.
    #[must_use]
    pub fn inverse(&self) -> Mat<f64> {
        self.llt.inverse()
    }

    /// `ln |A|`.
    #[must_use]
    pub fn log_det(&self) -> f64 {
        let l = self.llt.L();
        2.0 * (0..self.dim).map(|i| l[(i, i)].ln()).sum::<f64>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_and_rejects() {
        let a = Mat::<f64>::from_fn(3, 3, |i, j| if i == j { 4.0 } else { 1.0 });
        let f = DynSpdFactor::new(a.as_ref(), "A").unwrap();
        let b = Mat::<f64>::from_fn(3, 1, |i, _| i as f64 + 1.0);
        let x = f.solve(b.as_ref()).unwrap();
        let r = &a * &x - &b;
        for i in 0..3 {
            assert!(r[(i, 0)].abs() < 1e-12);
        }
        // det = (4-1)^2 (4+2) = 54 for this matrix.
        assert!((f.log_det() - 54f64.ln()).abs() < 1e-12);
        let bad = Mat::<f64>::from_fn(2, 2, |i, j| if i == j { -1.0 } else { 0.0 });
        assert!(matches!(
            DynSpdFactor::new(bad.as_ref(), "B"),
            Err(MathError::NotPositiveDefinite { .. })
        ));
        let nan = Mat::<f64>::from_fn(2, 2, |_, _| f64::NAN);
        assert!(matches!(
            DynSpdFactor::new(nan.as_ref(), "N"),
            Err(MathError::NonFinite { .. })
        ));
        assert!(f.solve(Mat::<f64>::zeros(2, 1).as_ref()).is_err());
    }
}

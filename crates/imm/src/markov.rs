//! A validated Markov mode-transition matrix and mode-probability helpers in log space.

use argus_core_math::Matrix;

use crate::ImmError;

/// Tolerance on a probability sum (rows of `Π`, initial probabilities).
pub const PROBABILITY_SUM_TOL: f64 = 1e-9;

/// A Markov mode-transition matrix `Π = [π_ij]`, `π_ij = P(mode j at k | mode i at k−1)`
/// (seed 000 eq (1), (20)). Every entry is a probability and every row sums to one.
///
/// The logarithms of the entries are stored as well: the IMM mixes in log space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MarkovMatrix<const R: usize> {
    pi: Matrix<R, R>,
    log_pi: Matrix<R, R>,
}

impl<const R: usize> MarkovMatrix<R> {
    /// Validates a transition matrix given row by row.
    ///
    /// # Errors
    /// [`ImmError::Empty`] for `R = 0`, [`ImmError::InvalidTransition`] for an entry outside
    /// `[0, 1]` or non-finite, [`ImmError::RowSum`] when a row does not sum to one within 1e-9.
    pub fn new(rows: [[f64; R]; R]) -> Result<Self, ImmError> {
        if R == 0 {
            return Err(ImmError::Empty {
                what: "Markov matrix",
            });
        }
        let mut pi = Matrix::<R, R>::zeros();
        for (i, row) in rows.iter().enumerate() {
            let mut sum = 0.0;
            for (j, &v) in row.iter().enumerate() {
                if !(v.is_finite() && (0.0..=1.0).contains(&v)) {
                    return Err(ImmError::InvalidTransition {
                        row: i,
                        col: j,
                        value: v,
                    });
                }
                pi[(i, j)] = v;
                sum += v;
            }
            if (sum - 1.0).abs() > PROBABILITY_SUM_TOL {
                return Err(ImmError::RowSum { row: i, sum });
            }
        }
        Ok(Self {
            pi,
            log_pi: pi.map(f64::ln),
        })
    }

    /// The matrix `Π`.
    #[must_use]
    pub fn matrix(&self) -> &Matrix<R, R> {
        &self.pi
    }

    /// `ln π_ij` (−∞ for a forbidden transition).
    #[must_use]
    pub fn log_matrix(&self) -> &Matrix<R, R> {
        &self.log_pi
    }
}

/// `ln Σ exp(aᵢ)`, stable for very negative entries; −∞ for an empty or all −∞ input.
#[must_use]
pub fn log_sum_exp(a: &[f64]) -> f64 {
    let max = a.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if max == f64::NEG_INFINITY || max.is_nan() {
        return max;
    }
    max + a.iter().map(|&v| (v - max).exp()).sum::<f64>().ln()
}

/// Validates probabilities and returns their logarithms.
///
/// # Errors
/// [`ImmError::InvalidProbabilities`] when an entry is negative or non-finite or the
/// sum differs from one by more than 1e-9; [`ImmError::Empty`] for `R = 0`.
pub fn log_probabilities<const R: usize>(
    p: &[f64; R],
    what: &'static str,
) -> Result<[f64; R], ImmError> {
    if R == 0 {
        return Err(ImmError::Empty { what });
    }
    let sum: f64 = p.iter().sum();
    if p.iter().any(|v| !(v.is_finite() && *v >= 0.0)) || (sum - 1.0).abs() > PROBABILITY_SUM_TOL {
        return Err(ImmError::InvalidProbabilities { what, sum });
    }
    Ok(p.map(f64::ln))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn accepts_the_paper_matrix_and_rejects_bad_ones() {
        // Seed 000 eq (20).
        let m = MarkovMatrix::new([[0.95, 0.025, 0.025], [0.05, 0.95, 0.0], [0.05, 0.0, 0.95]])
            .unwrap();
        assert!(m.log_matrix()[(1, 2)].is_infinite() && m.log_matrix()[(1, 2)] < 0.0);
        assert!(matches!(
            MarkovMatrix::new([[-0.2, 1.2], [0.5, 0.5]]),
            Err(ImmError::InvalidTransition { row: 0, col: 0, .. })
        ));
        assert!(matches!(
            MarkovMatrix::new([[0.9, 0.05], [0.5, 0.5]]),
            Err(ImmError::RowSum { row: 0, .. })
        ));
        assert!(matches!(
            MarkovMatrix::new([[f64::NAN, 1.0], [0.5, 0.5]]),
            Err(ImmError::InvalidTransition { .. })
        ));
        assert!(matches!(
            MarkovMatrix::<0>::new([]),
            Err(ImmError::Empty { .. })
        ));
    }

    #[test]
    fn log_sum_exp_survives_underflow() {
        // ln(e^-1000 + e^-1001) = -1000 + ln(1 + e^-1) exactly.
        let v = log_sum_exp(&[-1000.0, -1001.0]);
        assert!((v - (-1000.0 + (1.0 + (-1.0f64).exp()).ln())).abs() < 1e-12);
        let e = log_sum_exp(&[f64::NEG_INFINITY]);
        assert!(e.is_infinite() && e < 0.0);
        assert!(matches!(
            log_probabilities(&[0.5, 0.6], "mu"),
            Err(ImmError::InvalidProbabilities { .. })
        ));
        assert!(matches!(
            log_probabilities(&[1.5, -0.5], "mu"),
            Err(ImmError::InvalidProbabilities { .. })
        ));
    }
}

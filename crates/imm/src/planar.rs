//! The IMM of Kalman filters on planar motion models (CV or fixed-rate CT,
//! [`PlanarModel`]) built from a run-time description: a list of models and the Markov
//! matrix's rows. The mode count `R` is a compile-time size, so a caller with a run-time
//! count picks `R` with [`by_mode_count!`](crate::by_mode_count) (1 … [`MAX_PLANAR_MODES`]
//! are built); `argus track`'s single-target IMM and the Python package's IMM classes
//! build theirs here.

use argus_filters::Kf;
use argus_motion_models::PlanarModel;

use crate::{Imm, ImmError, MarkovMatrix};

/// An IMM of `R` Kalman filters on planar models over `[x, vx, y, vy]`.
pub type PlanarImm<const R: usize> = Imm<Kf<PlanarModel>, 4, R>;

/// The largest mode count [`by_mode_count!`](crate::by_mode_count) dispatches to.
pub const MAX_PLANAR_MODES: usize = 5;

/// A mode count other than `R`.
fn count_mismatch() -> ImmError {
    ImmError::Empty {
        what: "IMM modes (count mismatch)",
    }
}

/// One Kalman filter per model, `R` of them.
///
/// # Errors
/// [`ImmError::Empty`] when `models` has not `R` entries.
pub fn planar_filters<const R: usize>(
    models: &[PlanarModel],
) -> Result<[Kf<PlanarModel>; R], ImmError> {
    models
        .iter()
        .map(|m| Kf::new(*m))
        .collect::<Vec<_>>()
        .try_into()
        .map_err(|_| count_mismatch())
}

/// One value per mode (initial mode probabilities, a row of the Markov matrix), `R` of them.
///
/// # Errors
/// [`ImmError::Empty`] when `values` has not `R` entries.
pub fn per_mode<const R: usize>(values: &[f64]) -> Result<[f64; R], ImmError> {
    <[f64; R]>::try_from(values).map_err(|_| count_mismatch())
}

/// The Markov matrix of `rows` (`R` rows of `R` entries, "from" by rows).
///
/// # Errors
/// [`ImmError::Empty`] for another shape; [`MarkovMatrix::new`]'s errors.
pub fn markov_rows<const R: usize>(rows: &[Vec<f64>]) -> Result<MarkovMatrix<R>, ImmError> {
    let rows = rows
        .iter()
        .map(|r| per_mode::<R>(r))
        .collect::<Result<Vec<_>, _>>()?;
    let rows: [[f64; R]; R] = rows.try_into().map_err(|_| count_mismatch())?;
    MarkovMatrix::new(rows)
}

/// Calls `$f::<R>(args…)` for the run-time mode count `$r ∈ 1 ..= MAX_PLANAR_MODES`, and
/// `$other(count)` for any other count (the caller's error).
#[macro_export]
macro_rules! by_mode_count {
    ($r:expr, $other:expr, $f:ident, $($arg:expr),*) => {
        match $r {
            1 => $f::<1>($($arg),*),
            2 => $f::<2>($($arg),*),
            3 => $f::<3>($($arg),*),
            4 => $f::<4>($($arg),*),
            5 => $f::<5>($($arg),*),
            count => $other(count),
        }
    };
}

#[cfg(test)]
mod tests {
    use super::*;
    use argus_motion_models::{CoordinatedTurn, Cv2D};

    fn models(n: usize) -> Vec<PlanarModel> {
        (0..n)
            .map(|i| {
                if i == 0 {
                    PlanarModel::from(Cv2D::discrete(0.5).unwrap())
                } else {
                    PlanarModel::from(CoordinatedTurn::new(0.05 * i as f64, 0.5).unwrap())
                }
            })
            .collect()
    }

    /// The mode count of the IMM built for `R` (the dispatch picked `R`).
    fn built<const R: usize>(m: &[PlanarModel], rows: &[Vec<f64>]) -> Result<usize, ImmError> {
        let imm = Imm::new(planar_filters::<R>(m)?, markov_rows::<R>(rows)?)?;
        Ok(imm.markov().matrix().nrows())
    }

    #[test]
    fn every_built_mode_count_dispatches_and_others_fall_through() {
        let other = |c: usize| {
            Err(ImmError::Empty {
                what: if c > MAX_PLANAR_MODES { "many" } else { "none" },
            })
        };
        for r in 1..=MAX_PLANAR_MODES {
            let rows: Vec<Vec<f64>> = (0..r)
                .map(|i| (0..r).map(|j| if i == j { 1.0 } else { 0.0 }).collect())
                .collect();
            let got = by_mode_count!(r, other, built, &models(r), &rows);
            assert_eq!(got.unwrap(), r);
        }
        for r in [0, MAX_PLANAR_MODES + 1] {
            let e = by_mode_count!(r, other, built, &models(r), &[]).unwrap_err();
            assert!(matches!(e, ImmError::Empty { .. }), "{r}: {e}");
        }
    }

    #[test]
    fn a_shape_other_than_r_is_an_error_not_a_panic() {
        assert!(planar_filters::<3>(&models(2)).is_err());
        assert!(markov_rows::<2>(&[vec![0.9, 0.1]]).is_err());
        assert!(markov_rows::<2>(&[vec![0.9, 0.1], vec![0.1]]).is_err());
        assert!(markov_rows::<2>(&[vec![0.9, 0.2], vec![0.1, 0.9]]).is_err());
        assert!(markov_rows::<2>(&[vec![0.9, 0.1], vec![0.1, 0.9]]).is_ok());
        assert!(per_mode::<3>(&[0.5, 0.5]).is_err());
        assert_eq!(
            per_mode::<2>(&[0.25, 0.75]).unwrap().map(f64::to_bits),
            [0.25_f64, 0.75].map(f64::to_bits)
        );
    }
}

//! Linear Cartesian position measurement (e.g. a converted radar plot).

use argus_core_math::{Matrix, SpdFactor, Vector, check_finite_matrix, symmetrize};

use crate::error::{SensorError, check_indices};
use crate::{LinearMeasurementModel, MeasurementModel};

/// A linear measurement of `M` position components, `z = H x + w`, `w ~ N(0, R)`,
/// with `H` selecting the state entries at validated indices.
///
/// For converted radar plots, whose covariance changes from plot to plot, build
/// one model per plot with [`CartesianPosition::with_noise`] (a cheap copy).
///
/// # References
/// Seed 004 eq (5) (`H = [I 0]` for position); seed 003 eq (18).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CartesianPosition<const N: usize, const M: usize> {
    indices: [usize; M],
    noise: Matrix<M, M>,
}

impl<const N: usize, const M: usize> CartesianPosition<N, M> {
    /// A position measurement of the state entries at `indices` with noise covariance `noise`.
    ///
    /// # Errors
    /// [`SensorError::IndexOutOfRange`] / [`SensorError::DuplicateIndex`] for bad
    /// indices; [`SensorError::Math`] when `noise` is not finite, not symmetric or
    /// not positive definite.
    pub fn new(indices: [usize; M], noise: Matrix<M, M>) -> Result<Self, SensorError> {
        Ok(Self {
            indices: check_indices(indices, N)?,
            noise: validate_noise(&noise)?,
        })
    }

    /// The same measurement with another noise covariance.
    ///
    /// # Errors
    /// As [`CartesianPosition::new`] for `noise`.
    pub fn with_noise(&self, noise: Matrix<M, M>) -> Result<Self, SensorError> {
        Ok(Self {
            indices: self.indices,
            noise: validate_noise(&noise)?,
        })
    }

    /// The state indices measured.
    #[must_use]
    pub fn indices(&self) -> [usize; M] {
        self.indices
    }
}

impl CartesianPosition<4, 2> {
    /// `(x, y)` of the constant-velocity layout `[x, vx, y, vy]` (indices `[0, 2]`).
    ///
    /// # Errors
    /// As [`CartesianPosition::new`] for `noise`.
    pub fn cv(noise: Matrix<2, 2>) -> Result<Self, SensorError> {
        Self::new([0, 2], noise)
    }
}

impl CartesianPosition<6, 3> {
    /// `(x, y, z)` of the constant-velocity layout `[x, vx, y, vy, z, vz]` (indices `[0, 2, 4]`).
    ///
    /// # Errors
    /// As [`CartesianPosition::new`] for `noise`.
    pub fn cv(noise: Matrix<3, 3>) -> Result<Self, SensorError> {
        Self::new([0, 2, 4], noise)
    }
}

fn validate_noise<const M: usize>(noise: &Matrix<M, M>) -> Result<Matrix<M, M>, SensorError> {
    const WHAT: &str = "position measurement noise";
    check_finite_matrix(noise, WHAT)?;
    if is_exactly_symmetric(noise) {
        // The common case (a converted plot's covariance is built symmetric), once per plot:
        // its asymmetry is 0, so `SpdFactor::new` would pass the symmetry test and end in
        // this same factorisation (the same error when not positive definite), and
        // `symmetrize` would return it unchanged (`(x + x)/2 = x` exactly for `|x| ≤ MAX/2`,
        // the signs of zeros included since their bits are equal; above that the average
        // overflowed to ∞, which is no longer stored). Only the definiteness
        // test is left; the second finiteness pass, the asymmetry measure and the averaging
        // are skipped (about 120 instructions of the 157 per plot, callgrind).
        SpdFactor::new_symmetric(noise, WHAT)?;
        return Ok(*noise);
    }
    // SpdFactor::new checks symmetry (relative tolerance) and positive definiteness.
    SpdFactor::new(noise, WHAT)?;
    Ok(symmetrize(noise))
}

/// Whether `m` equals its transpose bit for bit.
fn is_exactly_symmetric<const M: usize>(m: &Matrix<M, M>) -> bool {
    (0..M).all(|c| (c + 1..M).all(|r| m[(r, c)].to_bits() == m[(c, r)].to_bits()))
}

impl<const N: usize, const M: usize> MeasurementModel<N, M> for CartesianPosition<N, M> {
    fn predict(&self, x: &Vector<N>) -> Vector<M> {
        Vector::<M>::from_fn(|k, _| x[self.indices[k]])
    }

    fn jacobian(&self, _x: &Vector<N>) -> Matrix<M, N> {
        self.matrix()
    }

    fn noise(&self, _x: &Vector<N>) -> Matrix<M, M> {
        self.noise
    }

    fn hessians(&self, _x: &Vector<N>) -> Option<[Matrix<N, N>; M]> {
        Some([Matrix::<N, N>::zeros(); M])
    }

    fn selection(&self) -> Option<[usize; M]> {
        Some(self.indices)
    }
}

impl<const N: usize, const M: usize> LinearMeasurementModel<N, M> for CartesianPosition<N, M> {
    fn matrix(&self) -> Matrix<M, N> {
        let mut h = Matrix::<M, N>::zeros();
        for (k, &i) in self.indices.iter().enumerate() {
            h[(k, i)] = 1.0;
        }
        h
    }
}

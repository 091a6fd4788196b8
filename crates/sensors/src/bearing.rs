//! Bearing-only 2-D sensor.

use argus_core_math::{Matrix, Vector};

use crate::MeasurementModel;
use crate::angle::wrap_angle;
use crate::error::{SensorError, check_indices, finite, non_negative};

/// A passive sensor at `sensor` measuring the bearing `z = atan2(y − ys, x − xs)`
/// (counter-clockwise from +x) with constant noise variance `σ²`.
///
/// At the sensor position the Jacobian and Hessian contain non-finite values,
/// which the filters reject as an error.
///
/// # References
/// Seed 001 (Lee & Kim 1987), "drag-bearing" scenario: `y = atan2(y, x) + v`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bearing2D<const N: usize> {
    indices: [usize; 2],
    sensor: Vector<2>,
    sigma: f64,
}

impl<const N: usize> Bearing2D<N> {
    /// A bearing sensor at `sensor = [xs, ys]` for a state whose `x` and `y` are at
    /// `indices`, with bearing noise standard deviation `sigma` (rad).
    ///
    /// # Errors
    /// [`SensorError::IndexOutOfRange`] / [`SensorError::DuplicateIndex`] for bad
    /// indices, [`SensorError::NonFinite`] / [`SensorError::Negative`] for a bad
    /// position or `sigma`.
    pub fn new(indices: [usize; 2], sensor: [f64; 2], sigma: f64) -> Result<Self, SensorError> {
        Ok(Self {
            indices: check_indices(indices, N)?,
            sensor: Vector::<2>::new(
                finite(sensor[0], "sensor x")?,
                finite(sensor[1], "sensor y")?,
            ),
            sigma: non_negative(sigma, "bearing sigma")?,
        })
    }

    /// The target position relative to the sensor, `(Δx, Δy)`.
    #[must_use]
    pub fn relative(&self, x: &Vector<N>) -> Vector<2> {
        let [ix, iy] = self.indices;
        Vector::<2>::new(x[ix], x[iy]) - self.sensor
    }

    /// The bearing noise standard deviation, rad.
    #[must_use]
    pub fn sigma(&self) -> f64 {
        self.sigma
    }

    /// The sensor position.
    #[must_use]
    pub fn sensor(&self) -> &Vector<2> {
        &self.sensor
    }
}

impl Bearing2D<4> {
    /// A bearing sensor for the constant-velocity layout `[x, vx, y, vy]` (indices `[0, 2]`).
    ///
    /// # Errors
    /// As [`Bearing2D::new`].
    pub fn cv(sensor: [f64; 2], sigma: f64) -> Result<Self, SensorError> {
        Self::new([0, 2], sensor, sigma)
    }
}

impl<const N: usize> MeasurementModel<N, 1> for Bearing2D<N> {
    fn predict(&self, x: &Vector<N>) -> Vector<1> {
        let d = self.relative(x);
        Vector::<1>::new(d[1].atan2(d[0]))
    }

    fn jacobian(&self, x: &Vector<N>) -> Matrix<1, N> {
        let d = self.relative(x);
        let r2 = d.norm_squared();
        let [ix, iy] = self.indices;
        let mut h = Matrix::<1, N>::zeros();
        h[(0, ix)] = -d[1] / r2;
        h[(0, iy)] = d[0] / r2;
        h
    }

    fn noise(&self, _x: &Vector<N>) -> Matrix<1, 1> {
        Matrix::<1, 1>::new(self.sigma * self.sigma)
    }

    fn residual(&self, z: &Vector<1>, z_pred: &Vector<1>) -> Vector<1> {
        Vector::<1>::new(wrap_angle(z[0] - z_pred[0]))
    }

    fn hessians(&self, x: &Vector<N>) -> Option<[Matrix<N, N>; 1]> {
        let d = self.relative(x);
        let (dx, dy) = (d[0], d[1]);
        let r2 = d.norm_squared();
        let r4 = r2 * r2;
        let [ix, iy] = self.indices;
        let mut h = Matrix::<N, N>::zeros();
        h[(ix, ix)] = 2.0 * dx * dy / r4;
        h[(iy, iy)] = -2.0 * dx * dy / r4;
        h[(ix, iy)] = (dy * dy - dx * dx) / r4;
        h[(iy, ix)] = h[(ix, iy)];
        Some([h])
    }
}

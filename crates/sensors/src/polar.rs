//! Two-dimensional polar radar: range and azimuth from a sensor position.

use argus_core_math::{Matrix, Vector};

use crate::MeasurementModel;
use crate::angle::wrap_angle;
use crate::error::{SensorError, check_indices, finite};
use crate::noise::RadarNoise;

/// A 2-D radar at `sensor` measuring `z = [r, θ]`:
///
/// `r = √(Δx² + Δy²)`, `θ = atan2(Δy, Δx)`, `(Δx, Δy) = (x − xs, y − ys)`,
///
/// with the target's `x`, `y` read from the state at validated indices (θ
/// counter-clockwise from +x). The noise is `diag(σr², σθ²)`, constant or from
/// the SNR at the predicted range ([`RadarNoise`]).
///
/// At the sensor position (`r = 0`) the Jacobian and Hessians are undefined and
/// contain non-finite values, which the filters reject as an error.
///
/// # References
/// Bar-Shalom, Li & Kirubarajan (2001), §10.4 (polar measurements); seed 004
/// eq (1) (plots relative to the sensor's position).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Polar2D<const N: usize> {
    indices: [usize; 2],
    sensor: Vector<2>,
    noise: RadarNoise,
}

impl<const N: usize> Polar2D<N> {
    /// A polar radar at `sensor = [xs, ys]` for a state whose `x` and `y` are at
    /// `indices = [ix, iy]`.
    ///
    /// # Errors
    /// [`SensorError::IndexOutOfRange`] / [`SensorError::DuplicateIndex`] for bad
    /// indices, [`SensorError::NonFinite`] for a non-finite sensor position.
    pub fn new(
        indices: [usize; 2],
        sensor: [f64; 2],
        noise: RadarNoise,
    ) -> Result<Self, SensorError> {
        Ok(Self {
            indices: check_indices(indices, N)?,
            sensor: Vector::<2>::new(
                finite(sensor[0], "sensor x")?,
                finite(sensor[1], "sensor y")?,
            ),
            noise,
        })
    }

    /// The target position relative to the sensor, `(Δx, Δy)`.
    #[must_use]
    pub fn relative(&self, x: &Vector<N>) -> Vector<2> {
        let [ix, iy] = self.indices;
        Vector::<2>::new(x[ix], x[iy]) - self.sensor
    }

    /// The sensor position.
    #[must_use]
    pub fn sensor(&self) -> &Vector<2> {
        &self.sensor
    }

    /// The state indices of `x` and `y`.
    #[must_use]
    pub fn indices(&self) -> [usize; 2] {
        self.indices
    }

    /// The noise model.
    #[must_use]
    pub fn noise_model(&self) -> &RadarNoise {
        &self.noise
    }
}

impl Polar2D<4> {
    /// A polar radar for the constant-velocity layout `[x, vx, y, vy]` (indices `[0, 2]`).
    ///
    /// # Errors
    /// [`SensorError::NonFinite`] for a non-finite sensor position.
    pub fn cv(sensor: [f64; 2], noise: RadarNoise) -> Result<Self, SensorError> {
        Self::new([0, 2], sensor, noise)
    }
}

impl<const N: usize> MeasurementModel<N, 2> for Polar2D<N> {
    fn predict(&self, x: &Vector<N>) -> Vector<2> {
        let d = self.relative(x);
        Vector::<2>::new(d.norm(), d[1].atan2(d[0]))
    }

    fn jacobian(&self, x: &Vector<N>) -> Matrix<2, N> {
        let d = self.relative(x);
        let r2 = d.norm_squared();
        let r = r2.sqrt();
        let [ix, iy] = self.indices;
        let mut h = Matrix::<2, N>::zeros();
        h[(0, ix)] = d[0] / r;
        h[(0, iy)] = d[1] / r;
        h[(1, ix)] = -d[1] / r2;
        h[(1, iy)] = d[0] / r2;
        h
    }

    fn noise(&self, x: &Vector<N>) -> Matrix<2, 2> {
        let s = self.noise.sigmas_at_range(self.relative(x).norm());
        Matrix::<2, 2>::from_diagonal(&Vector::<2>::new(
            s.range() * s.range(),
            s.azimuth() * s.azimuth(),
        ))
    }

    fn residual(&self, z: &Vector<2>, z_pred: &Vector<2>) -> Vector<2> {
        Vector::<2>::new(z[0] - z_pred[0], wrap_angle(z[1] - z_pred[1]))
    }

    fn hessians(&self, x: &Vector<N>) -> Option<[Matrix<N, N>; 2]> {
        let d = self.relative(x);
        let (dx, dy) = (d[0], d[1]);
        let r2 = d.norm_squared();
        let r3 = r2 * r2.sqrt();
        let r4 = r2 * r2;
        let [ix, iy] = self.indices;
        let mut hr = Matrix::<N, N>::zeros();
        hr[(ix, ix)] = dy * dy / r3;
        hr[(iy, iy)] = dx * dx / r3;
        hr[(ix, iy)] = -dx * dy / r3;
        hr[(iy, ix)] = hr[(ix, iy)];
        let mut ht = Matrix::<N, N>::zeros();
        ht[(ix, ix)] = 2.0 * dx * dy / r4;
        ht[(iy, iy)] = -2.0 * dx * dy / r4;
        ht[(ix, iy)] = (dy * dy - dx * dx) / r4;
        ht[(iy, ix)] = ht[(ix, iy)];
        Some([hr, ht])
    }
}

//! Three-dimensional spherical radar: range, azimuth and elevation.

use argus_core_math::{Matrix, Vector};

use crate::MeasurementModel;
use crate::angle::wrap_angle;
use crate::error::{SensorError, check_indices, finite};
use crate::noise::RadarNoise;

/// A 3-D radar at `sensor` measuring `z = [r, ψ, θ]`:
///
/// `r = |Δ|`, `ψ = atan2(Δy, Δx)` (azimuth, counter-clockwise from +x),
/// `θ = atan2(Δz, √(Δx² + Δy²))` (elevation above the horizontal plane),
///
/// the inverse of seed 003 eq (9), `x = r cosψ cosθ, y = r sinψ cosθ, z = r sinθ`.
/// The target's `x`, `y`, `z` are read from the state at validated indices. The
/// noise is `diag(σr², σψ², σθ²)`, constant or from the SNR at the predicted
/// range ([`RadarNoise`]).
///
/// On the vertical through the sensor (`Δx = Δy = 0`) the azimuth is undefined:
/// the Jacobian and Hessians then contain non-finite values, which the filters
/// reject as an error.
///
/// # References
/// Seed 003 (Kim & Hwang 2013), eqs (1)–(5) and (9); seed 002 (EKF with a
/// spherical measurement).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spherical3D<const N: usize> {
    indices: [usize; 3],
    sensor: Vector<3>,
    noise: RadarNoise,
}

impl<const N: usize> Spherical3D<N> {
    /// A spherical radar at `sensor = [xs, ys, zs]` for a state whose `x`, `y`, `z`
    /// are at `indices`.
    ///
    /// # Errors
    /// [`SensorError::IndexOutOfRange`] / [`SensorError::DuplicateIndex`] for bad
    /// indices, [`SensorError::NonFinite`] for a non-finite sensor position.
    pub fn new(
        indices: [usize; 3],
        sensor: [f64; 3],
        noise: RadarNoise,
    ) -> Result<Self, SensorError> {
        Ok(Self {
            indices: check_indices(indices, N)?,
            sensor: Vector::<3>::new(
                finite(sensor[0], "sensor x")?,
                finite(sensor[1], "sensor y")?,
                finite(sensor[2], "sensor z")?,
            ),
            noise,
        })
    }

    /// The target position relative to the sensor, `(Δx, Δy, Δz)`.
    #[must_use]
    pub fn relative(&self, x: &Vector<N>) -> Vector<3> {
        let [ix, iy, iz] = self.indices;
        Vector::<3>::new(x[ix], x[iy], x[iz]) - self.sensor
    }

    /// The sensor position.
    #[must_use]
    pub fn sensor(&self) -> &Vector<3> {
        &self.sensor
    }

    /// The state indices of `x`, `y` and `z`.
    #[must_use]
    pub fn indices(&self) -> [usize; 3] {
        self.indices
    }

    /// The noise model.
    #[must_use]
    pub fn noise_model(&self) -> &RadarNoise {
        &self.noise
    }
}

impl Spherical3D<6> {
    /// A spherical radar for the constant-velocity layout `[x, vx, y, vy, z, vz]`
    /// (indices `[0, 2, 4]`).
    ///
    /// # Errors
    /// [`SensorError::NonFinite`] for a non-finite sensor position.
    pub fn cv(sensor: [f64; 3], noise: RadarNoise) -> Result<Self, SensorError> {
        Self::new([0, 2, 4], sensor, noise)
    }
}

impl<const N: usize> MeasurementModel<N, 3> for Spherical3D<N> {
    fn predict(&self, x: &Vector<N>) -> Vector<3> {
        let d = self.relative(x);
        let rho = d[0].hypot(d[1]);
        Vector::<3>::new(d.norm(), d[1].atan2(d[0]), d[2].atan2(rho))
    }

    fn jacobian(&self, x: &Vector<N>) -> Matrix<3, N> {
        let d = self.relative(x);
        let (dx, dy, dz) = (d[0], d[1], d[2]);
        let rho2 = dx * dx + dy * dy;
        let rho = rho2.sqrt();
        let r2 = rho2 + dz * dz;
        let r = r2.sqrt();
        let [ix, iy, iz] = self.indices;
        let mut h = Matrix::<3, N>::zeros();
        h[(0, ix)] = dx / r;
        h[(0, iy)] = dy / r;
        h[(0, iz)] = dz / r;
        h[(1, ix)] = -dy / rho2;
        h[(1, iy)] = dx / rho2;
        h[(2, ix)] = -dx * dz / (r2 * rho);
        h[(2, iy)] = -dy * dz / (r2 * rho);
        h[(2, iz)] = rho / r2;
        h
    }

    fn noise(&self, x: &Vector<N>) -> Matrix<3, 3> {
        let s = self.noise.sigmas_at_range(self.relative(x).norm());
        Matrix::<3, 3>::from_diagonal(&Vector::<3>::new(
            s.range() * s.range(),
            s.azimuth() * s.azimuth(),
            s.elevation() * s.elevation(),
        ))
    }

    fn residual(&self, z: &Vector<3>, z_pred: &Vector<3>) -> Vector<3> {
        Vector::<3>::new(
            z[0] - z_pred[0],
            wrap_angle(z[1] - z_pred[1]),
            wrap_angle(z[2] - z_pred[2]),
        )
    }

    fn hessians(&self, x: &Vector<N>) -> Option<[Matrix<N, N>; 3]> {
        let d = self.relative(x);
        let (dx, dy, dz) = (d[0], d[1], d[2]);
        let rho2 = dx * dx + dy * dy;
        let rho = rho2.sqrt();
        let rho3 = rho2 * rho;
        let rho4 = rho2 * rho2;
        let r2 = rho2 + dz * dz;
        let r = r2.sqrt();
        let r3 = r2 * r;
        let r4 = r2 * r2;
        let [ix, iy, iz] = self.indices;
        let p = [ix, iy, iz];

        // Range: ∂²r/∂d² = (r² I − d dᵀ) / r³.
        let mut hr = Matrix::<N, N>::zeros();
        for (a, &ia) in p.iter().enumerate() {
            for (b, &ib) in p.iter().enumerate() {
                let delta = if a == b { r2 } else { 0.0 };
                hr[(ia, ib)] = (delta - d[a] * d[b]) / r3;
            }
        }

        // Azimuth: the 2-D bearing Hessian in (x, y) with ρ in place of r.
        let mut hpsi = Matrix::<N, N>::zeros();
        hpsi[(ix, ix)] = 2.0 * dx * dy / rho4;
        hpsi[(iy, iy)] = -2.0 * dx * dy / rho4;
        hpsi[(ix, iy)] = (dy * dy - dx * dx) / rho4;
        hpsi[(iy, ix)] = hpsi[(ix, iy)];

        // Elevation θ = atan2(Δz, ρ), from θ_x = −Δx Δz/(r² ρ), θ_y = −Δy Δz/(r² ρ), θ_z = ρ/r².
        let k = dz * (2.0 * rho2 + r2) / (r4 * rho3);
        let mut hth = Matrix::<N, N>::zeros();
        hth[(ix, ix)] = -dz / (r2 * rho) + dx * dx * k;
        hth[(iy, iy)] = -dz / (r2 * rho) + dy * dy * k;
        hth[(ix, iy)] = dx * dy * k;
        hth[(iy, ix)] = hth[(ix, iy)];
        let m = (2.0 * dz * dz - r2) / (r4 * rho);
        hth[(ix, iz)] = dx * m;
        hth[(iz, ix)] = hth[(ix, iz)];
        hth[(iy, iz)] = dy * m;
        hth[(iz, iy)] = hth[(iy, iz)];
        hth[(iz, iz)] = -2.0 * rho * dz / r4;
        Some([hr, hpsi, hth])
    }
}

//! Small local models for the unit tests (the real ones live in
//! `argus-motion-models` and `argus-sensors`).

use argus_core_math::{Matrix, Vector};
use argus_motion_models::{ContinuousModel, LinearMotionModel, MotionModel};
use argus_sensors::{LinearMeasurementModel, MeasurementModel};

/// 1-D constant velocity `[x, v]` with discrete white-noise acceleration (DWNA) of
/// standard deviation `sigma_v`: `Q = σ_v² Γ Γᵀ`, `Γ = [T²/2, T]ᵀ`.
pub(crate) struct Cv1Dwna {
    pub(crate) sigma_v: f64,
}

impl MotionModel<2> for Cv1Dwna {
    fn propagate(&self, x: &Vector<2>, dt: f64) -> Vector<2> {
        self.transition(dt) * x
    }
    fn jacobian(&self, _x: &Vector<2>, dt: f64) -> Matrix<2, 2> {
        self.transition(dt)
    }
    fn process_noise(&self, _x: &Vector<2>, dt: f64) -> Matrix<2, 2> {
        let g = Vector::<2>::new(0.5 * dt * dt, dt);
        g * g.transpose() * self.sigma_v.powi(2)
    }
}

impl LinearMotionModel<2> for Cv1Dwna {
    fn transition(&self, dt: f64) -> Matrix<2, 2> {
        Matrix::<2, 2>::new(1.0, dt, 0.0, 1.0)
    }
}

/// 2-D constant velocity `[x, vx, y, vy]`, continuous white-noise acceleration of
/// spectral density `q` per axis: `Q = q [[T³/3, T²/2], [T²/2, T]]` per axis.
#[derive(Clone, Copy)]
pub(crate) struct Cv2 {
    pub(crate) q: f64,
}

impl MotionModel<4> for Cv2 {
    fn propagate(&self, x: &Vector<4>, dt: f64) -> Vector<4> {
        self.transition(dt) * x
    }
    fn jacobian(&self, _x: &Vector<4>, dt: f64) -> Matrix<4, 4> {
        self.transition(dt)
    }
    fn process_noise(&self, _x: &Vector<4>, dt: f64) -> Matrix<4, 4> {
        let (a, b, c) = (dt.powi(3) / 3.0, dt.powi(2) / 2.0, dt);
        #[rustfmt::skip]
        let q = Matrix::<4, 4>::new(
            a, b, 0.0, 0.0,
            b, c, 0.0, 0.0,
            0.0, 0.0, a, b,
            0.0, 0.0, b, c,
        );
        q * self.q
    }
    fn hessians(&self, _x: &Vector<4>, _dt: f64) -> Option<[Matrix<4, 4>; 4]> {
        Some([Matrix::zeros(); 4])
    }
}

impl LinearMotionModel<4> for Cv2 {
    fn transition(&self, dt: f64) -> Matrix<4, 4> {
        #[rustfmt::skip]
        let f = Matrix::<4, 4>::new(
            1.0, dt, 0.0, 0.0,
            0.0, 1.0, 0.0, 0.0,
            0.0, 0.0, 1.0, dt,
            0.0, 0.0, 0.0, 1.0,
        );
        f
    }
}

/// Position of a 1-D `[x, v]` state with variance `r`.
pub(crate) struct Pos1 {
    pub(crate) r: f64,
}

impl MeasurementModel<2, 1> for Pos1 {
    fn predict(&self, x: &Vector<2>) -> Vector<1> {
        Vector::<1>::new(x[0])
    }
    fn jacobian(&self, _x: &Vector<2>) -> Matrix<1, 2> {
        self.matrix()
    }
    fn noise(&self, _x: &Vector<2>) -> Matrix<1, 1> {
        Matrix::<1, 1>::new(self.r)
    }
}

impl LinearMeasurementModel<2, 1> for Pos1 {
    fn matrix(&self) -> Matrix<1, 2> {
        Matrix::<1, 2>::new(1.0, 0.0)
    }
}

/// Cartesian position of a `[x, vx, y, vy]` state with covariance `r`.
#[derive(Clone, Copy)]
pub(crate) struct Pos2 {
    pub(crate) r: Matrix<2, 2>,
}

impl MeasurementModel<4, 2> for Pos2 {
    fn predict(&self, x: &Vector<4>) -> Vector<2> {
        Vector::<2>::new(x[0], x[2])
    }
    fn jacobian(&self, _x: &Vector<4>) -> Matrix<2, 4> {
        self.matrix()
    }
    fn noise(&self, _x: &Vector<4>) -> Matrix<2, 2> {
        self.r
    }
    fn hessians(&self, _x: &Vector<4>) -> Option<[Matrix<4, 4>; 2]> {
        Some([Matrix::zeros(); 2])
    }
}

impl LinearMeasurementModel<4, 2> for Pos2 {
    fn matrix(&self) -> Matrix<2, 4> {
        Matrix::<2, 4>::new(1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0)
    }
}

/// Range and azimuth (from +x, counter-clockwise) of a `[x, vx, y, vy]` state.
#[derive(Clone, Copy)]
pub(crate) struct Polar2 {
    pub(crate) sigma_r: f64,
    pub(crate) sigma_az: f64,
}

fn wrap(a: f64) -> f64 {
    let w =
        (a + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI) - std::f64::consts::PI;
    if w <= -std::f64::consts::PI {
        w + 2.0 * std::f64::consts::PI
    } else {
        w
    }
}

impl MeasurementModel<4, 2> for Polar2 {
    fn predict(&self, x: &Vector<4>) -> Vector<2> {
        Vector::<2>::new(x[0].hypot(x[2]), x[2].atan2(x[0]))
    }
    fn jacobian(&self, x: &Vector<4>) -> Matrix<2, 4> {
        let r2 = x[0] * x[0] + x[2] * x[2];
        let r = r2.sqrt();
        Matrix::<2, 4>::new(
            x[0] / r,
            0.0,
            x[2] / r,
            0.0,
            -x[2] / r2,
            0.0,
            x[0] / r2,
            0.0,
        )
    }
    fn noise(&self, _x: &Vector<4>) -> Matrix<2, 2> {
        Matrix::<2, 2>::new(self.sigma_r.powi(2), 0.0, 0.0, self.sigma_az.powi(2))
    }
    fn residual(&self, z: &Vector<2>, z_pred: &Vector<2>) -> Vector<2> {
        Vector::<2>::new(z[0] - z_pred[0], wrap(z[1] - z_pred[1]))
    }
}

/// A scalar quadratic measurement `h(x) = xᵀ A x` of a 2-D state, variance `r`.
pub(crate) struct Quadratic {
    pub(crate) a: Matrix<2, 2>,
    pub(crate) r: f64,
}

impl MeasurementModel<2, 1> for Quadratic {
    fn predict(&self, x: &Vector<2>) -> Vector<1> {
        Vector::<1>::new((x.transpose() * self.a * x)[0])
    }
    fn jacobian(&self, x: &Vector<2>) -> Matrix<1, 2> {
        (self.a * x * 2.0).transpose()
    }
    fn noise(&self, _x: &Vector<2>) -> Matrix<1, 1> {
        Matrix::<1, 1>::new(self.r)
    }
    fn hessians(&self, _x: &Vector<2>) -> Option<[Matrix<2, 2>; 1]> {
        Some([self.a * 2.0])
    }
}

/// Quadratic 2-D dynamics `f(x) = [x₀ + dt x₁², x₁ + dt x₀ x₁]` with process noise `q I`.
pub(crate) struct QuadraticMotion {
    pub(crate) q: f64,
}

impl MotionModel<2> for QuadraticMotion {
    fn propagate(&self, x: &Vector<2>, dt: f64) -> Vector<2> {
        Vector::<2>::new(x[0] + dt * x[1] * x[1], x[1] + dt * x[0] * x[1])
    }
    fn jacobian(&self, x: &Vector<2>, dt: f64) -> Matrix<2, 2> {
        Matrix::<2, 2>::new(1.0, 2.0 * dt * x[1], dt * x[1], 1.0 + dt * x[0])
    }
    fn process_noise(&self, _x: &Vector<2>, _dt: f64) -> Matrix<2, 2> {
        Matrix::<2, 2>::identity() * self.q
    }
    fn hessians(&self, _x: &Vector<2>, dt: f64) -> Option<[Matrix<2, 2>; 2]> {
        Some([
            Matrix::<2, 2>::new(0.0, 0.0, 0.0, 2.0 * dt),
            Matrix::<2, 2>::new(0.0, dt, dt, 0.0),
        ])
    }
}

/// Continuous-time 1-D constant velocity `ẋ = v`, `v̇ = w`, `E[w w] = q δ`.
pub(crate) struct ContinuousCv1 {
    pub(crate) q: f64,
}

impl ContinuousModel<2> for ContinuousCv1 {
    fn drift(&self, x: &Vector<2>) -> Vector<2> {
        Vector::<2>::new(x[1], 0.0)
    }
    fn drift_jacobian(&self, _x: &Vector<2>) -> Matrix<2, 2> {
        Matrix::<2, 2>::new(0.0, 1.0, 0.0, 0.0)
    }
    fn drift_hessians(&self, _x: &Vector<2>) -> [Matrix<2, 2>; 2] {
        [Matrix::zeros(); 2]
    }
    fn diffusion(&self) -> Matrix<2, 2> {
        Matrix::<2, 2>::new(0.0, 0.0, 0.0, self.q)
    }
}

/// `ẋ₁ = x₂²`, `ẋ₂ = 0`, no noise: `x₂` is a constant random rate.
pub(crate) struct SquareRate;

impl ContinuousModel<2> for SquareRate {
    fn drift(&self, x: &Vector<2>) -> Vector<2> {
        Vector::<2>::new(x[1] * x[1], 0.0)
    }
    fn drift_jacobian(&self, x: &Vector<2>) -> Matrix<2, 2> {
        Matrix::<2, 2>::new(0.0, 2.0 * x[1], 0.0, 0.0)
    }
    fn drift_hessians(&self, _x: &Vector<2>) -> [Matrix<2, 2>; 2] {
        [Matrix::<2, 2>::new(0.0, 0.0, 0.0, 2.0), Matrix::zeros()]
    }
    fn diffusion(&self) -> Matrix<2, 2> {
        Matrix::zeros()
    }
}

/// Exact mean and covariance of `g(x)`, `x ~ N(mean, cov)`, for `g` polynomial of
/// degree ≤ 2: tensor 3-point Gauss–Hermite quadrature (nodes 0, ±√3 with weights
/// 2/3, 1/6, 1/6 for a standard normal) is exact for polynomials of degree ≤ 5 in
/// each variable, so for all moments of a quadratic `g` up to the second
/// (Abramowitz & Stegun 25.4.46).
pub(crate) fn gauss_hermite_moments<const N: usize, const K: usize>(
    g: impl Fn(&Vector<N>) -> Vector<K>,
    mean: &Vector<N>,
    cov: &Matrix<N, N>,
) -> (Vector<K>, Matrix<K, K>) {
    let l = cov.cholesky().unwrap().l();
    let nodes = [0.0, 3f64.sqrt(), -(3f64.sqrt())];
    let weights = [2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0];
    let total = 3usize.pow(N as u32);
    let mut points = Vec::with_capacity(total);
    for mut k in 0..total {
        let mut u = Vector::<N>::zeros();
        let mut w = 1.0;
        for i in 0..N {
            u[i] = nodes[k % 3];
            w *= weights[k % 3];
            k /= 3;
        }
        points.push((w, g(&(mean + l * u))));
    }
    let m: Vector<K> = points.iter().map(|(w, y)| y * *w).sum();
    let c: Matrix<K, K> = points
        .iter()
        .map(|(w, y)| (y - m) * (y - m).transpose() * *w)
        .sum();
    (m, c)
}

/// `ẋ = −k x` in both components with `Q_c = q I`.
pub(crate) struct Decay {
    pub(crate) k: f64,
    pub(crate) q: f64,
}

impl ContinuousModel<2> for Decay {
    fn drift(&self, x: &Vector<2>) -> Vector<2> {
        -x * self.k
    }
    fn drift_jacobian(&self, _x: &Vector<2>) -> Matrix<2, 2> {
        -Matrix::<2, 2>::identity() * self.k
    }
    fn drift_hessians(&self, _x: &Vector<2>) -> [Matrix<2, 2>; 2] {
        [Matrix::zeros(); 2]
    }
    fn diffusion(&self) -> Matrix<2, 2> {
        Matrix::<2, 2>::identity() * self.q
    }
}

//! Planar target with quadratic drag (seed 001, the bearing-only drag scenario),
//! state `[x, vx, y, vy]`.
//!
//! Continuous-time model (seed 001 §5.2, the equation of motion of the submarine):
//!
//! ```text
//! ẋ  = vx
//! v̇x = −α vx |v| + ux
//! ẏ  = vy
//! v̇y = −α vy |v| + uy        |v| = √(vx² + vy²)
//! ```
//!
//! plus white noise `w(t)` on the two velocity components with power spectral density
//! `q` (m²/s³) each: `Q_c = diag(0, q, 0, q)` (the paper writes a generic `+ w(t)`; we put
//! the noise where the unknown input enters, through the same `B = [[0,0],[1,0],[0,0],[0,1]]`).
//! `α ≥ 0` is the drag coefficient (1/m), `u = (ux, uy)` a known input acceleration
//! (zero by default) so input estimation can feed its estimate back.
//!
//! The discrete model ([`MotionModel`]) integrates over `dt` with the classical RK4 method
//! in `n = ⌈|dt| / max_step⌉` equal substeps (default `max_step` = [`DEFAULT_MAX_STEP`]
//! = 0.1 s; the error is fourth order in the substep: measured for α|v| = 0.6 /s over 5 s,
//! 7e-5 m of a 700 m displacement, 1e-7 relative; see `tests/drag.rs`):
//!
//! - `propagate`: RK4 on `ẋ = a(x)`;
//! - `jacobian`: RK4 on the augmented system `ẋ = a(x)`, `Φ̇ = A(x) Φ`, `Φ(0) = I` — this is
//!   exactly the Jacobian of the RK4 map (Runge–Kutta methods commute with linearisation);
//! - `process_noise`: RK4 on `ẋ = a(x)`, `Q̇ = A(x) Q + Q A(x)ᵀ + Q_c`, `Q(0) = 0`, i.e. the
//!   covariance of the linearised model about the propagated trajectory
//!   (seed 001 eq. 2-4, `Ṗ = F P + P Fᵀ + N`, started from zero);
//! - `hessians`: RK4 on the second-order variational equation
//!   `Ṫᵢ = Σⱼ Aᵢⱼ Tⱼ + Φᵀ (∂²aᵢ/∂x²) Φ`, `Tᵢ(0) = 0` — exactly the Hessians of the RK4 map
//!   (not a first-order-in-`dt` approximation).
//!
//! At zero speed `v ↦ v|v|` is once but not twice differentiable: the drift Jacobian there is
//! the limit (the drag terms vanish) and the drift Hessians are returned as zero (their
//! limit depends on the direction of approach).
//!
//! # References
//! Seed 001 (Lee & Kim 1987) §5.2, the equation of motion with drag coefficient α and
//! control inputs `u_T1`, `u_T2`; eqs. (2-1), (2-4), (2-6) for the continuous–discrete EKF.

use argus_core_math::{Matrix, Vector};

use crate::error::{MotionError, check_finite, check_non_negative, check_positive};
use crate::rk4::{WithHessians, WithMatrix, rk4, substep_count};
use crate::{ContinuousModel, MotionModel};

/// Default longest RK4 substep, seconds.
pub const DEFAULT_MAX_STEP: f64 = 0.1;

/// Planar quadratic drag, state `[x, vx, y, vy]` (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuadraticDrag {
    alpha: f64,
    q: f64,
    input: Vector<2>,
    max_step: f64,
}

impl QuadraticDrag {
    /// A drag model with coefficient `alpha` (1/m, `≥ 0`) and velocity white-noise power
    /// spectral density `q` (m²/s³, `≥ 0`); no input, `max_step` = [`DEFAULT_MAX_STEP`].
    ///
    /// # Errors
    /// [`MotionError::NonFinite`] or [`MotionError::Negative`] when `alpha` or `q` is NaN,
    /// infinite or negative.
    pub fn new(alpha: f64, q: f64) -> Result<Self, MotionError> {
        Ok(Self {
            alpha: check_non_negative("alpha", alpha)?,
            q: check_non_negative("q", q)?,
            input: Vector::<2>::zeros(),
            max_step: DEFAULT_MAX_STEP,
        })
    }

    /// The same model with the known input acceleration `u = (ux, uy)` (m/s²).
    ///
    /// # Errors
    /// [`MotionError::NonFinite`] when a component is NaN or infinite.
    pub fn with_input(self, u: Vector<2>) -> Result<Self, MotionError> {
        check_finite("input ux", u[0])?;
        check_finite("input uy", u[1])?;
        Ok(Self { input: u, ..self })
    }

    /// The same model with RK4 substeps no longer than `max_step` seconds.
    ///
    /// # Errors
    /// [`MotionError::NonFinite`] or [`MotionError::NotPositive`] unless `max_step` is
    /// finite and positive.
    pub fn with_max_step(self, max_step: f64) -> Result<Self, MotionError> {
        Ok(Self {
            max_step: check_positive("max_step", max_step)?,
            ..self
        })
    }

    /// The drag coefficient α, 1/m.
    #[must_use]
    pub fn alpha(&self) -> f64 {
        self.alpha
    }

    /// The velocity noise power spectral density `q`, m²/s³.
    #[must_use]
    pub fn q(&self) -> f64 {
        self.q
    }

    /// The known input acceleration `u`, m/s².
    #[must_use]
    pub fn input(&self) -> Vector<2> {
        self.input
    }

    /// The longest RK4 substep, seconds.
    #[must_use]
    pub fn max_step(&self) -> f64 {
        self.max_step
    }

    /// The number of RK4 substeps used over `dt`: `⌈|dt| / max_step⌉`, at least 1
    /// (capped at one million).
    #[must_use]
    pub fn substeps(&self, dt: f64) -> usize {
        substep_count(dt, self.max_step)
    }
}

impl ContinuousModel<4> for QuadraticDrag {
    fn drift(&self, x: &Vector<4>) -> Vector<4> {
        let (vx, vy) = (x[1], x[3]);
        let speed = vx.hypot(vy);
        Vector::<4>::new(
            vx,
            -self.alpha * vx * speed + self.input[0],
            vy,
            -self.alpha * vy * speed + self.input[1],
        )
    }

    /// `A = ∂a/∂x`: with `s = |v|`, `∂(vx s)/∂vx = s + vx²/s`, `∂(vx s)/∂vy = vx vy/s`,
    /// `∂(vy s)/∂vy = s + vy²/s` (all → 0 as `s → 0`; exactly 0 at `s = 0`).
    #[allow(non_snake_case)]
    fn drift_jacobian(&self, x: &Vector<4>) -> Matrix<4, 4> {
        let (vx, vy) = (x[1], x[3]);
        let s = vx.hypot(vy);
        let (dxx, dxy, dyy) = if s > 0.0 {
            (s + vx * vx / s, vx * vy / s, s + vy * vy / s)
        } else {
            (0.0, 0.0, 0.0)
        };
        let a = self.alpha;
        #[rustfmt::skip]
        let A = Matrix::<4, 4>::new(
            0.0, 1.0,      0.0, 0.0,
            0.0, -a * dxx, 0.0, -a * dxy,
            0.0, 0.0,      0.0, 1.0,
            0.0, -a * dxy, 0.0, -a * dyy,
        );
        A
    }

    /// With `s = |v|`, the Hessian of `vx s` in `(vx, vy)` is
    /// `[[3vx/s − vx³/s³, vy/s − vx² vy/s³], [·, vx/s − vx vy²/s³]]` and that of `vy s` the
    /// same with `x ↔ y`; multiplied by `−α` and placed at the velocity indices (1, 3).
    /// Zero at `s = 0`, where the second derivative does not exist.
    fn drift_hessians(&self, x: &Vector<4>) -> [Matrix<4, 4>; 4] {
        let mut h = [Matrix::<4, 4>::zeros(); 4];
        let (vx, vy) = (x[1], x[3]);
        let s = vx.hypot(vy);
        if s > 0.0 {
            let (ux, uy) = (vx / s, vy / s);
            let a = self.alpha;
            // Hessian of vx·s: e_x ∇sᵀ + ∇s e_xᵀ + vx ∇²s, ∇s = v/s, ∇²s = (I − v̂v̂ᵀ)/s.
            let gx = [
                ux * (3.0 - ux * ux),
                uy * (1.0 - ux * ux),
                ux * (1.0 - uy * uy),
            ];
            let gy = [
                uy * (1.0 - ux * ux),
                ux * (1.0 - uy * uy),
                uy * (3.0 - uy * uy),
            ];
            for (hi, g) in [(1_usize, gx), (3_usize, gy)] {
                let m = &mut h[hi];
                m[(1, 1)] = -a * g[0];
                m[(1, 3)] = -a * g[1];
                m[(3, 1)] = -a * g[1];
                m[(3, 3)] = -a * g[2];
            }
        }
        h
    }

    /// `Q_c = diag(0, q, 0, q)`.
    fn diffusion(&self) -> Matrix<4, 4> {
        Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(0.0, self.q, 0.0, self.q))
    }
}

impl MotionModel<4> for QuadraticDrag {
    /// RK4 on `ẋ = a(x)` in [`QuadraticDrag::substeps`] substeps.
    fn propagate(&self, x: &Vector<4>, dt: f64) -> Vector<4> {
        rk4(*x, dt, self.substeps(dt), |s| self.drift(s))
    }

    /// RK4 on `(ẋ, Φ̇) = (a(x), A(x) Φ)`, `Φ(0) = I`: the exact Jacobian of the RK4 map.
    fn jacobian(&self, x: &Vector<4>, dt: f64) -> Matrix<4, 4> {
        let s0 = WithMatrix {
            x: *x,
            m: Matrix::<4, 4>::identity(),
        };
        rk4(s0, dt, self.substeps(dt), |s| WithMatrix {
            x: self.drift(&s.x),
            m: self.drift_jacobian(&s.x) * s.m,
        })
        .m
    }

    /// RK4 on `(ẋ, Q̇) = (a(x), A Q + Q Aᵀ + Q_c)`, `Q(0) = 0`, symmetrised.
    #[allow(non_snake_case)]
    fn process_noise(&self, x: &Vector<4>, dt: f64) -> Matrix<4, 4> {
        let Qc = self.diffusion();
        let s0 = WithMatrix {
            x: *x,
            m: Matrix::<4, 4>::zeros(),
        };
        let q = rk4(s0, dt, self.substeps(dt), |s| {
            let A = self.drift_jacobian(&s.x);
            let AQ = A * s.m;
            WithMatrix {
                x: self.drift(&s.x),
                m: AQ + AQ.transpose() + Qc,
            }
        })
        .m;
        (q + q.transpose()) * 0.5
    }

    /// RK4 on the second-order variational equation (module docs): the exact Hessians of
    /// the RK4 map.
    #[allow(non_snake_case)]
    fn hessians(&self, x: &Vector<4>, dt: f64) -> Option<[Matrix<4, 4>; 4]> {
        let s0 = WithHessians {
            x: *x,
            phi: Matrix::<4, 4>::identity(),
            hess: [Matrix::<4, 4>::zeros(); 4],
        };
        let out = rk4(s0, dt, self.substeps(dt), |s| {
            let A = self.drift_jacobian(&s.x);
            let Ha = self.drift_hessians(&s.x);
            let mut hess = [Matrix::<4, 4>::zeros(); 4];
            for (i, hi) in hess.iter_mut().enumerate() {
                let mut acc = s.phi.transpose() * Ha[i] * s.phi;
                for (j, tj) in s.hess.iter().enumerate() {
                    acc += tj * A[(i, j)];
                }
                *hi = acc;
            }
            WithHessians {
                x: self.drift(&s.x),
                phi: A * s.phi,
                hess,
            }
        });
        let mut h = out.hess;
        for m in &mut h {
            *m = (*m + m.transpose()) * 0.5;
        }
        Some(h)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Cv2D, LinearMotionModel};

    #[test]
    fn one_dimensional_closed_form() {
        // 1-D quadratic drag v̇ = −α v|v|: v(t) = v0/(1 + α v0 t), x(t) = x0 + ln(1 + α v0 t)/α.
        // α = 1e-3 /m, v0 = 100 m/s, t = 20 s: v = 100/3, x − x0 = 1000 ln 3.
        // RK4 with h = 0.1 s (α v h ≤ 0.01): global error ≈ 1e-9 relative, bound 1e-8.
        let m = QuadraticDrag::new(1e-3, 0.0).unwrap();
        let y = m.propagate(&Vector::<4>::new(50.0, 100.0, 0.0, 0.0), 20.0);
        let v = 100.0 / 3.0;
        let x = 50.0 + 1000.0 * 3.0_f64.ln();
        assert!((y[1] - v).abs() < 1e-8 * v, "{} vs {v}", y[1]);
        assert!((y[0] - x).abs() < 1e-8 * x, "{} vs {x}", y[0]);
        assert!(y[2].abs() < 1e-300 && y[3].abs() < 1e-300);
    }

    #[test]
    fn no_drag_equals_cv_continuous() {
        // α = 0: the model is CV with CWNA of density q. RK4 is exact here (the solutions
        // are polynomials of degree ≤ 3), so Φ and Q agree to rounding.
        let m = QuadraticDrag::new(0.0, 6.0).unwrap();
        let cv = Cv2D::continuous(6.0).unwrap();
        let x = Vector::<4>::new(1e4, 20.0, -3e3, -5.0);
        for dt in [0.05, 1.0, 3.3] {
            assert!((m.jacobian(&x, dt) - cv.transition(dt)).abs().max() < 1e-12);
            let q_cv = cv.process_noise(&x, dt);
            assert!((m.process_noise(&x, dt) - q_cv).abs().max() < 1e-12 * q_cv.abs().max());
            assert!((m.propagate(&x, dt) - cv.propagate(&x, dt)).abs().max() < 1e-9);
        }
    }

    #[test]
    fn input_accelerates() {
        // α = 0, u = (2, −1) m/s² for 3 s from rest: displacement u t²/2 = (9, −4.5),
        // velocity u t = (6, −3) (exact for RK4: quadratic solution).
        let m = QuadraticDrag::new(0.0, 0.0)
            .unwrap()
            .with_input(Vector::<2>::new(2.0, -1.0))
            .unwrap();
        let y = m.propagate(&Vector::<4>::zeros(), 3.0);
        assert!((y - Vector::<4>::new(9.0, 6.0, -4.5, -3.0)).abs().max() < 1e-12);
    }

    #[test]
    fn zero_speed_is_regular() {
        let m = QuadraticDrag::new(1e-3, 1.0).unwrap();
        let x = Vector::<4>::new(1.0, 0.0, 2.0, 0.0);
        let a = m.drift_jacobian(&x);
        assert!(a.iter().all(|v| v.is_finite()));
        assert!(
            m.drift_hessians(&x)
                .iter()
                .all(|h| h.abs().max() < f64::MIN_POSITIVE)
        );
        assert!(m.process_noise(&x, 1.0).iter().all(|v| v.is_finite()));
    }

    #[test]
    fn rejects_bad_parameters() {
        assert!(matches!(
            QuadraticDrag::new(-1e-3, 0.0),
            Err(MotionError::Negative { what: "alpha", .. })
        ));
        let m = QuadraticDrag::new(1e-3, 0.0).unwrap();
        assert!(matches!(
            m.with_max_step(0.0),
            Err(MotionError::NotPositive {
                what: "max_step",
                ..
            })
        ));
        assert!(matches!(
            m.with_input(Vector::<2>::new(f64::NAN, 0.0)),
            Err(MotionError::NonFinite { .. })
        ));
    }
}

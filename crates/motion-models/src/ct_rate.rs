//! Coordinated turn with the turn rate as a fifth state, `[x, vx, y, vy, ω]`.
//!
//! With `θ = ωT`, `S(θ) = sin θ/θ` and `C(θ) = (1 − cos θ)/θ`, the transition is
//!
//! ```text
//! x'  = x + T S vx − T C vy
//! vx' = cos θ vx − sin θ vy
//! y'  = y + T C vx + T S vy
//! vy' = sin θ vx + cos θ vy
//! ω'  = ω
//! ```
//!
//! The Jacobian's last column is
//!
//! ```text
//! ∂x'/∂ω  = T² (S' vx − C' vy)        ∂vx'/∂ω = −T (sin θ vx + cos θ vy)
//! ∂y'/∂ω  = T² (C' vx + S' vy)        ∂vy'/∂ω =  T (cos θ vx − sin θ vy)
//! ```
//!
//! with `S'`, `C'` the `θ`-derivatives; at `ω → 0` they tend to `S' → 0`, `C' → 1/2`
//! (so `∂x'/∂ω → −T² vy/2`, `∂y'/∂ω → T² vx/2`), evaluated by series near 0. The map is
//! bilinear in the velocity and the trigonometric functions of `ω`, so the only non-zero
//! second derivatives are the mixed `∂²/∂v∂ω` and `∂²/∂ω²` ones (see
//! [`CoordinatedTurnRate`]'s `hessians`).
//!
//! Process noise: the linear accelerations are discrete white noise of standard
//! deviation `σ_a` (seed 000's `Γ`) and the turn rate a discrete Wiener process,
//! `ω_{k+1} = ω_k + T w_ω`, `w_ω ~ N(0, σ_ω²)` (σ_ω in rad/s²):
//! `Q = diag(σ_a² Γ Γᵀ, σ_ω² T²)`.
//!
//! # References
//! Bar-Shalom, Li & Kirubarajan (2001) §11.7.2 (coordinated turn with unknown rate,
//! the rate augmented to the state); seed 000 for `Γ`.

use argus_core_math::{Matrix, Vector};

use crate::MotionModel;
use crate::cv::CvNoise;
use crate::error::{MotionError, check_non_negative};
use crate::turn::turn_coeffs;

/// Coordinated turn with the rate as a state, `[x, vx, y, vy, ω]` (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoordinatedTurnRate {
    sigma_a: f64,
    sigma_omega: f64,
}

impl CoordinatedTurnRate {
    /// A turn model with linear-acceleration noise `sigma_a` (m/s²) and turn-rate noise
    /// `sigma_omega` (rad/s²).
    ///
    /// # Errors
    /// [`MotionError::NonFinite`] or [`MotionError::Negative`] when either standard
    /// deviation is NaN, infinite or negative.
    pub fn new(sigma_a: f64, sigma_omega: f64) -> Result<Self, MotionError> {
        Ok(Self {
            sigma_a: check_non_negative("sigma_a", sigma_a)?,
            sigma_omega: check_non_negative("sigma_omega", sigma_omega)?,
        })
    }

    /// The linear-acceleration noise standard deviation, m/s².
    #[must_use]
    pub fn sigma_a(&self) -> f64 {
        self.sigma_a
    }

    /// The turn-rate noise standard deviation, rad/s².
    #[must_use]
    pub fn sigma_omega(&self) -> f64 {
        self.sigma_omega
    }
}

impl MotionModel<5> for CoordinatedTurnRate {
    fn propagate(&self, x: &Vector<5>, dt: f64) -> Vector<5> {
        let (vx, vy, omega) = (x[1], x[3], x[4]);
        let k = turn_coeffs(omega * dt);
        let (ts, tc) = (dt * k.s, dt * k.c);
        Vector::<5>::new(
            x[0] + ts * vx - tc * vy,
            k.cos * vx - k.sin * vy,
            x[2] + tc * vx + ts * vy,
            k.sin * vx + k.cos * vy,
            omega,
        )
    }

    #[allow(non_snake_case)]
    fn jacobian(&self, x: &Vector<5>, dt: f64) -> Matrix<5, 5> {
        let (vx, vy, omega) = (x[1], x[3], x[4]);
        let k = turn_coeffs(omega * dt);
        let (ts, tc) = (dt * k.s, dt * k.c);
        let t2 = dt * dt;
        #[rustfmt::skip]
        let F = Matrix::<5, 5>::new(
            1.0, ts,    0.0, -tc,    t2 * (k.ds * vx - k.dc * vy),
            0.0, k.cos, 0.0, -k.sin, -dt * (k.sin * vx + k.cos * vy),
            0.0, tc,    1.0, ts,     t2 * (k.dc * vx + k.ds * vy),
            0.0, k.sin, 0.0, k.cos,  dt * (k.cos * vx - k.sin * vy),
            0.0, 0.0,   0.0, 0.0,    1.0,
        );
        F
    }

    /// `Q = diag(σ_a² Γ Γᵀ, σ_ω² T²)` (module docs), independent of the state.
    fn process_noise(&self, _x: &Vector<5>, dt: f64) -> Matrix<5, 5> {
        let block = CvNoise::DiscreteWhiteAcceleration {
            sigma_a: self.sigma_a,
        }
        .axis_covariance(dt);
        let mut q = Matrix::<5, 5>::zeros();
        q.fixed_view_mut::<2, 2>(0, 0).copy_from(&block);
        q.fixed_view_mut::<2, 2>(2, 2).copy_from(&block);
        q[(4, 4)] = self.sigma_omega * self.sigma_omega * dt * dt;
        q
    }

    /// Exact Hessians `∂²fᵢ/∂x²` (state order `[x, vx, y, vy, ω]`, indices 0–4):
    ///
    /// ```text
    /// x':  ∂²/∂vx∂ω = T² S',     ∂²/∂vy∂ω = −T² C',    ∂²/∂ω² = T³ (S'' vx − C'' vy)
    /// vx': ∂²/∂vx∂ω = −T sin θ,  ∂²/∂vy∂ω = −T cos θ,  ∂²/∂ω² = −T² (cos θ vx − sin θ vy)
    /// y':  ∂²/∂vx∂ω = T² C',     ∂²/∂vy∂ω = T² S',     ∂²/∂ω² = T³ (C'' vx + S'' vy)
    /// vy': ∂²/∂vx∂ω = T cos θ,   ∂²/∂vy∂ω = −T sin θ,  ∂²/∂ω² = −T² (sin θ vx + cos θ vy)
    /// ω':  0
    /// ```
    fn hessians(&self, x: &Vector<5>, dt: f64) -> Option<[Matrix<5, 5>; 5]> {
        let (vx, vy, omega) = (x[1], x[3], x[4]);
        let k = turn_coeffs(omega * dt);
        let t2 = dt * dt;
        let t3 = t2 * dt;
        // (∂²/∂vx∂ω, ∂²/∂vy∂ω, ∂²/∂ω²) per output component.
        let rows = [
            (t2 * k.ds, -t2 * k.dc, t3 * (k.dds * vx - k.ddc * vy)),
            (-dt * k.sin, -dt * k.cos, -t2 * (k.cos * vx - k.sin * vy)),
            (t2 * k.dc, t2 * k.ds, t3 * (k.ddc * vx + k.dds * vy)),
            (dt * k.cos, -dt * k.sin, -t2 * (k.sin * vx + k.cos * vy)),
        ];
        let mut h = [Matrix::<5, 5>::zeros(); 5];
        for (hi, (dvx, dvy, dww)) in h.iter_mut().zip(rows) {
            hi[(1, 4)] = dvx;
            hi[(4, 1)] = dvx;
            hi[(3, 4)] = dvy;
            hi[(4, 3)] = dvy;
            hi[(4, 4)] = dww;
        }
        Some(h)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ct::ct_transition;

    #[test]
    fn matches_known_rate_model() {
        // With ω in the state the position/velocity part equals the known-rate transition.
        let omega = -2.5_f64.to_radians();
        let x = Vector::<5>::new(-6.0e4, 90.0, -2.0e4, 3.0, omega);
        let m = CoordinatedTurnRate::new(0.5, 0.01).unwrap();
        let y = m.propagate(&x, 4.7);
        let y4 = ct_transition(omega, 4.7) * x.fixed_rows::<4>(0);
        assert!((y.fixed_rows::<4>(0) - y4).abs().max() < 1e-9);
        assert!((y[4] - omega).abs() < f64::EPSILON);
    }

    #[test]
    fn omega_column_limit_at_zero() {
        // At ω = 0: ∂x'/∂ω = −T² vy/2, ∂y'/∂ω = T² vx/2, ∂vx'/∂ω = −T vy, ∂vy'/∂ω = T vx
        // (derived from the series, module docs).
        let (vx, vy, t) = (100.0, -40.0, 5.0);
        let m = CoordinatedTurnRate::new(1.0, 0.1).unwrap();
        let j = m.jacobian(&Vector::<5>::new(1.0, vx, 2.0, vy, 0.0), t);
        let expect = Vector::<5>::new(-t * t * vy / 2.0, -t * vy, t * t * vx / 2.0, t * vx, 1.0);
        assert!((j.column(4) - expect).abs().max() < 1e-12);
    }

    #[test]
    fn process_noise_layout() {
        // σ_a = 2, σ_ω = 0.1, T = 2: position variance σ_a² T⁴/4 = 16, ω variance 0.04.
        let m = CoordinatedTurnRate::new(2.0, 0.1).unwrap();
        let q = m.process_noise(&Vector::<5>::zeros(), 2.0);
        assert!((q[(0, 0)] - 16.0).abs() < 1e-12);
        assert!((q[(2, 2)] - 16.0).abs() < 1e-12);
        assert!((q[(4, 4)] - 0.04).abs() < 1e-15);
        assert!(q[(0, 2)].abs() < 1e-15 && q[(0, 4)].abs() < 1e-15);
    }
}

//! Coordinated turn with a known turn rate, state `[x, vx, y, vy]`.
//!
//! The target moves at constant speed on a circle with the known rate `ω` (rad/s,
//! `ω > 0` counter-clockwise). With `θ = ωT`, the exact transition is
//!
//! ```text
//! F(T) = [[1, sin θ/ω,       0, −(1 − cos θ)/ω],
//!         [0, cos θ,         0, −sin θ        ],
//!         [0, (1 − cos θ)/ω, 1, sin θ/ω       ],
//!         [0, sin θ,         0, cos θ         ]]
//! ```
//!
//! and `F → ` the CV transition as `ω → 0` (exactly equal at `ω = 0`; the ratios are
//! evaluated by series near 0, never as 0/0). The process noise is the discrete white
//! acceleration of seed 000: `Q = σv² Γ Γᵀ`, `Γ = [[T²/2, 0], [T, 0], [0, T²/2], [0, T]]`
//! (not rotated with the turn).
//!
//! # References
//! Seed 000 (Jeon et al. 2010), the CT models of the IMM (`ω = ±3 deg/s`,
//! `σv = 0.5 m/s²`); Bar-Shalom, Li & Kirubarajan (2001) §11.7.1 (coordinated turn with a
//! known rate).

use argus_core_math::{Matrix, Vector};

use crate::block::block_diag;
use crate::cv::CvNoise;
use crate::error::{MotionError, check_finite, check_non_negative};
use crate::turn::turn_sc;
use crate::{LinearMotionModel, MotionModel};

/// Coordinated turn at a known rate, state `[x, vx, y, vy]` (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoordinatedTurn {
    omega: f64,
    sigma_v: f64,
}

impl CoordinatedTurn {
    /// A turn at `omega` rad/s (positive counter-clockwise) with white acceleration noise
    /// of standard deviation `sigma_v` (m/s²).
    ///
    /// # Errors
    /// [`MotionError::NonFinite`] when `omega` or `sigma_v` is NaN or infinite,
    /// [`MotionError::Negative`] when `sigma_v < 0`.
    pub fn new(omega: f64, sigma_v: f64) -> Result<Self, MotionError> {
        Ok(Self {
            omega: check_finite("omega", omega)?,
            sigma_v: check_non_negative("sigma_v", sigma_v)?,
        })
    }

    /// A turn given in degrees per second (positive counter-clockwise).
    ///
    /// # Errors
    /// As [`Self::new`].
    pub fn from_degrees_per_second(omega_deg: f64, sigma_v: f64) -> Result<Self, MotionError> {
        Self::new(omega_deg.to_radians(), sigma_v)
    }

    /// The turn rate, rad/s.
    #[must_use]
    pub fn omega(&self) -> f64 {
        self.omega
    }

    /// The acceleration noise standard deviation, m/s².
    #[must_use]
    pub fn sigma_v(&self) -> f64 {
        self.sigma_v
    }

    /// `(F x, F P Fᵀ)` with `F` formed once, plus `axis_noise` on the two diagonal blocks
    /// when given: added to the lower triangle, then mirrored once (the mirror's stores last).
    #[inline(always)]
    fn moments(
        &self,
        x: &Vector<4>,
        p: &Matrix<4, 4>,
        dt: f64,
        axis_noise: Option<Matrix<2, 2>>,
    ) -> (Vector<4>, Matrix<4, 4>) {
        let f = ct_columns(self.omega, dt);
        let mut cov = ct_congruence_lower(&f, p);
        if let Some(q) = axis_noise {
            for k in [0, 2] {
                for c in 0..2 {
                    for r in c..2 {
                        cov[(k + r, k + c)] += q[(r, c)];
                    }
                }
            }
        }
        argus_core_math::kernels::mirror_lower(&mut cov);
        (Vector::<4>::from(ct_apply(&f, &x.data.0[0])), cov)
    }

    /// The per-axis DWNA block `σv² [[T⁴/4, T³/2], [T³/2, T²]]` of `Q = σv² Γ Γᵀ`.
    #[inline]
    fn axis_noise(&self, dt: f64) -> Matrix<2, 2> {
        CvNoise::DiscreteWhiteAcceleration {
            sigma_a: self.sigma_v,
        }
        .axis_covariance(dt)
    }
}

/// The exact CT transition over `dt` at the rate `omega` (module docs).
#[must_use]
#[inline]
pub fn ct_transition(omega: f64, dt: f64) -> Matrix<4, 4> {
    let [f1, f3] = ct_columns(omega, dt);
    Matrix::<4, 4>::from_data(nalgebra::ArrayStorage([
        [1.0, 0.0, 0.0, 0.0],
        f1,
        [0.0, 0.0, 1.0, 0.0],
        f3,
    ]))
}

/// Columns 1 and 3 of [`ct_transition`] (columns 0 and 2 are `e₀` and `e₂`), as arrays the
/// structured products use directly (a 4 × 4 matrix stored entry by entry and read back
/// in pairs stalls on store forwarding).
#[inline]
fn ct_columns(omega: f64, dt: f64) -> [[f64; 4]; 2] {
    let (sin, cos, s, c) = turn_sc(omega * dt);
    let ts = dt * s;
    let tc = dt * c;
    [[ts, cos, tc, sin], [-tc, -sin, ts, cos]]
}

/// `F m` for the CT transition with columns `f = [F₁, F₃]`: `e₀ m₀ + e₂ m₂ + F₁ m₁ + F₃ m₃`.
#[inline(always)]
fn ct_apply(f: &[[f64; 4]; 2], m: &[f64; 4]) -> [f64; 4] {
    let mut out = [0.0; 4];
    for (r, o) in out.iter_mut().enumerate() {
        *o = f[0][r] * m[1] + f[1][r] * m[3];
    }
    out[0] += m[0];
    out[2] += m[2];
    out
}

/// `F P Fᵀ` for a CT transition `F` (columns 0 and 2 are the unit vectors `e₀`, `e₂`): column
/// `c` of `F P` is `F₁ P(1, c) + F₃ P(3, c)` plus `P(0, c)` and `P(2, c)` in rows 0 and 2,
/// and likewise for `(F P) Fᵀ`; about 64 multiply-adds instead of 128 for two full
/// products. Only the lower triangle is meant: callers add to it and then mirror it (the
/// exact result is symmetric). `B` is still computed in whole columns: restricted to the
/// triangle it took more instructions, not fewer (the columns vectorise in pairs).
#[inline]
fn ct_congruence_lower(f: &[[f64; 4]; 2], p: &Matrix<4, 4>) -> Matrix<4, 4> {
    let p = &p.data.0;
    // A = F P, column by column.
    let mut a = [[0.0; 4]; 4];
    for (ac, pc) in a.iter_mut().zip(p) {
        *ac = ct_apply(f, pc);
    }
    // B = A Fᵀ: column j is Σ_k A_k F(j, k) = δ_{j0} A₀ + δ_{j2} A₂ + A₁ F(j, 1) + A₃ F(j, 3).
    let mut b = [[0.0; 4]; 4];
    for (j, bj) in b.iter_mut().enumerate() {
        for (r, v) in bj.iter_mut().enumerate() {
            *v = a[1][r] * f[0][j] + a[3][r] * f[1][j];
        }
        if j == 0 || j == 2 {
            for (v, &x) in bj.iter_mut().zip(&a[j]) {
                *v += x;
            }
        }
    }
    Matrix::<4, 4>::from_data(nalgebra::ArrayStorage(b))
}

impl MotionModel<4> for CoordinatedTurn {
    fn propagate(&self, x: &Vector<4>, dt: f64) -> Vector<4> {
        Vector::<4>::from(ct_apply(&ct_columns(self.omega, dt), &x.data.0[0]))
    }

    fn jacobian(&self, _x: &Vector<4>, dt: f64) -> Matrix<4, 4> {
        ct_transition(self.omega, dt)
    }

    /// `F` (with its sine and cosine) formed once for the mean and the covariance.
    #[inline(always)]
    fn propagate_with_covariance(
        &self,
        x: &Vector<4>,
        p: &Matrix<4, 4>,
        dt: f64,
    ) -> (Vector<4>, Matrix<4, 4>) {
        self.moments(x, p, dt, None)
    }

    /// `F` formed once; the DWNA noise added on the two diagonal blocks.
    #[inline(always)]
    fn predict_moments(
        &self,
        x: &Vector<4>,
        p: &Matrix<4, 4>,
        dt: f64,
    ) -> (Vector<4>, Matrix<4, 4>) {
        self.moments(x, p, dt, Some(self.axis_noise(dt)))
    }

    /// `Q = σv² Γ Γᵀ` (seed 000), independent of the state.
    fn process_noise(&self, _x: &Vector<4>, dt: f64) -> Matrix<4, 4> {
        block_diag::<4, 2>(&self.axis_noise(dt))
    }

    /// The transition is linear in the state: all Hessians are zero.
    fn hessians(&self, _x: &Vector<4>, _dt: f64) -> Option<[Matrix<4, 4>; 4]> {
        Some([Matrix::<4, 4>::zeros(); 4])
    }
}

impl LinearMotionModel<4> for CoordinatedTurn {
    fn transition(&self, dt: f64) -> Matrix<4, 4> {
        ct_transition(self.omega, dt)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Cv2D;

    #[test]
    fn quarter_turn_lands_on_circle() {
        // ω = π/20 rad/s for T = 10 s: a quarter turn counter-clockwise. Start at the origin
        // heading +x at 100 m/s; radius r = v/ω = 2000/π m; end at (r, r) heading +y.
        let omega = std::f64::consts::PI / 20.0;
        let m = CoordinatedTurn::new(omega, 0.0).unwrap();
        let y = m.propagate(&Vector::<4>::new(0.0, 100.0, 0.0, 0.0), 10.0);
        let r = 100.0 / omega;
        let expect = Vector::<4>::new(r, 0.0, r, 100.0);
        assert!((y - expect).abs().max() < 1e-10 * r);
    }

    #[test]
    fn equals_cv_at_zero_rate() {
        // Exact equality, not approximate: at ω = 0 the series give S = 1, C = 0.
        let ct = CoordinatedTurn::new(0.0, 0.5).unwrap();
        let cv = Cv2D::discrete(0.5).unwrap();
        for dt in [0.1, 1.0, 5.0, 37.5] {
            assert_eq!(ct.transition(dt), cv.transition(dt));
            let x = Vector::<4>::zeros();
            assert_eq!(ct.process_noise(&x, dt), cv.process_noise(&x, dt));
        }
    }

    #[test]
    fn seed000_gamma_form() {
        // Q = σv² Γ Γᵀ with Γ = [[T²/2,0],[T,0],[0,T²/2],[0,T]] (seed 000), σv = 0.5, T = 5.
        let m = CoordinatedTurn::from_degrees_per_second(3.0, 0.5).unwrap();
        let t = 5.0;
        #[rustfmt::skip]
        let gamma = Matrix::<4, 2>::new(
            t * t / 2.0, 0.0,
            t,           0.0,
            0.0,         t * t / 2.0,
            0.0,         t,
        );
        let expect = gamma * gamma.transpose() * 0.25;
        let q = m.process_noise(&Vector::<4>::zeros(), t);
        assert!((q - expect).abs().max() < 1e-12);
    }

    #[test]
    fn rejects_bad_parameters() {
        assert!(matches!(
            CoordinatedTurn::new(f64::NAN, 1.0),
            Err(MotionError::NonFinite { what: "omega", .. })
        ));
        assert!(matches!(
            CoordinatedTurn::new(0.1, -1.0),
            Err(MotionError::Negative {
                what: "sigma_v",
                ..
            })
        ));
    }
}

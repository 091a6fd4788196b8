//! Constant-velocity (CV) models in one, two and three dimensions.
//!
//! Per axis the state is `[p, v]` and
//!
//! ```text
//! F(T) = [[1, T],
//!         [0, 1]]
//! ```
//!
//! The axes are stacked in the interleaved order `[x, vx]`, `[x, vx, y, vy]`,
//! `[x, vx, y, vy, z, vz]`, so `F` and `Q` are block diagonal with one `2 × 2`
//! block per axis. Three process-noise models are offered by [`CvNoise`]
//! (the third, velocity-only per step, is seed 001's `Q = diag(0, q)`).
//!
//! # References
//! Bar-Shalom, Li & Kirubarajan (2001), *Estimation with Applications to Tracking and
//! Navigation*, §6.2.2 (continuous white-noise acceleration) and §6.3.2 (discrete
//! white-noise acceleration). Seed 000 (Jeon et al. 2010)
//! and seed 003 (Kim & Hwang 2013) use the discrete model; seed 004 (Kim et al. 2011) the
//! continuous one ("DCWNA", `q̃ = 6 m²/s³`).

use argus_core_math::Matrix;

use crate::block::impl_block_model;
use crate::error::{MotionError, check_non_negative};

/// Process noise of a constant-velocity model, the same on every axis.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum CvNoise {
    /// Discrete white-noise acceleration (DWNA): the acceleration is constant over each
    /// interval with standard deviation `sigma_a` (m/s²), `Q = σ² Γ Γᵀ`,
    /// `Γ = [T²/2, T]ᵀ` per axis:
    ///
    /// ```text
    /// Q = σ² [[T⁴/4, T³/2],
    ///         [T³/2, T² ]]
    /// ```
    DiscreteWhiteAcceleration {
        /// Standard deviation of the acceleration, m/s².
        sigma_a: f64,
    },
    /// Continuous white-noise acceleration (CWNA) of power spectral density `q_tilde`
    /// (m²/s³), discretised exactly:
    ///
    /// ```text
    /// Q = q̃ [[T³/3, T²/2],
    ///        [T²/2, T   ]]
    /// ```
    ContinuousWhiteAcceleration {
        /// Power spectral density of the acceleration, m²/s³.
        q_tilde: f64,
    },
    /// Velocity-only noise of variance `q` ((m/s)²) per step, whatever the interval
    /// (seed 001 §5.1: `Q = 0.5` entering the velocity through `G = diag(0, 1)`):
    ///
    /// ```text
    /// Q = [[0, 0],
    ///      [0, q]]
    /// ```
    ///
    /// Only positive semi-definite: a filter must get its positive definiteness from the
    /// prior and the plots.
    VelocityPerStep {
        /// Variance of the velocity increment per step, (m/s)².
        q: f64,
    },
}

impl CvNoise {
    /// Checks that the intensity is finite and non-negative.
    fn validate(self) -> Result<Self, MotionError> {
        match self {
            Self::DiscreteWhiteAcceleration { sigma_a } => {
                check_non_negative("sigma_a", sigma_a)?;
            }
            Self::ContinuousWhiteAcceleration { q_tilde } => {
                check_non_negative("q_tilde", q_tilde)?;
            }
            Self::VelocityPerStep { q } => {
                check_non_negative("q", q)?;
            }
        }
        Ok(self)
    }

    /// The `2 × 2` per-axis covariance over `dt` (see the variants for the formulas).
    /// Not validated here: the model constructors reject negative or non-finite intensities.
    #[must_use]
    #[inline]
    pub fn axis_covariance(&self, dt: f64) -> Matrix<2, 2> {
        let t2 = dt * dt;
        let t3 = t2 * dt;
        match *self {
            Self::DiscreteWhiteAcceleration { sigma_a } => {
                let s2 = sigma_a * sigma_a;
                Matrix::<2, 2>::new(t2 * t2 / 4.0, t3 / 2.0, t3 / 2.0, t2) * s2
            }
            Self::ContinuousWhiteAcceleration { q_tilde } => {
                Matrix::<2, 2>::new(t3 / 3.0, t2 / 2.0, t2 / 2.0, dt) * q_tilde
            }
            Self::VelocityPerStep { q } => Matrix::<2, 2>::new(0.0, 0.0, 0.0, q),
        }
    }
}

/// The per-axis CV transition `[[1, T], [0, 1]]`.
#[must_use]
#[inline]
pub fn cv_axis_transition(dt: f64) -> Matrix<2, 2> {
    Matrix::<2, 2>::new(1.0, dt, 0.0, 1.0)
}

macro_rules! cv_model {
    ($(#[$doc:meta])* $name:ident, $n:literal) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub struct $name {
            noise: CvNoise,
        }

        impl $name {
            /// A constant-velocity model with the given process noise.
            ///
            /// # Errors
            /// [`MotionError::NonFinite`] or [`MotionError::Negative`] when the noise
            /// intensity is NaN, infinite or negative.
            pub fn new(noise: CvNoise) -> Result<Self, MotionError> {
                Ok(Self { noise: noise.validate()? })
            }

            /// Discrete white-noise acceleration with standard deviation `sigma_a` (m/s²).
            ///
            /// # Errors
            /// As [`Self::new`].
            pub fn discrete(sigma_a: f64) -> Result<Self, MotionError> {
                Self::new(CvNoise::DiscreteWhiteAcceleration { sigma_a })
            }

            /// Continuous white-noise acceleration with spectral density `q_tilde` (m²/s³).
            ///
            /// # Errors
            /// As [`Self::new`].
            pub fn continuous(q_tilde: f64) -> Result<Self, MotionError> {
                Self::new(CvNoise::ContinuousWhiteAcceleration { q_tilde })
            }

            /// Velocity-only noise of variance `q` ((m/s)²) per step (seed 001 §5.1).
            ///
            /// # Errors
            /// As [`Self::new`].
            pub fn velocity_per_step(q: f64) -> Result<Self, MotionError> {
                Self::new(CvNoise::VelocityPerStep { q })
            }

            /// The process-noise model.
            #[must_use]
            pub fn noise(&self) -> CvNoise {
                self.noise
            }

            #[inline]
            fn axis_transition(dt: f64) -> Matrix<2, 2> {
                cv_axis_transition(dt)
            }

            #[inline]
            fn axis_noise(&self, dt: f64) -> Matrix<2, 2> {
                self.noise.axis_covariance(dt)
            }

            /// `A M Aᵀ` for one `2 × 2` block `M` of `P`, `A = [[1, T], [0, 1]]`, in closed
            /// form: `[[m₀₀ + T m₁₀ + T r₀₁, r₀₁], [m₁₀ + T m₁₁, m₁₁]]` with
            /// `r₀₁ = m₀₁ + T m₁₁` (five multiply-adds instead of two 2 × 2 products).
            #[inline]
            fn axis_congruence(dt: f64, m: &Matrix<2, 2>) -> Matrix<2, 2> {
                let r01 = m[(0, 1)] + dt * m[(1, 1)];
                let r10 = m[(1, 0)] + dt * m[(1, 1)];
                Matrix::<2, 2>::new(m[(0, 0)] + dt * m[(1, 0)] + dt * r01, r01, r10, m[(1, 1)])
            }
        }

        impl_block_model!($name, $n, 2);
    };
}

cv_model!(
    /// Constant velocity on one axis, state `[x, vx]` (N = 2).
    ///
    /// `F = [[1, T], [0, 1]]`, `Q` from [`CvNoise`].
    ///
    /// # References
    /// Bar-Shalom, Li & Kirubarajan (2001) §6.2.2, §6.3.2; seed 001's scenario "maneuver-1d".
    Cv1D,
    2
);
cv_model!(
    /// Constant velocity in the plane, state `[x, vx, y, vy]` (N = 4).
    ///
    /// `F = diag(F₁, F₁)`, `F₁ = [[1, T], [0, 1]]`; `Q = diag(Q₁, Q₁)` from [`CvNoise`]
    /// (for the discrete model this is `σ² Γ Γᵀ` with
    /// `Γ = [[T²/2, 0], [T, 0], [0, T²/2], [0, T]]`, seed 000).
    ///
    /// # References
    /// Seed 000 (Jeon et al. 2010), the CV model of its IMM; seed 004 (Kim et al. 2011), the
    /// local filters; Bar-Shalom, Li & Kirubarajan (2001) §6.2.2, §6.3.2.
    Cv2D,
    4
);
cv_model!(
    /// Constant velocity in space, state `[x, vx, y, vy, z, vz]` (N = 6).
    ///
    /// `F = diag(F₁, F₁, F₁)`, `F₁ = [[1, T], [0, 1]]`; `Q = diag(Q₁, Q₁, Q₁)` from [`CvNoise`].
    ///
    /// # References
    /// Seed 003 (Kim & Hwang 2013), the decoupled filter's CV model; seed 002 (Shin et al.);
    /// Bar-Shalom, Li & Kirubarajan (2001) §6.2.2, §6.3.2.
    Cv3D,
    6
);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{LinearMotionModel, MotionModel};
    use argus_core_math::Vector;

    #[test]
    fn discrete_q_closed_form() {
        // Bar-Shalom et al. (2001) §6.3.2 (DWNA) with σ = 2, T = 3:
        // σ²·[T⁴/4, T³/2; T³/2, T²] = 4·[81/4, 27/2; 27/2, 9] = [81, 54; 54, 36].
        let m = Cv1D::discrete(2.0).unwrap();
        let q = m.process_noise(&Vector::<2>::zeros(), 3.0);
        let expect = Matrix::<2, 2>::new(81.0, 54.0, 54.0, 36.0);
        assert!((q - expect).abs().max() < 1e-12);
        // Equals σ² Γ Γᵀ with Γ = [T²/2, T]ᵀ (seed 000, seed 003).
        let g = Vector::<2>::new(4.5, 3.0);
        assert!((q - g * g.transpose() * 4.0).abs().max() < 1e-12);
    }

    #[test]
    fn velocity_per_step_q() {
        // Seed 001 §5.1: Q = diag(0, 0.5) per step, independent of T (here T = 0.05 and 3).
        let m = Cv1D::velocity_per_step(0.5).unwrap();
        for dt in [0.05, 3.0] {
            let q = m.process_noise(&Vector::<2>::zeros(), dt);
            assert!((q - Matrix::<2, 2>::new(0.0, 0.0, 0.0, 0.5)).abs().max() < 1e-15);
        }
        let q2 = Cv2D::velocity_per_step(0.5)
            .unwrap()
            .process_noise(&Vector::<4>::zeros(), 1.0);
        assert!(
            (q2 - Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(0.0, 0.5, 0.0, 0.5)))
                .abs()
                .max()
                < 1e-15
        );
        assert!(matches!(
            Cv1D::velocity_per_step(-1.0),
            Err(MotionError::Negative { .. })
        ));
        assert!(Cv1D::velocity_per_step(f64::NAN).is_err());
    }

    #[test]
    fn continuous_q_closed_form() {
        // Bar-Shalom et al. (2001) §6.2.2 (CWNA) with q̃ = 6 (seed 004), T = 2:
        // 6·[8/3, 2; 2, 2] = [16, 12; 12, 12].
        let m = Cv2D::continuous(6.0).unwrap();
        let q = m.process_noise(&Vector::<4>::zeros(), 2.0);
        let block = Matrix::<2, 2>::new(16.0, 12.0, 12.0, 12.0);
        assert!((q.fixed_view::<2, 2>(0, 0) - block).abs().max() < 1e-12);
        assert!((q.fixed_view::<2, 2>(2, 2) - block).abs().max() < 1e-12);
        assert!(q.fixed_view::<2, 2>(0, 2).abs().max() < 1e-15);
    }

    #[test]
    fn continuous_q_is_integral_of_transition() {
        // Q = ∫₀ᵀ F(s) [0,0;0,q̃] F(s)ᵀ ds; midpoint rule with 20 000 panels, error O(h²)
        // relative ≈ 1e-9.
        let (q_tilde, t) = (0.7_f64, 4.0_f64);
        let n = 20_000;
        let h = t / f64::from(n);
        let mut acc = Matrix::<2, 2>::zeros();
        for i in 0..n {
            let s = (f64::from(i) + 0.5) * h;
            let g = Vector::<2>::new(s, 1.0);
            acc += g * g.transpose() * (q_tilde * h);
        }
        let q = CvNoise::ContinuousWhiteAcceleration { q_tilde }.axis_covariance(t);
        assert!((q - acc).abs().max() < 1e-8 * q.abs().max());
    }

    #[test]
    fn cv3d_transition_moves_each_axis() {
        let m = Cv3D::discrete(1.0).unwrap();
        let x = Vector::<6>::from_column_slice(&[1.0, 2.0, 3.0, -4.0, 5.0, 0.5]);
        let y = m.propagate(&x, 2.0);
        let expect = Vector::<6>::from_column_slice(&[5.0, 2.0, -5.0, -4.0, 6.0, 0.5]);
        assert!((y - expect).abs().max() < 1e-15);
        assert_eq!(m.transition(2.0), m.jacobian(&x, 2.0));
    }

    #[test]
    fn constructor_rejects_bad_noise() {
        assert!(matches!(
            Cv2D::discrete(-0.1),
            Err(MotionError::Negative {
                what: "sigma_a",
                ..
            })
        ));
        assert!(matches!(
            Cv2D::continuous(f64::NAN),
            Err(MotionError::NonFinite {
                what: "q_tilde",
                ..
            })
        ));
    }
}

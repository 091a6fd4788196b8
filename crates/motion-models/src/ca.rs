//! Constant-acceleration (CA) models in one, two and three dimensions.
//!
//! Per axis the state is `[p, v, a]` and
//!
//! ```text
//! F(T) = [[1, T, T²/2],
//!         [0, 1, T   ],
//!         [0, 0, 1   ]]
//! ```
//!
//! The axes are stacked as `[x, vx, ax]`, `[x, vx, ax, y, vy, ay]`,
//! `[x, vx, ax, y, vy, ay, z, vz, az]` (position, velocity and acceleration of one axis
//! together, the convention of the other models), so `F` and `Q` are block diagonal with
//! one `3 × 3` block per axis. Two process-noise models are offered by [`CaNoise`].
//!
//! # References
//! Bar-Shalom, Li & Kirubarajan (2001), *Estimation with Applications to Tracking and
//! Navigation*, §6.2.3 (continuous Wiener-process acceleration) and §6.3.3 (discrete
//! Wiener-process acceleration, the "white jerk" increment model).

use argus_core_math::Matrix;

use crate::block::impl_block_model;
use crate::error::{MotionError, check_non_negative};

/// Process noise of a constant-acceleration model, the same on every axis.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum CaNoise {
    /// Discrete white jerk (discrete Wiener-process acceleration): the acceleration
    /// increment over each interval is white with standard deviation `sigma_j` (m/s²),
    /// `Q = σ² Γ Γᵀ` with `Γ = [T²/2, T, 1]ᵀ` per axis:
    ///
    /// ```text
    /// Q = σ² [[T⁴/4, T³/2, T²/2],
    ///         [T³/2, T²,   T   ],
    ///         [T²/2, T,    1   ]]
    /// ```
    DiscreteWhiteJerk {
        /// Standard deviation of the acceleration increment per interval, m/s².
        sigma_j: f64,
    },
    /// Continuous white jerk (continuous Wiener-process acceleration) of power spectral
    /// density `q_tilde` (m²/s⁵), discretised exactly:
    ///
    /// ```text
    /// Q = q̃ [[T⁵/20, T⁴/8, T³/6],
    ///        [T⁴/8,  T³/3, T²/2],
    ///        [T³/6,  T²/2, T   ]]
    /// ```
    ContinuousWienerAcceleration {
        /// Power spectral density of the jerk, m²/s⁵.
        q_tilde: f64,
    },
}

impl CaNoise {
    /// Checks that the intensity is finite and non-negative.
    fn validate(self) -> Result<Self, MotionError> {
        match self {
            Self::DiscreteWhiteJerk { sigma_j } => {
                check_non_negative("sigma_j", sigma_j)?;
            }
            Self::ContinuousWienerAcceleration { q_tilde } => {
                check_non_negative("q_tilde", q_tilde)?;
            }
        }
        Ok(self)
    }

    /// The `3 × 3` per-axis covariance over `dt` (see the variants for the formulas).
    /// Not validated here: the model constructors reject negative or non-finite intensities.
    #[must_use]
    pub fn axis_covariance(&self, dt: f64) -> Matrix<3, 3> {
        let t2 = dt * dt;
        let t3 = t2 * dt;
        let t4 = t2 * t2;
        match *self {
            Self::DiscreteWhiteJerk { sigma_j } => {
                #[rustfmt::skip]
                let q = Matrix::<3, 3>::new(
                    t4 / 4.0, t3 / 2.0, t2 / 2.0,
                    t3 / 2.0, t2,       dt,
                    t2 / 2.0, dt,       1.0,
                );
                q * (sigma_j * sigma_j)
            }
            Self::ContinuousWienerAcceleration { q_tilde } => {
                #[rustfmt::skip]
                let q = Matrix::<3, 3>::new(
                    t4 * dt / 20.0, t4 / 8.0, t3 / 6.0,
                    t4 / 8.0,       t3 / 3.0, t2 / 2.0,
                    t3 / 6.0,       t2 / 2.0, dt,
                );
                q * q_tilde
            }
        }
    }
}

/// The per-axis CA transition `[[1, T, T²/2], [0, 1, T], [0, 0, 1]]`.
#[must_use]
pub fn ca_axis_transition(dt: f64) -> Matrix<3, 3> {
    #[rustfmt::skip]
    let f = Matrix::<3, 3>::new(
        1.0, dt,  dt * dt / 2.0,
        0.0, 1.0, dt,
        0.0, 0.0, 1.0,
    );
    f
}

macro_rules! ca_model {
    ($(#[$doc:meta])* $name:ident, $n:literal) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub struct $name {
            noise: CaNoise,
        }

        impl $name {
            /// A constant-acceleration model with the given process noise.
            ///
            /// # Errors
            /// [`MotionError::NonFinite`] or [`MotionError::Negative`] when the noise
            /// intensity is NaN, infinite or negative.
            pub fn new(noise: CaNoise) -> Result<Self, MotionError> {
                Ok(Self { noise: noise.validate()? })
            }

            /// Discrete white jerk with standard deviation `sigma_j` (m/s² per interval).
            ///
            /// # Errors
            /// As [`Self::new`].
            pub fn discrete(sigma_j: f64) -> Result<Self, MotionError> {
                Self::new(CaNoise::DiscreteWhiteJerk { sigma_j })
            }

            /// Continuous Wiener-process acceleration with jerk spectral density
            /// `q_tilde` (m²/s⁵).
            ///
            /// # Errors
            /// As [`Self::new`].
            pub fn continuous(q_tilde: f64) -> Result<Self, MotionError> {
                Self::new(CaNoise::ContinuousWienerAcceleration { q_tilde })
            }

            /// The process-noise model.
            #[must_use]
            pub fn noise(&self) -> CaNoise {
                self.noise
            }

            #[inline]
            fn axis_transition(dt: f64) -> Matrix<3, 3> {
                ca_axis_transition(dt)
            }

            #[inline]
            fn axis_noise(&self, dt: f64) -> Matrix<3, 3> {
                self.noise.axis_covariance(dt)
            }

            /// `A M Aᵀ` for one `3 × 3` block `M` of `P`.
            #[inline]
            fn axis_congruence(dt: f64, m: &Matrix<3, 3>) -> Matrix<3, 3> {
                $crate::block::block_product(&Self::axis_transition(dt), m)
            }
        }

        impl_block_model!($name, $n, 3);
    };
}

ca_model!(
    /// Constant acceleration on one axis, state `[x, vx, ax]` (N = 3).
    ///
    /// `F` per the module docs, `Q` from [`CaNoise`].
    ///
    /// # References
    /// Bar-Shalom, Li & Kirubarajan (2001) §6.2.3, §6.3.3.
    Ca1D,
    3
);
ca_model!(
    /// Constant acceleration in the plane, state `[x, vx, ax, y, vy, ay]` (N = 6).
    ///
    /// `F = diag(F₁, F₁)`, `Q = diag(Q₁, Q₁)` with the per-axis blocks of the module docs
    /// and [`CaNoise`].
    ///
    /// # References
    /// Bar-Shalom, Li & Kirubarajan (2001) §6.2.3, §6.3.3.
    Ca2D,
    6
);
ca_model!(
    /// Constant acceleration in space, state `[x, vx, ax, y, vy, ay, z, vz, az]` (N = 9).
    ///
    /// `F = diag(F₁, F₁, F₁)`, `Q = diag(Q₁, Q₁, Q₁)` with the per-axis blocks of the
    /// module docs and [`CaNoise`].
    ///
    /// # References
    /// Bar-Shalom, Li & Kirubarajan (2001) §6.2.3, §6.3.3.
    Ca3D,
    9
);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::MotionModel;
    use argus_core_math::Vector;

    #[test]
    fn discrete_q_closed_form() {
        // σ² Γ Γᵀ with Γ = [T²/2, T, 1]ᵀ, σ = 0.5, T = 2: Γ = [2, 2, 1],
        // 0.25·[[4,4,2],[4,4,2],[2,2,1]].
        let m = Ca1D::discrete(0.5).unwrap();
        let q = m.process_noise(&Vector::<3>::zeros(), 2.0);
        #[rustfmt::skip]
        let expect = Matrix::<3, 3>::new(
            1.0, 1.0, 0.5,
            1.0, 1.0, 0.5,
            0.5, 0.5, 0.25,
        );
        assert!((q - expect).abs().max() < 1e-15);
    }

    #[test]
    fn continuous_q_is_integral_of_transition() {
        // Q = ∫₀ᵀ g(s) g(s)ᵀ q̃ ds with g(s) = [s²/2, s, 1]ᵀ (the last column of F(s));
        // midpoint rule with 20 000 panels, relative error O(h²) ≈ 1e-9.
        let (q_tilde, t) = (1.3_f64, 3.0_f64);
        let n = 20_000;
        let h = t / f64::from(n);
        let mut acc = Matrix::<3, 3>::zeros();
        for i in 0..n {
            let s = (f64::from(i) + 0.5) * h;
            let g = Vector::<3>::new(s * s / 2.0, s, 1.0);
            acc += g * g.transpose() * (q_tilde * h);
        }
        let q = Ca3D::continuous(q_tilde)
            .unwrap()
            .process_noise(&Vector::<9>::zeros(), t);
        for k in 0..3 {
            let block = q.fixed_view::<3, 3>(3 * k, 3 * k);
            assert!((block - acc).abs().max() < 1e-8 * acc.abs().max());
        }
        assert!(q.fixed_view::<3, 3>(0, 3).abs().max() < 1e-15);
    }

    #[test]
    fn ca2d_propagates_parabola() {
        // x(t) = x0 + v0 t + a t²/2 exactly: x0 = 1, v0 = 2, a = 3, t = 2 → 11, v = 8.
        let m = Ca2D::continuous(0.0).unwrap();
        let x = Vector::<6>::from_column_slice(&[1.0, 2.0, 3.0, 0.0, -1.0, 0.5]);
        let y = m.propagate(&x, 2.0);
        let expect = Vector::<6>::from_column_slice(&[11.0, 8.0, 3.0, -1.0, 0.0, 0.5]);
        assert!((y - expect).abs().max() < 1e-14);
    }

    #[test]
    fn constructor_rejects_bad_noise() {
        assert!(matches!(
            Ca1D::discrete(f64::INFINITY),
            Err(MotionError::NonFinite {
                what: "sigma_j",
                ..
            })
        ));
        assert!(matches!(
            Ca2D::continuous(-1.0),
            Err(MotionError::Negative {
                what: "q_tilde",
                ..
            })
        ));
    }
}

//! Smoothing recorded tracks: fixed-interval Rauch–Tung–Striebel (RTS) smoothing for the
//! KF and the EKF, the unscented RTS smoother for the UKF, and fixed-lag smoothing.
//!
//! # The forward pass keeps what the backward pass needs
//! A filter that implements [`SmoothingFilter`] predicts and returns, with the predicted
//! moments `x̂ₖ₊₁⁻, Pₖ₊₁⁻`, the cross covariance of the two instants
//! `Cₖ₊₁ = Cov(xₖ, xₖ₊₁ | Z₁:ₖ)` (a [`Transition`]):
//!
//! - KF and EKF: `Cₖ₊₁ = Pₖ Fₖᵀ` with `Fₖ = ∂f/∂x(x̂ₖ, dtₖ)`, the Jacobian formed once for
//!   both `Cₖ₊₁` and `Pₖ₊₁⁻ = Fₖ Cₖ₊₁ + Qₖ`;
//! - UKF: `Cₖ₊₁ = Σᵢ Wᵢᶜ (χᵢ − x̂ₖ)(f(χᵢ) − x̂ₖ₊₁⁻)ᵀ` over the same sigma points that give
//!   the predicted moments (Särkkä 2008, eq 14; the centre point's term is zero and the
//!   symmetric points' mean offsets cancel, so it is `Σᵢ Wᵢ sᵢ dᵢᵀ` of the UKF's offsets).
//!
//! An [`RtsTrack`] records, per step `k`, the time, the [`Transition`] into it and the
//! filtered estimate ([`RtsStep`]); nothing is recomputed afterwards.
//!
//! # The backward pass
//! From `x̂ₙ|ₙ, Pₙ|ₙ` at the last step, for `k = n − 1, …, 0` (Rauch, Tung & Striebel 1965;
//! Särkkä 2013, *Bayesian Filtering and Smoothing*, Theorem 8.2 for the linear case and
//! eqs (9.4)–(9.6) / Algorithm 9.3 for the unscented one; Särkkä 2008, eqs (15)–(17)):
//!
//! ```text
//! Gₖ     = Cₖ₊₁ (Pₖ₊₁⁻)⁻¹
//! x̂ₖ|ₙ   = x̂ₖ|ₖ + Gₖ (x̂ₖ₊₁|ₙ − x̂ₖ₊₁⁻)
//! Pₖ|ₙ   = Pₖ|ₖ + Gₖ (Pₖ₊₁|ₙ − Pₖ₊₁⁻) Gₖᵀ
//! ```
//!
//! With `Cₖ₊₁ = Pₖ Fₖᵀ` this is the RTS smoother (extended RTS for a linearised model);
//! with the sigma-point `Cₖ₊₁` it is the unscented RTS smoother (URTS) of Särkkä (2008),
//! which on a linear model equals the RTS to round-off. Every quantity is a stack matrix:
//! the backward pass allocates nothing per step beyond the output sequence
//! (`tests/no_alloc.rs`). The intervals `dtₖ = tₖ₊₁ − tₖ` may vary from step to step.
//!
//! # Fixed lag
//! [`FixedLagSmoother`] keeps a window of the last steps and, after each new step `k`,
//! runs the same backward pass over it: the estimate it hands out for step `j` is
//! `x̂ⱼ|ₖ`, exactly the fixed-interval smoother of `Z₁:ₖ` at `j`, with `k − j = L` steps or
//! `tₖ − tⱼ ≥ T` seconds ([`Lag`]). Cost per step: `L` backward steps.
//!
//! # Errors
//! A sequence with a failed forward step, time going backwards, a missing transition or an
//! output of the wrong length gets a [`SmoothError`] naming the step; a track is smoothed
//! whole or not at all.
//!
//! # References
//! - H. E. Rauch, F. Tung, C. T. Striebel (1965), "Maximum likelihood estimates of linear
//!   dynamic systems", AIAA Journal 3(8), 1445–1450.
//! - S. Särkkä (2008), "Unscented Rauch–Tung–Striebel smoother", IEEE Trans. Automatic
//!   Control 53(3), 845–849, eqs (12)–(17).
//! - S. Särkkä (2013), *Bayesian Filtering and Smoothing*, Cambridge UP, ch. 8–9.
//! - Bar-Shalom, Li & Kirubarajan (2001), *Estimation with Applications to Tracking and
//!   Navigation*, §8.6 (fixed-interval and fixed-lag smoothing).
//!
//! # Example
//! ```
//! use argus_core_math::{Gaussian, Matrix, Vector};
//! use argus_filters::{Kf, RtsTrack};
//! use argus_motion_models::Cv2D;
//! use argus_sensors::CartesianPosition;
//!
//! let kf = Kf::new(Cv2D::discrete(0.5)?);
//! let pos = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 100.0)?;
//! let start = Gaussian::new(Vector::<4>::zeros(), Matrix::<4, 4>::identity() * 1e4)?;
//! let mut track = RtsTrack::new(0.0, start)?;
//! for k in 1..=20 {
//!     let t = f64::from(k) * 2.0;
//!     track.step(&kf, t, &pos, &Vector::<2>::new(10.0 * t, -5.0 * t))?;
//! }
//! let smoothed = track.smooth()?;
//! assert_eq!(smoothed.len(), 21);
//! // The last smoothed estimate is the last filtered one; earlier ones are tighter.
//! assert_eq!(smoothed[20], *track.latest());
//! assert!(smoothed[10].cov()[(0, 0)] < track.steps()[10].filtered().cov()[(0, 0)]);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod error;
mod fixed_lag;
mod rts;
mod step;
mod track;
mod urts;

pub use error::SmoothError;
pub use fixed_lag::{FixedLagSmoother, Lag, Lagged};
pub use rts::{rts_smooth, rts_smooth_into, rts_step, rts_step_across};
pub use step::RtsStep;
pub use track::RtsTrack;

use argus_core_math::{Gaussian, MathError, Matrix, check_finite_matrix};

use crate::{FilterError, GaussianFilter};

/// The prediction of one step with what the backward pass needs: the predicted moments
/// `x̂ₖ₊₁⁻, Pₖ₊₁⁻` and the cross covariance `Cₖ₊₁ = Cov(xₖ, xₖ₊₁ | Z₁:ₖ)`.
///
/// The state predicted from has `N` entries and the predicted one `NP` (`N` unless given):
/// a multiple-model smoother's pair of models of different state sizes (the aircraft
/// IMM's 4-state CV and 5-state CT) predicts one mode's estimate into another's state,
/// and [`rts_step_across`] smooths back across them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Transition<const N: usize, const NP: usize = N> {
    predicted: Gaussian<NP>,
    cross: Matrix<N, NP>,
}

impl<const N: usize, const NP: usize> Transition<N, NP> {
    /// A transition from a prediction and its cross covariance with the state it was
    /// predicted from (for a forward pass run outside this crate's filters).
    ///
    /// # Errors
    /// [`MathError::NonFinite`] when the cross covariance is not finite.
    pub fn new(predicted: Gaussian<NP>, cross: Matrix<N, NP>) -> Result<Self, MathError> {
        check_finite_matrix(&cross, "cross covariance")?;
        Ok(Self { predicted, cross })
    }

    /// The predicted estimate `x̂ₖ₊₁⁻, Pₖ₊₁⁻`.
    #[must_use]
    pub fn predicted(&self) -> &Gaussian<NP> {
        &self.predicted
    }

    /// The cross covariance `Cₖ₊₁ = Cov(xₖ, xₖ₊₁ | Z₁:ₖ)` (`N × NP`).
    #[must_use]
    pub fn cross(&self) -> &Matrix<N, NP> {
        &self.cross
    }
}

/// A Gaussian filter whose prediction also yields the cross covariance the RTS backward
/// pass needs ([`Transition`]).
pub trait SmoothingFilter<const N: usize>: GaussianFilter<N> {
    /// Predicts `prior` over `dt` seconds, returning the prediction (the same as
    /// [`GaussianFilter::predict`], to round-off) and `Cov(x(t), x(t + dt))`.
    ///
    /// # Errors
    /// As [`GaussianFilter::predict`].
    fn predict_with_cross(
        &self,
        prior: &Gaussian<N>,
        dt: f64,
    ) -> Result<Transition<N>, FilterError>;
}

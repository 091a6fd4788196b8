//! Motion models for target tracking.
//!
//! Every model implements [`MotionModel`]: propagation, its Jacobian and the
//! process noise, all taking the interval `dt` as an argument (a model stores no
//! time). Models whose transition does not depend on the state also implement
//! [`LinearMotionModel`]; continuous-time models implement [`ContinuousModel`]
//! for the continuous–discrete EKF and the truncated second-order filter.
//!
//! State layouts (documented per model) interleave position and velocity per
//! axis, as in the seed papers: `[x, vx]`, `[x, vx, y, vy]`, `[x, vx, y, vy, z, vz]`.
//!
//! Models are infallible on purpose: validating `dt` (finite, positive) and the
//! state is the filter's job, which reports a typed error.

use argus_core_math::{Matrix, Vector};

/// A discrete-time motion model `x(t + dt) = f(x(t), dt) + w`, `w ~ N(0, Q(x, dt))`.
pub trait MotionModel<const N: usize> {
    /// Propagates the state over `dt`: `f(x, dt)`.
    fn propagate(&self, x: &Vector<N>, dt: f64) -> Vector<N>;

    /// The Jacobian `∂f/∂x` at `x` over `dt` (the transition matrix for a linear model).
    fn jacobian(&self, x: &Vector<N>, dt: f64) -> Matrix<N, N>;

    /// The process-noise covariance `Q` over `dt` (evaluated at `x` where it depends on the state).
    fn process_noise(&self, x: &Vector<N>, dt: f64) -> Matrix<N, N>;

    /// The Hessians `∂²fᵢ/∂x²`, one per state component, for second-order filters.
    /// `None` when the model does not provide them (a second-order filter then reports an error).
    fn hessians(&self, _x: &Vector<N>, _dt: f64) -> Option<[Matrix<N, N>; N]> {
        None
    }
}

/// A motion model whose transition `F(dt)` does not depend on the state:
/// `f(x, dt) = F(dt) x`. The Kalman filter requires it.
pub trait LinearMotionModel<const N: usize>: MotionModel<N> {
    /// The transition matrix `F(dt)`.
    fn transition(&self, dt: f64) -> Matrix<N, N>;
}

/// A continuous-time model `ẋ = a(x) + w(t)`, `E[w(t) w(τ)ᵀ] = Q_c δ(t − τ)`, for the
/// continuous–discrete EKF (seed 001 eqs 2-1 to 2-6) and the truncated second-order filter.
pub trait ContinuousModel<const N: usize> {
    /// The drift `a(x)`.
    fn drift(&self, x: &Vector<N>) -> Vector<N>;
    /// The drift Jacobian `A(x) = ∂a/∂x`.
    fn drift_jacobian(&self, x: &Vector<N>) -> Matrix<N, N>;
    /// The drift Hessians `∂²aᵢ/∂x²`, one per state component.
    fn drift_hessians(&self, x: &Vector<N>) -> [Matrix<N, N>; N];
    /// The power spectral density `Q_c` of the driving white noise.
    fn diffusion(&self) -> Matrix<N, N>;
}

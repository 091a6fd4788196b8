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
//!
//! | model | state | transition | noise |
//! |---|---|---|---|
//! | [`Cv1D`], [`Cv2D`], [`Cv3D`] | `[x, vx, …]` | constant velocity | [`CvNoise`]: discrete or continuous white acceleration |
//! | [`Ca1D`], [`Ca2D`], [`Ca3D`] | `[x, vx, ax, …]` | constant acceleration | [`CaNoise`]: discrete or continuous white jerk |
//! | [`CoordinatedTurn`] | `[x, vx, y, vy]` | turn at a known rate ω, exact as ω → 0 | seed 000's `σv² Γ Γᵀ` |
//! | [`CoordinatedTurnRate`] | `[x, vx, y, vy, ω]` | turn with the rate as a state; Jacobian and Hessians | `σ_a`, `σ_ω` |
//! | [`QuadraticDrag`] | `[x, vx, y, vy]` | `v̇ = −α v\|v\| + u` (seed 001), RK4 | white acceleration `q` |
//! | [`PlanarModel`] | `[x, vx, y, vy]` | closed enum CV / CT for IMMs | delegated |
//!
//! Constructors validate their parameters and return [`MotionError`].
//!
//! # Example
//! ```
//! use argus_motion_models::{CoordinatedTurn, Cv2D, LinearMotionModel, MotionModel};
//! use argus_core_math::Vector;
//!
//! // Seed 000's CV model (σv = 0.1 m/s²) and a 3 deg/s counter-clockwise turn.
//! let cv = Cv2D::discrete(0.1)?;
//! let ct = CoordinatedTurn::from_degrees_per_second(3.0, 0.5)?;
//! let x = Vector::<4>::new(-60_000.0, 90.0, -20_000.0, 0.0);
//!
//! // CV moves 450 m along +x in 5 s.
//! let y = cv.propagate(&x, 5.0);
//! assert!((y[0] - (-59_550.0)).abs() < 1e-9);
//!
//! // The turn keeps the speed and rotates the velocity by 15 degrees.
//! let z = ct.propagate(&x, 5.0);
//! assert!((z[1].hypot(z[3]) - 90.0).abs() < 1e-9);
//! assert!((z[3].atan2(z[1]).to_degrees() - 15.0).abs() < 1e-9);
//!
//! // Q = σv² Γ Γᵀ: the position variance is σv² T⁴/4 = 0.01 · 625/4.
//! let q = cv.process_noise(&x, 5.0);
//! assert!((q[(0, 0)] - 1.5625).abs() < 1e-12);
//! assert_eq!(ct.transition(5.0), ct.jacobian(&x, 5.0));
//! # Ok::<(), argus_motion_models::MotionError>(())
//! ```

mod block;
mod ca;
mod ct;
mod ct_rate;
mod cv;
mod drag;
mod error;
mod planar;
mod rk4;
mod turn;

pub use ca::{Ca1D, Ca2D, Ca3D, CaNoise, ca_axis_transition};
pub use ct::{CoordinatedTurn, ct_transition};
pub use ct_rate::CoordinatedTurnRate;
pub use cv::{Cv1D, Cv2D, Cv3D, CvNoise, cv_axis_transition};
pub use drag::{DEFAULT_MAX_STEP, QuadraticDrag};
pub use error::MotionError;
pub use planar::PlanarModel;

use argus_core_math::{Matrix, Vector};

/// A discrete-time motion model `x(t + dt) = f(x(t), dt) + w`, `w ~ N(0, Q(x, dt))`.
pub trait MotionModel<const N: usize> {
    /// Propagates the state over `dt`: `f(x, dt)`.
    fn propagate(&self, x: &Vector<N>, dt: f64) -> Vector<N>;

    /// The Jacobian `∂f/∂x` at `x` over `dt` (the transition matrix for a linear model).
    fn jacobian(&self, x: &Vector<N>, dt: f64) -> Matrix<N, N>;

    /// The process-noise covariance `Q` over `dt` (evaluated at `x` where it depends on the state).
    fn process_noise(&self, x: &Vector<N>, dt: f64) -> Matrix<N, N>;

    /// The covariance propagation `F P Fᵀ` with `F = ∂f/∂x` at `x` over `dt` (process
    /// noise not included).
    ///
    /// The default forms the Jacobian and takes the full product; models with a
    /// structured Jacobian (the block-diagonal CV and CA models) override it with a
    /// cheaper computation of the same product. The result is exactly symmetric.
    fn propagate_covariance(&self, x: &Vector<N>, p: &Matrix<N, N>, dt: f64) -> Matrix<N, N> {
        argus_core_math::kernels::congruence(&self.jacobian(x, dt), p)
    }

    /// The predicted mean and the propagated covariance together: `(f(x, dt), F P Fᵀ)`.
    ///
    /// The default calls [`MotionModel::propagate`] and
    /// [`MotionModel::propagate_covariance`]; a model whose `F` is costly to form (the
    /// coordinated turn's trigonometry) overrides it to form `F` once.
    fn propagate_with_covariance(
        &self,
        x: &Vector<N>,
        p: &Matrix<N, N>,
        dt: f64,
    ) -> (Vector<N>, Matrix<N, N>) {
        (self.propagate(x, dt), self.propagate_covariance(x, p, dt))
    }

    /// The moments of the linearised prediction together: `(f(x, dt), F P Fᵀ + Q(x, dt))`.
    ///
    /// The default adds [`MotionModel::process_noise`] to
    /// [`MotionModel::propagate_with_covariance`]; the block-diagonal CV and CA models add
    /// their per-axis noise block by block instead of forming the full `Q`.
    fn predict_moments(
        &self,
        x: &Vector<N>,
        p: &Matrix<N, N>,
        dt: f64,
    ) -> (Vector<N>, Matrix<N, N>) {
        let (mean, fpf) = self.propagate_with_covariance(x, p, dt);
        (mean, fpf + self.process_noise(x, dt))
    }

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

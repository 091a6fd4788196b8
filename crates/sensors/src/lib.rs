//! Radar measurement models.
//!
//! Every sensor implements [`MeasurementModel`] for the state layouts it
//! supports: predicted measurement, Jacobian, noise covariance and a residual
//! that wraps angles. Angles are in radians, azimuth measured from +x
//! counter-clockwise (`x = r cos θ`) everywhere inside Argus.

use argus_core_math::{Matrix, Vector};

/// A measurement model `z = h(x) + v`, `v ~ N(0, R(x))`, of an `N`-state target
/// giving an `M`-dimensional measurement.
pub trait MeasurementModel<const N: usize, const M: usize> {
    /// The noise-free measurement `h(x)`.
    fn predict(&self, x: &Vector<N>) -> Vector<M>;

    /// The Jacobian `∂h/∂x` at `x`.
    fn jacobian(&self, x: &Vector<N>) -> Matrix<M, N>;

    /// The measurement-noise covariance `R` (evaluated at `x` where it depends on the state).
    fn noise(&self, x: &Vector<N>) -> Matrix<M, M>;

    /// The residual `z − ẑ`, with angle components wrapped to `(−π, π]`.
    fn residual(&self, z: &Vector<M>, z_pred: &Vector<M>) -> Vector<M> {
        z - z_pred
    }

    /// The Hessians `∂²hᵢ/∂x²`, one per measurement component, for second-order
    /// filters; `None` when the model does not provide them.
    fn hessians(&self, _x: &Vector<N>) -> Option<[Matrix<N, N>; M]> {
        None
    }
}

/// A measurement model with `h(x) = H x` (`H` independent of the state).
pub trait LinearMeasurementModel<const N: usize, const M: usize>: MeasurementModel<N, M> {
    /// The measurement matrix `H`.
    fn matrix(&self) -> Matrix<M, N>;
}

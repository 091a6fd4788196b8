//! Core mathematics for Argus: fixed-size Gaussians, Cholesky-based solves,
//! Gaussian log-likelihoods, Joseph-form updates, chi-square quantiles and
//! run-time-sized algebra through `faer` (the `dynamic` feature, off by default).
//!
//! Small per-track algebra uses nalgebra's const-generic stack types
//! ([`Vector`], [`Matrix`]); nothing here allocates except the run-time-sized
//! `dynamic` module (feature `dynamic`).
//!
//! # Example
//! ```
//! use argus_core_math::{Gaussian, Matrix, Vector};
//!
//! let g = Gaussian::new(Vector::<2>::new(1.0, 2.0), Matrix::<2, 2>::identity() * 4.0)?;
//! // Squared Mahalanobis distance of (3, 2) from the mean: (2^2)/4 = 1.
//! assert!((g.mahalanobis_sq(&Vector::<2>::new(3.0, 2.0)) - 1.0).abs() < 1e-12);
//! # Ok::<(), argus_core_math::MathError>(())
//! ```

mod chi2;
#[cfg(feature = "dynamic")]
pub mod dynamic;
mod error;
mod gaussian;
pub mod kernels;
mod linalg;

pub use chi2::{
    ChiSquareInterval, anees_interval, chi2_cdf, chi2_quantile, gate_threshold, unit_ball_volume,
};
pub use error::MathError;
pub use gaussian::Gaussian;
pub use linalg::{
    SpdFactor, check_finite_matrix, check_finite_vector, is_positive_definite, joseph_update,
    joseph_update_from_cross, joseph_update_from_innovation, log_det_of_pivots, log_likelihood,
    symmetrize,
};

/// Re-export of the faer version used for run-time-sized algebra (feature `dynamic`).
#[cfg(feature = "dynamic")]
pub use faer;
/// Re-export of the nalgebra version Argus is built on, so users name the same types.
pub use nalgebra;

/// A column vector of `N` `f64` values on the stack.
pub type Vector<const N: usize> = nalgebra::SVector<f64, N>;
/// An `R × C` matrix of `f64` values on the stack.
pub type Matrix<const R: usize, const C: usize> = nalgebra::SMatrix<f64, R, C>;

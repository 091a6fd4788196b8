//! Radar measurement models, noise, bias and converted measurements.
//!
//! Every sensor implements [`MeasurementModel`] for the state layouts it
//! supports: predicted measurement, Jacobian, noise covariance and a residual
//! that wraps angles. Angles are in radians, azimuth measured from +x
//! counter-clockwise (`x = r cos θ`) everywhere inside Argus; radar-convention
//! azimuths (clockwise from north) go through [`radar_to_math_azimuth`] /
//! [`RadarAzimuth`], never silently.
//!
//! - Models: [`Polar2D`] (range, azimuth), [`Spherical3D`] (range, azimuth,
//!   elevation), [`Bearing2D`] and the linear [`CartesianPosition`]. Each reads the
//!   target position from the state at indices validated at construction, with
//!   `cv` constructors for `[x, vx, y, vy]` and `[x, vx, y, vy, z, vz]`; all give
//!   analytic Jacobians and Hessians.
//! - Noise: constant standard deviations or from the SNR through a link budget
//!   ([`RadarNoise`], [`SnrNoise`], [`LinkBudget`]; seed 003 eqs (6)–(8)).
//! - Bias: [`PolarBias`] (seed 004 eqs (1)–(4)) and its linearised Cartesian form.
//! - Converted measurements: [`convert_polar`], [`convert_spherical`] with a
//!   [`ConversionMethod`] (linearised, debiased, unbiased).
//! - The workspace's plot vocabulary: a [`Plot`] is a time, a [`SensorId`], a
//!   [`Measurement`] ([`PolarMeasurement`], [`SphericalMeasurement`], or a
//!   [`CartesianMeasurement`] in 2-D or 3-D with its covariance) and an optional
//!   amplitude, each checked when built. [`wrap_angle`] is the one angle wrap (exact,
//!   to `(−π, π]`).
//!
//! # Example
//! ```
//! use argus_core_math::Vector;
//! use argus_sensors::{
//!     ConversionMethod, MeasurementModel, Polar2D, RadarNoise, convert_polar,
//! };
//!
//! // A radar at the origin, σr = 50 m, σθ = 2°, tracking [x, vx, y, vy].
//! let radar = Polar2D::cv([0.0, 0.0], RadarNoise::constant(50.0, 2f64.to_radians(), 0.0)?)?;
//! let x = Vector::<4>::new(30_000.0, -90.0, 40_000.0, 0.0);
//! let z = radar.predict(&x);
//! assert!((z[0] - 50_000.0).abs() < 1e-6); // 3-4-5 triangle
//!
//! // Residuals wrap across ±π.
//! let a = Vector::<2>::new(0.0, 3.1);
//! let b = Vector::<2>::new(0.0, -3.1);
//! assert!((radar.residual(&a, &b)[1] - (6.2 - std::f64::consts::TAU)).abs() < 1e-12);
//!
//! // The unbiased conversion divides by λ = exp(−σθ²/2) (Mo et al. 1998).
//! let c = convert_polar(z[0], z[1], 50.0, 2f64.to_radians(), ConversionMethod::Unbiased)?;
//! let lambda = (-0.5 * 2f64.to_radians().powi(2)).exp();
//! assert!((c.position[0] - 30_000.0 / lambda).abs() < 1e-6);
//! # Ok::<(), argus_sensors::SensorError>(())
//! ```

mod angle;
mod bearing;
mod bias;
mod cartesian;
mod conversion;
mod error;
mod noise;
mod plot;
mod polar;
mod sensor_id;
mod spherical;

pub use angle::{RadarAzimuth, math_to_radar_azimuth, radar_to_math_azimuth, wrap_angle};
pub use bearing::Bearing2D;
pub use bias::{PolarBias, bias_regressor, bias_sensitivity};
pub use cartesian::CartesianPosition;
pub use conversion::{
    ConversionMethod, ConvertedMeasurement, UnbiasedPolarConversion, convert_polar,
    convert_spherical, polar_jacobian, spherical_jacobian,
};
pub use error::SensorError;
pub use noise::{LinkBudget, RadarNoise, Sigmas, SnrNoise, db_to_linear, linear_to_db};
pub use plot::{CartesianMeasurement, Measurement, Plot, PolarMeasurement, SphericalMeasurement};
pub use polar::Polar2D;
pub use sensor_id::SensorId;
pub use spherical::Spherical3D;

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

    /// When the measurement picks state entries, `h(x) = (x[i₀], …, x[i_{M−1}])` (so `H`
    /// is the selection matrix of those indices), the indices; `None` (the default) for
    /// any other model. Filters then gather rows and columns of `P` instead of
    /// multiplying by `H`. An implementation must agree with [`MeasurementModel::predict`]
    /// and [`MeasurementModel::jacobian`]; filters ignore indices `≥ N`.
    fn selection(&self) -> Option<[usize; M]> {
        None
    }
}

/// A measurement model with `h(x) = H x` (`H` independent of the state).
pub trait LinearMeasurementModel<const N: usize, const M: usize>: MeasurementModel<N, M> {
    /// The measurement matrix `H`.
    fn matrix(&self) -> Matrix<M, N>;
}

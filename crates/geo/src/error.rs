//! The error type of `argus-geo`.

/// What went wrong when building a coordinate or an ellipsoid. Every variant names
/// the offending quantity and carries the value given.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum GeoError {
    /// A value that must be finite is NaN or infinite.
    #[error("{what} = {value} is not finite")]
    NonFinite {
        /// The quantity that was checked.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// A value that must be `≥ 0` (a range) is negative.
    #[error("{what} = {value} is negative")]
    Negative {
        /// The quantity that was checked.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// A latitude outside `[−90°, 90°]`.
    #[error("latitude {degrees}° is outside [−90°, 90°]")]
    LatitudeOutOfRange {
        /// The latitude given, in degrees.
        degrees: f64,
    },
    /// An ellipsoid whose equatorial radius is not positive or whose flattening is
    /// outside `[0, 1)` (prolate ellipsoids are not supported).
    #[error("ellipsoid a = {a} m, f = {f}: needs a > 0 and 0 ≤ f < 1")]
    InvalidEllipsoid {
        /// The equatorial radius given, metres.
        a: f64,
        /// The flattening given.
        f: f64,
    },
}

/// `Ok(value)` when `value` is finite.
pub(crate) fn finite(value: f64, what: &'static str) -> Result<f64, GeoError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(GeoError::NonFinite { what, value })
    }
}

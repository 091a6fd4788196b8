//! Geodetic coordinates (latitude, longitude, height above the ellipsoid) and
//! Earth-centred Earth-fixed Cartesian ones, with the forward conversion.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use crate::ellipsoid::Ellipsoid;
use crate::error::{GeoError, finite};

/// A point given by geodetic latitude `φ`, longitude `λ` (radians, east positive)
/// and height `h` above the ellipsoid (metres, along the ellipsoid normal).
///
/// Built through a validating constructor: `φ ∈ [−π/2, π/2]`, all finite; the
/// longitude is wrapped to `(−π, π]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geodetic {
    lat: f64,
    lon: f64,
    height: f64,
}

impl Geodetic {
    /// From latitude and longitude in degrees and height in metres.
    ///
    /// # Errors
    /// [`GeoError::NonFinite`] for a non-finite argument,
    /// [`GeoError::LatitudeOutOfRange`] for `|lat| > 90°`.
    pub fn from_degrees(lat_deg: f64, lon_deg: f64, height_m: f64) -> Result<Self, GeoError> {
        let lat_deg = finite(lat_deg, "latitude")?;
        if lat_deg.abs() > 90.0 {
            return Err(GeoError::LatitudeOutOfRange { degrees: lat_deg });
        }
        // ±90° converts to exactly ±π/2 (to_radians rounds 90 · π/180 to FRAC_PI_2).
        Self::from_radians(
            lat_deg.to_radians(),
            finite(lon_deg, "longitude")?.to_radians(),
            height_m,
        )
    }

    /// From latitude and longitude in radians and height in metres.
    ///
    /// # Errors
    /// [`GeoError::NonFinite`] for a non-finite argument,
    /// [`GeoError::LatitudeOutOfRange`] for `|lat| > π/2`.
    pub fn from_radians(lat: f64, lon: f64, height_m: f64) -> Result<Self, GeoError> {
        let lat = finite(lat, "latitude")?;
        let lon = finite(lon, "longitude")?;
        let height = finite(height_m, "height")?;
        if lat.abs() > FRAC_PI_2 {
            return Err(GeoError::LatitudeOutOfRange {
                degrees: lat.to_degrees(),
            });
        }
        Ok(Self {
            lat,
            lon: wrap_pi(lon),
            height,
        })
    }

    /// Already checked: `|lat| ≤ π/2`, all finite, `lon` wrapped.
    pub(crate) fn new_unchecked(lat: f64, lon: f64, height: f64) -> Self {
        Self { lat, lon, height }
    }

    /// Geodetic latitude `φ`, radians.
    #[must_use]
    pub fn lat(&self) -> f64 {
        self.lat
    }

    /// Longitude `λ`, radians east, in `(−π, π]`.
    #[must_use]
    pub fn lon(&self) -> f64 {
        self.lon
    }

    /// Latitude, degrees.
    #[must_use]
    pub fn lat_deg(&self) -> f64 {
        self.lat.to_degrees()
    }

    /// Longitude, degrees east.
    #[must_use]
    pub fn lon_deg(&self) -> f64 {
        self.lon.to_degrees()
    }

    /// Height above the ellipsoid, metres.
    #[must_use]
    pub fn height(&self) -> f64 {
        self.height
    }

    /// The Earth-centred Earth-fixed position on `ellipsoid`:
    ///
    /// `X = (N + h) cos φ cos λ`, `Y = (N + h) cos φ sin λ`, `Z = (N (1 − e²) + h) sin φ`,
    /// `N = a / √(1 − e² sin²φ)`.
    ///
    /// # References
    /// NIMA TR8350.2 (2000), eq. (4-14); Karney (2011), *Geodesics on an ellipsoid of
    /// revolution*, arXiv:1102.1215, Appendix B, eq. (B1).
    #[must_use]
    pub fn to_ecef(&self, ellipsoid: &Ellipsoid) -> Ecef {
        let (sl, cl) = self.lat.sin_cos();
        let (so, co) = self.lon.sin_cos();
        let n = ellipsoid.a() / ellipsoid.w(sl);
        let r = (n + self.height) * cl;
        Ecef {
            x: r * co,
            y: r * so,
            z: (n * (1.0 - ellipsoid.e2()) + self.height) * sl,
        }
    }
}

/// An Earth-centred Earth-fixed position, metres: origin at the centre of the
/// ellipsoid, `z` through the north pole, `x` through latitude 0, longitude 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ecef {
    /// Towards latitude 0, longitude 0.
    pub x: f64,
    /// Towards latitude 0, longitude 90° E.
    pub y: f64,
    /// Towards the north pole.
    pub z: f64,
}

/// Wraps an angle to `(−π, π]`.
pub(crate) fn wrap_pi(angle: f64) -> f64 {
    if angle > -PI && angle <= PI {
        return angle;
    }
    let r = PI - (PI - angle).rem_euclid(TAU);
    if r <= -PI { r + TAU } else { r }
}

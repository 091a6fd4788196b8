//! The reference ellipsoid of revolution (WGS-84 by default).

use crate::error::{GeoError, finite};

/// An oblate ellipsoid of revolution given by its equatorial radius `a` and
/// flattening `f = (a − b)/a`.
///
/// # References
/// NIMA TR8350.2 (2000), *Department of Defense World Geodetic System 1984*,
/// Table 3.1: `a = 6 378 137 m`, `1/f = 298.257 223 563`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ellipsoid {
    a: f64,
    f: f64,
    e2: f64,
}

impl Ellipsoid {
    /// WGS-84 (NIMA TR8350.2, Table 3.1).
    pub const WGS84: Self = Self {
        a: 6_378_137.0,
        f: 1.0 / 298.257_223_563,
        e2: (1.0 / 298.257_223_563) * (2.0 - 1.0 / 298.257_223_563),
    };

    /// An ellipsoid with equatorial radius `a` (metres) and flattening `f`
    /// (`f = 0` is a sphere).
    ///
    /// # Errors
    /// [`GeoError::NonFinite`] for a non-finite argument, [`GeoError::InvalidEllipsoid`]
    /// unless `a > 0` and `0 ≤ f < 1`.
    pub fn new(a: f64, f: f64) -> Result<Self, GeoError> {
        let a = finite(a, "ellipsoid equatorial radius")?;
        let f = finite(f, "ellipsoid flattening")?;
        if a <= 0.0 || !(0.0..1.0).contains(&f) {
            return Err(GeoError::InvalidEllipsoid { a, f });
        }
        Ok(Self {
            a,
            f,
            e2: f * (2.0 - f),
        })
    }

    /// The equatorial radius `a`, metres.
    #[must_use]
    pub fn a(&self) -> f64 {
        self.a
    }

    /// The flattening `f`.
    #[must_use]
    pub fn f(&self) -> f64 {
        self.f
    }

    /// The polar radius `b = a (1 − f)`, metres.
    #[must_use]
    pub fn b(&self) -> f64 {
        self.a * (1.0 - self.f)
    }

    /// The squared first eccentricity `e² = f (2 − f)`.
    #[must_use]
    pub fn e2(&self) -> f64 {
        self.e2
    }

    /// `w(φ) = √(1 − e² sin²φ)` given `sin φ`; the prime-vertical radius is `N = a / w`.
    pub(crate) fn w(&self, sin_lat: f64) -> f64 {
        (1.0 - self.e2 * sin_lat * sin_lat).sqrt()
    }
}

impl Default for Ellipsoid {
    fn default() -> Self {
        Self::WGS84
    }
}

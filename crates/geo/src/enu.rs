//! A local East-North-Up frame around a reference point.

use crate::ellipsoid::Ellipsoid;
use crate::error::GeoError;
use crate::geodetic::{Ecef, Geodetic};

/// A position or vector in a local East-North-Up frame, metres (or m/s): `east`
/// along the parallel, `north` along the meridian, `up` along the ellipsoid normal
/// at the frame's origin. Inside Argus `east` is `x` and `north` is `y`, so an
/// azimuth counter-clockwise from `x` is counter-clockwise from east.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Enu {
    /// East, metres.
    pub east: f64,
    /// North, metres.
    pub north: f64,
    /// Up (along the ellipsoid normal at the origin), metres.
    pub up: f64,
}

/// The local tangent-plane frame at `origin`: the system reference point of a
/// surveillance picture, or a radar's own site.
///
/// `[e, n, u]ᵀ = M (P − P₀)` with `P₀` the origin's ECEF position and the rows of `M`
///
/// `ê = (−sin λ₀, cos λ₀, 0)`, `n̂ = (−sin φ₀ cos λ₀, −sin φ₀ sin λ₀, cos φ₀)`,
/// `û = (cos φ₀ cos λ₀, cos φ₀ sin λ₀, sin φ₀)`,
///
/// the frame of GeographicLib's `LocalCartesian` and CartConvert `-l` (`z` normal to
/// the ellipsoid, `y` due north).
///
/// # Example
/// ```
/// use argus_geo::{Geodetic, LocalFrame};
/// // CartConvert's documented example: `echo 33.3 44.4 6000 | CartConvert -l 33 44 20`
/// // prints `37288.97 33374.29 5783.64`.
/// let frame = LocalFrame::wgs84(Geodetic::from_degrees(33.0, 44.0, 20.0)?);
/// let p = frame.geodetic_to_enu(&Geodetic::from_degrees(33.3, 44.4, 6000.0)?);
/// assert!((p.east - 37_288.97).abs() < 0.005);
/// assert!((p.north - 33_374.29).abs() < 0.005);
/// assert!((p.up - 5_783.64).abs() < 0.01); // the manual truncates 5783.6466
/// let back = frame.enu_to_geodetic(&p)?;
/// assert!((back.lat_deg() - 33.3).abs() < 1e-12);
/// # Ok::<(), argus_geo::GeoError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalFrame {
    origin: Geodetic,
    origin_ecef: Ecef,
    ellipsoid: Ellipsoid,
    /// Rows ê, n̂, û in ECEF.
    rows: [[f64; 3]; 3],
}

impl LocalFrame {
    /// The ENU frame at `origin` on `ellipsoid`.
    #[must_use]
    pub fn new(origin: Geodetic, ellipsoid: Ellipsoid) -> Self {
        let (sp, cp) = origin.lat().sin_cos();
        let (sl, cl) = origin.lon().sin_cos();
        Self {
            origin,
            origin_ecef: origin.to_ecef(&ellipsoid),
            ellipsoid,
            rows: [
                [-sl, cl, 0.0],
                [-sp * cl, -sp * sl, cp],
                [cp * cl, cp * sl, sp],
            ],
        }
    }

    /// The ENU frame at `origin` on WGS-84.
    #[must_use]
    pub fn wgs84(origin: Geodetic) -> Self {
        Self::new(origin, Ellipsoid::WGS84)
    }

    /// The frame's origin.
    #[must_use]
    pub fn origin(&self) -> Geodetic {
        self.origin
    }

    /// The ellipsoid the frame is built on.
    #[must_use]
    pub fn ellipsoid(&self) -> &Ellipsoid {
        &self.ellipsoid
    }

    /// An ECEF vector (a velocity, a displacement) in this frame's axes: `M v`.
    #[must_use]
    pub fn vector_from_ecef(&self, v: [f64; 3]) -> Enu {
        let m = &self.rows;
        let dot = |r: &[f64; 3]| r[0] * v[0] + r[1] * v[1] + r[2] * v[2];
        Enu {
            east: dot(&m[0]),
            north: dot(&m[1]),
            up: dot(&m[2]),
        }
    }

    /// An ENU vector of this frame in ECEF axes: `Mᵀ v`.
    #[must_use]
    pub fn vector_to_ecef(&self, v: &Enu) -> [f64; 3] {
        let m = &self.rows;
        let col = |j: usize| m[0][j] * v.east + m[1][j] * v.north + m[2][j] * v.up;
        [col(0), col(1), col(2)]
    }

    /// An ECEF position in this frame.
    #[must_use]
    pub fn ecef_to_enu(&self, p: &Ecef) -> Enu {
        let o = &self.origin_ecef;
        self.vector_from_ecef([p.x - o.x, p.y - o.y, p.z - o.z])
    }

    /// A position of this frame in ECEF.
    #[must_use]
    pub fn enu_to_ecef(&self, p: &Enu) -> Ecef {
        let [dx, dy, dz] = self.vector_to_ecef(p);
        let o = &self.origin_ecef;
        Ecef {
            x: o.x + dx,
            y: o.y + dy,
            z: o.z + dz,
        }
    }

    /// A geodetic position in this frame.
    #[must_use]
    pub fn geodetic_to_enu(&self, p: &Geodetic) -> Enu {
        self.ecef_to_enu(&p.to_ecef(&self.ellipsoid))
    }

    /// The geodetic coordinates of a position of this frame.
    ///
    /// # Errors
    /// [`GeoError::NonFinite`] for a non-finite coordinate.
    pub fn enu_to_geodetic(&self, p: &Enu) -> Result<Geodetic, GeoError> {
        self.enu_to_ecef(p).to_geodetic(&self.ellipsoid)
    }

    /// A vector given in `other`'s ENU axes (a velocity at a radar site or at an
    /// aircraft) expressed in this frame's axes.
    #[must_use]
    pub fn vector_from_frame(&self, other: &LocalFrame, v: &Enu) -> Enu {
        self.vector_from_ecef(other.vector_to_ecef(v))
    }
}

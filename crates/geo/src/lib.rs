//! WGS-84 geodetic ↔ Earth-centred Earth-fixed (ECEF) ↔ local East-North-Up (ENU)
//! coordinates, and radar sites whose azimuths are measured clockwise from their
//! own north.
//!
//! - [`Ellipsoid`]: WGS-84 by default, or any oblate `a`, `f`.
//! - [`Geodetic`] (latitude, longitude, height above the ellipsoid; validated) →
//!   [`Ecef`] by the closed form, [`Ecef`] → [`Geodetic`] by a safeguarded Newton
//!   iteration that reaches round-off at every point, poles and the Earth's centre
//!   included (see [`Ecef::to_geodetic`]).
//! - [`LocalFrame`]: the ENU frame at a system reference point or a radar site
//!   (GeographicLib's `LocalCartesian`); positions and vectors both ways.
//! - [`RadarSite`]: a radar's position, its plots in the reference frame, and the
//!   explicit azimuth conversion between the radar's clockwise-from-north azimuth
//!   ([`argus_sensors::RadarAzimuth`]) and Argus's counter-clockwise-from-east one.
//!
//! Angles are radians inside (degrees only at the `from_degrees` / `*_deg` edges),
//! lengths metres. Inside Argus `x` is east and `y` is north of the reference frame.
//!
//! # Example
//! ```
//! use argus_geo::{Ecef, Ellipsoid, Geodetic};
//! // GeographicLib's CartConvert documentation: `echo 33.3 44.4 6000 | CartConvert`
//! // prints `3816209.60 3737108.55 3485109.57`.
//! let p = Geodetic::from_degrees(33.3, 44.4, 6000.0)?;
//! let e = p.to_ecef(&Ellipsoid::WGS84);
//! assert!((e.x - 3_816_209.60).abs() < 0.005);
//! assert!((e.y - 3_737_108.55).abs() < 0.005);
//! assert!((e.z - 3_485_109.57).abs() < 0.005);
//! let back = e.to_geodetic(&Ellipsoid::WGS84)?;
//! assert!((back.height() - 6000.0).abs() < 1e-8);
//! // Latitudes outside [−90°, 90°] and NaN are typed errors.
//! assert!(Geodetic::from_degrees(90.5, 0.0, 0.0).is_err());
//! assert!(Ecef { x: f64::NAN, y: 0.0, z: 0.0 }.to_geodetic(&Ellipsoid::WGS84).is_err());
//! # Ok::<(), argus_geo::GeoError>(())
//! ```

mod ellipsoid;
mod enu;
mod error;
mod geodetic;
mod inverse;
mod site;

pub use ellipsoid::Ellipsoid;
pub use enu::{Enu, LocalFrame};
pub use error::GeoError;
pub use geodetic::{Ecef, Geodetic};
pub use site::RadarSite;

//! A radar site given by latitude, longitude and altitude, and its azimuths.
//!
//! A radar reports azimuth `α` clockwise from north at its own site
//! ([`RadarAzimuth`]); Argus works counter-clockwise from east (`x`) in the system
//! reference frame. The two differ by `π/2` and, for a radar away from the
//! reference point, by the angle `γ` between the site's north and the reference
//! frame's north (the convergence of meridians: `γ ≈ Δλ sin φ`, 0.21° for a radar
//! 30 km east of a reference point at Paris's latitude, more than twice σθ = 0.08°).
//! [`RadarSite::plot_to_reference`] converts a plot exactly through ECEF;
//! [`RadarSite::reference_azimuth`] is the planar rule `θ = π/2 − α + γ` for a
//! 2-D radar.

use argus_sensors::{RadarAzimuth, wrap_angle};

use crate::ellipsoid::Ellipsoid;
use crate::enu::{Enu, LocalFrame};
use crate::error::{GeoError, finite};
use crate::geodetic::Geodetic;

/// A radar at a geodetic position (antenna height above the ellipsoid), with its
/// own ENU frame.
///
/// # Example
/// ```
/// use argus_geo::{Geodetic, LocalFrame, RadarSite};
/// use argus_sensors::RadarAzimuth;
/// let reference = LocalFrame::wgs84(Geodetic::from_degrees(49.0097, 2.5479, 0.0)?);
/// // A radar at the reference point: a plot due east (α = 90°) is at θ = 0.
/// let cdg = RadarSite::wgs84(reference.origin());
/// let theta = cdg.reference_azimuth(&reference, RadarAzimuth(90f64.to_radians()))?;
/// assert!(theta.abs() < 1e-12);
/// // A plot 10 km due north of the radar, on the horizon (elevation 0).
/// let p = cdg.plot_to_reference(&reference, 10_000.0, RadarAzimuth(0.0), 0.0)?;
/// assert!(p.east.abs() < 1e-9 && (p.north - 10_000.0).abs() < 1e-9);
/// # Ok::<(), argus_geo::GeoError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RadarSite {
    frame: LocalFrame,
}

impl RadarSite {
    /// A radar at `position` on `ellipsoid`.
    #[must_use]
    pub fn new(position: Geodetic, ellipsoid: Ellipsoid) -> Self {
        Self {
            frame: LocalFrame::new(position, ellipsoid),
        }
    }

    /// A radar at `position` on WGS-84.
    #[must_use]
    pub fn wgs84(position: Geodetic) -> Self {
        Self::new(position, Ellipsoid::WGS84)
    }

    /// The site's own ENU frame (north is the radar's azimuth zero).
    #[must_use]
    pub fn frame(&self) -> &LocalFrame {
        &self.frame
    }

    /// The site's position in `reference`.
    #[must_use]
    pub fn position_in(&self, reference: &LocalFrame) -> Enu {
        reference.geodetic_to_enu(&self.frame.origin())
    }

    /// A plot at slant range `range` (m), azimuth `azimuth` (clockwise from the site's
    /// north) and elevation `elevation` (rad, above the site's horizontal plane) in the
    /// site's own frame: `r (cos ε sin α, cos ε cos α, sin ε)`.
    ///
    /// # Errors
    /// [`GeoError::NonFinite`] for a non-finite argument, [`GeoError::Negative`] for a
    /// negative range.
    pub fn plot_to_site(
        &self,
        range: f64,
        azimuth: RadarAzimuth,
        elevation: f64,
    ) -> Result<Enu, GeoError> {
        let range = finite(range, "range")?;
        if range < 0.0 {
            return Err(GeoError::Negative {
                what: "range",
                value: range,
            });
        }
        let (sa, ca) = finite(azimuth.0, "azimuth")?.sin_cos();
        let (se, ce) = finite(elevation, "elevation")?.sin_cos();
        Ok(Enu {
            east: range * ce * sa,
            north: range * ce * ca,
            up: range * se,
        })
    }

    /// The same plot as [`RadarSite::plot_to_site`], in `reference` (exact, through ECEF).
    ///
    /// # Errors
    /// As [`RadarSite::plot_to_site`].
    pub fn plot_to_reference(
        &self,
        reference: &LocalFrame,
        range: f64,
        azimuth: RadarAzimuth,
        elevation: f64,
    ) -> Result<Enu, GeoError> {
        let local = self.plot_to_site(range, azimuth, elevation)?;
        Ok(reference.ecef_to_enu(&self.frame.enu_to_ecef(&local)))
    }

    /// `γ`: the angle, counter-clockwise in `reference`'s horizontal plane, from
    /// `reference`'s east axis to the site's east axis (projected). 0 at the
    /// reference point; `≈ Δλ sin φ` nearby.
    #[must_use]
    pub fn grid_rotation(&self, reference: &LocalFrame) -> f64 {
        let east = reference.vector_from_frame(
            &self.frame,
            &Enu {
                east: 1.0,
                north: 0.0,
                up: 0.0,
            },
        );
        east.north.atan2(east.east)
    }

    /// A radar azimuth (clockwise from the site's north) as an Argus azimuth in
    /// `reference` (counter-clockwise from its east), wrapped to `(−π, π]`:
    /// `θ = π/2 − α + γ`. Exact for a radar at the reference point; elsewhere the
    /// direction of a horizontal ray's projection on `reference`'s plane at the site.
    ///
    /// # Errors
    /// [`GeoError::NonFinite`] for a non-finite azimuth.
    pub fn reference_azimuth(
        &self,
        reference: &LocalFrame,
        azimuth: RadarAzimuth,
    ) -> Result<f64, GeoError> {
        finite(azimuth.0, "azimuth")?;
        Ok(wrap_angle(
            azimuth.to_math() + self.grid_rotation(reference),
        ))
    }

    /// The inverse of [`RadarSite::reference_azimuth`]: an Argus azimuth in
    /// `reference` as the radar's azimuth clockwise from the site's north, in `[0, 2π)`.
    ///
    /// # Errors
    /// [`GeoError::NonFinite`] for a non-finite azimuth.
    pub fn radar_azimuth(
        &self,
        reference: &LocalFrame,
        theta: f64,
    ) -> Result<RadarAzimuth, GeoError> {
        let theta = finite(theta, "azimuth")?;
        Ok(RadarAzimuth::from_math(
            theta - self.grid_rotation(reference),
        ))
    }
}

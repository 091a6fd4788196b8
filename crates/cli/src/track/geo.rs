//! Geography in `argus track`: the optional `[reference]` point (WGS-84), sensors given
//! by latitude, longitude and altitude (their East-North-Up position around the reference,
//! by `argus_geo`), and the latitude and longitude of a track's `x, y`.
//!
//! Inside Argus `x` is east and `y` north of the reference's local tangent plane
//! ([`argus_geo::LocalFrame`], GeographicLib's `LocalCartesian`); altitudes are heights
//! above the WGS-84 ellipsoid.

use argus_geo::{Enu, GeoError, Geodetic, LocalFrame};
use toml::Spanned;

use super::schema::{ReferenceTable, SensorTable, Source};
use crate::error::CliError;

/// How close (m) the height of a track's `lat, lon` point is brought to the reference's
/// altitude; with the normals of points 100 km apart about 0.9° apart, a height error
/// `δh` moves the point's east/north by about `δh · 0.016`, far below 1 mm.
const HEIGHT_TOL: f64 = 1e-6;

/// The system reference point: the origin of the local East-North-Up plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Reference {
    frame: LocalFrame,
}

impl Reference {
    /// The WGS-84 latitude and longitude (°) of the point at the reference's altitude
    /// whose East-North position in the reference frame is `(east, north)`: the point
    /// `(east, north, u)` with `u` found so that its height is the reference's (a fixed
    /// point iteration on `u`, `∂h/∂u = cos` of the angle between the two normals ≈ 1;
    /// three or four iterations at 100 km).
    ///
    /// # Errors
    /// [`GeoError::NonFinite`] for a non-finite coordinate.
    pub(super) fn lat_lon(&self, east: f64, north: f64) -> Result<(f64, f64), GeoError> {
        let h0 = self.frame.origin().height();
        let mut up = 0.0;
        let mut g = self.frame.enu_to_geodetic(&Enu { east, north, up })?;
        for _ in 0..20 {
            let dh = g.height() - h0;
            if dh.abs() <= HEIGHT_TOL {
                break;
            }
            up -= dh;
            g = self.frame.enu_to_geodetic(&Enu { east, north, up })?;
        }
        Ok((g.lat_deg(), g.lon_deg()))
    }
}

/// A geodetic position from degrees and metres, its errors at the latitude's line.
fn geodetic(
    src: Source<'_>,
    what: &str,
    lat: &Spanned<f64>,
    lon: &Spanned<f64>,
    alt: Option<&Spanned<f64>>,
) -> Result<Geodetic, CliError> {
    let h = alt.map_or(0.0, |a| *a.get_ref());
    Geodetic::from_degrees(*lat.get_ref(), *lon.get_ref(), h)
        .map_err(|e| src.at(lat, "latitude", format!("{what}: {e}")))
}

/// Checks `[reference]`.
///
/// # Errors
/// [`CliError::Input`] at the latitude's line for a latitude outside [−90°, 90°] or a
/// non-finite value.
pub(super) fn reference(
    src: Source<'_>,
    table: Option<&Spanned<ReferenceTable>>,
) -> Result<Option<Reference>, CliError> {
    let Some(t) = table else { return Ok(None) };
    let t = t.get_ref();
    let origin = geodetic(
        src,
        "reference",
        &t.latitude,
        &t.longitude,
        t.altitude.as_ref(),
    )?;
    Ok(Some(Reference {
        frame: LocalFrame::wgs84(origin),
    }))
}

/// A sensor's position `[east, north, up]` (m) in the reference frame from its
/// `latitude, longitude, altitude`, or `None` when it gives none of them (then
/// `position` is used).
///
/// # Errors
/// [`CliError::Input`] naming the line: geodetic keys together with `position`, a
/// latitude without a longitude (or the reverse), geodetic keys without a `[reference]`,
/// a bad latitude.
pub(super) fn sensor_position(
    src: Source<'_>,
    s: &SensorTable,
    reference: Option<&Reference>,
) -> Result<Option<[f64; 3]>, CliError> {
    let id = *s.id.get_ref();
    let (lat, lon) = match (&s.latitude, &s.longitude) {
        (None, None) => {
            return match &s.altitude {
                Some(a) => Err(src.at(
                    a,
                    "altitude",
                    format!("sensor {id}: altitude goes with latitude and longitude"),
                )),
                None => Ok(None),
            };
        }
        (Some(lat), Some(lon)) => (lat, lon),
        (Some(v), None) | (None, Some(v)) => {
            return Err(src.at(
                v,
                "latitude",
                format!("sensor {id}: latitude and longitude go together"),
            ));
        }
    };
    if let Some(p) = &s.position {
        return Err(src.at(
            p,
            "position",
            format!(
                "sensor {id}: give either position = [x, y] or latitude, longitude, altitude, not both"
            ),
        ));
    }
    let Some(r) = reference else {
        return Err(src.at(
            lat,
            "latitude",
            format!(
                "sensor {id}: a geodetic site needs the system reference point ([reference] latitude, longitude, altitude)"
            ),
        ));
    };
    let g = geodetic(src, &format!("sensor {id}"), lat, lon, s.altitude.as_ref())?;
    let enu = r.frame.geodetic_to_enu(&g);
    Ok(Some([enu.east, enu.north, enu.up]))
}

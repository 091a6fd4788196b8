//! Geography in `argus track`: the optional `[reference]` point (WGS-84), sensors given
//! by latitude, longitude and altitude (their East-North-Up position around the reference,
//! by `argus_geo`), and the latitude and longitude of a track's `x, y`.
//!
//! Inside Argus `x` is east and `y` north of the reference's local tangent plane
//! ([`argus_geo::LocalFrame`], GeographicLib's `LocalCartesian`); altitudes are heights
//! above the WGS-84 ellipsoid.

use argus_geo::{Enu, GeoError, Geodetic, LocalFrame, RadarSite};
use toml::Spanned;

use crate::error::ConfigError;
use crate::schema::{ReferenceTable, SensorTable, Source};
use argus_sensors::{Measurement, Plot, PolarMeasurement, SphericalMeasurement, wrap_angle};

/// How close (m) the height of a track's `lat, lon` point is brought to the reference's
/// altitude; with the normals of points 100 km apart about 0.9° apart, a height error
/// `δh` moves the point's east/north by about `δh · 0.016`, far below 1 mm.
const HEIGHT_TOL: f64 = 1e-6;

/// The system reference point: the origin of the local East-North-Up plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reference {
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
    pub fn lat_lon(&self, east: f64, north: f64) -> Result<(f64, f64), GeoError> {
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
) -> Result<Geodetic, ConfigError> {
    let h = alt.map_or(0.0, |a| *a.get_ref());
    Geodetic::from_degrees(*lat.get_ref(), *lon.get_ref(), h)
        .map_err(|e| src.at(lat, "latitude", format!("{what}: {e}")))
}

/// Checks `[reference]`.
///
/// # Errors
/// [`ConfigError::Input`] at the latitude's line for a latitude outside [−90°, 90°] or a
/// non-finite value.
pub(crate) fn reference(
    src: Source<'_>,
    table: Option<&Spanned<ReferenceTable>>,
) -> Result<Option<Reference>, ConfigError> {
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
/// `latitude, longitude, altitude`, and `γ`, the angle (rad, counter-clockwise) from the
/// reference frame's east axis to the site's own east axis
/// ([`argus_geo::RadarSite::grid_rotation`]; ≈ Δλ sin φ, 0.5° for a site 50 km east of
/// a reference at 49° N): the site's azimuths, measured from its own north, are turned
/// by `γ` into the reference frame. `None` when the sensor gives none of them (then
/// `position` is used and `γ = 0`).
///
/// # Errors
/// [`ConfigError::Input`] naming the line: geodetic keys together with `position`, a
/// latitude without a longitude (or the reverse), geodetic keys without a `[reference]`,
/// a bad latitude.
pub(crate) fn sensor_position(
    src: Source<'_>,
    s: &SensorTable,
    reference: Option<&Reference>,
) -> Result<Option<([f64; 3], f64)>, ConfigError> {
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
    let site = RadarSite::wgs84(g);
    let enu = site.position_in(&r.frame);
    Ok(Some((
        [enu.east, enu.north, enu.up],
        site.grid_rotation(&r.frame),
    )))
}

/// `p` in the reference frame: the azimuth of a polar or spherical plot of a geodetic
/// site turned by its `γ` (`rotations`: `(sensor, γ)`, `sensor_position`) and wrapped to
/// (−π, π]; every other plot as it is.
pub fn to_reference(rotations: &[(u32, f64)], p: Plot) -> Plot {
    let Some(&(_, gamma)) = rotations.iter().find(|(id, _)| *id == p.sensor().0) else {
        return p;
    };
    let turned = match *p.measurement() {
        Measurement::Polar(m) => {
            PolarMeasurement::new(m.range(), wrap_angle(m.azimuth() + gamma)).map(Measurement::from)
        }
        Measurement::Spherical(m) => {
            SphericalMeasurement::new(m.range(), wrap_angle(m.azimuth() + gamma), m.elevation())
                .map(Measurement::from)
        }
        Measurement::Cartesian2(_) | Measurement::Cartesian3(_) => return p,
    };
    // The measurement was valid and only its (wrapped) azimuth changed.
    turned
        .and_then(|m| Plot::new(p.time(), p.sensor(), m))
        .and_then(|plot| plot.with_amplitude(p.amplitude()))
        .unwrap_or(p)
}

#[cfg(test)]
mod tests {
    use crate::error::ConfigError;
    use crate::job::{Job, Loaded};

    /// Loads `text` as a configuration file.
    fn load(text: &str) -> Result<Loaded, ConfigError> {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("g.toml");
        std::fs::write(&p, text).unwrap();
        crate::job::load(&p)
    }

    const EST: &str = "\n[estimator]\nkind = \"kf-converted\"\nsigma_a = 1.0\n";

    #[test]
    fn a_geodetic_site_is_at_its_enu_position() {
        // GeographicLib's CartConvert documentation: `echo 33.3 44.4 6000 | CartConvert
        // -l 33 44 20` prints `37288.97 33374.29 5783.64` (cm: tolerance 0.005 m; the up
        // value is truncated, 0.01 m).
        let text = format!(
            "[reference]\nlatitude = 33.0\nlongitude = 44.0\naltitude = 20.0\n\n[[sensor]]\nid = 1\nlatitude = 33.3\nlongitude = 44.4\naltitude = 6000.0\n{EST}"
        );
        let l = load(&text).unwrap();
        let Job::Single { sensors, .. } = l.job else {
            panic!("not single");
        };
        let [e, n, u] = sensors[0].position;
        assert!((e - 37_288.97).abs() < 0.005, "{e}");
        assert!((n - 33_374.29).abs() < 0.005, "{n}");
        assert!((u - 5_783.64).abs() < 0.01, "{u}");
        // lat, lon of (e, n) at the reference's altitude, back by the closed form.
        let r = l.reference.unwrap();
        let (lat, lon) = r.lat_lon(e, n).unwrap();
        let g = argus_geo::Geodetic::from_degrees(lat, lon, 20.0).unwrap();
        let back = r.frame.geodetic_to_enu(&g);
        // 1 mm (issue 18); the point is 50 km out, 195 m below the tangent plane.
        assert!((back.east - e).hypot(back.north - n) < 1e-3);
        assert!((back.up + 195.0).abs() < 5.0, "{}", back.up);
    }

    #[test]
    fn a_geodetic_rotating_site_points_at_its_own_north_at_its_north_time() {
        // γ of a site 55 km east of the reference, at 49° N: ≈ Δλ sin φ = 0.566°. Its beam
        // points at the site's north at north_time = 2 s, which is the reference frame's
        // azimuth π/2 + γ; its plots' azimuths are turned by the same γ.
        for (dir, sense) in [("clockwise", -1.0), ("counterclockwise", 1.0)] {
            let text = format!(
                "[reference]\nlatitude = 49.0\nlongitude = 2.55\n\n[[sensor]]\nid = 1\nlatitude = 49.0\nlongitude = 3.3\nsigma_range = 70.0\nsigma_azimuth_deg = 0.08\nrevolution_period = 5.0\nrotation = \"{dir}\"\nnorth_time = 2.0\n{EST}"
            );
            let l = load(&text).unwrap();
            let Job::Single { sensors, .. } = &l.job else {
                panic!("not single");
            };
            let gamma = sensors[0].grid_rotation;
            // Δλ sin φ to first order; the exact value differs by O(Δλ³) (1e-6 rad here).
            let approx = 0.75_f64.to_radians() * 49.0_f64.to_radians().sin();
            assert!((gamma - approx).abs() < 1e-5, "{gamma} against {approx}");
            assert_eq!(l.grid_rotations, vec![(1, gamma)]);
            let r = sensors[0].rotation.unwrap();
            let beam = r.beam_azimuth(2.0);
            // Round-off of π/2 + γ through the time shift: 1e-12 rad.
            assert!(
                (beam - (std::f64::consts::FRAC_PI_2 + gamma)).abs() < 1e-12,
                "{dir}: {beam}"
            );
            // Half a second later the beam has turned 36° in its direction.
            let later = r.beam_azimuth(2.5);
            let turned = sense * 36.0_f64.to_radians();
            assert!((later - beam - turned).abs() < 1e-12, "{dir}: {later}");
        }
    }

    #[test]
    fn bad_geodetic_keys_name_their_line() {
        let cases = [
            // No reference.
            (
                "[[sensor]]\nid = 1\nlatitude = 33.3\nlongitude = 44.4\n",
                3,
                "reference",
            ),
            // Both a position and a site.
            (
                "[reference]\nlatitude = 33.0\nlongitude = 44.0\n[[sensor]]\nid = 1\nposition = [0.0, 0.0]\nlatitude = 33.3\nlongitude = 44.4\n",
                6,
                "not both",
            ),
            // A latitude alone.
            (
                "[reference]\nlatitude = 33.0\nlongitude = 44.0\n[[sensor]]\nid = 1\nlatitude = 33.3\n",
                6,
                "go together",
            ),
            // A latitude beyond the pole.
            (
                "[reference]\nlatitude = 91.0\nlongitude = 44.0\n",
                2,
                "reference",
            ),
            // Neither.
            ("[[sensor]]\nid = 4\n", 2, "needs position"),
        ];
        for (text, line, msg) in cases {
            let e = load(&format!("{text}{EST}")).unwrap_err();
            let s = e.to_string();
            assert!(
                s.contains(&format!("g.toml:{line}")) && s.contains(msg),
                "{text}: {s}"
            );
        }
    }
}

//! Radar sites: azimuth conventions, meridian convergence, typed errors.

#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use std::f64::consts::FRAC_PI_2;

use argus_geo::{Enu, GeoError, Geodetic, LocalFrame, RadarSite};
use argus_sensors::RadarAzimuth;

fn cdg() -> Geodetic {
    Geodetic::from_degrees(49.0097, 2.5479, 119.0).unwrap()
}

#[test]
fn site_at_reference_uses_the_plain_rule() {
    let reference = LocalFrame::wgs84(cdg());
    let site = RadarSite::wgs84(cdg());
    // θ = π/2 − α exactly (tolerance: round-off).
    for deg in [0.0, 45.0, 90.0, 180.0, 270.0, 359.0] {
        let alpha = f64::to_radians(deg);
        let theta = site
            .reference_azimuth(&reference, RadarAzimuth(alpha))
            .unwrap();
        let want = argus_sensors::radar_to_math_azimuth(alpha);
        assert!((theta - want).abs() < 1e-12, "{deg}: {theta} vs {want}");
        let back = site.radar_azimuth(&reference, theta).unwrap();
        assert!((back.0 - alpha).abs() < 1e-12, "{deg}");
    }
    let p = site
        .plot_to_reference(&reference, 50e3, RadarAzimuth(FRAC_PI_2), 0.0)
        .unwrap();
    assert!(
        (p.east - 50e3).abs() < 1e-8 && p.north.abs() < 1e-8 && p.up.abs() < 1e-8,
        "{p:?}"
    );
}

#[test]
fn meridian_convergence_of_a_site_east_of_the_reference() {
    let reference = LocalFrame::wgs84(cdg());
    // 0.4° of longitude east at the same latitude (≈ 29 km).
    let east = Geodetic::from_degrees(49.0097, 2.9479, 119.0).unwrap();
    let site = RadarSite::wgs84(east);
    let gamma = site.grid_rotation(&reference);
    // γ ≈ Δλ sin φ (spherical first order); tolerance 1 % of it for the ellipsoid and
    // second-order terms.
    let approx = 0.4f64.to_radians() * 49.0097f64.to_radians().sin();
    assert!(
        (gamma - approx).abs() < 0.01 * approx,
        "{gamma} vs {approx}"
    );
    // The site's north points slightly west of the reference's north: a plot due
    // north of the site lies at θ = π/2 + γ in the reference plane.
    let theta = site
        .reference_azimuth(&reference, RadarAzimuth(0.0))
        .unwrap();
    assert!((theta - (FRAC_PI_2 + gamma)).abs() < 1e-15);
    // The exact plot position agrees with the planar rule to the plane's tilt (a
    // plot 20 km out: the rule's direction error is below 1e-4 rad).
    let s = site.position_in(&reference);
    let p = site
        .plot_to_reference(&reference, 20e3, RadarAzimuth(0.0), 0.0)
        .unwrap();
    let dir = (p.north - s.north).atan2(p.east - s.east);
    assert!((dir - theta).abs() < 1e-4, "{dir} vs {theta}");
}

#[test]
fn typed_errors() {
    assert!(matches!(
        Geodetic::from_degrees(91.0, 0.0, 0.0),
        Err(GeoError::LatitudeOutOfRange { degrees }) if (degrees - 91.0).abs() < 1e-12
    ));
    assert!(matches!(
        Geodetic::from_degrees(f64::NAN, 0.0, 0.0),
        Err(GeoError::NonFinite {
            what: "latitude",
            ..
        })
    ));
    assert!(matches!(
        Geodetic::from_degrees(0.0, f64::INFINITY, 0.0),
        Err(GeoError::NonFinite {
            what: "longitude",
            ..
        })
    ));
    assert!(matches!(
        Geodetic::from_radians(0.0, 0.0, f64::NAN),
        Err(GeoError::NonFinite { what: "height", .. })
    ));
    assert!(matches!(
        argus_geo::Ellipsoid::new(6.4e6, -0.01),
        Err(GeoError::InvalidEllipsoid { .. })
    ));
    let site = RadarSite::wgs84(cdg());
    assert!(matches!(
        site.plot_to_site(-1.0, RadarAzimuth(0.0), 0.0),
        Err(GeoError::Negative { what: "range", .. })
    ));
    assert!(matches!(
        site.plot_to_site(1.0, RadarAzimuth(f64::NAN), 0.0),
        Err(GeoError::NonFinite {
            what: "azimuth",
            ..
        })
    ));
    // Longitude wraps; ±90° is accepted exactly.
    let g = Geodetic::from_degrees(90.0, 190.0, 0.0).unwrap();
    assert!((g.lon_deg() + 170.0).abs() < 1e-12 && (g.lat() - FRAC_PI_2).abs() < 1e-16);
    let _ = Enu {
        east: 0.0,
        north: 0.0,
        up: 0.0,
    };
}

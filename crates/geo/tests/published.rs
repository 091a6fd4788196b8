//! Against GeographicLib's published values.
//!
//! Sources: the EXAMPLES section of GeographicLib's CartConvert manual
//! (man/CartConvert.pod):
//!   `echo 33.3 44.4 6000 | CartConvert`          => `3816209.60 3737108.55 3485109.57`
//!   `echo 33.3 44.4 6000 | CartConvert -l 33 44 20` => `37288.97 33374.29 5783.64`
//!   `echo 30000 30000 0 | CartConvert -r`        => `6.483 45 -6335709.73`
//! and GeographicLib's test suite (tools/tests.cmake, test CartConvert0):
//!   `CartConvert -e 6.4e6 1/100 -r --input-string "10e3 0 1e3"`
//!   must match `85\.57[0-9]+ 0\.0[0]+ -6334614\.[0-9]+`.
//! Tolerances: half a unit of the last printed digit.

#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use argus_geo::{Ecef, Ellipsoid, Geodetic, LocalFrame};

#[test]
fn cartconvert_forward() {
    let e = Geodetic::from_degrees(33.3, 44.4, 6000.0)
        .unwrap()
        .to_ecef(&Ellipsoid::WGS84);
    assert!((e.x - 3_816_209.60).abs() <= 0.005, "{e:?}");
    assert!((e.y - 3_737_108.55).abs() <= 0.005, "{e:?}");
    assert!((e.z - 3_485_109.57).abs() <= 0.005, "{e:?}");
}

#[test]
fn cartconvert_local() {
    let frame = LocalFrame::wgs84(Geodetic::from_degrees(33.0, 44.0, 20.0).unwrap());
    let p = frame.geodetic_to_enu(&Geodetic::from_degrees(33.3, 44.4, 6000.0).unwrap());
    assert!((p.east - 37_288.97).abs() <= 0.005, "{p:?}");
    assert!((p.north - 33_374.29).abs() <= 0.005, "{p:?}");
    // The manual prints 5783.64; this gives 5783.6466 and so does map_3d 0.1.7's
    // independent geodetic2enu: the manual's digits are consistent with truncation
    // (37288.973 → .97, 33374.295 → .29, 5783.647 → .64), so the tolerance here is
    // one unit of the last digit.
    assert!((p.up - 5_783.64).abs() <= 0.01, "{p:?}");
}

#[test]
fn cartconvert_reverse_near_centre() {
    // Inside WGS-84's evolute (R = 42.4 km < a e² = 42.7 km): the nearest surface
    // point is off the equator.
    let g = Ecef {
        x: 30e3,
        y: 30e3,
        z: 0.0,
    }
    .to_geodetic(&Ellipsoid::WGS84)
    .unwrap();
    assert!((g.lat_deg() - 6.483).abs() <= 0.0005, "{g:?}");
    assert!((g.lon_deg() - 45.0).abs() <= 1e-12, "{g:?}");
    assert!((g.height() - -6_335_709.73).abs() <= 0.005, "{g:?}");
    // The mirror point below the equatorial plane has the mirror latitude... or, on
    // the plane itself, either sign: GeographicLib returns the northern one.
    assert!(g.lat() > 0.0);
}

#[test]
fn cartconvert0_other_ellipsoid() {
    let ell = Ellipsoid::new(6.4e6, 1.0 / 100.0).unwrap();
    let g = Ecef {
        x: 10e3,
        y: 0.0,
        z: 1e3,
    }
    .to_geodetic(&ell)
    .unwrap();
    assert!(g.lat_deg() >= 85.57 && g.lat_deg() < 85.58, "{g:?}");
    assert!(g.lon_deg().abs() < 0.5e-6, "{g:?}");
    assert!(
        g.height() <= -6_334_614.0 && g.height() > -6_334_615.0,
        "{g:?}"
    );
}

#[test]
fn centre_and_poles() {
    let wgs = Ellipsoid::WGS84;
    // At the centre the nearest surface points are the poles: h = −b.
    let c = Ecef {
        x: 0.0,
        y: 0.0,
        z: 0.0,
    }
    .to_geodetic(&wgs)
    .unwrap();
    assert!(
        (c.lat_deg() - 90.0).abs() < 1e-12 && (c.height() + wgs.b()).abs() < 1e-6,
        "{c:?}"
    );
    // On the axis: exactly ±90°, h = |z| − b (tolerance: round-off of b, 1e-9 m).
    for z in [wgs.b(), wgs.b() + 10_000.0, -(wgs.b() + 35_786e3)] {
        let g = Ecef { x: 0.0, y: 0.0, z }.to_geodetic(&wgs).unwrap();
        assert!(
            (g.lat().abs() - std::f64::consts::FRAC_PI_2).abs() < 1e-15,
            "{g:?}"
        );
        assert!(g.lat().signum() == z.signum());
        assert!((g.height() - (z.abs() - wgs.b())).abs() < 1e-9, "{g:?}");
    }
}

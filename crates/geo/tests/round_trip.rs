//! Geodetic → ECEF → geodetic over the whole Earth, poles included.
//!
//! One ulp of an ECEF coordinate near the surface is 9.3e-10 m; the forward map
//! and the inverse each round by about 1.5 ulp, so a round trip returns the height
//! to a few ulps at best: the tolerance is 4e-9 m (scaled up with the distance
//! from the centre for satellites), and 1e-14 rad in angle. The inverse alone is
//! checked to 1e-9 m in `high_precision.rs`.

#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use argus_geo::{Ellipsoid, Enu, Geodetic, LocalFrame};
use proptest::prelude::*;

const H_TOL: f64 = 4e-9;
const ANGLE_TOL: f64 = 1e-14;

fn check(lat_deg: f64, lon_deg: f64, h: f64) {
    let wgs = Ellipsoid::WGS84;
    let p = Geodetic::from_degrees(lat_deg, lon_deg, h).unwrap();
    let q = p.to_ecef(&wgs).to_geodetic(&wgs).unwrap();
    assert!((q.lat() - p.lat()).abs() <= ANGLE_TOL, "lat {p:?} -> {q:?}");
    // Longitude is undefined on the axis.
    if lat_deg.abs() < 90.0 {
        let dl = (q.lon() - p.lon()).abs();
        assert!(
            dl.min(std::f64::consts::TAU - dl) <= ANGLE_TOL / p.lat().cos().max(1e-3),
            "lon {p:?} -> {q:?}"
        );
    }
    assert!(
        (q.height() - h).abs() <= H_TOL * (1.0 + h.abs() / 6.4e6),
        "h {p:?} -> {q:?}"
    );
}

#[test]
fn grid_including_poles() {
    let heights = [-10_000.0, -100.0, 0.0, 1.0, 11_000.0, 400e3, 35_786e3];
    let mut lats: Vec<f64> = (-900..=900).map(|i| f64::from(i) * 0.1).collect();
    lats.extend([89.999_999_9, -89.999_999_9, 1e-9, -1e-9, 89.9, 45.0 + 1e-10]);
    for &lat in &lats {
        for &h in &heights {
            check(lat, 37.5, h);
        }
    }
}

proptest! {
    #[test]
    fn random_points(lat in -90.0f64..=90.0, lon in -180.0f64..180.0, h in -20e3f64..1e6) {
        check(lat, lon, h);
    }

    #[test]
    fn enu_round_trip(lat0 in -89.0f64..89.0, lon0 in -180.0f64..180.0,
                      e in -300e3f64..300e3, n in -300e3f64..300e3, u in -5e3f64..15e3) {
        let frame = LocalFrame::wgs84(Geodetic::from_degrees(lat0, lon0, 100.0).unwrap());
        let p = Enu { east: e, north: n, up: u };
        let q = frame.geodetic_to_enu(&frame.enu_to_geodetic(&p).unwrap());
        // Tolerance: a few ulps of the ECEF coordinates (see the module docs).
        prop_assert!((q.east - e).abs() < 1e-8 && (q.north - n).abs() < 1e-8 && (q.up - u).abs() < 1e-8,
            "{p:?} -> {q:?}");
    }
}

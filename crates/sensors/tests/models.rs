//! Residual wrapping, azimuth conventions, construction checks, SNR-dependent
//! noise and the linearised bias model.

#![allow(clippy::unwrap_used)] // test helpers: a failure is a test failure

use std::f64::consts::{FRAC_PI_2, PI};

use argus_core_math::{Matrix, Vector};
use argus_sensors::{
    Bearing2D, CartesianPosition, LinkBudget, MeasurementModel, Polar2D, PolarBias, RadarAzimuth,
    RadarNoise, SensorError, SnrNoise, Spherical3D, math_to_radar_azimuth, radar_to_math_azimuth,
    wrap_angle,
};
use proptest::prelude::*;

fn noise() -> RadarNoise {
    RadarNoise::constant(10.0, 1e-3, 1e-3).unwrap()
}

#[test]
fn residuals_wrap_across_pi() {
    // z = π − 0.01, ẑ = −π + 0.02: the true angular difference is −0.03 rad, not 2π − 0.03.
    let p = Polar2D::cv([0.0, 0.0], noise()).unwrap();
    let r = p.residual(
        &Vector::<2>::new(100.0, PI - 0.01),
        &Vector::<2>::new(90.0, -PI + 0.02),
    );
    assert!((r[0] - 10.0).abs() < 1e-12);
    assert!((r[1] + 0.03).abs() < 1e-12);
    let r = p.residual(
        &Vector::<2>::new(0.0, -PI + 0.02),
        &Vector::<2>::new(0.0, PI - 0.01),
    );
    assert!((r[1] - 0.03).abs() < 1e-12);

    let s = Spherical3D::cv([0.0, 0.0, 0.0], noise()).unwrap();
    let r = s.residual(
        &Vector::<3>::new(5.0, -PI + 0.005, 0.1),
        &Vector::<3>::new(5.0, PI - 0.005, 0.2),
    );
    assert!((r[1] - 0.01).abs() < 1e-12);
    assert!((r[2] + 0.1).abs() < 1e-12);

    let b = Bearing2D::cv([0.0, 0.0], 1e-3).unwrap();
    let r = b.residual(&Vector::<1>::new(PI), &Vector::<1>::new(-PI + 1e-3));
    assert!((r[0] + 1e-3).abs() < 1e-12);
}

#[test]
fn predictions_at_known_geometry() {
    // Target at (xs + 300, ys + 400): r = 500 (3-4-5), θ = atan2(4, 3) = 0.927295218 rad.
    let p = Polar2D::cv([100.0, -50.0], noise()).unwrap();
    let z = p.predict(&Vector::<4>::new(400.0, 0.0, 350.0, 0.0));
    assert!((z[0] - 500.0).abs() < 1e-10);
    assert!((z[1] - 0.927_295_218_001_612_2).abs() < 1e-14);
    // 3-D: (2, 3, 6) gives r = 7, ψ = atan2(3, 2), θ = atan2(6, √13).
    let s = Spherical3D::cv([1.0, 1.0, 1.0], noise()).unwrap();
    let z = s.predict(&Vector::<6>::new(3.0, 0.0, 4.0, 0.0, 7.0, 0.0));
    assert!((z[0] - 7.0).abs() < 1e-12);
    assert!((z[1] - 3f64.atan2(2.0)).abs() < 1e-15);
    assert!((z[2] - 6f64.atan2(13f64.sqrt())).abs() < 1e-15);
    // Inverting with seed 003 eq (9) gives back the relative position.
    let (r, psi, th) = (z[0], z[1], z[2]);
    assert!((r * psi.cos() * th.cos() - 2.0).abs() < 1e-12);
    assert!((r * psi.sin() * th.cos() - 3.0).abs() < 1e-12);
    assert!((r * th.sin() - 6.0).abs() < 1e-12);
}

#[test]
fn bad_indices_and_positions_are_rejected() {
    assert_eq!(
        Polar2D::<4>::new([0, 4], [0.0, 0.0], noise()),
        Err(SensorError::IndexOutOfRange { index: 4, dim: 4 })
    );
    assert_eq!(
        Spherical3D::<6>::new([0, 2, 0], [0.0; 3], noise()),
        Err(SensorError::DuplicateIndex { index: 0 })
    );
    assert!(matches!(
        Bearing2D::<4>::new([0, 2], [f64::NAN, 0.0], 1e-3),
        Err(SensorError::NonFinite { .. })
    ));
    assert!(matches!(
        Bearing2D::<4>::cv([0.0, 0.0], -1.0),
        Err(SensorError::Negative { .. })
    ));
    // Not positive definite / not symmetric / non-finite noise.
    assert!(matches!(
        CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::new(1.0, 2.0, 2.0, 1.0)),
        Err(SensorError::Math(_))
    ));
    assert!(CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::new(1.0, 0.5, 0.0, 1.0)).is_err());
    assert!(CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::new(f64::NAN, 0.0, 0.0, 1.0)).is_err());
    assert!(CartesianPosition::<4, 2>::new([0, 7], Matrix::<2, 2>::identity()).is_err());
}

#[test]
fn snr_noise_follows_the_link_budget() {
    // Δr = 150 m, BW = 0.04 rad, k_m = 2, SNR = 100 at 10 km (hand computation):
    // at 10 km: √(2·100) = 14.1421; σr = 150/14.1421 = 10.6066 m, σψ = 0.04/(2·14.1421) = 1.41421e-3.
    // at 20 km: SNR = 25, √50 = 7.07107; σr = 21.2132 m, σψ = 2.82843e-3.
    let link = LinkBudget::new(100.0, 10_000.0).unwrap();
    let snr = SnrNoise::new(150.0, 0.04, 0.04, 2.0, link).unwrap();
    let m = Polar2D::cv([0.0, 0.0], RadarNoise::Snr(snr)).unwrap();
    let r1 = m.noise(&Vector::<4>::new(6000.0, 0.0, 8000.0, 0.0));
    assert!((r1[(0, 0)].sqrt() - 10.6066).abs() < 1e-4);
    assert!((r1[(1, 1)].sqrt() - 1.41421e-3).abs() < 1e-8);
    assert!(r1[(0, 1)].abs() < 1e-300);
    let r2 = m.noise(&Vector::<4>::new(0.0, 0.0, -20_000.0, 0.0));
    assert!((r2[(0, 0)].sqrt() - 21.2132).abs() < 1e-4);
    assert!((r2[(1, 1)].sqrt() - 2.82843e-3).abs() < 1e-8);
    // The 3-D model uses the full slant range: (6 km, 0, 8 km) is also 10 km away.
    let s = Spherical3D::cv([0.0; 3], RadarNoise::Snr(snr)).unwrap();
    let r3 = s.noise(&Vector::<6>::new(6000.0, 0.0, 0.0, 0.0, 8000.0, 0.0));
    assert!((r3[(2, 2)].sqrt() - 1.41421e-3).abs() < 1e-8);
}

#[test]
fn bias_linearisation_is_first_order() {
    // Seed 004 eq (2): the biased converted plot minus the true position equals
    // B C β up to O(|β|²). Halving β must divide the remainder by ≈ 4.
    let beta = Vector::<4>::new(20.0, 2e-3, 3e-5, 2e-4); // seed 004 scenario biases
    for &(r, t) in &[(10_000.0, 0.5), (50_000.0, -2.0), (3_000.0, 2.9)] {
        let truth = Vector::<2>::new(r * f64::cos(t), r * f64::sin(t));
        let remainder = |k: f64| {
            let b = PolarBias::from_vector(&(beta * k)).unwrap();
            let (rb, tb) = b.apply(r, t).unwrap();
            let shifted = Vector::<2>::new(rb * tb.cos(), rb * tb.sin()) - truth;
            (shifted - b.cartesian_offset(r, t)).norm()
        };
        let first_order = PolarBias::from_vector(&beta)
            .unwrap()
            .cartesian_offset(r, t)
            .norm();
        let (e1, e2) = (remainder(1.0), remainder(0.5));
        // The remainder is tiny against the first-order term and scales as k².
        assert!(
            e1 < 1e-2 * first_order,
            "r = {r}: remainder {e1} vs {first_order}"
        );
        assert!((e1 / e2 - 4.0).abs() < 0.05, "r = {r}: ratio {}", e1 / e2);
    }
}

#[test]
fn radar_azimuth_newtype_round_trip() {
    let a = RadarAzimuth(1.25 * PI);
    assert!((RadarAzimuth::from_math(a.to_math()).0 - a.0).abs() < 1e-14);
    // South-west: 225° clockwise from north = −135° from +x.
    assert!((a.to_math() + 0.75 * PI).abs() < 1e-14);
    assert!((radar_to_math_azimuth(-FRAC_PI_2) - PI).abs() < 1e-14);
}

proptest! {
    #[test]
    fn azimuth_round_trip(radar in 0.0..std::f64::consts::TAU, math in -PI..PI) {
        // Round trips are the identity up to round-off (and the 0 ≡ 2π seam).
        let back = math_to_radar_azimuth(radar_to_math_azimuth(radar));
        prop_assert!(wrap_angle(back - radar).abs() < 1e-12);
        let m2 = radar_to_math_azimuth(math_to_radar_azimuth(math));
        prop_assert!(wrap_angle(m2 - math).abs() < 1e-12);
        prop_assert!((0.0..std::f64::consts::TAU).contains(&math_to_radar_azimuth(math)));
    }

    #[test]
    fn wrap_is_in_range_and_congruent(a in -1e4..1e4f64) {
        let w = wrap_angle(a);
        prop_assert!(w > -PI && w <= PI);
        let k = (a - w) / std::f64::consts::TAU;
        prop_assert!((k - k.round()).abs() < 1e-9);
    }
}

//! Analytic Jacobians and Hessians against central differences (proptest).

#![allow(clippy::unwrap_used)] // test helpers: a failure is a test failure

use argus_core_math::{Matrix, Vector};
use argus_sensors::{
    Bearing2D, CartesianPosition, LinearMeasurementModel, MeasurementModel, Polar2D, RadarNoise,
    Spherical3D,
};
use proptest::prelude::*;

/// Central-difference Jacobian, step `h` (truncation error O(h²)).
fn numeric_jacobian<const N: usize, const M: usize>(
    m: &impl MeasurementModel<N, M>,
    x: &Vector<N>,
    h: f64,
) -> Matrix<M, N> {
    let mut j = Matrix::<M, N>::zeros();
    for k in 0..N {
        let mut xp = *x;
        let mut xm = *x;
        xp[k] += h;
        xm[k] -= h;
        // residual() wraps the azimuth difference, so the difference is local.
        let d = m.residual(&m.predict(&xp), &m.predict(&xm)) / (2.0 * h);
        j.set_column(k, &d);
    }
    j
}

/// Central-difference Hessians from the analytic Jacobian (O(h²)).
fn numeric_hessians<const N: usize, const M: usize>(
    m: &impl MeasurementModel<N, M>,
    x: &Vector<N>,
    h: f64,
) -> [Matrix<N, N>; M] {
    let mut out = [Matrix::<N, N>::zeros(); M];
    for k in 0..N {
        let mut xp = *x;
        let mut xm = *x;
        xp[k] += h;
        xm[k] -= h;
        let dj = (m.jacobian(&xp) - m.jacobian(&xm)) / (2.0 * h);
        for (i, hi) in out.iter_mut().enumerate() {
            for l in 0..N {
                hi[(k, l)] = dj[(i, l)];
            }
        }
    }
    out
}

/// Relative closeness `|a − b| ≤ tol · max(1, scale)` entry by entry, `scale` the largest |a|.
fn close<const R: usize, const C: usize>(a: &Matrix<R, C>, b: &Matrix<R, C>, tol: f64) -> bool {
    let scale = a.amax().max(b.amax()).max(1e-300);
    (a - b).amax() <= tol * scale
}

fn noise2() -> RadarNoise {
    RadarNoise::constant(10.0, 1e-3, 1e-3).unwrap()
}

// Positions kept ≥ 100 m from the sensor (and off its vertical in 3-D), steps
// h = 1e-3·distance: central-difference error ~ (h/r)² ≈ 1e-6 relative, plus
// round-off ~1e-16·r/h ≈ 1e-13; tolerance 1e-5 relative.
proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn polar_derivatives(x in -5e4..5e4f64, y in -5e4..5e4f64, vx in -300.0..300.0f64,
                         vy in -300.0..300.0f64, xs in -1e3..1e3f64, ys in -1e3..1e3f64) {
        prop_assume!((x - xs).hypot(y - ys) > 100.0);
        let m = Polar2D::cv([xs, ys], noise2()).unwrap();
        let s = Vector::<4>::new(x, vx, y, vy);
        let h = 1e-3 * (x - xs).hypot(y - ys);
        prop_assert!(close(&m.jacobian(&s), &numeric_jacobian(&m, &s, h), 1e-5));
        let an = m.hessians(&s).unwrap();
        let nu = numeric_hessians(&m, &s, h);
        for i in 0..2 {
            prop_assert!(close(&an[i], &nu[i], 1e-5), "component {}: {} vs {}", i, an[i], nu[i]);
            prop_assert!(close(&an[i], &an[i].transpose(), 1e-14));
        }
    }

    #[test]
    fn polar_generic_layout(x in -5e4..5e4f64, y in -5e4..5e4f64) {
        prop_assume!(x.hypot(y) > 100.0);
        // Position at indices [3, 1] of a 5-state vector.
        let m = Polar2D::<5>::new([3, 1], [0.0, 0.0], noise2()).unwrap();
        let s = Vector::<5>::new(7.0, y, -2.0, x, 4.0);
        let h = 1e-3 * x.hypot(y);
        prop_assert!(close(&m.jacobian(&s), &numeric_jacobian(&m, &s, h), 1e-5));
        let an = m.hessians(&s).unwrap();
        let nu = numeric_hessians(&m, &s, h);
        for i in 0..2 {
            prop_assert!(close(&an[i], &nu[i], 1e-5));
        }
    }

    #[test]
    fn spherical_derivatives(x in -5e4..5e4f64, y in -5e4..5e4f64, z in -2e4..2e4f64,
                             xs in -1e3..1e3f64, ys in -1e3..1e3f64, zs in -100.0..100.0f64) {
        let rho = (x - xs).hypot(y - ys);
        prop_assume!(rho > 100.0);
        let m = Spherical3D::cv([xs, ys, zs], noise2()).unwrap();
        let s = Vector::<6>::new(x, 1.0, y, -2.0, z, 3.0);
        // Step relative to the horizontal distance, which sets the curvature scale of ψ and θ.
        let h = 1e-3 * rho;
        prop_assert!(close(&m.jacobian(&s), &numeric_jacobian(&m, &s, h), 1e-5));
        let an = m.hessians(&s).unwrap();
        let nu = numeric_hessians(&m, &s, h);
        for i in 0..3 {
            prop_assert!(close(&an[i], &nu[i], 1e-5), "component {}: {} vs {}", i, an[i], nu[i]);
            prop_assert!(close(&an[i], &an[i].transpose(), 1e-14));
        }
    }

    #[test]
    fn bearing_derivatives(x in -5e4..5e4f64, y in -5e4..5e4f64, xs in -1e3..1e3f64) {
        prop_assume!((x - xs).hypot(y) > 100.0);
        let m = Bearing2D::cv([xs, 0.0], 1e-3).unwrap();
        let s = Vector::<4>::new(x, 0.0, y, 0.0);
        let h = 1e-3 * (x - xs).hypot(y);
        prop_assert!(close(&m.jacobian(&s), &numeric_jacobian(&m, &s, h), 1e-5));
        let an = m.hessians(&s).unwrap();
        let nu = numeric_hessians(&m, &s, h);
        prop_assert!(close(&an[0], &nu[0], 1e-5));
    }

    #[test]
    fn cartesian_is_linear(x in -5e4..5e4f64, y in -5e4..5e4f64, z in -5e4..5e4f64) {
        let m = CartesianPosition::<6, 3>::cv(Matrix::<3, 3>::identity()).unwrap();
        let s = Vector::<6>::new(x, 1.0, y, 2.0, z, 3.0);
        // h(x) = H x exactly; the central difference of a linear map is exact up to round-off.
        prop_assert!((m.predict(&s) - m.matrix() * s).amax() < 1e-12 * s.amax().max(1.0));
        prop_assert!(close(&m.jacobian(&s), &numeric_jacobian(&m, &s, 1.0), 1e-9));
        prop_assert!(m.hessians(&s).unwrap().iter().all(|h| h.amax() < 1e-300));
        // The selection it declares is the one H applies: H's row k is the unit vector at
        // index k, and h(x)_k = x[index k] exactly.
        let sel = m.selection().unwrap();
        for (k, &i) in sel.iter().enumerate() {
            prop_assert!(i < 6);
            prop_assert!(m.matrix().row(k).iter().enumerate().all(|(j, &v)| (v - f64::from(u8::from(j == i))).abs() < 1e-300));
            prop_assert!(m.predict(&s)[k].to_bits() == s[i].to_bits());
        }
    }
}

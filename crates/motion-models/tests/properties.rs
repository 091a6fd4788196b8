//! Property tests: every Jacobian and Hessian against central differences, CT → CV as
//! ω → 0, the semigroup property `F(a) F(b) = F(a + b)`, and `Q` symmetric positive
//! semi-definite.
//!
//! Tolerances: central differences with step `h` have truncation error `O(h² f''')` and
//! rounding error `≈ ε |f| / h` (ε = 2.2e-16). Each comparison allows
//! `1e-6 · (max |column| + 1)` plus `1e3 ε max|f| / h` for the rounding of the states'
//! large position entries (1e5 m); a wrong term (a sign, a missing factor) shows as an
//! O(1) relative error, far outside.

// Test code: a failed constructor on a literal parameter is a test failure.
#![allow(clippy::unwrap_used)]

use argus_core_math::{Matrix, Vector};
use argus_motion_models::{
    Ca1D, Ca2D, Ca3D, ContinuousModel, CoordinatedTurn, CoordinatedTurnRate, Cv1D, Cv2D, Cv3D,
    LinearMotionModel, MotionModel, PlanarModel, QuadraticDrag,
};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

fn config(cases: u32) -> Config {
    Config {
        cases,
        rng_seed: RngSeed::Fixed(0x0A12_6D05),
        ..Config::default()
    }
}

/// Central-difference Jacobian of `f` at `x` with per-component steps `h`.
fn fd_jacobian<const N: usize, const M: usize>(
    f: impl Fn(&Vector<N>) -> Vector<M>,
    x: &Vector<N>,
    h: &Vector<N>,
) -> Matrix<M, N> {
    let mut j = Matrix::<M, N>::zeros();
    for k in 0..N {
        let mut xp = *x;
        let mut xm = *x;
        xp[k] += h[k];
        xm[k] -= h[k];
        j.set_column(k, &((f(&xp) - f(&xm)) / (2.0 * h[k])));
    }
    j
}

/// Checks `analytic ≈ numeric` column by column (tolerance in the module docs);
/// `fmax` is the magnitude of the differenced function's values.
fn assert_columns_close<const M: usize, const N: usize>(
    what: &str,
    analytic: &Matrix<M, N>,
    numeric: &Matrix<M, N>,
    h: &Vector<N>,
    fmax: f64,
) -> Result<(), TestCaseError> {
    for k in 0..N {
        let col = analytic
            .column(k)
            .abs()
            .max()
            .max(numeric.column(k).abs().max());
        let tol = 1e-6 * (col + 1.0) + 1e3 * f64::EPSILON * fmax / h[k];
        let err = (analytic.column(k) - numeric.column(k)).abs().max();
        prop_assert!(
            err <= tol,
            "{what}: column {k}: error {err:e} > tol {tol:e}\nanalytic {analytic}\nnumeric {numeric}"
        );
    }
    Ok(())
}

/// Checks every Hessian `∂²fᵢ/∂x²` against central differences of the analytic Jacobian.
fn check_hessians<const N: usize>(
    what: &str,
    model: &impl MotionModel<N>,
    x: &Vector<N>,
    dt: f64,
    h: &Vector<N>,
) -> Result<(), TestCaseError> {
    let hess = model.hessians(x, dt);
    prop_assert!(hess.is_some(), "{what}: no Hessians");
    let hess = hess.unwrap_or([Matrix::<N, N>::zeros(); N]);
    let jmax = model.jacobian(x, dt).abs().max();
    for (i, hi) in hess.iter().enumerate() {
        // Row i of the Jacobian as a function of x.
        let row = |y: &Vector<N>| model.jacobian(y, dt).row(i).transpose();
        let fd = fd_jacobian(row, x, h);
        prop_assert!((hi - hi.transpose()).abs().max() <= 1e-12 * (hi.abs().max() + 1.0));
        assert_columns_close(&format!("{what} Hessian {i}"), hi, &fd, h, jmax)?;
    }
    Ok(())
}

/// Checks the analytic Jacobian against central differences of `propagate`.
fn check_jacobian<const N: usize>(
    what: &str,
    model: &impl MotionModel<N>,
    x: &Vector<N>,
    dt: f64,
    h: &Vector<N>,
) -> Result<(), TestCaseError> {
    let fd = fd_jacobian(|y| model.propagate(y, dt), x, h);
    let fmax = model.propagate(x, dt).abs().max();
    assert_columns_close(what, &model.jacobian(x, dt), &fd, h, fmax)
}

/// `Q` symmetric and positive semi-definite (smallest eigenvalue ≥ −1e-12 max|Q|).
fn check_psd<const N: usize>(what: &str, q: &Matrix<N, N>) -> Result<(), TestCaseError> {
    let scale = q.abs().max();
    prop_assert!(
        (q - q.transpose()).abs().max() <= 1e-14 * scale,
        "{what}: asymmetric"
    );
    let dynamic = argus_core_math::nalgebra::DMatrix::from_column_slice(N, N, q.as_slice());
    let min_eig = dynamic.symmetric_eigenvalues().min();
    prop_assert!(
        min_eig >= -1e-12 * scale,
        "{what}: eigenvalue {min_eig:e}, scale {scale:e}"
    );
    Ok(())
}

fn position() -> impl Strategy<Value = f64> {
    -1e5..1e5_f64
}

fn velocity() -> impl Strategy<Value = f64> {
    // |v| ≤ 500 m/s with both components in ±353.
    -353.0..353.0_f64
}

/// Turn rates including exactly 0, tiny rates and the full ±0.2 rad/s.
fn turn_rate() -> impl Strategy<Value = f64> {
    prop_oneof![Just(0.0), -1e-9..1e-9_f64, -1e-3..1e-3_f64, -0.2..0.2_f64,]
}

fn interval() -> impl Strategy<Value = f64> {
    0.01..10.0_f64
}

fn planar_state() -> impl Strategy<Value = Vector<4>> {
    (position(), velocity(), position(), velocity())
        .prop_map(|(x, vx, y, vy)| Vector::<4>::new(x, vx, y, vy))
}

/// FD steps: 1 m for positions, 1e-3 m/s for velocities, 1e-6 rad/s for the turn rate.
fn steps4() -> Vector<4> {
    Vector::<4>::new(1.0, 1e-3, 1.0, 1e-3)
}

fn steps5() -> Vector<5> {
    Vector::<5>::new(1.0, 1e-3, 1.0, 1e-3, 1e-6)
}

proptest! {
    #![proptest_config(config(256))]

    #[test]
    fn linear_models_jacobian_and_hessians(
        x in planar_state(),
        omega in turn_rate(),
        dt in interval(),
    ) {
        let cv = Cv2D::discrete(1.0).unwrap();
        let ct = CoordinatedTurn::new(omega, 1.0).unwrap();
        let h = steps4();
        check_jacobian("CV2D", &cv, &x, dt, &h)?;
        check_jacobian("CT", &ct, &x, dt, &h)?;
        check_hessians("CV2D", &cv, &x, dt, &h)?;
        check_hessians("CT", &ct, &x, dt, &h)?;
        let planar = PlanarModel::Ct(ct);
        check_jacobian("Planar CT", &planar, &x, dt, &h)?;
        prop_assert_eq!(planar.transition(dt), planar.jacobian(&x, dt));
        // Linear models: propagate = F x.
        let fx = ct.transition(dt) * x;
        prop_assert!((ct.propagate(&x, dt) - fx).abs().max() <= 1e-12 * fx.abs().max());
    }

    #[test]
    fn ca_jacobian_and_hessians(
        p in prop::array::uniform9(-1e5..1e5_f64),
        dt in interval(),
    ) {
        let mut x = Vector::<9>::from_column_slice(&p);
        // Realistic velocities and accelerations: ≤ 500 m/s, ≤ 100 m/s².
        for k in 0..3 {
            x[3 * k + 1] *= 500.0 / 1e5;
            x[3 * k + 2] *= 100.0 / 1e5;
        }
        let ca = Ca3D::continuous(2.0).unwrap();
        let h = Vector::<9>::from_column_slice(&[1.0, 1e-3, 1e-3, 1.0, 1e-3, 1e-3, 1.0, 1e-3, 1e-3]);
        check_jacobian("CA3D", &ca, &x, dt, &h)?;
        check_hessians("CA3D", &ca, &x, dt, &h)?;
    }

    #[test]
    fn ct_rate_jacobian_and_hessians(
        x4 in planar_state(),
        omega in turn_rate(),
        dt in interval(),
    ) {
        let x = Vector::<5>::new(x4[0], x4[1], x4[2], x4[3], omega);
        let m = CoordinatedTurnRate::new(1.0, 0.01).unwrap();
        let h = steps5();
        check_jacobian("CT rate", &m, &x, dt, &h)?;
        check_hessians("CT rate", &m, &x, dt, &h)?;
        check_psd("CT rate Q", &m.process_noise(&x, dt))?;
    }

    #[test]
    fn drag_drift_derivatives(
        x in planar_state(),
        alpha in 0.0..1e-3_f64,
        u in (-5.0..5.0_f64, -5.0..5.0_f64),
    ) {
        // The continuous drift, Jacobian and Hessians; speeds kept ≥ 1 m/s (the drift is
        // not twice differentiable at zero speed).
        prop_assume!(x[1].hypot(x[3]) >= 1.0);
        let m = QuadraticDrag::new(alpha, 1.0)
            .unwrap()
            .with_input(Vector::<2>::new(u.0, u.1))
            .unwrap();
        let h = steps4();
        let fd = fd_jacobian(|y| m.drift(y), &x, &h);
        assert_columns_close("drift Jacobian", &m.drift_jacobian(&x), &fd, &h, m.drift(&x).abs().max())?;
        let a = m.drift_hessians(&x);
        let amax = m.drift_jacobian(&x).abs().max();
        for (i, hi) in a.iter().enumerate() {
            let fd = fd_jacobian(|y| m.drift_jacobian(y).row(i).transpose(), &x, &h);
            assert_columns_close(&format!("drift Hessian {i}"), hi, &fd, &h, amax)?;
        }
        prop_assert_eq!(m.diffusion(), Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(0.0, 1.0, 0.0, 1.0)));
    }
}

proptest! {
    // The drag model integrates RK4 (up to 50 substeps, Hessians on 4 + 16·5 numbers):
    // fewer cases keep the dev-profile run short.
    #![proptest_config(config(96))]

    #[test]
    fn drag_jacobian_and_hessians(
        pos in (position(), position()),
        speed in 50.0..500.0_f64,
        heading in -std::f64::consts::PI..std::f64::consts::PI,
        alpha in 0.0..1e-3_f64,
        u in (-5.0..5.0_f64, -5.0..5.0_f64),
        dt in 0.01..5.0_f64,
    ) {
        // |u| ≤ 7.1 m/s², dt ≤ 5 s: the speed changes by ≤ 36 m/s < 50, never reaching 0.
        let x = Vector::<4>::new(pos.0, speed * heading.cos(), pos.1, speed * heading.sin());
        let m = QuadraticDrag::new(alpha, 2.0)
            .unwrap()
            .with_input(Vector::<2>::new(u.0, u.1))
            .unwrap();
        let h = steps4();
        check_jacobian("drag", &m, &x, dt, &h)?;
        check_hessians("drag", &m, &x, dt, &h)?;
        check_psd("drag Q", &m.process_noise(&x, dt))?;
    }

    #[test]
    fn drag_jacobian_pure_drag_low_speed(
        x in planar_state(),
        scale in 1e-3..1.0_f64,
        alpha in 0.0..1e-3_f64,
        dt in 0.01..5.0_f64,
    ) {
        // Pure drag never stops the target, so speeds down to ~1 m/s are fine.
        let x = Vector::<4>::new(x[0], x[1] * scale, x[2], x[3] * scale);
        prop_assume!(x[1].hypot(x[3]) >= 1.0);
        let m = QuadraticDrag::new(alpha, 2.0).unwrap();
        check_jacobian("pure drag", &m, &x, dt, &steps4())?;
        check_hessians("pure drag", &m, &x, dt, &steps4())?;
    }

    #[test]
    fn semigroup_property(
        a in interval(),
        b in interval(),
        omega in turn_rate(),
    ) {
        // F(a) F(b) = F(a + b): exact for CV, CA and the CT rotation.
        let tol = |m: &Matrix<4, 4>| 1e-12 * m.abs().max().max(1.0);
        let cv = Cv2D::discrete(0.0).unwrap();
        let fab = cv.transition(a + b);
        prop_assert!((cv.transition(a) * cv.transition(b) - fab).abs().max() <= tol(&fab));
        let ct = CoordinatedTurn::new(omega, 0.0).unwrap();
        let fab = ct.transition(a + b);
        prop_assert!((ct.transition(a) * ct.transition(b) - fab).abs().max() <= tol(&fab));
        let ca = Ca2D::discrete(0.0).unwrap();
        let fab = ca.transition(a + b);
        let err = (ca.transition(a) * ca.transition(b) - fab).abs().max();
        prop_assert!(err <= 1e-12 * fab.abs().max());
        let cv3 = Cv3D::discrete(0.0).unwrap();
        let fab = cv3.transition(a + b);
        prop_assert!((cv3.transition(a) * cv3.transition(b) - fab).abs().max() <= 1e-12 * fab.abs().max());
        let ca1 = Ca1D::discrete(0.0).unwrap();
        let fab = ca1.transition(a + b);
        prop_assert!((ca1.transition(a) * ca1.transition(b) - fab).abs().max() <= 1e-12 * fab.abs().max());
    }

    #[test]
    fn ct_tends_to_cv(dt in interval(), sign in prop::bool::ANY) {
        let cv = Cv2D::discrete(0.5).unwrap().transition(dt);
        // Exact at ω = 0.
        prop_assert_eq!(CoordinatedTurn::new(0.0, 0.5).unwrap().transition(dt), cv);
        // At ω = ±1e-9: every entry differs from CV by at most θ·max(1, T), θ = |ω| T
        // (|sin θ| ≤ θ, 1 − cos θ ≤ θ²/2, T(1 − S) ≤ Tθ²/6, T C ≤ Tθ/2), i.e. within 1e-9
        // relative for T ≤ 1 s.
        let omega = if sign { 1e-9 } else { -1e-9 };
        let ct = CoordinatedTurn::new(omega, 0.5).unwrap().transition(dt);
        let theta = omega.abs() * dt;
        prop_assert!((ct - cv).abs().max() <= theta * cv.abs().max());
        // Continuity to first order: F(ω) − F(0) − ω ∂F/∂ω(0) is O(θ²), with ∂F/∂ω(0) from
        // the 5-state Jacobian's ω column for the unit velocity vectors.
        let m = CoordinatedTurnRate::new(0.0, 0.0).unwrap();
        let dvx = m.jacobian(&Vector::<5>::new(0.0, 1.0, 0.0, 0.0, 0.0), dt).column(4).into_owned();
        let dvy = m.jacobian(&Vector::<5>::new(0.0, 0.0, 0.0, 1.0, 0.0), dt).column(4).into_owned();
        let resid_vx = ct.column(1) - cv.column(1) - dvx.fixed_rows::<4>(0) * omega;
        let resid_vy = ct.column(3) - cv.column(3) - dvy.fixed_rows::<4>(0) * omega;
        let bound = theta * theta * dt.max(1.0) + 4.0 * f64::EPSILON * dt.max(1.0);
        prop_assert!(resid_vx.abs().max() <= bound, "{resid_vx}");
        prop_assert!(resid_vy.abs().max() <= bound, "{resid_vy}");
    }

    #[test]
    fn process_noise_psd(
        dt in interval(),
        sigma in 0.0..10.0_f64,
        omega in turn_rate(),
        x in planar_state(),
    ) {
        let z2 = Vector::<2>::zeros();
        let z3 = Vector::<3>::zeros();
        check_psd("CV1D d", &Cv1D::discrete(sigma).unwrap().process_noise(&z2, dt))?;
        check_psd("CV1D c", &Cv1D::continuous(sigma).unwrap().process_noise(&z2, dt))?;
        check_psd("CV2D c", &Cv2D::continuous(sigma).unwrap().process_noise(&x, dt))?;
        check_psd("CV3D d", &Cv3D::discrete(sigma).unwrap().process_noise(&Vector::<6>::zeros(), dt))?;
        check_psd("CA1D d", &Ca1D::discrete(sigma).unwrap().process_noise(&z3, dt))?;
        check_psd("CA1D c", &Ca1D::continuous(sigma).unwrap().process_noise(&z3, dt))?;
        check_psd("CA2D c", &Ca2D::continuous(sigma).unwrap().process_noise(&Vector::<6>::zeros(), dt))?;
        check_psd("CA3D d", &Ca3D::discrete(sigma).unwrap().process_noise(&Vector::<9>::zeros(), dt))?;
        check_psd("CT", &CoordinatedTurn::new(omega, sigma).unwrap().process_noise(&x, dt))?;
    }
}

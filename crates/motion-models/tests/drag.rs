//! The quadratic-drag model of seed 001: RK4 convergence order, conservation of direction
//! under pure drag, the closed form of 1-D quadratic drag, and the process noise against
//! an independent quadrature.

// Test code: a failed constructor on a literal parameter is a test failure.
#![allow(clippy::unwrap_used)]

use argus_core_math::{Matrix, Vector};
use argus_motion_models::{ContinuousModel, MotionModel, QuadraticDrag};

/// Closed form of pure quadratic drag along the initial direction:
/// `s(t) = s0 / (1 + α s0 t)`, distance `ln(1 + α s0 t) / α`.
fn exact_pure_drag(x0: &Vector<4>, alpha: f64, t: f64) -> Vector<4> {
    let s0 = x0[1].hypot(x0[3]);
    let (ux, uy) = (x0[1] / s0, x0[3] / s0);
    let k = 1.0 + alpha * s0 * t;
    let s = s0 / k;
    let d = k.ln() / alpha;
    Vector::<4>::new(x0[0] + d * ux, s * ux, x0[2] + d * uy, s * uy)
}

/// Checks errors `e` at steps h, h/2, h/4, … behave as `c h⁴ (1 + k h)`: every halving
/// ratio is above 16 minus rounding, the excess over 16 halves per halving of h (1.6–2.4),
/// and the finest ratio is within 16 ± 1.5.
fn assert_fourth_order(e: &[f64]) {
    let ratios: Vec<f64> = e.windows(2).map(|w| w[0] / w[1]).collect();
    for w in ratios.windows(2) {
        let shrink = (w[0] - 16.0) / (w[1] - 16.0);
        assert!(
            (1.6..2.4).contains(&shrink),
            "errors {e:?}, ratios {ratios:?}"
        );
    }
    let last = ratios.last().copied().unwrap_or(0.0);
    assert!((last - 16.0).abs() < 1.5, "errors {e:?}, ratios {ratios:?}");
}

fn model(alpha: f64, h: f64) -> QuadraticDrag {
    QuadraticDrag::new(alpha, 0.0)
        .and_then(|m| m.with_max_step(h))
        .unwrap()
}

#[test]
fn closed_form_planar_and_fourth_order() {
    // α = 2e-3 /m, 300 m/s heading 30°, 5 s: α s0 = 0.6 /s, a stiff enough case for the
    // RK4 error to stand above rounding. For a fourth-order method the error is
    // E(h) = c h⁴ (1 + k h + O(h²)), so the halving ratio E(h)/E(h/2) = 16 (1 + k h/2 + …):
    // it tends to 16 and its excess over 16 halves with each halving of h.
    let alpha = 2e-3;
    let x0 = Vector::<4>::new(1e4, 300.0 * 30f64.to_radians().cos(), -5e3, 150.0);
    let exact = exact_pure_drag(&x0, alpha, 5.0);
    let errs: Vec<f64> = [0.5, 0.25, 0.125, 0.0625]
        .iter()
        .map(|&h| (model(alpha, h).propagate(&x0, 5.0) - exact).abs().max())
        .collect();
    assert_fourth_order(&errs);
    // Default step (0.1 s): from the finest error, E(0.1) ≈ E(0.0625)·1.6⁴ ≈ 7e-5 m on a
    // 700 m track (1e-7 relative; measured 7.3e-5 m); bound 1e-4 m.
    let def = QuadraticDrag::new(alpha, 0.0).unwrap().propagate(&x0, 5.0);
    assert!(
        (def - exact).abs().max() < 1e-4,
        "{}",
        (def - exact).abs().max()
    );
}

#[test]
fn richardson_ratio_with_input() {
    // No closed form with an input: the successive differences x_h − x_{h/2} and
    // x_{h/2} − x_{h/4} of a fourth-order method have ratio 2⁴ = 16.
    let m = |h: f64| {
        model(1.5e-3, h)
            .with_input(Vector::<2>::new(3.0, -8.0))
            .unwrap()
    };
    let x0 = Vector::<4>::new(0.0, 250.0, 0.0, -40.0);
    let xs: Vec<Vector<4>> = [0.4, 0.2, 0.1, 0.05]
        .iter()
        .map(|&h| m(h).propagate(&x0, 8.0))
        .collect();
    let d: Vec<f64> = xs.windows(2).map(|w| (w[0] - w[1]).abs().max()).collect();
    // x_h − x_{h/2} = E(h) − E(h/2) = c h⁴ (15/16)(1 + O(h)): same law as the errors.
    assert_fourth_order(&d);
}

#[test]
fn pure_drag_conserves_direction() {
    // Every RK4 stage of v̇ = −α v|v| is parallel to v, so the heading is kept to rounding.
    let m = QuadraticDrag::new(1e-3, 0.0).unwrap();
    for heading in [0.3_f64, 2.0, -2.9, -0.7] {
        let x0 = Vector::<4>::new(100.0, 400.0 * heading.cos(), -50.0, 400.0 * heading.sin());
        let y = m.propagate(&x0, 30.0);
        let turned = (y[3].atan2(y[1]) - heading).abs();
        assert!(turned < 1e-14, "heading {heading}: turned {turned:e}");
        // Position moves along the same line.
        let moved = (y[2] - x0[2]).atan2(y[0] - x0[0]);
        assert!((moved - heading).abs() < 1e-13);
    }
}

#[test]
fn one_dimensional_speed_decay() {
    // v(t) = v0 / (1 + α v0 t) (1-D quadratic drag) at several times; RK4, h = 0.1 s,
    // α v0 h ≤ 0.02: relative error ≤ 1e-8 (measured 4e-11 to 8e-10).
    let (alpha, v0) = (5e-4, 400.0);
    let m = QuadraticDrag::new(alpha, 0.0).unwrap();
    for t in [1.0, 10.0, 60.0, 300.0] {
        let y = m.propagate(&Vector::<4>::new(0.0, -v0, 0.0, 0.0), t);
        let v = -v0 / (1.0 + alpha * v0 * t);
        assert!(
            (y[1] - v).abs() < 1e-8 * v.abs(),
            "t = {t}: {} vs {v}",
            y[1]
        );
    }
}

#[test]
#[allow(non_snake_case)]
fn process_noise_matches_quadrature() {
    // Q(T) = ∫₀ᵀ Φ(T, s) Q_c Φ(T, s)ᵀ ds for the linearisation about the trajectory, with
    // Φ(T, s) = the model's Jacobian at x(s) over T − s (independent of the Lyapunov
    // integration inside `process_noise`). Composite Simpson, 200 panels; both sides carry
    // O(h⁴) errors, relative ≈ 1e-8 (measured 7e-11);
    // bound 1e-6.
    let alpha = 1e-3;
    let m = QuadraticDrag::new(alpha, 3.0)
        .and_then(|m| m.with_max_step(0.01))
        .unwrap();
    let x0 = Vector::<4>::new(3e3, 200.0, 3e3, -120.0);
    let t = 4.0;
    let n = 200;
    let hq = t / f64::from(n);
    let Qc = m.diffusion();
    let mut acc = Matrix::<4, 4>::zeros();
    for i in 0..=n {
        let s = f64::from(i) * hq;
        let xs = m.propagate(&x0, s);
        let phi = m.jacobian(&xs, t - s);
        let w = if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        acc += phi * Qc * phi.transpose() * (w * hq / 3.0);
    }
    let q = m.process_noise(&x0, t);
    let err = (q - acc).abs().max();
    assert!(err < 1e-6 * q.abs().max(), "err {err:e}\n{q}\n{acc}");
}

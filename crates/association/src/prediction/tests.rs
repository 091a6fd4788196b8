use super::hyca::R_PANELS;
use super::irf::IrfNodes;
use super::*;
use crate::gate::Gate;
use crate::quadrature::gamma_half;
use argus_core_math::unit_ball_volume;

/// The previous evaluation of `q₂` (trapezoid step 0.04 in `ln t`, 8 × 16 radius
/// nodes, all recomputed per `t`), kept as the reference for the fast one.
/// Calls `f(r, weight)` on the composite Gauss–Legendre nodes of `[0, rmax]`.
fn nodes<F: FnMut(f64, f64)>(rmax: f64, f: &mut F) {
    let (x, w) = crate::quadrature::gauss_legendre::<16>();
    let h = rmax / R_PANELS as f64;
    for p in 0..R_PANELS {
        let mid = (p as f64 + 0.5) * h;
        for (xi, wi) in x.iter().zip(w.iter()) {
            f(mid + 0.5 * h * xi, 0.5 * h * wi);
        }
    }
}

fn q2_reference(gate: &Gate, mu: f64, p_d: f64) -> f64 {
    let n = gate.dim();
    let nf = n as f64;
    let gamma = gate.gamma();
    let rmax = gamma.sqrt();
    let miss = 1.0 - p_d * gate.p_gate();
    let b = mu * (2.0 * std::f64::consts::PI).powf(nf / 2.0) * miss
        / (p_d * unit_ball_volume(n) * gamma.powf(nf / 2.0));
    let h_norm = nf / gamma.powf(nf / 2.0);
    let g_norm = 2.0 / (2f64.powf(nf / 2.0) * gamma_half(n));
    let inner = |t: f64| {
        let (mut phi, mut psi, mut phi_t, mut psi_t) = (0.0, 0.0, 0.0, 0.0);
        let mut acc = |r: f64, wgt: f64| {
            let q = r * r;
            let eps = (-0.5 * q).exp();
            let et = (-t * eps).exp();
            let rn1 = r.powi(n as i32 - 1);
            let h = h_norm * rn1 * wgt;
            let g = g_norm * rn1 * eps * wgt;
            phi += h * et;
            psi += h * eps * eps * q * et;
            phi_t += g * et;
            psi_t += g * eps * eps * q * et;
        };
        nodes(rmax, &mut acc);
        let c = (-mu * (1.0 - phi)).exp();
        c * ((miss + p_d * phi_t) * mu * psi + p_d * psi_t)
    };
    let eps_min = (-0.5 * gamma).exp();
    let s_lo = (1e-4f64).ln();
    let s_hi = (60.0 / b.max(eps_min)).ln();
    let steps = ((s_hi - s_lo) / 0.04).ceil().max(10.0) as usize;
    let hs = (s_hi - s_lo) / steps as f64;
    let mut total = 0.0;
    for k in 0..=steps {
        let t = (s_lo + k as f64 * hs).exp();
        let w = if k == 0 || k == steps { 0.5 } else { 1.0 };
        total += w * t * t * (-t * b).exp() * inner(t);
    }
    total * hs / nf
}

#[test]
fn fast_q2_matches_finer_quadratures_and_the_previous_one() {
    // The rule used (h = 0.3 from t = 1e-8, 4 × 16 radius nodes) against the same
    // nodes with h = 0.05 from t = 1e-10: below 1e-9 relative (IRF_STEP's stated
    // error). Against the previous rule, which cut the t-integral at 1e-4: below
    // 2e-5 relative (its truncation error at μ = 50; below 1e-6 for μ ≤ 10).
    for n in 1..=3 {
        for gamma in [4.0, 9.0, 16.0, 25.0] {
            let gate = Gate::from_threshold(gamma, n).unwrap();
            for p_d in [0.5, 0.9, 1.0] {
                let nodes = IrfNodes::new(&gate, p_d).unwrap();
                for mu in [0.0, 1e-3, 0.1, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0] {
                    let fast = pda_irf(&gate, mu, p_d).unwrap();
                    let fine = nodes.q2_with(mu, 0.05, 1e-10);
                    let old = q2_reference(&gate, mu, p_d);
                    let case = format!("n {n} γ {gamma} P_D {p_d} μ {mu}");
                    assert!((fast / fine - 1.0).abs() < 1e-9, "{case}: {fast} vs {fine}");
                    let tol = if mu <= 10.0 { 1e-6 } else { 2e-5 };
                    assert!((fast / old - 1.0).abs() < tol, "{case}: {fast} vs {old}");
                }
            }
        }
    }
}

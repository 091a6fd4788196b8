//! The information reduction factor `q₂` of the PDA filter.

use argus_core_math::unit_ball_volume;

use crate::error::{AssociationError, check_non_negative, check_prob_open_closed};
use crate::gate::Gate;
use crate::quadrature::gamma_half;

/// The PDA filter's information reduction factor `q₂`: with `μ = λV` expected clutter
/// plots in the gate, the expected PDA covariance is `E[P(k|k)] = P⁻ − q₂ W S Wᵀ`,
/// where `q₂ S = E[ν̄ ν̄ᵀ]` (`ν̄ = Σβᵢνᵢ`, the combined innovation).
///
/// Computed without simulation: in whitened coordinates the gate is the ball of radius
/// `√γ`, `eᵢ ∝ εᵢ = e^{−qᵢ/2}`, and `E‖ν̄‖² = E[Σ εᵢ² qᵢ / (b′ + Σ εᵢ)²]` over a Poisson(μ)
/// number of uniform clutter plots plus the target's plot (probability `P_D`, density
/// `χ_n` in the gate). Writing `1/D² = ∫₀^∞ t e^{−tD} dt` and using the Poisson
/// generating functional reduces it to one integral over `t` of integrals over the
/// radius:
///
/// ```text
/// n q₂ = ∫₀^∞ t e^{−t b′} C(t) { [1 − P_D P_G + P_D φ_T(t)] μ ψ(t) + P_D ψ_T(t) } dt
/// C(t) = exp(−μ [1 − φ(t)]),   φ = E_u[e^{−tε}],  ψ = E_u[ε² q e^{−tε}]  (uniform in gate)
/// φ_T = E_t[e^{−tε}; gate],   ψ_T = E_t[ε² q e^{−tε}; gate]              (target, χ²_n)
/// b′ = μ (2π)^{n/2} (1 − P_D P_G) / (P_D c_n γ^{n/2})
/// ```
///
/// At `μ = 0` this is `q₂ = P_D P(χ²_{n+2} ≤ γ)` (checked in the tests), and the whole
/// function is checked against direct sampling of the PDA weights.
///
/// # References
/// Kershaw, D. J. & Evans, R. J. (1996), "A contribution to performance prediction for
/// probabilistic data association tracking filters", IEEE TAES 32(3) (the
/// information-reduction-factor Riccati recursion); Fortmann, Bar-Shalom, Scheffe &
/// Gelfand (1985) (`q₂`); seed 002 §2.3. The reduction to a single `t`-integral is ours.
///
/// # Errors
/// [`AssociationError::InvalidParameter`] for `μ < 0` or `P_D ∉ (0, 1]`.
pub fn pda_irf(gate: &Gate, mu: f64, p_d: f64) -> Result<f64, AssociationError> {
    IrfNodes::new(gate, p_d)?.q2(mu)
}

/// Step of the trapezoid rule in `s = ln t` for the `t`-integral of [`pda_irf`].
///
/// The integrand is analytic in a strip around the real `s`-axis and negligible at
/// both ends (`t ∈ [10⁻⁸, 60/max(b′, e^{−γ/2})]`), so the trapezoid error falls
/// exponentially with `1/h`: against the same rule with `h = 0.05` and `t` from
/// `10⁻¹⁰` the relative difference is below 1e-9 for `μ ∈ [0, 50]`,
/// `P_D ∈ [0.5, 1]`, `γ ∈ [4, 25]`, `n ∈ {1, 2, 3}` (tested). The previous rule
/// (`h = 0.04`, `t` from `10⁻⁴`, 8 × 16 radius nodes recomputed at every `t`) cut the
/// integral off too early at large `μ`: it differs by up to 2e-5 relative at `μ = 50`.
const IRF_STEP: f64 = 0.3;
/// Lower end of the `t`-integral of [`pda_irf`].
const IRF_T_MIN: f64 = 1e-8;
/// Radius panels (16 nodes each) for the inner integrals of [`pda_irf`].
const IRF_PANELS: usize = 4;
/// Radius nodes of [`pda_irf`].
const IRF_NODES: usize = 16 * IRF_PANELS;

/// The radius nodes of the [`pda_irf`] integrals, precomputed once per gate and `P_D`
/// (they do not depend on `μ`), so that one `q₂(μ)` costs one `exp` per node and
/// `t`-point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct IrfNodes {
    n: usize,
    gamma: f64,
    p_d: f64,
    miss: f64,
    /// `b′ / μ`.
    b_per_mu: f64,
    /// `ε = e^{−q/2}` per node.
    eps: [f64; IRF_NODES],
    /// Uniform-in-gate weight per node.
    h: [f64; IRF_NODES],
    /// Target (`χ_n`) weight per node, `ε` included.
    g: [f64; IRF_NODES],
    /// `ε² q` per node.
    e2q: [f64; IRF_NODES],
}

impl IrfNodes {
    pub(super) fn new(gate: &Gate, p_d: f64) -> Result<Self, AssociationError> {
        check_prob_open_closed(p_d, "detection probability")?;
        let n = gate.dim();
        let nf = n as f64;
        let gamma = gate.gamma();
        let rmax = gamma.sqrt();
        let miss = 1.0 - p_d * gate.p_gate();
        let b_per_mu = (2.0 * std::f64::consts::PI).powf(nf / 2.0) * miss
            / (p_d * unit_ball_volume(n) * gamma.powf(nf / 2.0));
        let h_norm = nf / gamma.powf(nf / 2.0);
        let g_norm = 2.0 / (2f64.powf(nf / 2.0) * gamma_half(n));
        let mut out = Self {
            n,
            gamma,
            p_d,
            miss,
            b_per_mu,
            eps: [0.0; IRF_NODES],
            h: [0.0; IRF_NODES],
            g: [0.0; IRF_NODES],
            e2q: [0.0; IRF_NODES],
        };
        let (x, w) = crate::quadrature::gauss_legendre::<16>();
        let hr = rmax / IRF_PANELS as f64;
        let mut i = 0;
        for p in 0..IRF_PANELS {
            let mid = (p as f64 + 0.5) * hr;
            for (xi, wi) in x.iter().zip(w.iter()) {
                let r = mid + 0.5 * hr * xi;
                let wgt = 0.5 * hr * wi;
                let q = r * r;
                let eps = (-0.5 * q).exp();
                let rn1 = r.powi(n as i32 - 1);
                if let (Some(e), Some(h), Some(g), Some(e2q)) = (
                    out.eps.get_mut(i),
                    out.h.get_mut(i),
                    out.g.get_mut(i),
                    out.e2q.get_mut(i),
                ) {
                    *e = eps;
                    *h = h_norm * rn1 * wgt;
                    *g = g_norm * rn1 * eps * wgt;
                    *e2q = eps * eps * q;
                }
                i += 1;
            }
        }
        Ok(out)
    }

    /// `q₂(μ)` (see [`pda_irf`]).
    fn q2(&self, mu: f64) -> Result<f64, AssociationError> {
        check_non_negative(mu, "expected clutter plots in the gate μ = λV")?;
        Ok(self.q2_with(mu, IRF_STEP, IRF_T_MIN))
    }

    /// `q₂(μ)` with trapezoid step `step` in `ln t` from `t = t_min`.
    pub(super) fn q2_with(&self, mu: f64, step: f64, t_min: f64) -> f64 {
        let b = mu * self.b_per_mu;
        let inner = |t: f64| {
            let (mut phi, mut psi, mut phi_t, mut psi_t) = (0.0, 0.0, 0.0, 0.0);
            for (((eps, h), g), e2q) in self.eps.iter().zip(&self.h).zip(&self.g).zip(&self.e2q) {
                let et = (-t * eps).exp();
                let (he, ge) = (h * et, g * et);
                phi += he;
                psi += he * e2q;
                phi_t += ge;
                psi_t += ge * e2q;
            }
            let c = (-mu * (1.0 - phi)).exp();
            c * ((self.miss + self.p_d * phi_t) * mu * psi + self.p_d * psi_t)
        };
        // t = e^s, dt = t ds: ∫ t² e^{−tb′} inner(t) ds by the trapezoid rule.
        let eps_min = (-0.5 * self.gamma).exp();
        let s_lo = t_min.ln();
        let s_hi = (60.0 / b.max(eps_min)).ln();
        let steps = ((s_hi - s_lo) / step).ceil().max(10.0) as usize;
        let hs = (s_hi - s_lo) / steps as f64;
        let mut total = 0.0;
        for k in 0..=steps {
            let t = (s_lo + k as f64 * hs).exp();
            let w = if k == 0 || k == steps { 0.5 } else { 1.0 };
            total += w * t * t * (-t * b).exp() * inner(t);
        }
        total * hs / self.n as f64
    }
}

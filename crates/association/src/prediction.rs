//! Off-line performance prediction in clutter: the HYCA recursion of the NN filter
//! and the information-reduction-factor recursion of the PDA filter.

use argus_core_math::{
    Matrix, SpdFactor, check_finite_matrix, chi2_cdf, symmetrize, unit_ball_volume,
};

use crate::error::{AssociationError, check_non_negative, check_prob_open_closed};
use crate::gate::Gate;
use crate::quadrature::{gamma_half, integrate};

/// Quadrature panels (16 nodes each) over the gate radius `r = √q ∈ [0, √γ]`.
const R_PANELS: usize = 8;

/// The scalars `(c_T, c_F)` of the NN filter's HYCA recursion,
/// `P̄(k|k) = P̄(k|k−1) − [c_T − c_F] W̄ S̄ W̄ᵀ`, with `β = λ c_n |S̄|^{1/2}`:
///
/// ```text
/// c_F = (β/2) ∫₀^γ q^{n/2} e^{−β q^{n/2}} [1 − P_D P(χ²_n ≤ q)] dq
/// c_T = P_D / (2^{n/2+1} Γ(n/2+1)) ∫₀^γ q^{n/2} e^{−β q^{n/2} − q/2} dq
/// ```
///
/// `c_T` is `E[(q/n) 1{M_T}]` (target plot nearest at normalised distance `q`), `c_F`
/// is `E[(q/n) 1{M_F}]` (a clutter plot nearest; `β (n/2) q^{n/2−1} e^{−βq^{n/2}}` is the
/// density of the nearest clutter plot's distance).
///
/// Seed 002's Fig. 2 prints the exponent of `q` and the upper limits as `γ/2`; they are
/// `n/2` and `γ` (re-derived above, and by the closed form for `n = 2` in the tests).
///
/// # References
/// Li, X. R. & Bar-Shalom, Y. (1996), "Tracking in clutter with nearest neighbor
/// filters: analysis and performance", IEEE TAES 32(3); seed 002 §2.2, Fig. 2 (corrected).
///
/// # Errors
/// [`AssociationError::InvalidParameter`] for `β < 0`, `P_D ∉ (0, 1]`; chi-square
/// errors for `n ∉` the supported range.
pub fn hyca_factors(gate: &Gate, beta: f64, p_d: f64) -> Result<(f64, f64), AssociationError> {
    check_non_negative(beta, "HYCA β = λ c_n |S|^{1/2}")?;
    check_prob_open_closed(p_d, "detection probability")?;
    let n = gate.dim();
    let nf = n as f64;
    let rmax = gate.gamma().sqrt();
    let norm = 2.0 * p_d / (nf * 2f64.powf(nf / 2.0) * gamma_half(n));
    let c_t = integrate(0.0, rmax, R_PANELS, |r| {
        norm * r.powi(n as i32 + 1) * (-0.5 * r * r - beta * r.powi(n as i32)).exp()
    });
    let mut err = None;
    let c_f = integrate(0.0, rmax, R_PANELS, |r| {
        let q = r * r;
        let g = if n == 2 {
            -(-0.5 * q).exp_m1()
        } else {
            chi2_cdf(q, nf).unwrap_or_else(|e| {
                err = Some(e);
                0.0
            })
        };
        beta * r.powi(n as i32 + 1) * (-beta * r.powi(n as i32)).exp() * (1.0 - p_d * g)
    });
    if let Some(e) = err {
        return Err(e.into());
    }
    Ok((c_t, c_f))
}

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
    check_non_negative(mu, "expected clutter plots in the gate μ = λV")?;
    check_prob_open_closed(p_d, "detection probability")?;
    let n = gate.dim();
    let nf = n as f64;
    let gamma = gate.gamma();
    let rmax = gamma.sqrt();
    let p_g = gate.p_gate();
    let miss = 1.0 - p_d * p_g;
    let b = mu * (2.0 * std::f64::consts::PI).powf(nf / 2.0) * miss
        / (p_d * unit_ball_volume(n) * gamma.powf(nf / 2.0));
    let h_norm = nf / gamma.powf(nf / 2.0);
    let g_norm = 2.0 / (2f64.powf(nf / 2.0) * gamma_half(n));
    let inner = |t: f64| {
        let (mut phi, mut psi, mut phi_t, mut psi_t) = (0.0, 0.0, 0.0, 0.0);
        // Four integrals on the same nodes: evaluate each node once.
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
    // t = e^s, dt = t ds: ∫ t² e^{−tb′} inner(t) ds by the trapezoid rule (smooth,
    // decaying at both ends).
    let eps_min = (-0.5 * gamma).exp();
    let s_lo = (1e-4f64).ln();
    let s_hi = (60.0 / b.max(eps_min)).ln();
    let steps = ((s_hi - s_lo) / 0.04).ceil().max(10.0) as usize;
    let hs = (s_hi - s_lo) / steps as f64;
    let mut total = 0.0;
    for k in 0..=steps {
        let s = s_lo + k as f64 * hs;
        let t = s.exp();
        let w = if k == 0 || k == steps { 0.5 } else { 1.0 };
        total += w * t * t * (-t * b).exp() * inner(t);
    }
    Ok(total * hs / nf)
}

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

/// Which filter's expected covariance to predict.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PredictedFilter {
    /// The NN filter's HYCA recursion (factor `c_T − c_F`); the NN filter is assumed to
    /// use the recursion's own gain `W̄` (Li & Bar-Shalom 1996).
    NearestNeighbour,
    /// The PDA filter's information-reduction-factor recursion (factor `q₂`).
    Pda,
}

/// A linear-Gaussian system `x(k) = F x(k−1) + v`, `Cov v = Q`; `z = H x + w`,
/// `Cov w = R`, for the off-line recursions.
#[allow(non_snake_case)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearSystem<const N: usize, const M: usize> {
    F: Matrix<N, N>,
    Q: Matrix<N, N>,
    H: Matrix<M, N>,
    R: Matrix<M, M>,
}

impl<const N: usize, const M: usize> LinearSystem<N, M> {
    /// The system `(F, Q, H, R)`.
    ///
    /// # Errors
    /// [`AssociationError::Math`] when a matrix is non-finite, `Q` is not symmetric
    /// positive semi-definite (checked as `Q + εI` PD) or `R` is not positive definite.
    #[allow(non_snake_case)]
    pub fn new(
        F: Matrix<N, N>,
        Q: Matrix<N, N>,
        H: Matrix<M, N>,
        R: Matrix<M, M>,
    ) -> Result<Self, AssociationError> {
        check_finite_matrix(&F, "transition matrix F")?;
        check_finite_matrix(&Q, "process noise Q")?;
        check_finite_matrix(&H, "measurement matrix H")?;
        check_finite_matrix(&R, "measurement noise R")?;
        let scale = Q.abs().max().max(1e-300);
        SpdFactor::new(
            &(Q + Matrix::<N, N>::identity() * (scale * 1e-9)),
            "process noise Q",
        )?;
        SpdFactor::new(&R, "measurement noise R")?;
        Ok(Self { F, Q, H, R })
    }
}

/// One step of an off-line recursion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PredictionStep<const N: usize, const M: usize> {
    /// `P̄(k|k−1)`.
    pub predicted: Matrix<N, N>,
    /// `S̄(k)`.
    pub s: Matrix<M, M>,
    /// `W̄(k) = P̄(k|k−1) Hᵀ S̄⁻¹`.
    pub gain: Matrix<N, M>,
    /// Expected clutter plots in the gate `μ = λ V̄`.
    pub mu: f64,
    /// The information reduction factor (`c_T − c_F` or `q₂`).
    pub factor: f64,
    /// `P̄(k|k) = P̄(k|k−1) − factor · W̄ S̄ W̄ᵀ`.
    pub posterior: Matrix<N, N>,
}

/// The outcome of iterating a recursion to steady state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SteadyState<const N: usize, const M: usize> {
    /// The recursion converged.
    Converged {
        /// The last step (its `posterior` is the steady state).
        step: PredictionStep<N, M>,
        /// Iterations used.
        iterations: usize,
    },
    /// The covariance grew without bound: the prediction says the track is lost (no
    /// finite steady-state error to report).
    Diverged {
        /// Iteration at which the trace exceeded the bound.
        iterations: usize,
        /// `tr P̄(k|k)` then.
        trace: f64,
    },
}

/// Off-line predictor of a clutter filter's expected error covariance from `P_D`, the
/// clutter density and the gate, without simulation.
///
/// # References
/// Li & Bar-Shalom (1996) (HYCA, NN); Kershaw & Evans (1996) (PDA); seed 002 §2.2–2.3.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PerformancePredictor<const N: usize, const M: usize> {
    system: LinearSystem<N, M>,
    gate: Gate,
    p_d: f64,
    density: f64,
    filter: PredictedFilter,
}

impl<const N: usize, const M: usize> PerformancePredictor<N, M> {
    /// The predictor of `filter` on `system` with gate `gate`, detection probability
    /// `p_d` and clutter density `density`.
    ///
    /// # Errors
    /// [`AssociationError::InvalidParameter`] for `P_D ∉ (0, 1]` or a negative density;
    /// [`AssociationError::DimensionMismatch`] for a gate of another dimension.
    pub fn new(
        system: LinearSystem<N, M>,
        gate: Gate,
        p_d: f64,
        density: f64,
        filter: PredictedFilter,
    ) -> Result<Self, AssociationError> {
        check_prob_open_closed(p_d, "detection probability")?;
        check_non_negative(density, "clutter density")?;
        gate.check_dim::<M>()?;
        Ok(Self {
            system,
            gate,
            p_d,
            density,
            filter,
        })
    }

    /// One step from `P̄(k−1|k−1) = posterior`.
    ///
    /// # Errors
    /// [`AssociationError::Math`] for a non-finite or non-PD `S̄`.
    #[allow(non_snake_case)]
    pub fn step(&self, posterior: &Matrix<N, N>) -> Result<PredictionStep<N, M>, AssociationError> {
        let sys = &self.system;
        let P_pred = symmetrize(&(sys.F * posterior * sys.F.transpose() + sys.Q));
        check_finite_matrix(&P_pred, "predicted MSE P̄(k|k−1)")?;
        let S = symmetrize(&(sys.H * P_pred * sys.H.transpose() + sys.R));
        let Sf = SpdFactor::new_symmetric(&S, "predicted innovation covariance S̄")?;
        let W = Sf.solve_matrix(&(sys.H * P_pred)).transpose();
        let sqrt_det = (0.5 * Sf.log_det()).exp();
        let mu = self.density * self.gate.volume_from_sqrt_det(sqrt_det);
        let factor = match self.filter {
            PredictedFilter::NearestNeighbour => {
                let beta = self.density * unit_ball_volume(M) * sqrt_det;
                let (c_t, c_f) = hyca_factors(&self.gate, beta, self.p_d)?;
                c_t - c_f
            }
            PredictedFilter::Pda => pda_irf(&self.gate, mu, self.p_d)?,
        };
        let P_post = symmetrize(&(P_pred - W * S * W.transpose() * factor));
        check_finite_matrix(&P_post, "predicted MSE P̄(k|k)")?;
        Ok(PredictionStep {
            predicted: P_pred,
            s: S,
            gain: W,
            mu,
            factor,
            posterior: P_post,
        })
    }

    /// Iterates from `initial` until the relative change of `P̄(k|k)` is below `tol`
    /// (at most `max_iter` steps). Reports [`SteadyState::Diverged`] when the trace
    /// exceeds `10⁶` times the larger of the initial trace and `tr Q`'s.
    ///
    /// # Errors
    /// As [`Self::step`]; [`AssociationError::InvalidParameter`] for a non-positive `tol`
    /// or a zero `max_iter`; a run that neither converges nor diverges in `max_iter`
    /// steps is reported as [`AssociationError::InvalidParameter`] on `max_iter`.
    pub fn steady_state(
        &self,
        initial: &Matrix<N, N>,
        tol: f64,
        max_iter: usize,
    ) -> Result<SteadyState<N, M>, AssociationError> {
        if !(tol.is_finite() && tol > 0.0) {
            return Err(AssociationError::InvalidParameter {
                what: "tolerance",
                value: tol,
                reason: "must be finite and positive",
            });
        }
        check_finite_matrix(initial, "initial MSE")?;
        let bound = 1e6
            * initial
                .trace()
                .max(self.system.Q.trace())
                .max(self.system.R.trace());
        let mut p = *initial;
        for it in 1..=max_iter {
            let step = self.step(&p)?;
            let trace = step.posterior.trace();
            if trace.is_nan() || trace > bound {
                return Ok(SteadyState::Diverged {
                    iterations: it,
                    trace,
                });
            }
            let change = (step.posterior - p).abs().max() / step.posterior.abs().max();
            p = step.posterior;
            if change < tol {
                return Ok(SteadyState::Converged {
                    step,
                    iterations: it,
                });
            }
        }
        Err(AssociationError::InvalidParameter {
            what: "max_iter",
            value: max_iter as f64,
            reason: "the recursion neither converged nor diverged within this many steps",
        })
    }
}

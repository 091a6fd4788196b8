//! The general-gain moments of the NN filter's update in clutter.

use argus_core_math::{Matrix, Vector, check_finite_matrix, symmetrize};

use crate::error::{AssociationError, check_non_negative, check_prob_open_closed};
use crate::gate::Gate;

/// Radius panels (16 nodes each) of the general-gain NN moments.
const NN_PANELS: usize = 8;
/// Trapezoid points on the circle (`n = 2`) and in longitude (`n = 3`).
const NN_ANGLES: usize = 64;
/// Directions of [`sphere_nodes`] at most (`n = 3`: 16 latitudes × 32 longitudes).
const MAX_DIRECTIONS: usize = 16 * NN_ANGLES / 2;

/// Calls `f(ω, weight)` on a quadrature of the unit sphere `S^{M−1}` (weights sum to
/// its area): `±1` for `M = 1`, the trapezoid rule on the circle for `M = 2`,
/// Gauss–Legendre in `cos θ` × trapezoid in longitude for `M = 3`.
fn sphere_nodes<const M: usize, F: FnMut(&Vector<M>, f64)>(
    mut f: F,
) -> Result<(), AssociationError> {
    let mut w = Vector::<M>::zeros();
    let tau = 2.0 * std::f64::consts::PI;
    match M {
        1 => {
            for sgn in [-1.0, 1.0] {
                w[0] = sgn;
                f(&w, 1.0);
            }
        }
        2 => {
            for j in 0..NN_ANGLES {
                let th = tau * j as f64 / NN_ANGLES as f64;
                w[0] = th.cos();
                w[1] = th.sin();
                f(&w, tau / NN_ANGLES as f64);
            }
        }
        3 => {
            let (x, wz) = crate::quadrature::gauss_legendre::<16>();
            let half = NN_ANGLES / 2;
            for (z, wzi) in x.iter().zip(wz.iter()) {
                let rho = (1.0 - z * z).max(0.0).sqrt();
                for j in 0..half {
                    let ph = tau * j as f64 / half as f64;
                    w[0] = rho * ph.cos();
                    w[1] = rho * ph.sin();
                    w[2] = *z;
                    f(&w, wzi * tau / half as f64);
                }
            }
        }
        _ => {
            return Err(AssociationError::InvalidParameter {
                what: "measurement dimension of the general-gain NN prediction",
                value: M as f64,
                reason: "implemented for 1-, 2- and 3-dimensional plots",
            });
        }
    }
    Ok(())
}

/// Moments of the nearest-neighbour plot when the filter gates with its own `S` but
/// the target's innovation has covariance `S̄` (see
/// [`PredictedFilter::NearestNeighbourKalmanGain`](crate::PredictedFilter::NearestNeighbourKalmanGain)). All in the filter's whitened
/// coordinates `u = L⁻¹ν`, `S = L Lᵀ`, where the target's innovation is `N(0, Σ)`,
/// `Σ = L⁻¹ S̄ L⁻ᵀ`, and the clutter is uniform with `β r^n` expected plots within
/// radius `r`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NnMoments<const M: usize> {
    /// `E[u uᵀ 1{M_T}]` (the target's plot is the nearest).
    pub target: Matrix<M, M>,
    /// `c_F` with `E[u uᵀ 1{M_F}] = c_F I` (a clutter plot is the nearest).
    pub clutter: f64,
    /// `P(M₀)`: no plot in the gate.
    pub none: f64,
    /// `P(uᵀu ≤ γ)` for the target's innovation.
    pub target_in_gate: f64,
}

/// The moments [`NnMoments`] for gate `gate`, clutter `β = λ c_n |S|^{1/2}`,
/// detection probability `p_d` and `Σ⁻¹ = sigma_inv`, `|Σ|^{1/2} = sqrt_det_sigma`:
///
/// ```text
/// E[uuᵀ1{M_T}] = P_D ∫_{|u|²≤γ} u uᵀ N(u; 0, Σ) e^{−β|u|^n} du
/// c_F          = ∫₀^{√γ} (r²/n) β n r^{n−1} e^{−βr^n} [1 − P_D G_Σ(r)] dr
/// P(M₀)        = [1 − P_D G_Σ(√γ)] e^{−β γ^{n/2}},   G_Σ(r) = P(|u_T| ≤ r)
/// ```
///
/// (the nearest clutter plot is at radius `r` with density `βn r^{n−1}e^{−βr^n}` and
/// in a uniform direction, independent of the target's plot). Radius: composite
/// Gauss–Legendre; directions: the quadrature of `sphere_nodes`. At `Σ = I` these are the HYCA
/// factors `c_T I`, `c_F` of [`hyca_factors`](crate::hyca_factors) (tested).
///
/// # Errors
/// [`AssociationError::InvalidParameter`] for `β < 0`, `P_D ∉ (0, 1]`, a non-finite
/// or non-positive `sqrt_det_sigma`, or `M ∉ {1, 2, 3}`;
/// [`AssociationError::DimensionMismatch`] for a gate of another dimension.
pub fn nn_moments<const M: usize>(
    gate: &Gate,
    beta: f64,
    p_d: f64,
    sigma_inv: &Matrix<M, M>,
    sqrt_det_sigma: f64,
) -> Result<NnMoments<M>, AssociationError> {
    check_non_negative(beta, "NN clutter factor β = λ c_n |S|^{1/2}")?;
    check_prob_open_closed(p_d, "detection probability")?;
    gate.check_dim::<M>()?;
    check_finite_matrix(sigma_inv, "whitened target innovation information Σ⁻¹")?;
    if !(sqrt_det_sigma.is_finite() && sqrt_det_sigma > 0.0) {
        return Err(AssociationError::InvalidParameter {
            what: "|Σ|^{1/2} of the whitened target innovation",
            value: sqrt_det_sigma,
            reason: "must be finite and positive",
        });
    }
    let n = M as i32;
    let nf = M as f64;
    let rmax = gate.gamma().sqrt();
    let norm = 1.0 / ((2.0 * std::f64::consts::PI).powf(nf / 2.0) * sqrt_det_sigma);
    let (x, w) = crate::quadrature::gauss_legendre::<16>();
    let hr = rmax / NN_PANELS as f64;
    // ∫_s^R β r^{n+1} e^{−βr^n} dr by 16-point Gauss–Legendre (smooth on [s, R]).
    let tail = |s: f64| {
        let half = 0.5 * (rmax - s);
        let mid = 0.5 * (rmax + s);
        x.iter()
            .zip(w.iter())
            .map(|(xi, wi)| {
                let r = mid + half * xi;
                wi * beta * r.powi(n + 1) * (-beta * r.powi(n)).exp()
            })
            .sum::<f64>()
            * half
    };
    // Pass 1: the quadratic form ωᵀΣ⁻¹ω and weight of every direction.
    let mut quad = [0.0; MAX_DIRECTIONS];
    let mut wdir = [0.0; MAX_DIRECTIONS];
    let mut count = 0;
    sphere_nodes::<M, _>(|om, wa| {
        if let (Some(q), Some(w)) = (quad.get_mut(count), wdir.get_mut(count)) {
            *q = (om.transpose() * sigma_inv * om)[(0, 0)];
            *w = wa;
        }
        count += 1;
    })?;
    let dirs = count.min(MAX_DIRECTIONS);
    // Radius × direction: φ_Σ(rω) = norm e^{−r² ωᵀΣ⁻¹ω / 2}.
    let mut cdir = [0.0; MAX_DIRECTIONS];
    let (mut clutter_all, mut clutter_target, mut in_gate) = (0.0, 0.0, 0.0);
    for p in 0..NN_PANELS {
        let mid = (p as f64 + 0.5) * hr;
        for (xi, wi) in x.iter().zip(w.iter()) {
            let r = mid + 0.5 * hr * xi;
            let wr = 0.5 * hr * wi;
            let rn1 = r.powi(n - 1);
            let no_clutter = (-beta * r.powi(n)).exp();
            let wt = p_d * wr * rn1 * r * r * no_clutter;
            let mut a = 0.0;
            for ((q, wa), c) in quad.iter().zip(&wdir).zip(cdir.iter_mut()).take(dirs) {
                let phi = wa * norm * (-0.5 * r * r * q).exp();
                a += phi;
                *c += wt * phi;
            }
            let g = rn1 * a; // radial density of |u_T|
            in_gate += wr * g;
            clutter_all += wr * beta * r.powi(n + 1) * no_clutter;
            clutter_target += wr * g * tail(r);
        }
    }
    // Pass 2: E[uuᵀ1{M_T}] = Σ_j c_j ω_j ω_jᵀ.
    let mut target = Matrix::<M, M>::zeros();
    let mut j = 0;
    sphere_nodes::<M, _>(|om, _| {
        if let Some(c) = cdir.get(j) {
            target += om * om.transpose() * *c;
        }
        j += 1;
    })?;
    Ok(NnMoments {
        target: symmetrize(&target),
        clutter: clutter_all - p_d * clutter_target,
        none: (1.0 - p_d * in_gate) * (-beta * gate.gamma().powf(nf / 2.0)).exp(),
        target_in_gate: in_gate,
    })
}

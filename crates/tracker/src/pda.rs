//! The PDA and IMM-PDA updates of one track with its JPDA weights `β_j`.
//!
//! These are not `argus_association`'s [`argus_association::Pda`] and
//! [`argus_association::imm_associate`], and cannot go through them without changing the
//! tracker's results: those compute a lone track's own weights from `λ` and `P_D`, where a
//! JPDA track's weights are the marginals of its cluster's joint events (`crate::jpda`), and
//! they update in the closed form `x⁻ + K ν̄` with one `S`, which holds only when all plots
//! share one `R` — converted polar plots each have their own, and the EKF updates in
//! `(r, θ)` per plot. The form here, a moment-matched mixture of per-plot updates, is the
//! general one; for a single track with the PDA's weights it is the same estimate.

use argus_core_math::Gaussian;
use argus_filters::{GaussianFilter, Kf};
use argus_imm::{Imm, ImmEstimate, ImmPrediction, log_sum_exp};
use argus_motion_models::Cv2D;

use crate::plot::ScanPoint;

/// The moment-matched Gaussian of the weighted parts (weights need not sum to one: they
/// are normalised here) by [`Gaussian::mixture_of`]; `None` when the weights vanish or the
/// result is not finite.
pub(crate) fn mixture(weights: &mut [f64], parts: &[Gaussian<4>]) -> Option<Gaussian<4>> {
    let total: f64 = weights.iter().sum();
    if !(total.is_finite() && total > 0.0) {
        return None;
    }
    for w in weights.iter_mut() {
        *w /= total;
    }
    Gaussian::mixture_of(weights, parts).ok()
}

/// The JPDA (PDA) update of a single-filter track: the moment-matched mixture of the
/// prediction (weight `β₀ = 1 − Σ β_j`) and the update with each plot (weight `β_j`, by
/// `update`), which is the standard PDA update when all plots share one `R` (Bar-Shalom &
/// Tse 1975).
pub(crate) fn jpda_update(
    pred: &Gaussian<4>,
    weights: &[(usize, f64)],
    points: &[ScanPoint],
    update: impl Fn(&ScanPoint) -> Option<Gaussian<4>>,
) -> Option<Gaussian<4>> {
    let b0 = (1.0 - weights.iter().map(|w| w.1).sum::<f64>()).max(0.0);
    let mut w = Vec::with_capacity(weights.len() + 1);
    let mut parts = Vec::with_capacity(weights.len() + 1);
    w.push(b0);
    parts.push(*pred);
    for &(j, b) in weights {
        w.push(b);
        parts.push(update(&points[j])?);
    }
    mixture(&mut w, &parts)
}

/// The IMM-JPDA update of one track from its mode-matched predictions and its JPDA
/// marginals `β_j` (computed from the mixed likelihoods `Σ_r μ̄_r N_r,j`).
///
/// With `N_r,j = N(ν_r,j; 0, S_r,j)` and `N_j = Σ_s μ̄_s N_s,j`, the joint posterior of
/// mode `r` and "plot `j` is the target's" is `P(r, j) = β_j μ̄_r N_r,j / N_j` and of
/// "no plot is" `P(r, 0) = β₀ μ̄_r` (the miss factor does not depend on the mode). So:
/// - mode probability `μ_r = Σ_j P(r, j) = μ̄_r (β₀ + Σ_j β_j N_r,j / N_j)`: the mode
///   likelihood summed over the plot events;
/// - mode `r`'s estimate: the PDA mixture of its prediction and its Kalman updates with
///   the weights `P(r, j) / μ_r`.
///
/// With identical modes `N_r,j = N_j`, `μ_r = μ̄_r` and every mode gets the JPDA+KF update.
///
/// # References
/// H. A. P. Blom, E. A. Bloem, "Probabilistic data association avoiding track
/// coalescence", IEEE Trans. Automatic Control 45(2), 2000 (IMM-JPDA); Y. Bar-Shalom,
/// P. Willett, X. Tian, *Tracking and Data Fusion*, YBS 2011 (IMM-JPDA, and IMM-PDA as its
/// one-track case).
pub(crate) fn imm_jpda_update(
    imm: &Imm<Kf<Cv2D>, 4, 2>,
    pred: &ImmPrediction<4, 2>,
    weights: &[(usize, f64)],
    points: &[ScanPoint],
) -> Option<(Gaussian<4>, ImmEstimate<4, 2>)> {
    let lc = pred.log_predicted_probabilities();
    let modes = pred.modes();
    let b0 = (1.0 - weights.iter().map(|w| w.1).sum::<f64>()).max(0.0);
    let n = weights.len() + 1;
    let mut w: [Vec<f64>; 2] = [Vec::with_capacity(n), Vec::with_capacity(n)];
    let mut parts: [Vec<Gaussian<4>>; 2] = [Vec::with_capacity(n), Vec::with_capacity(n)];
    for r in 0..2 {
        w[r].push(b0 * lc[r].exp());
        parts[r].push(modes[r]);
    }
    for &(j, b) in weights {
        let p = &points[j];
        let mut post = [modes[0]; 2];
        let mut joint = [f64::NEG_INFINITY; 2];
        for (r, (f, g)) in imm.filters().iter().zip(modes).enumerate() {
            let (g_post, innov) = f.update(g, &p.model, &p.position).ok()?;
            post[r] = g_post;
            joint[r] = lc[r] + innov.log_likelihood();
        }
        let total = log_sum_exp(&joint);
        if !total.is_finite() {
            return None;
        }
        for r in 0..2 {
            w[r].push(b * (joint[r] - total).exp());
            parts[r].push(post[r]);
        }
    }
    let mut mu = [0.0; 2];
    let mut new_modes = *modes;
    for r in 0..2 {
        mu[r] = w[r].iter().sum();
        if mu[r] > 0.0 {
            new_modes[r] = mixture(&mut w[r], &parts[r])?;
        }
    }
    let sum: f64 = mu.iter().sum();
    if !(sum.is_finite() && sum > 0.0) {
        return None;
    }
    let est = ImmEstimate::new(new_modes, mu.map(|m| m / sum)).ok()?;
    Some((est.combined().ok()?, est))
}

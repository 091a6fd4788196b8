//! A likelihood-fitted measurement-noise estimator over five IMMs (beyond seed 000).

use argus_core_math::Gaussian;
use argus_filters::GaussianFilter;
use argus_sensors::PolarMeasurement;

use crate::error::{check_clip, check_forgetting, check_positive};
use crate::markov::log_sum_exp;
use crate::{Imm, ImmError, ImmEstimate, NoiseVariances, PlotConversion};

/// The hypotheses of an [`EvidenceNoiseImm`] as `(range, azimuth)` offsets in units of the
/// log step `h`: the anchor, then range `−h`, `+h`, then azimuth `−h`, `+h` (a "plus" grid).
const OFFSETS: [[f64; 2]; 5] = [[0.0, 0.0], [-1.0, 0.0], [1.0, 0.0], [0.0, -1.0], [0.0, 1.0]];

/// For each axis, the hypotheses at `−h`, `0`, `+h` (indices into [`OFFSETS`]).
const AXES: [[usize; 3]; 2] = [[1, 0, 2], [3, 0, 4]];

/// The state of an [`EvidenceNoiseImm`]: five IMM estimates, the anchor variances the
/// hypotheses are built on, and the accumulated evidence statistics `(B, G)` per axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EvidenceEstimate<const N: usize, const R: usize> {
    imms: [ImmEstimate<N, R>; 5],
    anchor: NoiseVariances,
    /// `[B_r, B_θ]`: accumulated coefficient of `ln σ²` (negative).
    b: [f64; 2],
    /// `[G_r, G_θ]`: accumulated coefficient of `1/σ²` (negative, in the variance's units).
    g: [f64; 2],
    /// The current estimate `G / B` (the previous one while the fit is degenerate).
    estimate: NoiseVariances,
    /// Consecutive steps without a clipped anchor change.
    settled: usize,
    /// Post-fit statistic: count and sums of `ε² + (J P Jᵀ)ᵢᵢ` per axis.
    post: [f64; 3],
}

impl<const N: usize, const R: usize> EvidenceEstimate<N, R> {
    /// Every IMM starts from `start`; the anchor (and the estimate) is the initial guess
    /// `initial`, held with the weight of `prior_count` pseudo-plots (`B₀ = −w/2`,
    /// `G₀ = −w/2 · σ²₀`, so that the estimate `G/B` is the guess).
    ///
    /// # Errors
    /// [`ImmError::InvalidParameter`] unless `prior_count` is finite and positive.
    pub fn new(
        start: ImmEstimate<N, R>,
        initial: NoiseVariances,
        prior_count: f64,
    ) -> Result<Self, ImmError> {
        check_positive("prior count", prior_count)?;
        let w = -0.5 * prior_count;
        Ok(Self {
            imms: [start; 5],
            anchor: initial,
            b: [w; 2],
            g: [w * initial.range(), w * initial.azimuth()],
            estimate: initial,
            settled: 0,
            post: [0.0; 3],
        })
    }

    /// The five IMM estimates (anchor, range −h, +h, azimuth −h, +h).
    #[must_use]
    pub fn imms(&self) -> &[ImmEstimate<N, R>; 5] {
        &self.imms
    }

    /// The anchor variances the next step's hypotheses are built on.
    #[must_use]
    pub fn anchor(&self) -> &NoiseVariances {
        &self.anchor
    }

    /// The current variance estimates `σ̂² = G / B` per axis (while the accumulated curve
    /// of an axis is not concave, the previous estimate).
    #[must_use]
    pub fn variances(&self) -> &NoiseVariances {
        &self.estimate
    }

    /// The output state: the anchor IMM's combined estimate (its `R` is the anchor, which
    /// follows the estimate).
    ///
    /// # Errors
    /// As [`ImmEstimate::combined`].
    pub fn combined(&self) -> Result<Gaussian<N>, ImmError> {
        self.imms[0].combined()
    }

    /// The motion-mode probabilities of the anchor IMM.
    #[must_use]
    pub fn mode_probabilities(&self) -> [f64; R] {
        self.imms[0].mode_probabilities()
    }
}

/// Range and azimuth measurement-noise variances estimated from the IMM likelihoods of
/// five hypotheses, with a fitted evidence curve accumulated over the whole track.
///
/// Five IMMs assume `(σ̄r² e^{iₘh}, σ̄θ² e^{jₘh})` around the anchor `σ̄²`, with
/// `(iₘ, jₘ) ∈ {(0,0), (±1,0), (0,±1)}` (a "plus" grid: 5 IMMs, the cost of the paper's
/// 5 × 3 rule). Per plot, per axis, the three log-likelihoods `ln Λ` at `u = −h, 0, +h`
/// (`u = ln σ² − ln σ̄²`) are fitted exactly by `ℓ(u) = α + β u + γ e^{−u}`, the form of a
/// Gaussian log-likelihood in its variance (`−½ (ln σ² + ε²/σ²)`). In the absolute
/// variable `U = ln σ²` that is `β U + γ σ̄² e^{−U}`, so the statistics
/// `B ← ρ B + β`, `G ← ρ G + γ σ̄²` can be summed across steps whatever the anchor did,
/// and the accumulated curve peaks at `σ̂² = G / B`. The anchor then moves towards `σ̂²`
/// (its relative change clipped to `±clip`).
///
/// Why the truth is the fixed point: the expected log-likelihood of the plot is largest for
/// the hypothesis with the true `R` (the log score is proper), and for the pure Gaussian
/// form the three-point fit recovers that maximum exactly wherever the grid sits; unlike
/// the paper's rule there is no fresh uniform prior each step, so the estimate does not
/// drift with the grid. The residual error comes from `S = H P Hᵀ + R` not being
/// proportional to `R` and from maneuvers no mode matches. With `ρ = 1` the statistics
/// cover the whole track and the start is forgotten as plots accumulate.
///
/// # References
/// Seed 000 (Jeon et al. 2010) eqs (8)–(10) for the per-IMM likelihoods; the curve fit and
/// the accumulation are ours (a maximum-likelihood estimate of the noise scale from the
/// IMM's prediction-error decomposition, cf. Mehra, "Approaches to adaptive filtering",
/// IEEE TAC 17(5), 1972, for maximum-likelihood noise identification).
#[derive(Debug, Clone, PartialEq)]
pub struct EvidenceNoiseImm<F, const N: usize, const R: usize> {
    imm: Imm<F, N, R>,
    step: f64,
    forgetting: f64,
    clip: Option<f64>,
    post_fit: Option<usize>,
    observed_information: bool,
}

impl<F: GaussianFilter<N>, const N: usize, const R: usize> EvidenceNoiseImm<F, N, R> {
    /// Around `imm`, hypotheses `e^{±h}` apart with `h = ln(1 + spacing)`, evidence
    /// forgetting factor `forgetting` (`ρ`, 1 = keep everything) and the anchor's relative
    /// change per step clipped to `±clip` (`None`: the anchor jumps to the estimate).
    ///
    /// # Errors
    /// [`ImmError::InvalidParameter`] unless `spacing > 0`, `forgetting ∈ (0, 1]` and
    /// `clip ∈ (0, 1)`.
    pub fn new(
        imm: Imm<F, N, R>,
        spacing: f64,
        forgetting: f64,
        clip: Option<f64>,
    ) -> Result<Self, ImmError> {
        check_positive("hypothesis spacing", spacing)?;
        check_forgetting(forgetting)?;
        check_clip("anchor clip", clip)?;
        Ok(Self {
            imm,
            step: spacing.ln_1p(),
            forgetting,
            clip,
            post_fit: None,
            observed_information: false,
        })
    }

    /// Reports the post-fit moment estimate of the anchor IMM once the anchor has settled:
    /// after `settle` consecutive steps in which the anchor's change was not clipped, every
    /// plot adds `ε² + (J P⁺ Jᵀ)ᵢᵢ` per axis (`ε` the polar residual of the anchor IMM's
    /// combined posterior, `J = ∂(r, θ)/∂(x, y)`), and from 10 such plots on the estimate
    /// is their mean. `E[ε εᵀ] = R − J P⁺ Jᵀ` for a consistent filter (the fixed point of
    /// [`crate::VariationalNoiseImm`]); the evidence has already brought the filter's `R`
    /// near the truth, so the start is forgotten, and the post-fit residuals are less
    /// inflated by unmatched maneuvers than the likelihoods. The anchor keeps following
    /// the evidence. Without this option the estimate is `G / B`.
    #[must_use]
    pub fn with_post_fit(mut self, settle: usize) -> Self {
        self.post_fit = Some(settle);
        self
    }

    /// Uses each plot's fitted curvature as its information (`B += β`, `G += γσ̄²`), the
    /// estimator as first built: a single plot's curvature is noisy, and while `B` holds
    /// little more than the prior one plot can make `G/B` huge. Kept for comparison
    /// (docs/papers/000-gimpo.md); the default uses the expected information.
    #[must_use]
    pub fn with_observed_information(mut self) -> Self {
        self.observed_information = true;
        self
    }

    /// The IMM.
    #[must_use]
    pub fn imm(&self) -> &Imm<F, N, R> {
        &self.imm
    }

    /// The variances the five IMMs assume in the next step.
    #[must_use]
    pub fn hypotheses(&self, est: &EvidenceEstimate<N, R>) -> [NoiseVariances; 5] {
        OFFSETS.map(|[i, j]| {
            est.anchor
                .scaled((i * self.step).exp(), (j * self.step).exp())
        })
    }

    /// One step with `plot` after `dt` seconds.
    ///
    /// # Errors
    /// [`ImmError::InvalidInterval`] for `dt` not finite and positive; any error of the
    /// conversion or of an IMM (naming the mode); [`ImmError::NoLikelihood`] if no
    /// hypothesis explains the plot. `est` is never modified.
    #[allow(non_snake_case)]
    pub fn step<const M: usize, C: PlotConversion<N, M>>(
        &self,
        est: &EvidenceEstimate<N, R>,
        dt: f64,
        plot: &PolarMeasurement,
        conversion: &C,
    ) -> Result<EvidenceEstimate<N, R>, ImmError> {
        let hyp = self.hypotheses(est);
        let mut imms = est.imms;
        // The bank of IMMs runs on the path the multi-IMM uses (in place, no copies).
        let ll = self
            .imm
            .step_hypotheses(&est.imms, &mut imms, dt, plot, &hyp, conversion)?;
        if !(log_sum_exp(&ll).is_finite() && ll.iter().all(|l| l.is_finite())) {
            return Err(ImmError::NoLikelihood {
                what: "noise hypotheses",
            });
        }
        // The anchor IMM's combined posterior in polar coordinates: the residual and
        // (J P⁺ Jᵀ)ᵢᵢ per axis (`None` when the estimate sits on the radar).
        let polar = polar_posterior(&imms[0], plot, conversion)?;
        let h = self.step;
        let curv = 2.0 * (h.cosh() - 1.0);
        let anchor = est.anchor.as_array();
        let mut inc = [0.0; 4];
        for (ax, [lo, mid, hi]) in AXES.iter().enumerate() {
            let (lm, l0, lp) = (ll[*lo], ll[*mid], ll[*hi]);
            let gamma = (lm + lp - 2.0 * l0) / curv;
            let beta = (lp - lm + 2.0 * gamma * h.sinh()) / (2.0 * h);
            // The observed score dℓ/du at the anchor (the fitted curve's slope at u = 0).
            let score = beta - gamma;
            // Expected information ½w², w = σ̄²/S = 1 − (J P⁺ Jᵀ)ᵢᵢ/σ̄² (scalar Kalman
            // identity P⁺ = P⁻σ̄²/S), so the curvature is not read off one noisy plot.
            let w = polar.map_or(0.0, |(_, jpj)| (1.0 - jpj[ax] / anchor[ax]).clamp(0.0, 1.0));
            let b_inc = if self.observed_information {
                beta
            } else {
                -0.5 * w * w
            };
            inc[2 * ax] = b_inc;
            inc[2 * ax + 1] = (b_inc - score) * anchor[ax];
        }
        let rho = self.forgetting;
        let (mut b, mut g) = (est.b, est.g);
        let mut target = est.estimate.as_array();
        let mut new = anchor;
        let mut clipped = false;
        for ax in 0..2 {
            b[ax] = rho * b[ax] + inc[2 * ax];
            g[ax] = rho * g[ax] + inc[2 * ax + 1];
            let fit = g[ax] / b[ax];
            if b[ax] < 0.0 && g[ax] < 0.0 && fit.is_finite() {
                target[ax] = fit;
            }
            let ratio = target[ax] / anchor[ax];
            let ratio = match self.clip {
                Some(c) => {
                    clipped |= !(1.0 - c..=1.0 + c).contains(&ratio);
                    ratio.clamp(1.0 - c, 1.0 + c)
                }
                None => ratio,
            };
            new[ax] = anchor[ax] * ratio;
        }
        let settled = if clipped { 0 } else { est.settled + 1 };
        let mut post = est.post;
        if let Some(k) = self.post_fit
            && settled >= k
        {
            if let Some((e, jpj)) = polar {
                post[0] += 1.0;
                post[1] += e[0] * e[0] + jpj[0];
                post[2] += e[1] * e[1] + jpj[1];
            }
            if post[0] >= 10.0 {
                target = [post[1] / post[0], post[2] / post[0]];
            }
        }
        Ok(EvidenceEstimate {
            imms,
            anchor: NoiseVariances::new(new[0], new[1])?,
            b,
            g,
            estimate: NoiseVariances::new(target[0], target[1])?,
            settled,
            post,
        })
    }
}

/// `([ε_r, ε_θ], [(J P Jᵀ)_rr, (J P Jᵀ)_θθ])`: a polar residual and posterior variances.
type PolarMoments = ([f64; 2], [f64; 2]);

/// The polar residual `(ε_r, ε_θ)` of an IMM's combined posterior against `plot`, and
/// `(J P⁺ Jᵀ)ᵢᵢ` with `J = ∂(r, θ)/∂(x, y)` at the estimate; `None` when the estimate
/// sits on the radar.
#[allow(non_snake_case)]
fn polar_posterior<const N: usize, const R: usize, const M: usize, C: PlotConversion<N, M>>(
    imm: &ImmEstimate<N, R>,
    plot: &PolarMeasurement,
    conversion: &C,
) -> Result<Option<PolarMoments>, ImmError> {
    let c = imm.combined()?;
    let p = conversion.position(c.mean());
    let rng = p.norm();
    if !(rng.is_finite() && rng > 0.0) {
        return Ok(None);
    }
    let (cs, sn) = (p[0] / rng, p[1] / rng);
    let J = argus_core_math::Matrix::<2, 2>::new(cs, sn, -sn / rng, cs / rng);
    let JPJ = J * conversion.position_cov(c.cov()) * J.transpose();
    let e_r = plot.range() - rng;
    let e_t = argus_sensors::wrap_angle(plot.azimuth() - p[1].atan2(p[0]));
    Ok(Some(([e_r, e_t], [JPJ[(0, 0)], JPJ[(1, 1)]])))
}

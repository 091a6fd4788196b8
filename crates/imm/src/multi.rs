//! The multi-IMM measurement-noise estimator, seed 000 eqs (8)–(14), generalised.

use argus_core_math::Gaussian;
use argus_filters::GaussianFilter;
use argus_sensors::PolarMeasurement;

use crate::error::{check_clip, check_positive};
use crate::imm::{ModeWeights, moment_match};
use crate::{Imm, ImmError, ImmEstimate, NoiseVariances, PlotConversion};

/// The `K` noise hypotheses of a multi-IMM, as multiplicative factors
/// `(aₘ, bₘ)` on the reference variances: IMM `m` assumes `(aₘ σr²_ref, bₘ σθ²_ref)`.
///
/// - [`NoiseGrid::common`] is the paper's grid (eq 14): `aₘ = bₘ = 1 + (m − (K−1)/2) p`,
///   i.e. `(1−2p, 1−p, 1, 1+p, 1+2p)` for `K = 5`: one common scale of `R`.
/// - [`NoiseGrid::independent`] estimates range and azimuth variances separately: a
///   `k × k` product grid (`K = k²`), `aₘ` the range factor of row `m / k`, `bₘ` the
///   azimuth factor of column `m mod k`. Eq (13) is then applied per component, which
///   amounts to using the marginal noise-mode probabilities of each component.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NoiseGrid<const K: usize> {
    factors: [[f64; 2]; K],
}

impl<const K: usize> NoiseGrid<K> {
    /// The paper's symmetric grid with spacing `p` (seed 000 eq (14): `K = 5`, `p = 0.1`).
    ///
    /// # Errors
    /// [`ImmError::Empty`] for `K = 0`; [`ImmError::InvalidParameter`] unless `p` is finite,
    /// positive and every factor `1 ± …p` stays positive.
    pub fn common(p: f64) -> Result<Self, ImmError> {
        let half = (K as f64 - 1.0) / 2.0;
        let mut factors = [[1.0; 2]; K];
        for (m, f) in factors.iter_mut().enumerate() {
            let a = 1.0 + (m as f64 - half) * p;
            *f = [a, a];
        }
        Self::checked(factors, p)
    }

    /// A `k × k` product grid (`K = k²`) with spacing `p` on each component.
    ///
    /// # Errors
    /// As [`NoiseGrid::common`], and [`ImmError::InvalidParameter`] when `K` is not a square.
    pub fn independent(p: f64) -> Result<Self, ImmError> {
        let k = (K as f64).sqrt().round() as usize;
        if k * k != K {
            return Err(ImmError::InvalidParameter {
                what: "number of noise hypotheses K",
                value: K as f64,
                reason: "an independent grid needs K = k² hypotheses",
            });
        }
        let half = (k as f64 - 1.0) / 2.0;
        let mut factors = [[1.0; 2]; K];
        for (m, f) in factors.iter_mut().enumerate() {
            let a = 1.0 + ((m / k) as f64 - half) * p;
            let b = 1.0 + ((m % k) as f64 - half) * p;
            *f = [a, b];
        }
        Self::checked(factors, p)
    }

    /// Arbitrary positive factors `(range, azimuth)` per hypothesis.
    ///
    /// # Errors
    /// [`ImmError::Empty`] for `K = 0`; [`ImmError::InvalidParameter`] for a factor that is not
    /// finite and positive.
    pub fn custom(factors: [[f64; 2]; K]) -> Result<Self, ImmError> {
        Self::checked(factors, 1.0)
    }

    fn checked(factors: [[f64; 2]; K], p: f64) -> Result<Self, ImmError> {
        if K == 0 {
            return Err(ImmError::Empty {
                what: "noise hypotheses",
            });
        }
        check_positive("grid spacing p", p)?;
        for f in factors.iter().flatten() {
            if !(f.is_finite() && *f > 0.0) {
                return Err(ImmError::InvalidParameter {
                    what: "noise grid factor",
                    value: *f,
                    reason: "every factor must be finite and positive (p too large for K?)",
                });
            }
        }
        Ok(Self { factors })
    }

    /// The factors `(aₘ, bₘ)`.
    #[must_use]
    pub fn factors(&self) -> &[[f64; 2]; K] {
        &self.factors
    }
}

/// The state of a multi-IMM: `K` IMM estimates, the reference variances for the next
/// step and the latest noise-mode probabilities `νᵐ`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MultiImmEstimate<const N: usize, const R: usize, const K: usize> {
    imms: [ImmEstimate<N, R>; K],
    reference: NoiseVariances,
    nu: [f64; K],
}

impl<const N: usize, const R: usize, const K: usize> MultiImmEstimate<N, R, K> {
    /// Every IMM starts from `start`; the reference variances are `reference` (the initial
    /// guess of `R`); `ν` is uniform.
    #[must_use]
    pub fn new(start: ImmEstimate<N, R>, reference: NoiseVariances) -> Self {
        Self {
            imms: [start; K],
            reference,
            nu: [1.0 / K as f64; K],
        }
    }

    /// The `K` IMM estimates.
    #[must_use]
    pub fn imms(&self) -> &[ImmEstimate<N, R>; K] {
        &self.imms
    }

    /// The reference variances `σ²_ref` the next step's grid is built on (eq (13), clipped).
    #[must_use]
    pub fn reference(&self) -> &NoiseVariances {
        &self.reference
    }

    /// The noise-mode probabilities `νᵐ` of the last step (eq (12)).
    #[must_use]
    pub fn noise_probabilities(&self) -> &[f64; K] {
        &self.nu
    }

    /// The combined output `x = Σ νᵐ xᵐ` with the spread-of-means term, `xᵐ` each IMM's
    /// combined output (seed 000 §2.2, third step).
    ///
    /// # Errors
    /// [`ImmError::Math`] if a covariance is not positive definite.
    pub fn combined(&self) -> Result<Gaussian<N>, ImmError> {
        let first = self
            .imms
            .first()
            .and_then(|e| e.modes().first())
            .ok_or(ImmError::Empty {
                what: "noise hypotheses",
            })?;
        let mut parts = [*first; K];
        for (p, imm) in parts.iter_mut().zip(&self.imms) {
            *p = imm.combined()?;
        }
        moment_match(&self.nu, &parts)
    }

    /// The motion-mode probabilities `Σₘ νᵐ μⱼᵐ`.
    #[must_use]
    pub fn mode_probabilities(&self) -> [f64; R] {
        let mut mu = [0.0; R];
        for (nu, imm) in self.nu.iter().zip(&self.imms) {
            for (acc, p) in mu.iter_mut().zip(imm.mode_probabilities()) {
                *acc += nu * p;
            }
        }
        mu
    }
}

/// The multi-IMM measurement-noise estimator of seed 000 §2.2.
///
/// `K` IMMs with identical motion models differ only in the measurement-noise variances
/// they assume. Per plot:
/// 1. IMM `m` assumes `σ²ᵐ = (aₘ σr²_ref, bₘ σθ²_ref)` ([`NoiseGrid`], eq (14)), converts
///    the plot with its own variances ([`PlotConversion`]) and runs one IMM cycle;
/// 2. its total likelihood `Λᵐ = Σⱼ μ̄ⱼᵐ Λⱼᵐ` (eqs (8)–(10));
/// 3. noise-mode probabilities with a fresh uniform prior, `νᵐ = Λᵐ / Σ Λ` (eq (12));
/// 4. new reference `σ²_ref ← Σ νᵐ σ²ᵐ` per component (eq (13)), its relative change
///    clipped to `±clip` (the paper: 5 %);
/// 5. output `x = Σ νᵐ xᵐ` (with the spread term).
///
/// The paper fixes `K = 5`, `p = 0.1`, a 5 % clip and one common scale; all are parameters
/// here (see [`NoiseGrid`] for independent range and azimuth variances).
///
/// Note: the rule's fixed point is not the true `R` (a fresh uniform prior every step and a
/// grid that moves with the estimate bias it; the bias depends on `p`). See
/// [`crate::VariationalNoiseImm`] for an estimator whose fixed point is the truth.
///
/// # References
/// Jeon et al. (2010), seed 000 eqs (8)–(14) (eq (9) with the normaliser `|2πS|^{−½}`).
#[derive(Debug, Clone, PartialEq)]
pub struct MultiImm<F, const N: usize, const R: usize, const K: usize> {
    imm: Imm<F, N, R>,
    grid: NoiseGrid<K>,
    clip: Option<f64>,
}

/// The result of one multi-IMM step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MultiImmUpdate<const N: usize, const R: usize, const K: usize> {
    /// The updated estimate (its reference is the one for the next step).
    pub estimate: MultiImmEstimate<N, R, K>,
    /// The variances each IMM assumed in this step.
    pub hypotheses: [NoiseVariances; K],
    /// `ln Λᵐ` per IMM.
    pub log_likelihoods: [f64; K],
}

impl<F: GaussianFilter<N>, const N: usize, const R: usize, const K: usize> MultiImm<F, N, R, K> {
    /// A multi-IMM of `imm` over the hypotheses `grid`, with the relative change of the
    /// reference per step clipped to `±clip` (`None`: unclipped).
    ///
    /// # Errors
    /// [`ImmError::InvalidParameter`] unless `clip` is in `(0, 1)`.
    pub fn new(imm: Imm<F, N, R>, grid: NoiseGrid<K>, clip: Option<f64>) -> Result<Self, ImmError> {
        check_clip("reference clip", clip)?;
        Ok(Self { imm, grid, clip })
    }

    /// The shared IMM.
    #[must_use]
    pub fn imm(&self) -> &Imm<F, N, R> {
        &self.imm
    }

    /// The noise hypotheses.
    #[must_use]
    pub fn grid(&self) -> &NoiseGrid<K> {
        &self.grid
    }

    /// The variances each IMM will assume in the next step.
    #[must_use]
    pub fn hypotheses(&self, est: &MultiImmEstimate<N, R, K>) -> [NoiseVariances; K] {
        self.grid.factors.map(|[a, b]| est.reference.scaled(a, b))
    }

    /// Mixing and mode-matched prediction of every IMM over `dt` seconds, as an estimate
    /// (each IMM's [`crate::ImmPrediction::into_estimate`]: coasting through a missed
    /// plot); the reference variances and `ν` are unchanged. [`MultiImm::update`] takes it.
    ///
    /// # Errors
    /// As [`Imm::predict`]. `est` is never modified.
    pub fn predict(
        &self,
        est: &MultiImmEstimate<N, R, K>,
        dt: f64,
    ) -> Result<MultiImmEstimate<N, R, K>, ImmError> {
        let mut out = *est;
        for (imm_est, src) in out.imms.iter_mut().zip(&est.imms) {
            // As `predict(src, dt)?.into_estimate()`, without the round trip through logs.
            let cbar = self.imm.predict_into(src, dt, imm_est.modes_mut())?;
            imm_est.set_weights(cbar);
        }
        Ok(out)
    }

    /// One step with `plot` after `dt` seconds: [`MultiImm::predict`], then
    /// [`MultiImm::update`] (fused: every IMM is predicted and updated in one buffer).
    ///
    /// # Errors
    /// [`ImmError::InvalidInterval`] for `dt` not finite and positive; any error of the
    /// conversion or of an IMM (naming the mode); [`ImmError::NoLikelihood`] if no
    /// hypothesis explains the plot. `est` is never modified.
    pub fn step<const M: usize, C: PlotConversion<N, M>>(
        &self,
        est: &MultiImmEstimate<N, R, K>,
        dt: f64,
        plot: &PolarMeasurement,
        conversion: &C,
    ) -> Result<MultiImmUpdate<N, R, K>, ImmError> {
        // One buffer for the result, updated in place (no copies of the K estimates).
        let mut out = self.start_update(est);
        out.log_likelihoods = self.imm.step_hypotheses(
            &est.imms,
            &mut out.estimate.imms,
            dt,
            plot,
            &out.hypotheses,
            conversion,
        )?;
        self.finish(&mut out)?;
        Ok(out)
    }

    /// The update of a prediction from [`MultiImm::predict`] with `plot` (steps 1–5 above,
    /// each IMM updated from its prediction).
    ///
    /// # Errors
    /// Any error of the conversion or of an IMM (naming the mode);
    /// [`ImmError::NoLikelihood`] if no hypothesis explains the plot. `predicted` is never
    /// modified.
    pub fn update<const M: usize, C: PlotConversion<N, M>>(
        &self,
        predicted: &MultiImmEstimate<N, R, K>,
        plot: &PolarMeasurement,
        conversion: &C,
    ) -> Result<MultiImmUpdate<N, R, K>, ImmError> {
        let cbar = predicted.imms.map(|e| *e.weights());
        let mut out = self.start_update(predicted);
        out.log_likelihoods = self.imm.update_hypotheses(
            &mut out.estimate.imms,
            &cbar,
            plot,
            &out.hypotheses,
            conversion,
        )?;
        self.finish(&mut out)?;
        Ok(out)
    }

    /// The buffer `step` and `update` fill: `est` (to be updated in place), this step's
    /// hypotheses, and no likelihoods yet.
    fn start_update(&self, est: &MultiImmEstimate<N, R, K>) -> MultiImmUpdate<N, R, K> {
        MultiImmUpdate {
            estimate: *est,
            hypotheses: self.hypotheses(est),
            log_likelihoods: [f64::NEG_INFINITY; K],
        }
    }

    /// Steps 3–5 in place on `out`, which holds the updated IMMs, their likelihoods, this
    /// step's hypotheses and the previous reference.
    fn finish(&self, out: &mut MultiImmUpdate<N, R, K>) -> Result<(), ImmError> {
        let hyp = &out.hypotheses;
        let ll = &out.log_likelihoods;
        // Eq (12) with the max shift: νᵐ = exp(ln Λᵐ − max) / Σ exp(ln Λⁱ − max).
        let max = ll.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if !max.is_finite() {
            return Err(ImmError::NoLikelihood {
                what: "noise hypotheses",
            });
        }
        let mut nu = ll.map(|l| (l - max).exp());
        let sum: f64 = nu.iter().sum();
        if !sum.is_finite() {
            return Err(ImmError::NoLikelihood {
                what: "noise hypotheses",
            });
        }
        for n in &mut nu {
            *n /= sum;
        }
        let mut raw = [0.0; 2];
        for (n, h) in nu.iter().zip(hyp) {
            raw[0] += n * h.range();
            raw[1] += n * h.azimuth();
        }
        let old = out.estimate.reference.as_array();
        let mut new = [0.0; 2];
        for ((nv, rv), ov) in new.iter_mut().zip(raw).zip(old) {
            let ratio = rv / ov;
            let ratio = match self.clip {
                Some(c) => ratio.clamp(1.0 - c, 1.0 + c),
                None => ratio,
            };
            *nv = ov * ratio;
        }
        out.estimate.reference = NoiseVariances::new(new[0], new[1])?;
        out.estimate.nu = nu;
        Ok(())
    }
}

impl<F: GaussianFilter<N>, const N: usize, const R: usize> Imm<F, N, R> {
    /// One IMM cycle for each of `K` noise hypotheses, the path shared by every estimator
    /// that runs a bank of IMMs differing only in `R` ([`MultiImm`], the evidence
    /// estimator): `out` (a copy of `src` on entry) receives the updated estimates; returns
    /// `ln Λᵐ` per IMM. All predictions come first (a prediction error is reported before a
    /// conversion error), then IMM `m` is updated in place with the plot converted under
    /// `hyp[m]`. On an error `out` is partly updated: callers work on a copy.
    pub(crate) fn step_hypotheses<const K: usize, const M: usize, C: PlotConversion<N, M>>(
        &self,
        src: &[ImmEstimate<N, R>; K],
        out: &mut [ImmEstimate<N, R>; K],
        dt: f64,
        plot: &PolarMeasurement,
        hyp: &[NoiseVariances; K],
        conversion: &C,
    ) -> Result<[f64; K], ImmError> {
        let mut cbar = [ModeWeights::ZERO; K];
        for ((o, s), c) in out.iter_mut().zip(src).zip(cbar.iter_mut()) {
            *c = self.predict_into(s, dt, o.modes_mut())?;
        }
        self.update_hypotheses(out, &cbar, plot, hyp, conversion)
    }

    /// The update half of [`Imm::step_hypotheses`]: `imms` hold predictions with
    /// `μ̄` = `cbar`; each is updated in place with the plot converted under its own
    /// hypothesis. Returns `ln Λᵐ`.
    pub(crate) fn update_hypotheses<const K: usize, const M: usize, C: PlotConversion<N, M>>(
        &self,
        imms: &mut [ImmEstimate<N, R>; K],
        cbar: &[ModeWeights<R>; K],
        plot: &PolarMeasurement,
        hyp: &[NoiseVariances; K],
        conversion: &C,
    ) -> Result<[f64; K], ImmError> {
        let mut ll = [f64::NEG_INFINITY; K];
        for (((imm_est, h), l), c) in imms.iter_mut().zip(hyp).zip(ll.iter_mut()).zip(cbar) {
            let (meas, z) = conversion.convert(plot, h)?;
            *l = self.update_in_place(imm_est, c, &meas, &z)?.0;
        }
        Ok(ll)
    }
}

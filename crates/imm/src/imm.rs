//! The interacting multiple model (IMM) estimator, seed 000 eqs (1)–(7).

use argus_core_math::{Gaussian, Vector};
use argus_filters::{FilterError, GaussianFilter, Innovation, check_dt};
use argus_sensors::MeasurementModel;

use crate::markov::{log_probabilities, log_sum_exp};
use crate::{ImmError, MarkovMatrix};

/// Below this a probability is also kept as a logarithm ([`ModeWeights`]).
const TINY: f64 = 1e-300;

/// Mode probabilities `μⱼ`, kept linear (they sum to one, so the largest is at least
/// `1/R`: no logarithms or exponentials per cycle), with `ln μⱼ` kept as well for every
/// mode below [`TINY`], whose linear value has lost precision or underflowed to 0: such a
/// mode keeps a usable (tiny) probability, e.g. `e^{-2000}`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ModeWeights<const R: usize> {
    /// `μⱼ`.
    lin: [f64; R],
    /// `ln μⱼ` where `lin[j] < TINY` (−∞ for an impossible mode); 0 elsewhere (unused).
    log: [f64; R],
}

impl<const R: usize> ModeWeights<R> {
    /// All zero (a buffer).
    pub(crate) const ZERO: Self = Self {
        lin: [0.0; R],
        log: [0.0; R],
    };

    /// From (normalised) logarithms `ln μⱼ`.
    pub(crate) fn from_logs(log: &[f64; R]) -> Self {
        let lin = log.map(f64::exp);
        let mut kept = [0.0; R];
        for ((k, l), p) in kept.iter_mut().zip(log).zip(&lin) {
            if *p < TINY {
                *k = *l;
            }
        }
        Self { lin, log: kept }
    }

    /// `ln μⱼ`.
    fn ln(&self, j: usize) -> f64 {
        if self.lin[j] >= TINY {
            self.lin[j].ln()
        } else {
            self.log[j]
        }
    }

    /// `ln μⱼ` for every mode.
    fn logs(&self) -> [f64; R] {
        core::array::from_fn(|j| self.ln(j))
    }
}

/// `ln x` out of line, for rare paths (so that it is not hoisted into the common one).
#[cold]
#[inline(never)]
fn cold_ln(x: f64) -> f64 {
    x.ln()
}

/// The state of an IMM: one Gaussian per mode and the mode probabilities, kept linear with
/// logarithms for the modes too improbable for `f64` (a mode whose likelihood underflows
/// keeps a usable, tiny probability).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImmEstimate<const N: usize, const R: usize> {
    modes: [Gaussian<N>; R],
    mu: ModeWeights<R>,
}

impl<const N: usize, const R: usize> ImmEstimate<N, R> {
    /// An estimate from per-mode Gaussians and mode probabilities `μ`.
    ///
    /// # Errors
    /// [`ImmError::Empty`] for `R = 0`; [`ImmError::InvalidProbabilities`] when `μ` has a
    /// negative or non-finite entry or does not sum to one (within 1e-9).
    pub fn new(modes: [Gaussian<N>; R], mu: [f64; R]) -> Result<Self, ImmError> {
        let log_mu = log_probabilities(&mu, "initial mode probabilities")?;
        // Normalised (the sum may differ from one by 1e-9), in log space so that a tiny
        // entry keeps its logarithm.
        let ln_sum = mu.iter().sum::<f64>().ln();
        Ok(Self {
            modes,
            mu: ModeWeights::from_logs(&log_mu.map(|l| l - ln_sum)),
        })
    }

    /// Every mode starts from the same Gaussian (e.g. a two-point initialisation).
    ///
    /// # Errors
    /// As [`ImmEstimate::new`].
    pub fn from_common(start: Gaussian<N>, mu: [f64; R]) -> Result<Self, ImmError> {
        Self::new([start; R], mu)
    }

    /// The mode-conditioned estimates `x̂ⱼ, Pⱼ`.
    #[must_use]
    pub fn modes(&self) -> &[Gaussian<N>; R] {
        &self.modes
    }

    /// The modes, for an update in place.
    pub(crate) fn modes_mut(&mut self) -> &mut [Gaussian<N>; R] {
        &mut self.modes
    }

    /// The mode probabilities in their stored form.
    pub(crate) fn weights(&self) -> &ModeWeights<R> {
        &self.mu
    }

    /// Sets the mode probabilities (a prediction's `μ̄`, coasting).
    pub(crate) fn set_weights(&mut self, mu: ModeWeights<R>) {
        self.mu = mu;
    }

    /// The mode probabilities `μⱼ` (a mode below about `e^{-745}` is 0;
    /// [`ImmEstimate::log_mode_probabilities`] keeps it).
    #[must_use]
    pub fn mode_probabilities(&self) -> [f64; R] {
        self.mu.lin
    }

    /// `ln μⱼ` (−∞ for a mode that has become impossible).
    #[must_use]
    pub fn log_mode_probabilities(&self) -> [f64; R] {
        self.mu.logs()
    }

    /// The estimate as a "prediction" for a plot of the same instant as the last one: no
    /// mixing and no motion (`μ̄ = μ`), so that [`Imm::update`] can apply several plots of
    /// one scan (several sensors) in turn.
    #[must_use]
    pub fn into_prediction(self) -> ImmPrediction<N, R> {
        ImmPrediction {
            predicted: self.modes,
            log_cbar: self.mu.logs(),
        }
    }

    /// The combined output, seed 000 eq (7): `x = Σ μⱼ x̂ⱼ`,
    /// `P = Σ μⱼ [Pⱼ + (x̂ⱼ − x)(x̂ⱼ − x)ᵀ]`.
    ///
    /// # Errors
    /// [`ImmError::Math`] if the result is not positive definite (cannot happen in exact
    /// arithmetic for valid inputs; reported rather than returned).
    pub fn combined(&self) -> Result<Gaussian<N>, ImmError> {
        moment_match(&self.mode_probabilities(), &self.modes)
    }
}

/// The moment-matched Gaussian of a mixture `Σ wₘ N(xₘ, Pₘ)` with weights that sum to one:
/// `x = Σ wₘ xₘ`, `P = Σ wₘ [Pₘ + (xₘ − x)(xₘ − x)ᵀ]` (the spread-of-means term,
/// seed 000 eqs (2), (7)); [`Gaussian::mixture`]. Parts with a weight that is not positive
/// are skipped. `P` is positive definite by construction (a positive combination of
/// positive-definite covariances plus positive semi-definite spread terms), so only
/// finiteness is checked.
///
/// # Errors
/// [`ImmError::Math`] if the result is non-finite, a weight is not finite or no weight is
/// positive.
#[inline]
pub fn moment_match<const N: usize, const K: usize>(
    weights: &[f64; K],
    parts: &[Gaussian<N>; K],
) -> Result<Gaussian<N>, ImmError> {
    Ok(Gaussian::mixture(weights, parts)?)
}

/// The mode-matched predictions of one IMM cycle, before a plot is used.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImmPrediction<const N: usize, const R: usize> {
    predicted: [Gaussian<N>; R],
    log_cbar: [f64; R],
}

impl<const N: usize, const R: usize> ImmPrediction<N, R> {
    /// The predicted mode-conditioned estimates `x̂ⱼ(k|k−1), Pⱼ(k|k−1)` (eq (3)).
    #[must_use]
    pub fn modes(&self) -> &[Gaussian<N>; R] {
        &self.predicted
    }

    /// The predicted mode probabilities `ln μ̄ⱼ = ln Σᵢ πᵢⱼ μᵢ` (eqs (1), (8)).
    #[must_use]
    pub fn log_predicted_probabilities(&self) -> &[f64; R] {
        &self.log_cbar
    }

    /// Coasts through a missing plot: the predictions become the estimate, with `μ = μ̄`.
    #[must_use]
    pub fn into_estimate(self) -> ImmEstimate<N, R> {
        ImmEstimate {
            modes: self.predicted,
            mu: ModeWeights::from_logs(&self.log_cbar),
        }
    }
}

/// The result of an IMM update with one plot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImmUpdate<const N: usize, const R: usize> {
    /// The updated estimate.
    pub estimate: ImmEstimate<N, R>,
    /// `ln Λ = ln Σⱼ μ̄ⱼ Λⱼ`, the IMM's total likelihood of the plot (seed 000 eq (10)).
    pub log_likelihood: f64,
    /// `ln Λⱼ = ln N(rⱼ; 0, Sⱼ)` per mode (eq (5), with the corrected normaliser `|2πS|^{−½}`).
    pub mode_log_likelihoods: [f64; R],
}

/// An IMM over `R` mode-matched filters that share one `N`-dimensional state.
///
/// `F` is one filter type for all modes; a closed set of different models is an enum
/// (e.g. a Kalman filter over `enum Motion { Cv, Ct }`). Models of different state size
/// share the common state through [`crate::Embedded`].
///
/// Per cycle (seed 000 §2.1): mixing probabilities `μᵢ|ⱼ = πᵢⱼ μᵢ / μ̄ⱼ` (eq 1), mixed
/// initial conditions with the spread-of-means term (eq 2), mode-matched prediction and
/// update (eqs 3–4), likelihoods `Λⱼ = N(rⱼ; 0, Sⱼ)` (eq 5), mode probabilities
/// `μⱼ ∝ μ̄ⱼ Λⱼ` (eq 6) and the combination (eq 7). Probabilities are computed as
/// logarithms (log-sum-exp), so a likelihood of `e^{−2000}` does not underflow to a zero
/// probability. The interval `dt` is an argument of each cycle, so the sampling may vary.
///
/// # References
/// Jeon et al. (2010), seed 000, eqs (1)–(7) (eq (4) read as `x = x⁻ + K r`,
/// `P = P⁻ − K S Kᵀ`; eq (5) with `|2πS|^{−½}`); Bar-Shalom, Li & Kirubarajan (2001) §11.6.6.
#[derive(Debug, Clone, PartialEq)]
pub struct Imm<F, const N: usize, const R: usize> {
    filters: [F; R],
    markov: MarkovMatrix<R>,
}

impl<F: GaussianFilter<N>, const N: usize, const R: usize> Imm<F, N, R> {
    /// An IMM of the mode-matched `filters` with transition matrix `markov`.
    ///
    /// # Errors
    /// [`ImmError::Empty`] when `R = 0`.
    pub fn new(filters: [F; R], markov: MarkovMatrix<R>) -> Result<Self, ImmError> {
        if R == 0 {
            return Err(ImmError::Empty { what: "IMM modes" });
        }
        Ok(Self { filters, markov })
    }

    /// The mode-matched filters.
    #[must_use]
    pub fn filters(&self) -> &[F; R] {
        &self.filters
    }

    /// The transition matrix.
    #[must_use]
    pub fn markov(&self) -> &MarkovMatrix<R> {
        &self.markov
    }

    /// Interaction (mixing), seed 000 eqs (1)–(2): the mixed initial condition of every
    /// mode and `ln μ̄ⱼ`.
    ///
    /// # Errors
    /// [`ImmError::Math`] if a mixed covariance is not positive definite.
    pub fn mix(&self, est: &ImmEstimate<N, R>) -> Result<([Gaussian<N>; R], [f64; R]), ImmError> {
        let mut mixed = est.modes;
        let cbar = self.mix_into(est, &mut mixed)?;
        Ok((mixed, cbar.logs()))
    }

    /// Mixing into `mixed` (which must hold `est`'s modes: an unreachable mode keeps its
    /// own estimate); returns `μ̄ⱼ`.
    fn mix_into(
        &self,
        est: &ImmEstimate<N, R>,
        mixed: &mut [Gaussian<N>; R],
    ) -> Result<ModeWeights<R>, ImmError> {
        // Linear arithmetic on μ (no logarithms or exponentials); a mode whose predicted
        // probability would be below TINY falls back to log-sum-exp over the kept
        // logarithms, so nothing is lost to underflow.
        let pi = self.markov.matrix();
        let mu = &est.mu.lin;
        let mut cbar = ModeWeights::ZERO;
        for (j, ((cl, lc), out)) in cbar
            .lin
            .iter_mut()
            .zip(cbar.log.iter_mut())
            .zip(mixed.iter_mut())
            .enumerate()
        {
            let mut w = [0.0; R];
            let mut c = 0.0;
            for (i, (wi, m)) in w.iter_mut().zip(mu).enumerate() {
                *wi = pi[(i, j)] * m;
                c += *wi;
            }
            if c >= TINY {
                *cl = c;
                let inv = 1.0 / c;
                for wi in &mut w {
                    *wi *= inv;
                }
            } else {
                *lc = self.mixing_in_logs(&est.mu, j, &mut w);
                *cl = lc.exp();
                if *lc == f64::NEG_INFINITY {
                    // Mode j cannot be reached: its probability is zero; keep its own estimate.
                    continue;
                }
            }
            // The mixed covariance Σᵢ μᵢ|ⱼ (Pᵢ + dᵢ dᵢᵀ): a convex combination of
            // positive-definite matrices plus positive-semidefinite spread terms (checked
            // for finiteness).
            out.assign_mixture(&w, &est.modes)?;
        }
        Ok(cbar)
    }

    /// The rare path of mixing, a predicted probability below [`TINY`]: `ln μ̄ⱼ` by
    /// log-sum-exp over `ln πᵢⱼ + ln μᵢ`, and the mixing weights `μᵢ|ⱼ` into `w` (untouched
    /// when `ln μ̄ⱼ = −∞`). Out of line and cold, so that the logarithms are not hoisted
    /// into the common path.
    #[cold]
    #[inline(never)]
    fn mixing_in_logs(&self, mu: &ModeWeights<R>, j: usize, w: &mut [f64; R]) -> f64 {
        let log_pi = self.markov.log_matrix();
        let mut terms = [f64::NEG_INFINITY; R];
        for (i, t) in terms.iter_mut().enumerate() {
            *t = log_pi[(i, j)] + mu.ln(i);
        }
        let lc = log_sum_exp(&terms);
        if lc > f64::NEG_INFINITY {
            *w = terms.map(|t| (t - lc).exp());
        }
        lc
    }

    /// Mixing and mode-matched prediction over `dt` seconds (eqs (1)–(3)).
    ///
    /// # Errors
    /// [`ImmError::InvalidInterval`] when `dt` is not finite and positive (time going
    /// backwards); [`ImmError::Filter`] naming the mode whose prediction failed.
    pub fn predict(
        &self,
        est: &ImmEstimate<N, R>,
        dt: f64,
    ) -> Result<ImmPrediction<N, R>, ImmError> {
        let mut predicted = est.modes;
        let cbar = self.predict_into(est, dt, &mut predicted)?;
        Ok(ImmPrediction {
            predicted,
            log_cbar: cbar.logs(),
        })
    }

    /// [`Imm::predict`] into `out` (which must hold `est`'s modes); returns `μ̄ⱼ`.
    pub(crate) fn predict_into(
        &self,
        est: &ImmEstimate<N, R>,
        dt: f64,
        out: &mut [Gaussian<N>; R],
    ) -> Result<ModeWeights<R>, ImmError> {
        check_dt(dt).map_err(|_| ImmError::InvalidInterval { dt })?;
        let cbar = self.mix_into(est, out)?;
        for (j, (f, g)) in self.filters.iter().zip(out.iter_mut()).enumerate() {
            // In place, and the error mapped only on the error path: a `Result` holding the
            // Gaussian (and `map_err` moving it between two `Result` layouts) costs copies
            // that read freshly stored values back in other widths, which stalls.
            if let Err(source) = f.predict_in_place(g, dt) {
                return Err(ImmError::Filter { mode: j, source });
            }
        }
        Ok(cbar)
    }

    /// The mode-matched updates of the predictions held in `est` (modes `x̂ⱼ(k|k−1)`), in
    /// place; returns `ln Λⱼ`. On an error `est` is left partly updated: callers work on a
    /// copy.
    fn update_modes<const M: usize, Me: MeasurementModel<N, M>>(
        &self,
        est: &mut ImmEstimate<N, R>,
        meas: &Me,
        z: &Vector<M>,
    ) -> Result<[f64; R], ImmError> {
        self.each_mode(est, |f, g| f.update_in_place(g, meas, z))
    }

    /// `ln Λⱼ` of `stage` (a mode-matched update, or a prediction and update) applied to
    /// each mode of `est` in place by its filter; the first failure names its mode. On an
    /// error `est` is left partly updated: callers work on a copy.
    #[inline(always)]
    fn each_mode<const M: usize>(
        &self,
        est: &mut ImmEstimate<N, R>,
        mut stage: impl FnMut(&F, &mut Gaussian<N>) -> Result<Innovation<M>, FilterError>,
    ) -> Result<[f64; R], ImmError> {
        let mut ll = [f64::NEG_INFINITY; R];
        for (j, ((f, g), l)) in self
            .filters
            .iter()
            .zip(est.modes.iter_mut())
            .zip(ll.iter_mut())
            .enumerate()
        {
            match stage(f, g) {
                Ok(innov) => *l = innov.log_likelihood(),
                Err(source) => return Err(ImmError::Filter { mode: j, source }),
            }
        }
        Ok(ll)
    }

    /// The update of a prediction held in `est` (modes `x̂ⱼ(k|k−1)`) with `μ̄ⱼ` = `cbar`,
    /// in place; returns `(ln Λ, ln Λⱼ)`. On an error `est` is left partly updated:
    /// callers work on a copy.
    pub(crate) fn update_in_place<const M: usize, Me: MeasurementModel<N, M>>(
        &self,
        est: &mut ImmEstimate<N, R>,
        cbar: &ModeWeights<R>,
        meas: &Me,
        z: &Vector<M>,
    ) -> Result<(f64, [f64; R]), ImmError> {
        let ll = self.update_modes(est, meas, z)?;
        Self::weigh_modes(est, cbar, ll)
    }

    /// One cycle from `prior` into `est` (which must hold `prior`'s modes): mixing, each
    /// mode's prediction and update in one [`GaussianFilter::step_in_place`] (for a Kalman
    /// filter its intermediate prediction is checked for finiteness, the posterior in full),
    /// then the mode probabilities; returns `(ln Λ, ln Λⱼ)`. The same values as
    /// [`Imm::predict_into`] then [`Imm::update_in_place`]; when several things are wrong
    /// the error may name another of them (mode by mode rather than all predictions first).
    /// On an error `est` is left partly updated: callers work on a copy.
    fn cycle_into<const M: usize, Me: MeasurementModel<N, M>>(
        &self,
        prior: &ImmEstimate<N, R>,
        dt: f64,
        meas: &Me,
        z: &Vector<M>,
        est: &mut ImmEstimate<N, R>,
    ) -> Result<(f64, [f64; R]), ImmError> {
        check_dt(dt).map_err(|_| ImmError::InvalidInterval { dt })?;
        let cbar = self.mix_into(prior, &mut est.modes)?;
        let ll = self.each_mode(est, |f, g| f.step_in_place(g, dt, meas, z))?;
        Self::weigh_modes(est, &cbar, ll)
    }

    /// Eq (6) after the mode-matched updates: `μⱼ ∝ μ̄ⱼ Λⱼ` into `est` from `μ̄ⱼ` = `cbar`
    /// and `ln Λⱼ` = `ll`; returns `(ln Λ, ln Λⱼ)`.
    fn weigh_modes(
        est: &mut ImmEstimate<N, R>,
        cbar: &ModeWeights<R>,
        ll: [f64; R],
    ) -> Result<(f64, [f64; R]), ImmError> {
        if !cbar.lin.iter().all(|&c| c >= TINY) {
            // A predicted probability kept as a logarithm: the update in log space.
            let total = Self::update_log_space(est, &cbar.logs(), &ll)?;
            return Ok((total, ll));
        }
        // μⱼ ∝ μ̄ⱼ Λⱼ with the likelihoods shifted by their largest logarithm:
        // Λ = e^max Σⱼ μ̄ⱼ exp(ln Λⱼ − max), at least e^max · TINY (the most likely mode's
        // term), so the sum neither overflows nor vanishes.
        let max = ll.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if !max.is_finite() {
            return Err(ImmError::NoLikelihood { what: "IMM modes" });
        }
        let mut w = [0.0; R];
        let mut sum = 0.0;
        for ((wj, c), l) in w.iter_mut().zip(&cbar.lin).zip(&ll) {
            // The most likely mode's factor is e⁰ = 1 exactly (IEEE `exp(0)` is exact), so
            // its exponential is not called: the same bits, one `exp` fewer per cycle.
            // (`max` is one of the `ll` themselves, so its bits match that mode's.)
            *wj = if l.to_bits() == max.to_bits() {
                *c
            } else {
                c * (l - max).exp()
            };
            sum += *wj;
        }
        let ln_sum = sum.ln();
        let total = max + ln_sum;
        if !total.is_finite() {
            return Err(ImmError::NoLikelihood { what: "IMM modes" });
        }
        let mu = &mut est.mu;
        let inv_sum = 1.0 / sum;
        for (j, ((p, lg), wj)) in mu.lin.iter_mut().zip(mu.log.iter_mut()).zip(&w).enumerate() {
            *p = wj * inv_sum;
            *lg = if *p >= TINY {
                0.0
            } else {
                // ln μⱼ = ln μ̄ⱼ + ln Λⱼ − ln Λ (rare: a mode e^{-690} below the rest).
                cold_ln(cbar.lin[j]) + (ll[j] - max) - ln_sum
            };
        }
        Ok((total, ll))
    }

    /// Eq (6) in log space: `ln μⱼ = ln μ̄ⱼ + ln Λⱼ − ln Λ` with `ln Λ` by log-sum-exp, into
    /// `est`; returns `ln Λ`.
    fn update_log_space(
        est: &mut ImmEstimate<N, R>,
        log_cbar: &[f64; R],
        ll: &[f64; R],
    ) -> Result<f64, ImmError> {
        let mut joint = [f64::NEG_INFINITY; R];
        for ((v, lc), l) in joint.iter_mut().zip(log_cbar).zip(ll) {
            *v = lc + l;
        }
        let max = joint.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if !max.is_finite() {
            return Err(ImmError::NoLikelihood { what: "IMM modes" });
        }
        let scaled = joint.map(|v| (v - max).exp());
        let sum: f64 = scaled.iter().sum();
        let total = max + sum.ln();
        if !total.is_finite() {
            return Err(ImmError::NoLikelihood { what: "IMM modes" });
        }
        let mu = &mut est.mu;
        for (((p, lg), s), v) in mu
            .lin
            .iter_mut()
            .zip(mu.log.iter_mut())
            .zip(&scaled)
            .zip(&joint)
        {
            *p = s / sum;
            *lg = if *p >= TINY { 0.0 } else { v - total };
        }
        Ok(total)
    }

    /// Mode-matched updates with plot `z`, likelihoods and mode probabilities (eqs (4)–(6)).
    ///
    /// # Errors
    /// [`ImmError::Filter`] naming the mode whose update failed (non-finite `z`, `S` not
    /// positive definite); [`ImmError::NoLikelihood`] if no mode can explain the plot.
    pub fn update<const M: usize, Me: MeasurementModel<N, M>>(
        &self,
        pred: &ImmPrediction<N, R>,
        meas: &Me,
        z: &Vector<M>,
    ) -> Result<ImmUpdate<N, R>, ImmError> {
        let mut estimate = ImmEstimate {
            modes: pred.predicted,
            mu: ModeWeights::ZERO,
        };
        let mode_log_likelihoods = self.update_modes(&mut estimate, meas, z)?;
        let log_likelihood =
            Self::update_log_space(&mut estimate, &pred.log_cbar, &mode_log_likelihoods)?;
        Ok(ImmUpdate {
            estimate,
            log_likelihood,
            mode_log_likelihoods,
        })
    }

    /// [`Imm::step`] in place: `est` becomes the updated estimate; returns
    /// `(ln Λ, ln Λⱼ)`. On an error `est` is restored (left unchanged). For a batch run
    /// that keeps only the latest estimate: the estimate (about 0.5 kB for 3 modes of 4
    /// states) is copied once per cycle (the prior, which the mixing reads while it writes
    /// the mixed modes) instead of three times ([`Imm::step`]'s working copy, its result,
    /// and the caller's assignment).
    ///
    /// # Errors
    /// As [`Imm::step`].
    pub fn step_in_place<const M: usize, Me: MeasurementModel<N, M>>(
        &self,
        est: &mut ImmEstimate<N, R>,
        dt: f64,
        meas: &Me,
        z: &Vector<M>,
    ) -> Result<(f64, [f64; R]), ImmError> {
        let prior = *est;
        let result = self.cycle_into(&prior, dt, meas, z, est);
        if result.is_err() {
            *est = prior;
        }
        result
    }

    /// One full cycle: [`Imm::predict`] over `dt`, then [`Imm::update`] with `z`.
    ///
    /// # Errors
    /// As [`Imm::predict`] and [`Imm::update`]; `est` is never modified.
    pub fn step<const M: usize, Me: MeasurementModel<N, M>>(
        &self,
        est: &ImmEstimate<N, R>,
        dt: f64,
        meas: &Me,
        z: &Vector<M>,
    ) -> Result<ImmUpdate<N, R>, ImmError> {
        let mut estimate = *est;
        let (log_likelihood, mode_log_likelihoods) =
            self.cycle_into(est, dt, meas, z, &mut estimate)?;
        Ok(ImmUpdate {
            estimate,
            log_likelihood,
            mode_log_likelihoods,
        })
    }
}

//! The interacting multiple model (IMM) estimator, seed 000 eqs (1)–(7).

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{GaussianFilter, check_dt};
use argus_sensors::MeasurementModel;

use crate::markov::{log_probabilities, log_sum_exp};
use crate::{ImmError, MarkovMatrix};

/// The state of an IMM: one Gaussian per mode and the mode probabilities, kept as logarithms
/// so that a mode whose likelihood underflows `f64` keeps a usable (tiny) probability.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImmEstimate<const N: usize, const R: usize> {
    modes: [Gaussian<N>; R],
    log_mu: [f64; R],
}

impl<const N: usize, const R: usize> ImmEstimate<N, R> {
    /// An estimate from per-mode Gaussians and mode probabilities `μ`.
    ///
    /// # Errors
    /// [`ImmError::Empty`] for `R = 0`; [`ImmError::InvalidProbabilities`] when `μ` has a
    /// negative or non-finite entry or does not sum to one (within 1e-9).
    pub fn new(modes: [Gaussian<N>; R], mu: [f64; R]) -> Result<Self, ImmError> {
        let log_mu = log_probabilities(&mu, "initial mode probabilities")?;
        Ok(Self { modes, log_mu })
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

    /// The mode probabilities `μⱼ`.
    #[must_use]
    pub fn mode_probabilities(&self) -> [f64; R] {
        self.log_mu.map(f64::exp)
    }

    /// `ln μⱼ` (−∞ for a mode that has become impossible).
    #[must_use]
    pub fn log_mode_probabilities(&self) -> &[f64; R] {
        &self.log_mu
    }

    /// The estimate as a "prediction" for a plot of the same instant as the last one: no
    /// mixing and no motion (`μ̄ = μ`), so that [`Imm::update`] can apply several plots of
    /// one scan (several sensors) in turn.
    #[must_use]
    pub fn into_prediction(self) -> ImmPrediction<N, R> {
        ImmPrediction {
            predicted: self.modes,
            log_cbar: self.log_mu,
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
/// seed 000 eqs (2), (7)).
///
/// # Errors
/// [`ImmError::Math`] if the result is non-finite or not positive definite.
pub fn moment_match<const N: usize, const K: usize>(
    weights: &[f64; K],
    parts: &[Gaussian<N>; K],
) -> Result<Gaussian<N>, ImmError> {
    let mut mean = Vector::<N>::zeros();
    for (w, g) in weights.iter().zip(parts) {
        if *w > 0.0 {
            mean += g.mean() * *w;
        }
    }
    let mut cov = Matrix::<N, N>::zeros();
    for (w, g) in weights.iter().zip(parts) {
        if *w > 0.0 {
            let d = g.mean() - mean;
            cov += (g.cov() + d * d.transpose()) * *w;
        }
    }
    Ok(Gaussian::from_symmetrized(mean, &cov)?)
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
            log_mu: self.log_cbar,
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
        // Linear arithmetic on μ scaled by the largest one (R exponentials, not R²); a mode
        // whose predicted probability would underflow (every contribution below e^{-690}
        // of the largest) falls back to log-sum-exp, so nothing is lost to underflow.
        let pi = self.markov.matrix();
        let max = est.log_mu.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let scaled = est.log_mu.map(|l| (l - max).exp());
        let mut log_cbar = [f64::NEG_INFINITY; R];
        let mut mixed = est.modes;
        for j in 0..R {
            let mut w = [0.0; R];
            let mut c = 0.0;
            for (i, (wi, mu)) in w.iter_mut().zip(&scaled).enumerate() {
                *wi = pi[(i, j)] * mu;
                c += *wi;
            }
            if c > 1e-300 && c.is_finite() {
                log_cbar[j] = c.ln() + max;
                for wi in &mut w {
                    *wi /= c;
                }
            } else {
                let log_pi = self.markov.log_matrix();
                let mut terms = [f64::NEG_INFINITY; R];
                for (i, t) in terms.iter_mut().enumerate() {
                    *t = log_pi[(i, j)] + est.log_mu[i];
                }
                let lc = log_sum_exp(&terms);
                log_cbar[j] = lc;
                if lc == f64::NEG_INFINITY {
                    // Mode j cannot be reached: its probability is zero; keep its own estimate.
                    continue;
                }
                w = terms.map(|t| (t - lc).exp());
            }
            mixed[j] = moment_match(&w, &est.modes)?;
        }
        Ok((mixed, log_cbar))
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
        check_dt(dt).map_err(|_| ImmError::InvalidInterval { dt })?;
        let (mut modes, log_cbar) = self.mix(est)?;
        for (j, (f, g)) in self.filters.iter().zip(modes.iter_mut()).enumerate() {
            *g = f
                .predict(g, dt)
                .map_err(|source| ImmError::Filter { mode: j, source })?;
        }
        Ok(ImmPrediction {
            predicted: modes,
            log_cbar,
        })
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
        let mut modes = pred.predicted;
        let mut ll = [f64::NEG_INFINITY; R];
        for (j, (f, g)) in self.filters.iter().zip(modes.iter_mut()).enumerate() {
            let (post, innov) = f
                .update(g, meas, z)
                .map_err(|source| ImmError::Filter { mode: j, source })?;
            *g = post;
            ll[j] = innov.log_likelihood;
        }
        let mut joint = [f64::NEG_INFINITY; R];
        for (j, v) in joint.iter_mut().enumerate() {
            *v = pred.log_cbar[j] + ll[j];
        }
        let total = log_sum_exp(&joint);
        if !total.is_finite() {
            return Err(ImmError::NoLikelihood { what: "IMM modes" });
        }
        let log_mu = joint.map(|v| v - total);
        Ok(ImmUpdate {
            estimate: ImmEstimate { modes, log_mu },
            log_likelihood: total,
            mode_log_likelihoods: ll,
        })
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
        let pred = self.predict(est, dt)?;
        self.update(&pred, meas, z)
    }
}

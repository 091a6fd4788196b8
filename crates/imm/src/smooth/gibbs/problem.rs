//! The jump-Markov problem behind an IMM, validated and tabulated once: per step every
//! mode's `F`, `Q` and the plot's `H`, `R`, `z` with its information `Hᵀ R⁻¹ H`,
//! `Hᵀ R⁻¹ z`, so that a sweep only multiplies stack matrices.

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::Kf;
use argus_motion_models::LinearMotionModel;
use argus_sensors::LinearMeasurementModel;

use super::error::GibbsError;
use super::kalman::Moments;
use super::step_model::StepModel;
use crate::{Imm, PROBABILITY_SUM_TOL};

/// The jump-Markov linear system an IMM of Kalman filters assumes, over one track:
/// `m₀ ~ μ₀`, `mₖ | mₖ₋₁ ~ π`, `x₀ ~ start` (at `times[0]`), `xₖ = F_{mₖ}(Δₖ) xₖ₋₁ + w`,
/// `w ~ N(0, Q_{mₖ}(Δₖ))`, `zₖ = Hₖ xₖ + v`, `v ~ N(0, Rₖ)` for `k = 1 … n`. `N` is the
/// state dimension, `D` the plot's, `R` the number of modes. Linear models only: the
/// modes' `F`, `Q` and each plot's `H`, `R` are read once (at the zero state; they do not
/// depend on it for linear models).
#[derive(Debug, Clone)]
pub struct GibbsProblem<const N: usize, const D: usize, const R: usize> {
    pub(super) log_pi: [[f64; R]; R],
    pub(super) log_mu0: [f64; R],
    pub(super) start: Moments<N>,
    pub(super) times: Vec<f64>,
    /// `steps[k − 1]` is step `k`.
    pub(super) steps: Vec<StepModel<N, D, R>>,
}

fn ln(x: f64) -> f64 {
    if x > 0.0 { x.ln() } else { f64::NEG_INFINITY }
}

fn finite<const A: usize, const B: usize>(
    m: &Matrix<A, B>,
    step: usize,
    what: &'static str,
) -> Result<(), GibbsError> {
    if m.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(GibbsError::NonFinite { step, what })
    }
}

impl<const N: usize, const D: usize, const R: usize> GibbsProblem<N, D, R> {
    /// The problem of `imm`'s modes and Markov matrix, the prior `mu0` of the first mode,
    /// the state `start` at `times[0]`, and `plots[k − 1]` (measurement model and plot) at
    /// `times[k]`.
    ///
    /// # Errors
    /// [`GibbsError::LengthMismatch`] unless `times.len() = plots.len() + 1`;
    /// [`GibbsError::TimeNotIncreasing`], [`GibbsError::NonFinite`] (time, plot, `F`, `Q`,
    /// `H`, `R`) and [`GibbsError::NotPositiveDefinite`] (`R`) naming the step;
    /// [`GibbsError::InvalidPrior`] for a `mu0` that is not a probability vector.
    pub fn new<Mo, Me>(
        imm: &Imm<Kf<Mo>, N, R>,
        mu0: [f64; R],
        start: &Gaussian<N>,
        times: &[f64],
        plots: &[(Me, Vector<D>)],
    ) -> Result<Self, GibbsError>
    where
        Mo: LinearMotionModel<N>,
        Me: LinearMeasurementModel<N, D>,
        Kf<Mo>: argus_filters::GaussianFilter<N>,
    {
        if times.len() != plots.len() + 1 {
            return Err(GibbsError::LengthMismatch {
                what: "times (one more than plots)",
                expected: plots.len() + 1,
                got: times.len(),
            });
        }
        let sum: f64 = mu0.iter().sum();
        if mu0.iter().any(|p| !(p.is_finite() && *p >= 0.0))
            || (sum - 1.0).abs() > PROBABILITY_SUM_TOL
        {
            return Err(GibbsError::InvalidPrior);
        }
        if !times[0].is_finite() {
            return Err(GibbsError::NonFinite {
                step: 0,
                what: "time",
            });
        }
        let m = imm.markov().matrix();
        let log_pi = core::array::from_fn(|i| core::array::from_fn(|j| ln(m[(i, j)])));
        let zero = Vector::<N>::zeros();
        let mut steps = Vec::with_capacity(plots.len());
        for (k, (meas, z)) in plots.iter().enumerate() {
            let step = k + 1;
            let (prev, now) = (times[k], times[step]);
            if !now.is_finite() {
                return Err(GibbsError::NonFinite { step, what: "time" });
            }
            if now <= prev {
                return Err(GibbsError::TimeNotIncreasing { step, prev, now });
            }
            let dt = now - prev;
            let models = imm.filters().each_ref().map(Kf::model);
            let f = models.map(|mo| mo.transition(dt));
            let q = models.map(|mo| mo.process_noise(&zero, dt));
            for j in 0..R {
                finite(&f[j], step, "transition matrix F")?;
                finite(&q[j], step, "process noise Q")?;
            }
            let h = meas.matrix();
            let r = meas.noise(&zero);
            finite(&h, step, "measurement matrix H")?;
            finite(&r, step, "measurement noise R")?;
            finite(z, step, "plot")?;
            let rinv =
                r.cholesky()
                    .map(|c| c.inverse())
                    .ok_or(GibbsError::NotPositiveDefinite {
                        step,
                        what: "measurement noise R",
                    })?;
            let ht_rinv = h.transpose() * rinv;
            let info = ht_rinv * h;
            steps.push(StepModel {
                f,
                q,
                h,
                r,
                z: *z,
                info: 0.5 * (info + info.transpose()),
                info_z: ht_rinv * z,
            });
        }
        Ok(Self {
            log_pi,
            log_mu0: mu0.map(ln),
            start: Moments {
                x: *start.mean(),
                p: *start.cov(),
            },
            times: times.to_vec(),
            steps,
        })
    }

    /// The number of plots `n` (the steps are `0 … n`).
    #[must_use]
    pub fn plots(&self) -> usize {
        self.steps.len()
    }

    /// The times `times[0] … times[n]`.
    #[must_use]
    pub fn times(&self) -> &[f64] {
        &self.times
    }

    /// Checks a mode sequence `m₀ … mₙ`: the right length, modes in range, every
    /// transition of nonzero prior probability.
    ///
    /// # Errors
    /// [`GibbsError::LengthMismatch`] or [`GibbsError::InvalidSequence`] naming the step.
    pub fn check_sequence(&self, seq: &[usize]) -> Result<(), GibbsError> {
        if seq.len() != self.times.len() {
            return Err(GibbsError::LengthMismatch {
                what: "mode sequence",
                expected: self.times.len(),
                got: seq.len(),
            });
        }
        for (k, &mode) in seq.iter().enumerate() {
            let ok = mode < R
                && if k == 0 {
                    self.log_mu0[mode] > f64::NEG_INFINITY
                } else {
                    self.log_pi[seq[k - 1]][mode] > f64::NEG_INFINITY
                };
            if !ok {
                return Err(GibbsError::InvalidSequence { step: k, mode });
            }
        }
        Ok(())
    }

    /// A start sequence for a chain from per-step mode probabilities `m₀ … mₙ` (e.g. an
    /// IMM smoother's): at each step the most probable mode among those of nonzero prior
    /// after the mode chosen before (at step 0, of nonzero `μ₀`), so the sequence is always
    /// a valid [`crate::smooth::gibbs::GibbsChain::new`] start.
    ///
    /// # Errors
    /// [`GibbsError::LengthMismatch`] unless there are `n + 1` probability vectors.
    pub fn most_probable_sequence(
        &self,
        probabilities: impl IntoIterator<Item = [f64; R]>,
    ) -> Result<Vec<usize>, GibbsError> {
        let mut seq: Vec<usize> = Vec::with_capacity(self.times.len());
        for mu in probabilities {
            let allowed = |j: usize| match seq.last() {
                None => self.log_mu0[j] > f64::NEG_INFINITY,
                Some(&prev) => self.log_pi[prev][j] > f64::NEG_INFINITY,
            };
            let best = (0..R)
                .filter(|&j| allowed(j))
                .max_by(|&a, &b| mu[a].total_cmp(&mu[b]))
                .unwrap_or(0);
            seq.push(best);
        }
        if seq.len() != self.times.len() {
            return Err(GibbsError::LengthMismatch {
                what: "mode probabilities (one per step)",
                expected: self.times.len(),
                got: seq.len(),
            });
        }
        Ok(seq)
    }
}

//! The smoother's output: the chains' averages pooled and validated, and the one-call
//! smoother.

use argus_core_math::{Gaussian, Matrix, Vector};

use super::chain::GibbsChain;
use super::config::GibbsConfig;
use super::error::GibbsError;
use super::problem::GibbsProblem;

/// One step of the Gibbs smoother's output: the posterior mean and covariance of the
/// state (the average over sweeps of each drawn sequence's RTS-smoothed moments) and the
/// mode probabilities (the average of the block conditionals, Rao–Blackwellised).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GibbsSmoothed<const N: usize, const R: usize> {
    /// `E[xₖ | Z]` and `Cov[xₖ | Z]`.
    pub state: Gaussian<N>,
    /// `P(mₖ = j | Z)`.
    pub mode_probabilities: [f64; R],
}

/// The estimate of chains over the same problem, each weighted by its recorded sweeps:
/// per step the pooled mean `Σ w_c x̄_c / Σ w_c` and covariance `Σ w_c (P_c + (x̄_c − x̄)
/// (x̄_c − x̄)ᵀ) / Σ w_c` (the law of total covariance), and the pooled mode probabilities.
///
/// # Errors
/// [`GibbsError::LengthMismatch`] for no chains or chains of other lengths,
/// [`GibbsError::InvalidConfig`] if no sweep is recorded, [`GibbsError::Estimate`]
/// naming a step whose covariance is not positive definite.
pub fn pooled<const N: usize, const D: usize, const R: usize>(
    chains: &[GibbsChain<'_, N, D, R>],
) -> Result<Vec<GibbsSmoothed<N, R>>, GibbsError> {
    let Some(first) = chains.first() else {
        return Err(GibbsError::LengthMismatch {
            what: "chains",
            expected: 1,
            got: 0,
        });
    };
    let n1 = first.sequence().len();
    for c in chains {
        if c.sequence().len() != n1 {
            return Err(GibbsError::LengthMismatch {
                what: "chain length",
                expected: n1,
                got: c.sequence().len(),
            });
        }
    }
    let total: usize = chains.iter().map(GibbsChain::sweeps).sum();
    if total == 0 {
        return Err(GibbsError::InvalidConfig {
            what: "recorded sweeps",
            value: 0,
            domain: "≥ 1",
        });
    }
    let total = total as f64;
    let mut out = Vec::with_capacity(n1);
    for k in 0..n1 {
        let parts: Vec<_> = chains.iter().map(|c| c.averages(k)).collect();
        let mean: Vector<N> = parts.iter().map(|a| a.mean * a.weight).sum::<Vector<N>>() / total;
        let cov: Matrix<N, N> = parts
            .iter()
            .map(|a| {
                let d = a.mean - mean;
                (a.cov + d * d.transpose()) * a.weight
            })
            .sum::<Matrix<N, N>>()
            / total;
        let state = Gaussian::from_symmetrized(mean, &cov)
            .map_err(|source| GibbsError::Estimate { step: k, source })?;
        let mode_probabilities = core::array::from_fn(|j| {
            parts.iter().map(|a| a.modes[j] * a.weight).sum::<f64>() / total
        });
        out.push(GibbsSmoothed {
            state,
            mode_probabilities,
        });
    }
    Ok(out)
}

/// The Gibbs smoother in one call: one chain from `init` (or every mode 0 — the first
/// mode must then be allowed to follow itself), `config.burn_in` sweeps discarded, then
/// `config.sweeps` recorded in blocks of `config.block`; per step `0 … n` the smoothed
/// state and mode probabilities.
///
/// # Errors
/// A bad configuration or start sequence, or a sweep's numerical failure naming the step.
pub fn gibbs_smooth<const N: usize, const D: usize, const R: usize>(
    problem: &GibbsProblem<N, D, R>,
    config: &GibbsConfig,
    init: Option<&[usize]>,
) -> Result<Vec<GibbsSmoothed<N, R>>, GibbsError> {
    config.validate(R)?;
    let zeros;
    let init = if let Some(s) = init {
        s
    } else {
        zeros = vec![0; problem.times().len()];
        &zeros
    };
    let mut chain = GibbsChain::new(problem, init, config.seed, config.block)?;
    for _ in 0..config.burn_in {
        chain.sweep(config.block, false)?;
    }
    for _ in 0..config.sweeps {
        chain.sweep(config.block, true)?;
    }
    pooled(core::slice::from_ref(&chain))
}

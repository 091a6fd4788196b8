//! The backward pass of the IMM smoother (module docs, eqs (1)–(7)).

use argus_core_math::Gaussian;
use argus_filters::{SmoothError, rts_step};

use super::ImmSmoothError;
use super::likelihood::BackwardLikelihood;
use super::record::backward_pass;
use super::step::ImmStep;
use crate::MarkovMatrix;
use crate::markov::log_sum_exp;

/// How the backward pass weighs a mode pair `(mₖ = i, mₖ₊₁ = j)` (module docs, eq (1)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PairWeights {
    /// Kim (1994): `P(mₖ = i | mₖ₊₁ = j, Z₁:ₙ) ≈ πᵢⱼ μᵢₖ / μ̄ⱼₖ₊₁`, the future plots ignored.
    Kim,
    /// Barber (2006), expectation correction with the mean approximation: the pair weight
    /// also carries how well mode `i`'s prediction through model `j` explains mode `j`'s
    /// smoothed mean, `N(x̂ʲₖ₊₁|ₙ; x̂ⁱʲₖ₊₁|ₖ, Pⁱʲₖ₊₁|ₖ)`.
    ExpectationCorrection,
    /// The backward likelihood of mode `j` (the ratio of its smoothed estimate to the IMM's
    /// mode-`j` prediction, the `smooth::likelihood` module) weighs each pair by
    /// `∫ N(x; x̂ⁱʲₖ₊₁|ₖ, Pⁱʲₖ₊₁|ₖ) βⱼ(x) dx` and gives the pair's own smoothed estimate at
    /// `k + 1`, towards which the pair's RTS step goes (module docs, eqs (1b)–(5b)).
    #[default]
    BackwardLikelihood,
}

/// The smoothed IMM estimate of one step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImmSmoothed<const N: usize, const R: usize> {
    /// The smoothed mode-conditioned estimates `x̂ᵢₖ|ₙ, Pᵢₖ|ₙ` (eq 6).
    pub modes: [Gaussian<N>; R],
    /// The smoothed mode probabilities `μᵢₖ|ₙ` (eq 2).
    pub mode_probabilities: [f64; R],
    /// The smoothed mode probabilities as logarithms (kept below `f64`'s range).
    pub log_mode_probabilities: [f64; R],
    /// The combined smoothed estimate (eq 7).
    pub combined: Gaussian<N>,
}

/// The smoothed estimate at the last step: the filter's.
fn last<const N: usize, const R: usize>(
    step: &ImmStep<N, R>,
    index: usize,
) -> Result<ImmSmoothed<N, R>, ImmSmoothError> {
    let est = step.filtered();
    let combined = est.combined().map_err(|e| backward_error(index, None, e))?;
    Ok(ImmSmoothed {
        modes: *est.modes(),
        mode_probabilities: est.mode_probabilities(),
        log_mode_probabilities: est.log_mode_probabilities(),
        combined,
    })
}

fn backward_error(step: usize, mode: Option<usize>, e: crate::ImmError) -> ImmSmoothError {
    match e {
        crate::ImmError::Math(source) => ImmSmoothError::Backward { step, mode, source },
        source => ImmSmoothError::ForwardFailed { step, source },
    }
}

/// One backward step (module docs, eqs 1–7): from the smoothed estimate at `k + 1` and the forward
/// record of step `k` and of the transition into `k + 1`.
#[allow(clippy::similar_names)]
fn step_back<const N: usize, const R: usize>(
    pi: &MarkovMatrix<R>,
    weights: PairWeights,
    here: &ImmStep<N, R>,
    next: &ImmStep<N, R>,
    smoothed_next: &ImmSmoothed<N, R>,
    k: usize,
) -> Result<ImmSmoothed<N, R>, ImmSmoothError> {
    let tr = next
        .transition()
        .ok_or(SmoothError::MissingTransition { step: k + 1 })?;
    let log_pi = pi.log_matrix();
    let log_mu = here.filtered().log_mode_probabilities();
    let filtered = here.filtered().modes();
    let log_cbar = tr.log_predicted_probabilities();
    let backward = |source| ImmSmoothError::Backward {
        step: k,
        mode: None,
        source,
    };
    // The smoothed estimate at k + 1 each pair's RTS step goes towards: mode j's (Kim,
    // expectation correction) or the pair's own (backward likelihood).
    let mut targets = [smoothed_next.modes; R];
    // Eq (1): ln bᵢ|ⱼ = ln πᵢⱼ + ln μᵢₖ [+ ln N(x̂ʲₖ₊₁|ₙ; x̂ⁱʲₖ₊₁|ₖ, Pⁱʲₖ₊₁|ₖ)] − normaliser
    // (eq (1b): + ln ∫ N(x; x̂ⁱʲₖ₊₁|ₖ, Pⁱʲₖ₊₁|ₖ) βⱼ(x) dx);
    // eq (2′): ln P(i, j | Z₁:ₙ) = ln bᵢ|ⱼ + ln μʲₖ₊₁|ₙ.
    let mut joint = [[f64::NEG_INFINITY; R]; R];
    for j in 0..R {
        let ls = smoothed_next.log_mode_probabilities[j];
        if ls == f64::NEG_INFINITY || log_cbar[j] == f64::NEG_INFINITY {
            continue;
        }
        let mut col = [f64::NEG_INFINITY; R];
        for (i, c) in col.iter_mut().enumerate() {
            *c = log_pi[(i, j)] + log_mu[i];
        }
        match weights {
            PairWeights::Kim => {}
            PairWeights::ExpectationCorrection => {
                for (i, c) in col.iter_mut().enumerate() {
                    if *c > f64::NEG_INFINITY {
                        *c += tr.pairs()[i][j]
                            .predicted()
                            .log_pdf(smoothed_next.modes[j].mean());
                    }
                }
            }
            PairWeights::BackwardLikelihood => {
                // The IMM's mode-j prediction: the pairs' predictions mixed with the
                // forward mixing probabilities μᵢ|ⱼ = πᵢⱼ μᵢ / μ̄ⱼ (for linear models the
                // prediction of the mixed estimate, seed 000 eqs (1)–(3)).
                let mix = col.map(|c| (c - log_cbar[j]).exp());
                let preds: [Gaussian<N>; R] =
                    core::array::from_fn(|i| *tr.pairs()[i][j].predicted());
                let predicted = Gaussian::mixture(&mix, &preds).map_err(backward)?;
                let beta = BackwardLikelihood::new(&smoothed_next.modes[j], &predicted)
                    .map_err(backward)?;
                for (i, c) in col.iter_mut().enumerate() {
                    if *c > f64::NEG_INFINITY {
                        let (post, log_l) = beta.posterior(&preds[i]).map_err(|source| {
                            ImmSmoothError::Backward {
                                step: k,
                                mode: Some(i),
                                source,
                            }
                        })?;
                        targets[i][j] = post;
                        *c += log_l;
                    }
                }
            }
        }
        let norm = log_sum_exp(&col);
        if norm == f64::NEG_INFINITY {
            continue;
        }
        for (row, c) in joint.iter_mut().zip(&col) {
            row[j] = c - norm + ls;
        }
    }
    let mut modes = *filtered;
    let mut log_s = [f64::NEG_INFINITY; R];
    for (i, (out, ls)) in modes.iter_mut().zip(log_s.iter_mut()).enumerate() {
        // Eq (2): ln μᵢₖ|ₙ = ln Σⱼ P(i, j | Z₁:ₙ); eq (3): wⱼ|ᵢ = P(i, j | Z₁:ₙ) / μᵢₖ|ₙ.
        *ls = log_sum_exp(&joint[i]);
        if *ls == f64::NEG_INFINITY {
            // Mode i has smoothed probability 0: its estimate stays the filtered one.
            continue;
        }
        let w: [f64; R] = joint[i].map(|l| (l - *ls).exp());
        // Eqs (4)–(5): the RTS step of mode i's filtered estimate through each model j,
        // towards mode j's smoothed estimate; eq (6): their mixture.
        let mut parts = [filtered[i]; R];
        for (j, (part, wj)) in parts.iter_mut().zip(&w).enumerate() {
            if *wj > 0.0 {
                *part = rts_step(&filtered[i], &tr.pairs()[i][j], &targets[i][j]).map_err(
                    |source| ImmSmoothError::Backward {
                        step: k,
                        mode: Some(i),
                        source,
                    },
                )?;
            }
        }
        *out = Gaussian::mixture(&w, &parts).map_err(|source| ImmSmoothError::Backward {
            step: k,
            mode: Some(i),
            source,
        })?;
    }
    // Normalised (eq (2) sums to one in exact arithmetic).
    let total = log_sum_exp(&log_s);
    let log_s = log_s.map(|l| l - total);
    let mu = log_s.map(f64::exp);
    let combined = Gaussian::mixture(&mu, &modes).map_err(|source| ImmSmoothError::Backward {
        step: k,
        mode: None,
        source,
    })?;
    Ok(ImmSmoothed {
        modes,
        mode_probabilities: mu,
        log_mode_probabilities: log_s,
        combined,
    })
}

/// Fixed-interval IMM smoothing of a recorded forward pass (module docs, eqs (1)–(7)).
/// The sequence is checked whole before the backward pass starts.
///
/// # Errors
/// [`ImmSmoothError::Sequence`] for an empty sequence, time not increasing or a missing
/// transition (naming the step); [`ImmSmoothError::Backward`] for a numerical failure.
pub fn imm_smooth<const N: usize, const R: usize>(
    markov: &MarkovMatrix<R>,
    weights: PairWeights,
    steps: &[ImmStep<N, R>],
) -> Result<Vec<ImmSmoothed<N, R>>, ImmSmoothError> {
    backward_pass(steps, last, |step, next, later, k| {
        step_back(markov, weights, step, next, later, k)
    })
}

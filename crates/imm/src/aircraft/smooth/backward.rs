//! The backward pass of the aircraft-IMM smoother (module docs, eqs (1)–(7) with the
//! pair maps).

use argus_core_math::{Gaussian, MathError};
use argus_filters::SmoothError;

use super::pair::pair_rts;
use super::step::{AircraftStep, AircraftTransition};
use crate::aircraft::mixing::kinematic_marginal;
use crate::markov::log_sum_exp;
use crate::smooth::{BackwardLikelihood, backward_pass};
use crate::{ImmSmoothError, MarkovMatrix, PairWeights};

/// The smoothed aircraft-IMM estimate of one step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AircraftSmoothed<const C: usize, const R: usize> {
    /// The smoothed CV-mode estimates `x̂ⁱₖ|ₙ, Pⁱₖ|ₙ` on `[x, vx, y, vy]` (eq 6).
    pub cv: [Gaussian<4>; C],
    /// The smoothed CT-mode estimate on `[x, vx, y, vy, ω]` (eq 6).
    pub ct: Gaussian<5>,
    /// The smoothed mode probabilities `μⁱₖ|ₙ` (CV modes, then CT; eq 2).
    pub mode_probabilities: [f64; R],
    /// The same as logarithms.
    pub log_mode_probabilities: [f64; R],
    /// The combined smoothed estimate on `[x, vx, y, vy]` (eq 7, the CT mode by its
    /// kinematic marginal).
    pub combined: Gaussian<4>,
}

impl<const C: usize, const R: usize> AircraftSmoothed<C, R> {
    /// The CT mode's smoothed turn rate and its standard deviation, rad/s (conditional
    /// on the CT mode).
    #[must_use]
    pub fn turn_rate(&self) -> (f64, f64) {
        (self.ct.mean()[4], self.ct.cov()[(4, 4)].sqrt())
    }
}

fn backward(step: usize, mode: Option<usize>) -> impl Fn(MathError) -> ImmSmoothError {
    move |source| ImmSmoothError::Backward { step, mode, source }
}

/// The combined estimate on `[x, vx, y, vy]`: the CV modes and the CT marginal mixed.
fn combine<const C: usize, const R: usize>(
    cv: &[Gaussian<4>; C],
    ct: &Gaussian<5>,
    mu: &[f64; R],
) -> Result<Gaussian<4>, MathError> {
    let ct4 = kinematic_marginal(ct)?;
    let parts: [Gaussian<4>; R] = core::array::from_fn(|j| if j < C { cv[j] } else { ct4 });
    Gaussian::mixture(mu, &parts)
}

/// The smoothed estimate at the last step: the filter's.
fn last<const C: usize, const R: usize>(
    step: &AircraftStep<C, R>,
    index: usize,
) -> Result<AircraftSmoothed<C, R>, ImmSmoothError> {
    let est = step.filtered();
    let mu = est.mode_probabilities();
    let combined = combine(est.cv_modes(), est.ct_mode(), &mu).map_err(backward(index, None))?;
    Ok(AircraftSmoothed {
        cv: *est.cv_modes(),
        ct: *est.ct_mode(),
        mode_probabilities: mu,
        log_mode_probabilities: *est.log_mode_probabilities(),
        combined,
    })
}

/// One column `j` of the pair weights (module docs, eqs (1), (1b)), in mode `j`'s state
/// of size `NJ`: from `ln πᵢⱼ + ln μⁱₖ` (`col`), the pairs' predictions `preds[i]` and
/// mode `j`'s smoothed estimate at `k + 1`, the unnormalised `ln bᵢ|ⱼ` and each pair's
/// target at `k + 1` (mode `j`'s smoothed estimate, or with the backward likelihood the
/// pair's own posterior).
fn column<const NJ: usize, const R: usize>(
    weights: PairWeights,
    mut col: [f64; R],
    log_cbar: f64,
    preds: &[Gaussian<NJ>; R],
    smoothed: &Gaussian<NJ>,
    k: usize,
) -> Result<([f64; R], [Gaussian<NJ>; R]), ImmSmoothError> {
    let mut targets = [*smoothed; R];
    match weights {
        PairWeights::Kim => {}
        PairWeights::ExpectationCorrection => {
            for (c, p) in col.iter_mut().zip(preds) {
                if *c > f64::NEG_INFINITY {
                    *c += p.log_pdf(smoothed.mean());
                }
            }
        }
        PairWeights::BackwardLikelihood => {
            // The IMM's mode-j prediction: the pairs' predictions mixed with μᵢ|ⱼ.
            let mix = col.map(|c| (c - log_cbar).exp());
            let predicted = Gaussian::mixture(&mix, preds).map_err(backward(k, None))?;
            let beta = BackwardLikelihood::new(smoothed, &predicted).map_err(backward(k, None))?;
            for (i, (c, t)) in col.iter_mut().zip(targets.iter_mut()).enumerate() {
                if *c > f64::NEG_INFINITY {
                    let (post, log_l) = beta.posterior(&preds[i]).map_err(backward(k, Some(i)))?;
                    *t = post;
                    *c += log_l;
                }
            }
        }
    }
    Ok((col, targets))
}

/// One backward step (module docs): from the smoothed estimate at `k + 1` and the
/// forward record of step `k` and of the transition into `k + 1`.
#[allow(clippy::similar_names, clippy::too_many_lines)]
fn step_back<const C: usize, const R: usize>(
    pi: &MarkovMatrix<R>,
    weights: PairWeights,
    here: &AircraftStep<C, R>,
    next: &AircraftStep<C, R>,
    smoothed_next: &AircraftSmoothed<C, R>,
    k: usize,
) -> Result<AircraftSmoothed<C, R>, ImmSmoothError> {
    let tr: &AircraftTransition<C, R> = next
        .transition()
        .ok_or(SmoothError::MissingTransition { step: k + 1 })?;
    let log_pi = pi.log_matrix();
    let filtered = here.filtered();
    let log_mu = filtered.log_mode_probabilities();
    let log_cbar = &tr.log_cbar;
    // Eq (1) per column j, in mode j's state.
    let mut joint = [[f64::NEG_INFINITY; R]; R];
    let mut cv_targets: [[Gaussian<4>; R]; C] = core::array::from_fn(|j| [smoothed_next.cv[j]; R]);
    let mut ct_targets = [smoothed_next.ct; R];
    for j in 0..R {
        let ls = smoothed_next.log_mode_probabilities[j];
        if ls == f64::NEG_INFINITY || log_cbar[j] == f64::NEG_INFINITY {
            continue;
        }
        let col: [f64; R] = core::array::from_fn(|i| log_pi[(i, j)] + log_mu[i]);
        let col = if j < C {
            let preds: [Gaussian<4>; R] = core::array::from_fn(|i| {
                if i < C {
                    *tr.cv_cv[i][j].predicted()
                } else {
                    *tr.ct_cv[j].predicted()
                }
            });
            let (col, t) = column(weights, col, log_cbar[j], &preds, &smoothed_next.cv[j], k)?;
            cv_targets[j] = t;
            col
        } else {
            let preds: [Gaussian<5>; R] = core::array::from_fn(|i| {
                if i < C {
                    *tr.cv_ct[i].predicted()
                } else {
                    *tr.ct_ct.predicted()
                }
            });
            let (col, t) = column(weights, col, log_cbar[j], &preds, &smoothed_next.ct, k)?;
            ct_targets = t;
            col
        };
        let norm = log_sum_exp(&col);
        if norm == f64::NEG_INFINITY {
            continue;
        }
        for (row, c) in joint.iter_mut().zip(&col) {
            row[j] = c - norm + ls;
        }
    }
    let mut cv = *filtered.cv_modes();
    let mut ct = *filtered.ct_mode();
    let mut log_s = [f64::NEG_INFINITY; R];
    for i in 0..R {
        // Eq (2): ln μⁱₖ|ₙ = ln Σⱼ P(i, j | Z₁:ₙ); eq (3): wⱼ|ᵢ = P(i, j | Z₁:ₙ) / μⁱₖ|ₙ.
        let ls = log_sum_exp(&joint[i]);
        log_s[i] = ls;
        if ls == f64::NEG_INFINITY {
            // Smoothed probability 0: the filtered estimate is kept.
            continue;
        }
        let w: [f64; R] = joint[i].map(|l| (l - ls).exp());
        let err = backward(k, Some(i));
        if i < C {
            let f = &filtered.cv_modes()[i];
            let mut parts = [*f; R];
            for (j, (part, wj)) in parts.iter_mut().zip(&w).enumerate() {
                if *wj > 0.0 {
                    *part = if j < C {
                        pair_rts(f, &tr.cv_cv[i][j], &cv_targets[j][i])
                    } else {
                        pair_rts(f, &tr.cv_ct[i], &ct_targets[i])
                    }
                    .map_err(&err)?;
                }
            }
            cv[i] = Gaussian::mixture(&w, &parts).map_err(&err)?;
        } else {
            let f = filtered.ct_mode();
            let mut parts = [*f; R];
            for (j, (part, wj)) in parts.iter_mut().zip(&w).enumerate() {
                if *wj > 0.0 {
                    *part = if j < C {
                        pair_rts(f, &tr.ct_cv[j], &cv_targets[j][C])
                    } else {
                        pair_rts(f, &tr.ct_ct, &ct_targets[C])
                    }
                    .map_err(&err)?;
                }
            }
            ct = Gaussian::mixture(&w, &parts).map_err(&err)?;
        }
    }
    // Normalised (eq (2) sums to one in exact arithmetic).
    let total = log_sum_exp(&log_s);
    let log_s = log_s.map(|l| l - total);
    let mu = log_s.map(f64::exp);
    let combined = combine(&cv, &ct, &mu).map_err(backward(k, None))?;
    Ok(AircraftSmoothed {
        cv,
        ct,
        mode_probabilities: mu,
        log_mode_probabilities: log_s,
        combined,
    })
}

/// Fixed-interval smoothing of a recorded aircraft-IMM forward pass (module docs). The
/// sequence is checked whole before the backward pass starts; a slice of a record (steps
/// `j … k`) is the fixed-interval smoother of `Z₁:ₖ` at those steps (fixed lag).
///
/// # Errors
/// [`ImmSmoothError::Sequence`] for an empty sequence, time not increasing or a missing
/// transition (naming the step); [`ImmSmoothError::Backward`] for a numerical failure
/// (naming the step and mode).
pub fn aircraft_smooth<const C: usize, const R: usize>(
    markov: &MarkovMatrix<R>,
    weights: PairWeights,
    steps: &[AircraftStep<C, R>],
) -> Result<Vec<AircraftSmoothed<C, R>>, ImmSmoothError> {
    backward_pass(steps, last, |step, next, later, k| {
        step_back(markov, weights, step, next, later, k)
    })
}

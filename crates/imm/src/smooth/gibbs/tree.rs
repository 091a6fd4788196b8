//! The exhaustive search over one block's mode paths: a tree of Kalman steps from the
//! filtered state before the block, each leaf weighed by its prior between the block's
//! neighbours, its plots' likelihoods and its last posterior's integral against the
//! backward information. The last plot's likelihood and that integral are one integral,
//! `N(z; H x̂, S) ∫ N(x; x̂⁺, P⁺) β(x) dx =
//! c(z) ∫ N(x; x̂⁻, P⁻) exp(−½ xᵀ (Ω + Hᵀ R⁻¹ H) x + (η + Hᵀ R⁻¹ z)ᵀ x) dx` with `c(z) = N(z; 0, R)` the same for every leaf (it cancels
//! in the normalisation): the leaves take a prediction and that integral, no update.
//! `R + R² + … + R^(L−1)` Kalman updates and `R^L` predictions for a block of `L`; paths of
//! zero prior are cut where they start. The buffers are the chain's, grown once.

use super::error::GibbsError;
use super::kalman::{self, Info, Moments};
use super::problem::GibbsProblem;

/// The search's buffers and its result: leaf `i` is the path
/// `paths[i·len … (i + 1)·len]` with log weight `weights[i]`.
#[derive(Debug, Clone)]
pub(super) struct Tree<const N: usize> {
    len: usize,
    path: Vec<usize>,
    stack: Vec<Moments<N>>,
    pub(super) weights: Vec<f64>,
    pub(super) paths: Vec<usize>,
}

impl<const N: usize> Tree<N> {
    /// Buffers for blocks of up to `block` modes out of `modes` (`modes^block` leaves).
    pub(super) fn new(block: usize, modes: usize, start: Moments<N>) -> Self {
        let mut t = Self {
            len: 0,
            path: Vec::new(),
            stack: Vec::new(),
            weights: Vec::new(),
            paths: Vec::new(),
        };
        t.reserve(block, modes, start);
        t
    }

    /// Grows the buffers for blocks of `block` (a no-op once they are large enough).
    pub(super) fn reserve(&mut self, block: usize, modes: usize, start: Moments<N>) {
        let leaves = modes.saturating_pow(u32::try_from(block).unwrap_or(u32::MAX));
        if self.path.len() < block {
            self.path.resize(block, 0);
            self.stack.resize(block, start);
        }
        self.weights
            .reserve(leaves.saturating_sub(self.weights.len()));
        self.paths
            .reserve((leaves * block).saturating_sub(self.paths.len()));
    }

    /// The block length of the last search.
    pub(super) fn len(&self) -> usize {
        self.len
    }

    /// Every path of nonzero prior of the block `k … k + len − 1` (`k ≥ 1`) along `seq`
    /// (its neighbours `seq[k − 1]`, `seq[k + len]`), from `prev` (the filtered state at
    /// `k − 1`), the last posterior integrated against `beta` (`β` at `k + len − 1`).
    ///
    /// # Errors
    /// [`GibbsError::NotPositiveDefinite`] (an innovation covariance) or
    /// [`GibbsError::StepFailed`] (a singular integral) naming the step.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn search<const D: usize, const R: usize>(
        &mut self,
        p: &GibbsProblem<N, D, R>,
        seq: &[usize],
        k: usize,
        len: usize,
        prev: &Moments<N>,
        beta: &Info<N>,
    ) -> Result<(), GibbsError> {
        self.reserve(len, R, *prev);
        self.len = len;
        self.weights.clear();
        self.paths.clear();
        self.stack[0] = *prev;
        let last = &p.steps[k + len - 2];
        let with_plot = Info {
            omega: beta.omega + last.info,
            eta: beta.eta + last.info_z,
        };
        self.grow(p, seq, k, 0, 0.0, &with_plot)
    }

    /// `beta`: the backward information at the block's last step with its plot.
    fn grow<const D: usize, const R: usize>(
        &mut self,
        p: &GibbsProblem<N, D, R>,
        seq: &[usize],
        k: usize,
        depth: usize,
        lw: f64,
        beta: &Info<N>,
    ) -> Result<(), GibbsError> {
        let site = k + depth;
        let before = if depth == 0 {
            seq[k - 1]
        } else {
            self.path[depth - 1]
        };
        let last = depth + 1 == self.len;
        let sm = &p.steps[site - 1];
        let g = self.stack[depth];
        for j in 0..R {
            let mut w = lw + p.log_pi[before][j];
            if last && site < p.plots() {
                w += p.log_pi[j][seq[site + 1]];
            }
            if w == f64::NEG_INFINITY {
                continue;
            }
            let pred = kalman::predict(&g, sm, j);
            self.path[depth] = j;
            if last {
                let li = kalman::log_integral(&pred, beta).ok_or(GibbsError::StepFailed {
                    step: site,
                    what: "the integral against the backward information (a covariance not positive definite)",
                })?;
                self.weights.push(w + li);
                self.paths.extend_from_slice(&self.path[..self.len]);
            } else {
                let (post, ll) =
                    kalman::update(&pred, sm).ok_or(GibbsError::NotPositiveDefinite {
                        step: site,
                        what: "innovation covariance",
                    })?;
                w += ll;
                self.stack[depth + 1] = post;
                self.grow(p, seq, k, depth + 1, w, beta)?;
            }
        }
        Ok(())
    }
}

//! The sampler's conditionals computed from scratch for one mode sequence: what a sweep
//! draws from, exposed so that it can be checked against an exact enumeration.

use super::error::GibbsError;
use super::kalman::{self, Info, Moments};
use super::problem::GibbsProblem;
use super::tree::Tree;

impl<const N: usize, const D: usize, const R: usize> GibbsProblem<N, D, R> {
    /// `p(mₖ … mₖ₊ₗₑₙ₋₁ = path | the other modes of seq, Z)` for every path of nonzero
    /// prior (`1 ≤ k`, `k + len − 1 ≤ n`), from the forward filter along `seq` to `k − 1`
    /// and the backward information along `seq` after the block. Allocates (a check, not
    /// the sweep).
    ///
    /// # Errors
    /// A bad `seq` or block ([`GibbsError::LengthMismatch`], [`GibbsError::InvalidSequence`],
    /// [`GibbsError::InvalidConfig`]); a numerical failure naming the step.
    pub fn block_conditional(
        &self,
        seq: &[usize],
        k: usize,
        len: usize,
    ) -> Result<Vec<(Vec<usize>, f64)>, GibbsError> {
        self.check_sequence(seq)?;
        if k == 0 || len == 0 || k + len - 1 > self.plots() {
            return Err(GibbsError::InvalidConfig {
                what: "block start k (1 ≤ k, k + len − 1 ≤ n)",
                value: k,
                domain: "the plots",
            });
        }
        super::config::check_block(len, R)?;
        let n = self.plots();
        let mut beta = Info::flat();
        for i in (k + len - 1..n).rev() {
            beta = kalman::backward(&beta, &self.steps[i], seq[i + 1]).ok_or(
                GibbsError::StepFailed {
                    step: i + 1,
                    what: "backward information step (I + QΩ singular)",
                },
            )?;
        }
        let mut g: Moments<N> = self.start;
        for (i, &m) in seq.iter().enumerate().take(k).skip(1) {
            let sm = &self.steps[i - 1];
            g = kalman::update(&kalman::predict(&g, sm, m), sm)
                .ok_or(GibbsError::NotPositiveDefinite {
                    step: i,
                    what: "innovation covariance",
                })?
                .0;
        }
        let mut tree = Tree::new(len, R, g);
        tree.search(self, seq, k, len, &g, &beta)?;
        let max = tree
            .weights
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
        let total: f64 = tree.weights.iter().map(|l| (l - max).exp()).sum();
        Ok(tree
            .weights
            .iter()
            .enumerate()
            .map(|(i, l)| {
                (
                    tree.paths[i * len..(i + 1) * len].to_vec(),
                    (l - max).exp() / total,
                )
            })
            .collect())
    }

    /// `p(mₖ = · | m₋ₖ, Z)` along `seq`, from scratch (`k = 0`: the prior against `m₁`).
    ///
    /// # Errors
    /// As [`Self::block_conditional`].
    pub fn conditional(&self, seq: &[usize], k: usize) -> Result<[f64; R], GibbsError> {
        if k == 0 {
            self.check_sequence(seq)?;
            let l: [f64; R] = core::array::from_fn(|i| {
                self.log_mu0[i]
                    + if self.plots() > 0 {
                        self.log_pi[i][seq[1]]
                    } else {
                        0.0
                    }
            });
            let max = l.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let w = l.map(|x| (x - max).exp());
            let s: f64 = w.iter().sum();
            return Ok(w.map(|x| x / s));
        }
        let mut p = [0.0; R];
        for (path, pr) in self.block_conditional(seq, k, 1)? {
            p[path[0]] += pr;
        }
        Ok(p)
    }
}

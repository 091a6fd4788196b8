//! One Gibbs chain over the mode sequence: its buffers (allocated when the chain is made,
//! reused by every sweep), the sweep, and its running averages.

use argus_core_math::{Matrix, Vector};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::config::check_block;
use super::error::GibbsError;
use super::kalman::{self, Info, Moments};
use super::problem::GibbsProblem;
use super::tree::Tree;

/// Probabilities from log weights (`exp(l − max l)`, normalised).
fn normalise<const R: usize>(l: [f64; R]) -> [f64; R] {
    let max = l.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let w = l.map(|x| (x - max).exp());
    let s: f64 = w.iter().sum();
    w.map(|x| x / s)
}

/// The index `i` with `Σ_{<i} w < u ≤ Σ_{≤i} w` for `u` uniform on `[0, Σ w)`; the last
/// positive weight if round-off leaves `u` beyond the sum.
fn pick(w: &[f64], u: f64) -> usize {
    let mut c = 0.0;
    for (i, wi) in w.iter().enumerate() {
        c += wi;
        if u < c {
            return i;
        }
    }
    w.iter().rposition(|&x| x > 0.0).unwrap_or(0)
}

/// A Gibbs chain over the mode sequence of a [`GibbsProblem`], with its running averages
/// of the RTS-smoothed moments and of the mode conditionals.
#[derive(Debug, Clone)]
pub struct GibbsChain<'a, const N: usize, const D: usize, const R: usize> {
    problem: &'a GibbsProblem<N, D, R>,
    seq: Vec<usize>,
    rng: ChaCha8Rng,
    calls: usize,
    sweeps: usize,
    tree: Tree<N>,
    beta: Vec<Info<N>>,
    filt: Vec<Moments<N>>,
    /// `pred[k]`: the prediction into step `k` (`pred[0]` unused).
    pred: Vec<Moments<N>>,
    smooth: Vec<Moments<N>>,
    probs: Vec<[f64; R]>,
    /// Per step the first recorded sweep's smoothed mean: the sums are of deviations from
    /// it, so that `E[x xᵀ] − x̄ x̄ᵀ` does not cancel kilometre-sized positions.
    shift: Vec<Vector<N>>,
    sum_d: Vec<Vector<N>>,
    sum_dd: Vec<Matrix<N, N>>,
    sum_mode: Vec<[f64; R]>,
}

/// One step's averaged moments and mode probabilities, before validation.
pub(super) struct Averages<const N: usize, const R: usize> {
    pub(super) weight: f64,
    pub(super) mean: Vector<N>,
    pub(super) cov: Matrix<N, N>,
    pub(super) modes: [f64; R],
}

impl<'a, const N: usize, const D: usize, const R: usize> GibbsChain<'a, N, D, R> {
    /// A chain from the mode sequence `init` (`m₀ … mₙ`, of nonzero prior), drawing from
    /// `seed`, with buffers for blocks of up to `block` modes.
    ///
    /// # Errors
    /// [`GibbsError::LengthMismatch`] / [`GibbsError::InvalidSequence`] for a bad `init`,
    /// [`GibbsError::InvalidConfig`] for a bad `block`.
    pub fn new(
        problem: &'a GibbsProblem<N, D, R>,
        init: &[usize],
        seed: u64,
        block: usize,
    ) -> Result<Self, GibbsError> {
        problem.check_sequence(init)?;
        check_block(block, R)?;
        let n1 = init.len();
        let s = problem.start;
        Ok(Self {
            problem,
            seq: init.to_vec(),
            rng: ChaCha8Rng::seed_from_u64(seed),
            calls: 0,
            sweeps: 0,
            tree: Tree::new(block, R, s),
            beta: vec![Info::flat(); n1],
            filt: vec![s; n1],
            pred: vec![s; n1],
            smooth: vec![s; n1],
            probs: vec![[0.0; R]; n1],
            shift: vec![Vector::zeros(); n1],
            sum_d: vec![Vector::zeros(); n1],
            sum_dd: vec![Matrix::zeros(); n1],
            sum_mode: vec![[0.0; R]; n1],
        })
    }

    /// One sweep in blocks of `block` consecutive modes drawn jointly (the first block's
    /// length cycles through `1 … block` from sweep to sweep, so block boundaries move);
    /// `record` adds the sequence drawn (RTS-smoothed) and the block conditionals to the
    /// averages. Allocates nothing once the buffers hold blocks of this length.
    ///
    /// # Errors
    /// [`GibbsError::InvalidConfig`] for a bad `block`; a numerical failure naming the
    /// step ([`GibbsError::StepFailed`], [`GibbsError::NotPositiveDefinite`]). The chain's
    /// averages are unchanged by a failed sweep only if it failed before recording.
    pub fn sweep(&mut self, block: usize, record: bool) -> Result<(), GibbsError> {
        check_block(block, R)?;
        let p = self.problem;
        let n = p.plots();
        self.backward()?;
        let c0 = normalise(core::array::from_fn(|i| {
            p.log_mu0[i] + if n > 0 { p.log_pi[i][self.seq[1]] } else { 0.0 }
        }));
        let u: f64 = self.rng.random();
        self.seq[0] = pick(&c0, u);
        self.probs[0] = c0;
        self.filt[0] = p.start;
        let mut k = 1;
        let mut len = 1 + self.calls % block;
        self.calls += 1;
        while k <= n {
            let l = len.min(n - k + 1);
            len = block;
            self.block(k, l)?;
            k += l;
        }
        if record {
            self.record()?;
        }
        Ok(())
    }

    /// `β₀ … βₙ` along the current sequence (`βₙ = 1`).
    fn backward(&mut self) -> Result<(), GibbsError> {
        let p = self.problem;
        let n = p.plots();
        self.beta[n] = Info::flat();
        for k in (0..n).rev() {
            self.beta[k] = kalman::backward(&self.beta[k + 1], &p.steps[k], self.seq[k + 1])
                .ok_or(GibbsError::StepFailed {
                    step: k + 1,
                    what: "backward information step (I + QΩ singular)",
                })?;
        }
        Ok(())
    }

    /// Draws the block `k … k + l − 1` and runs the forward filter through it.
    fn block(&mut self, k: usize, l: usize) -> Result<(), GibbsError> {
        let p = self.problem;
        let prev = self.filt[k - 1];
        self.tree
            .search(p, &self.seq, k, l, &prev, &self.beta[k + l - 1])?;
        let len = self.tree.len();
        let w = &mut self.tree.weights;
        let max = w.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        w.iter_mut().for_each(|x| *x = (*x - max).exp());
        let total: f64 = w.iter().sum();
        if !(total.is_finite() && total > 0.0) {
            return Err(GibbsError::StepFailed {
                step: k,
                what: "no block path of positive finite weight",
            });
        }
        for m in &mut self.probs[k..k + l] {
            *m = [0.0; R];
        }
        for (i, wi) in w.iter().enumerate() {
            for (d, m) in self.probs[k..k + l].iter_mut().enumerate() {
                m[self.tree.paths[i * len + d]] += wi / total;
            }
        }
        let u: f64 = self.rng.random::<f64>() * total;
        let chosen = pick(w, u);
        for d in 0..l {
            let site = k + d;
            let j = self.tree.paths[chosen * len + d];
            self.seq[site] = j;
            let sm = &p.steps[site - 1];
            self.pred[site] = kalman::predict(&self.filt[site - 1], sm, j);
            self.filt[site] = kalman::update(&self.pred[site], sm)
                .ok_or(GibbsError::NotPositiveDefinite {
                    step: site,
                    what: "innovation covariance",
                })?
                .0;
        }
        Ok(())
    }

    /// RTS-smooths the current sequence and adds it to the averages.
    fn record(&mut self) -> Result<(), GibbsError> {
        let p = self.problem;
        let n = p.plots();
        self.smooth[n] = self.filt[n];
        for k in (0..n).rev() {
            self.smooth[k] = kalman::rts(
                &self.filt[k],
                &p.steps[k].f[self.seq[k + 1]],
                &self.pred[k + 1],
                &self.smooth[k + 1],
            )
            .ok_or(GibbsError::NotPositiveDefinite {
                step: k + 1,
                what: "predicted covariance",
            })?;
        }
        let first = self.sweeps == 0;
        for k in 0..=n {
            let s = &self.smooth[k];
            if first {
                self.shift[k] = s.x;
            }
            let d = s.x - self.shift[k];
            self.sum_d[k] += d;
            self.sum_dd[k] += s.p + d * d.transpose();
            for (a, b) in self.sum_mode[k].iter_mut().zip(&self.probs[k]) {
                *a += b;
            }
        }
        self.sweeps += 1;
        Ok(())
    }

    /// The current mode sequence.
    #[must_use]
    pub fn sequence(&self) -> &[usize] {
        &self.seq
    }

    /// The number of recorded sweeps.
    #[must_use]
    pub fn sweeps(&self) -> usize {
        self.sweeps
    }

    /// The problem the chain samples.
    #[must_use]
    pub fn problem(&self) -> &'a GibbsProblem<N, D, R> {
        self.problem
    }

    /// Step `k`'s averages over the recorded sweeps (unvalidated; `k ≤ n`).
    pub(super) fn averages(&self, k: usize) -> Averages<N, R> {
        let s = self.sweeps.max(1) as f64;
        let md = self.sum_d[k] / s;
        Averages {
            weight: self.sweeps as f64,
            mean: self.shift[k] + md,
            cov: self.sum_dd[k] / s - md * md.transpose(),
            modes: self.sum_mode[k].map(|x| x / s),
        }
    }
}

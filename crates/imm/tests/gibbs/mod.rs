//! A reference smoother for the jump-Markov linear system behind an IMM: the same models,
//! Markov matrix, process noise, per-step measurement models and prior, smoothed by Gibbs
//! sampling of the mode sequence with the Gaussian part integrated out (Carter & Kohn
//! 1996; Doucet & Andrieu 2001, "Iterative algorithms for state estimation of jump Markov
//! linear systems", IEEE Trans. Signal Processing 49(6), 1216–1227: the single-site sampler
//! whose conditional uses a backward information filter, `O(n R)` per sweep).
//!
//! Model (as in the exact enumeration of `smoothing_exact.rs`): `m₀ ~ μ₀`, `mₖ | mₖ₋₁ ~ π`,
//! `xₖ = F_{mₖ}(Δₖ) xₖ₋₁ + w`, `w ~ N(0, Q_{mₖ}(Δₖ))`, `x₀ ~ g₀`, `zₖ = H xₖ + v`,
//! `v ~ N(0, Rₖ)` for `k = 1 … n`. The full conditional of `mₖ` given every other mode is
//!
//! ```text
//! p(mₖ = j | m₋ₖ, Z) ∝ π(mₖ₋₁, j) π(j, mₖ₊₁) N(zₖ; ẑʲₖ, Sʲₖ) ∫ N(x; x̂ʲₖ|ₖ, Pʲₖ|ₖ) βₖ(x) dx
//! ```
//!
//! with `x̂ʲₖ|ₖ, Pʲₖ|ₖ` the Kalman update of the filter along `m₀ … mₖ₋₁` predicted with
//! model `j`, and `βₖ(x) = p(zₖ₊₁:ₙ | xₖ = x, mₖ₊₁:ₙ) ∝ exp(−½ xᵀ Ω x + ηᵀ x)` the backward
//! information filter along `mₖ₊₁ … mₙ` (its constant does not depend on `mₖ`):
//!
//! ```text
//! Ω' = Ωₖ₊₁ + Hᵀ R⁻¹ H,  η' = ηₖ₊₁ + Hᵀ R⁻¹ zₖ₊₁          (plot k + 1)
//! Ωₖ = Fᵀ Ω' (I + Q Ω')⁻¹ F,  ηₖ = Fᵀ (I + Ω' Q)⁻¹ η'      (F, Q of mₖ₊₁; no Q⁻¹ needed)
//! ∫ N(x; μ, P) exp(−½ xᵀ Ω x + ηᵀ x) dx = |I + P Ω|^(−½) exp(−½ μᵀ Ω μ + ηᵀ μ + ½ bᵀ (I + P Ω)⁻¹ P b),
//! b = η − Ω μ
//! ```
//!
//! (derived here by completing the square; the Woodbury identity turns `(Ω'⁻¹ + Q)⁻¹`
//! into `Ω' (I + Q Ω')⁻¹`). A sweep recomputes `β` along the current sequence, draws `m₀`,
//! then `m₁ … mₙ` forwards (the forward filter follows the new draws), and RTS-smooths the
//! sequence drawn. The estimate is the average over sweeps of each sequence's smoothed
//! moments (`E[x]`, `E[P + x xᵀ]`), and of the site conditionals for the mode
//! probabilities (a Rao–Blackwellised estimate). As the sweeps grow it tends to the exact
//! posterior mean of the jump-Markov model, which no IMM smoother (one Gaussian per mode
//! and step) can beat in mean squared error on the model's own data.

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{GaussianFilter, Kf, RtsStep, SmoothingFilter, rts_smooth};
use argus_motion_models::{LinearMotionModel, MotionModel, PlanarModel};
use argus_sensors::{CartesianPosition, LinearMeasurementModel};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A Cartesian position measurement model (the short-track checks).
pub(crate) type Pos = CartesianPosition<4, 2>;

/// The jump-Markov problem: `filters[j]` is mode `j`'s Kalman filter (model and `Q`),
/// `pi` the Markov matrix, `mu0` the prior of `m₀`, `g0` the state at `times[0]`, and
/// `plots[k]` the measurement model and plot at `times[k]` (`plots[0]` unused).
pub(crate) struct Problem<'a, const R: usize, Me> {
    pub(crate) filters: &'a [Kf<PlanarModel>; R],
    pub(crate) pi: [[f64; R]; R],
    pub(crate) mu0: [f64; R],
    pub(crate) g0: Gaussian<4>,
    pub(crate) times: &'a [f64],
    pub(crate) plots: &'a [(Me, Vector<2>)],
}

/// The backward information `βₖ(x) ∝ exp(−½ xᵀ Ω x + ηᵀ x)`.
#[derive(Clone, Copy)]
struct Info {
    omega: Matrix<4, 4>,
    eta: Vector<4>,
}

/// `ln ∫ N(x; g) exp(−½ xᵀ Ω x + ηᵀ x) dx`.
fn log_integral(g: &Gaussian<4>, b: &Info) -> f64 {
    let (mu, p) = (g.mean(), g.cov());
    let a = Matrix::<4, 4>::identity() + p * b.omega;
    let lu = a.lu();
    let det = lu.determinant();
    let r = b.eta - b.omega * mu;
    let y = lu
        .solve(&(p * r))
        .expect("I + PΩ is invertible (PΩ has eigenvalues ≥ 0)");
    -0.5 * det.ln() - 0.5 * mu.dot(&(b.omega * mu)) + b.eta.dot(mu) + 0.5 * r.dot(&y)
}

fn ln(x: f64) -> f64 {
    if x > 0.0 { x.ln() } else { f64::NEG_INFINITY }
}

/// Normalises log weights into probabilities.
fn normalise<const R: usize>(l: [f64; R]) -> [f64; R] {
    let max = l.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let w = l.map(|x| (x - max).exp());
    let s: f64 = w.iter().sum();
    w.map(|x| x / s)
}

impl<const R: usize, Me: LinearMeasurementModel<4, 2>> Problem<'_, R, Me> {
    fn n(&self) -> usize {
        self.times.len() - 1
    }

    /// `β₀ … βₙ` along `seq` (`βₙ = 1`).
    fn backward(&self, seq: &[usize]) -> Vec<Info> {
        let n = self.n();
        let mut out = vec![
            Info {
                omega: Matrix::<4, 4>::zeros(),
                eta: Vector::<4>::zeros(),
            };
            n + 1
        ];
        for k in (0..n).rev() {
            let (meas, z) = &self.plots[k + 1];
            let h = meas.matrix();
            let rinv = meas
                .noise(&Vector::<4>::zeros())
                .try_inverse()
                .expect("R is invertible");
            let om = out[k + 1].omega + h.transpose() * rinv * h;
            let et = out[k + 1].eta + h.transpose() * rinv * z;
            let dt = self.times[k + 1] - self.times[k];
            let model = self.filters[seq[k + 1]].model();
            let f = model.transition(dt);
            let q = model.process_noise(&Vector::<4>::zeros(), dt);
            let a = (Matrix::<4, 4>::identity() + q * om)
                .try_inverse()
                .expect("I + QΩ is invertible");
            let omega = f.transpose() * om * a * f;
            out[k] = Info {
                omega: 0.5 * (omega + omega.transpose()),
                eta: f.transpose() * a.transpose() * et,
            };
        }
        out
    }

    /// Every mode path `b₀ … b_{len−1}` of the block `k … k + len − 1` (`k ≥ 1`) with
    /// nonzero prior, and its log weight `ln p(m_block = b | m_rest, Z)` up to a constant:
    /// the prior of the path between its neighbours `seq[k − 1]` and `seq[k + len]`, the
    /// plots' likelihoods along it from `prev` (the filtered state at `k − 1`), and the
    /// last posterior's integral against `beta` (`β` at `k + len − 1`). A tree search:
    /// `R + R² + … + R^len` Kalman steps.
    fn block_paths(
        &self,
        seq: &[usize],
        k: usize,
        len: usize,
        prev: &Gaussian<4>,
        beta: &Info,
    ) -> Vec<(Vec<usize>, f64)> {
        let mut out = Vec::new();
        let mut path = Vec::with_capacity(len);
        self.grow(seq, k, len, prev, 0.0, beta, &mut path, &mut out);
        out
    }

    #[allow(clippy::too_many_arguments)]
    fn grow(
        &self,
        seq: &[usize],
        k: usize,
        len: usize,
        g: &Gaussian<4>,
        lw: f64,
        beta: &Info,
        path: &mut Vec<usize>,
        out: &mut Vec<(Vec<usize>, f64)>,
    ) {
        let site = k + path.len();
        let before = path.last().copied().unwrap_or(seq[k - 1]);
        let (meas, z) = &self.plots[site];
        let dt = self.times[site] - self.times[site - 1];
        for j in 0..R {
            let mut w = lw + ln(self.pi[before][j]);
            if path.len() + 1 == len && site < self.n() {
                w += ln(self.pi[j][seq[site + 1]]);
            }
            if w == f64::NEG_INFINITY {
                continue;
            }
            let f = &self.filters[j];
            let pred = f.predict(g, dt).expect("prediction");
            let (post, innov) = f.update(&pred, meas, z).expect("update");
            w += innov.log_likelihood();
            path.push(j);
            if path.len() == len {
                out.push((path.clone(), w + log_integral(&post, beta)));
            } else {
                self.grow(seq, k, len, &post, w, beta, path, out);
            }
            path.pop();
        }
    }

    fn site0(&self, seq: &[usize]) -> [f64; R] {
        normalise(core::array::from_fn(|i| {
            ln(self.mu0[i])
                + if self.n() > 0 {
                    ln(self.pi[i][seq[1]])
                } else {
                    0.0
                }
        }))
    }

    /// The filtered state at `k − 1` along `seq`.
    fn filtered_before(&self, seq: &[usize], k: usize) -> Gaussian<4> {
        let mut g = self.g0;
        for (i, &m) in seq.iter().enumerate().take(k).skip(1) {
            let f = &self.filters[m];
            let pred = f.predict(&g, self.times[i] - self.times[i - 1]).unwrap();
            g = f
                .update(&pred, &self.plots[i].0, &self.plots[i].1)
                .unwrap()
                .0;
        }
        g
    }

    /// `p(mₖ = · | m₋ₖ, Z)` along `seq`, computed from scratch (for the checks).
    pub(crate) fn conditional(&self, seq: &[usize], k: usize) -> [f64; R] {
        if k == 0 {
            return self.site0(seq);
        }
        let mut p = [0.0; R];
        for (path, pr) in self.block_conditional(seq, k, 1) {
            p[path[0]] += pr;
        }
        p
    }

    /// `p(mₖ … mₖ₊ₗₑₙ₋₁ = · | the other modes, Z)` along `seq` (`k ≥ 1`), from scratch.
    pub(crate) fn block_conditional(
        &self,
        seq: &[usize],
        k: usize,
        len: usize,
    ) -> Vec<(Vec<usize>, f64)> {
        let g = self.filtered_before(seq, k);
        let beta = self.backward(seq)[k + len - 1];
        let paths = self.block_paths(seq, k, len, &g, &beta);
        let max = paths.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max);
        let total: f64 = paths.iter().map(|p| (p.1 - max).exp()).sum();
        paths
            .into_iter()
            .map(|(path, l)| (path, (l - max).exp() / total))
            .collect()
    }
}

/// A Gibbs chain over the mode sequence with its running averages.
pub(crate) struct Chain<'a, const R: usize, Me> {
    problem: &'a Problem<'a, R, Me>,
    seq: Vec<usize>,
    rng: ChaCha8Rng,
    sweeps: usize,
    calls: usize,
    sum_mean: Vec<Vector<4>>,
    sum_second: Vec<Matrix<4, 4>>,
    sum_mode: Vec<[f64; R]>,
}

fn draw<const R: usize>(p: &[f64; R], rng: &mut ChaCha8Rng) -> usize {
    let u: f64 = rng.random();
    let mut c = 0.0;
    for (j, pj) in p.iter().enumerate() {
        c += pj;
        if u < c {
            return j;
        }
    }
    p.iter().rposition(|&x| x > 0.0).unwrap_or(0)
}

impl<'a, const R: usize, Me: LinearMeasurementModel<4, 2>> Chain<'a, R, Me> {
    /// A chain from the mode sequence `init` (length `n + 1`, a sequence of nonzero
    /// prior), drawing from `seed`.
    pub(crate) fn new(problem: &'a Problem<'a, R, Me>, init: Vec<usize>, seed: u64) -> Self {
        let n1 = problem.times.len();
        assert_eq!(init.len(), n1);
        Self {
            problem,
            seq: init,
            rng: ChaCha8Rng::seed_from_u64(seed),
            sweeps: 0,
            calls: 0,
            sum_mean: vec![Vector::<4>::zeros(); n1],
            sum_second: vec![Matrix::<4, 4>::zeros(); n1],
            sum_mode: vec![[0.0; R]; n1],
        }
    }

    /// One sweep in blocks of `len` consecutive modes drawn jointly (`len = 1`: the
    /// single-site sampler; the first block's length cycles through `1 … len` from sweep
    /// to sweep so that block boundaries move); `record` adds the sequence drawn to the
    /// averages.
    pub(crate) fn sweep(&mut self, len: usize, record: bool) {
        let p = self.problem;
        let n = p.n();
        let beta = p.backward(&self.seq);
        let c0 = p.site0(&self.seq);
        self.seq[0] = draw(&c0, &mut self.rng);
        let mut steps = Vec::with_capacity(self.seq.len());
        steps.push(RtsStep::first(p.times[0], p.g0));
        let mut g = p.g0;
        let mut probs = vec![c0];
        let mut k = 1;
        let mut block = 1 + self.calls % len;
        self.calls += 1;
        while k <= n {
            let l = block.min(n - k + 1);
            block = len;
            let paths = p.block_paths(&self.seq, k, l, &g, &beta[k + l - 1]);
            let max = paths.iter().map(|x| x.1).fold(f64::NEG_INFINITY, f64::max);
            let w: Vec<f64> = paths.iter().map(|x| (x.1 - max).exp()).collect();
            let total: f64 = w.iter().sum();
            let mut marg = vec![[0.0; R]; l];
            for ((path, _), wi) in paths.iter().zip(&w) {
                for (m, &j) in marg.iter_mut().zip(path) {
                    m[j] += wi / total;
                }
            }
            let u: f64 = self.rng.random::<f64>() * total;
            let mut c = 0.0;
            let mut pick = paths.len() - 1;
            for (i, wi) in w.iter().enumerate() {
                c += wi;
                if u < c {
                    pick = i;
                    break;
                }
            }
            for (i, &j) in paths[pick].0.iter().enumerate() {
                let site = k + i;
                self.seq[site] = j;
                let f = &p.filters[j];
                let tr = f
                    .predict_with_cross(&g, p.times[site] - p.times[site - 1])
                    .expect("prediction");
                let post = f
                    .update(tr.predicted(), &p.plots[site].0, &p.plots[site].1)
                    .expect("update")
                    .0;
                steps.push(RtsStep::new(p.times[site], tr, post));
                g = post;
            }
            probs.extend(marg);
            k += l;
        }
        if record {
            let s = rts_smooth(&steps).expect("RTS along a sequence");
            for k in 0..s.len() {
                let m = *s[k].mean();
                self.sum_mean[k] += m;
                self.sum_second[k] += s[k].cov() + m * m.transpose();
                for (acc, pj) in self.sum_mode[k].iter_mut().zip(&probs[k]) {
                    *acc += pj;
                }
            }
            self.sweeps += 1;
        }
    }

    /// The current mode sequence.
    pub(crate) fn sequence(&self) -> &[usize] {
        &self.seq
    }

    /// Recorded sweeps.
    pub(crate) fn sweeps(&self) -> usize {
        self.sweeps
    }

    /// Per step: the running sums (mean, second moment, mode probabilities), for pooling
    /// chains.
    pub(crate) fn sums(&self) -> (&[Vector<4>], &[Matrix<4, 4>], &[[f64; R]]) {
        (&self.sum_mean, &self.sum_second, &self.sum_mode)
    }
}

/// The pooled estimate of chains: per step the posterior moments (mean, covariance) and
/// the mode probabilities.
pub(crate) fn pooled<const R: usize, Me>(
    chains: &[Chain<'_, R, Me>],
) -> (Vec<Gaussian<4>>, Vec<[f64; R]>) {
    let n1 = chains[0].sum_mean.len();
    let total: f64 = chains.iter().map(|c| c.sweeps as f64).sum();
    let mut g = Vec::with_capacity(n1);
    let mut mu = Vec::with_capacity(n1);
    for k in 0..n1 {
        let m: Vector<4> = chains.iter().map(|c| c.sum_mean[k]).sum::<Vector<4>>() / total;
        let s: Matrix<4, 4> = chains.iter().map(|c| c.sum_second[k]).sum::<Matrix<4, 4>>() / total;
        let cov = s - m * m.transpose();
        g.push(Gaussian::from_symmetrized(m, &cov).expect("a covariance"));
        mu.push(core::array::from_fn(|j| {
            chains.iter().map(|c| c.sum_mode[k][j]).sum::<f64>() / total
        }));
    }
    (g, mu)
}

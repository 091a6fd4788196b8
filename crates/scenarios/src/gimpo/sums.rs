//! What gimpo's report needs of the runs, accumulated one run at a time in run order, so
//! that a merge of any number of runs holds a few per-step sums instead of every run's
//! record. Each sum adds the same numbers in the same order as a pass over all the records
//! would (the per-step sums start at −0.0, as `Iterator::sum` does), so the means are the
//! same bit for bit. The final ratios' standard deviations are Welford's one-pass form
//! ([`MeanSd`]), within a few ulps of the two-pass form they replaced.

use super::estimate::{RunOut, STARTS};
use crate::campaign::{Footprint, Retained};
use crate::error::ScenarioError;

const N: usize = STARTS.len();

/// `(Σ squared error, count)` over the runs and the steps of the RMS window.
pub(super) type Tail = (f64, f64);

/// The accumulated statistics of the runs.
pub(crate) struct Sums {
    /// Plot times after the two initialising plots (the same in every run).
    pub(super) times: Vec<f64>,
    /// First step of the RMS window.
    first: usize,
    /// The number of runs the stream holds (the mode probabilities are averaged as
    /// `Σ μ / n` term by term, as they always were).
    expected: usize,
    /// Runs added so far.
    pub(super) count: usize,
    pub(super) tail_fixed: [Tail; N],
    /// The IMM smoother's and the Gibbs smoother's squared errors over the RMS window.
    pub(super) tail_smooth: Tail,
    pub(super) tail_gibbs: Tail,
    /// Their NEES over every step after the start (the ANEES window).
    pub(super) nees_smooth: Tail,
    pub(super) nees_gibbs: Tail,
    pub(super) tail_multi: [Tail; N],
    pub(super) tail_vb: [Tail; N],
    pub(super) tail_ev: [Tail; N],
    pub(super) tail_df: [Tail; N],
    /// Per step, Σ over the runs.
    pub(super) step_fixed: [Vec<f64>; N],
    pub(super) step_multi: [Vec<f64>; N],
    pub(super) step_vb: [[Vec<f64>; 2]; N],
    pub(super) step_ev: [[Vec<f64>; 2]; N],
    pub(super) step_df: [[Vec<f64>; 2]; N],
    /// Per step, Σ over the runs of μ / n.
    pub(super) step_mu: Vec<[f64; 3]>,
    /// The final ratios' mean and standard deviation over the runs.
    pub(super) last_multi: [MeanSd; N],
    pub(super) last_vb: [[MeanSd; 2]; N],
    pub(super) last_ev: [[MeanSd; 2]; N],
    pub(super) last_df: [[MeanSd; 2]; N],
    /// The first run's track (run 0 records one).
    pub(super) track: Vec<[f64; 6]>,
}

fn tail(acc: &mut Tail, v: &[f64], first: usize) {
    for x in v.iter().skip(first) {
        acc.0 += x;
        acc.1 += 1.0;
    }
}

fn step(acc: &mut [f64], v: impl Iterator<Item = f64>) {
    for (a, x) in acc.iter_mut().zip(v) {
        *a += x;
    }
}

fn axes(acc: &mut [Vec<f64>; 2], v: &[[f64; 2]]) {
    for (c, a) in acc.iter_mut().enumerate() {
        step(a, v.iter().map(|x| x[c]));
    }
}

fn finals(acc: &mut [MeanSd; 2], v: &[[f64; 2]]) {
    if let Some(x) = v.last() {
        acc[0].add(x[0]);
        acc[1].add(x[1]);
    }
}

/// The mean and sample standard deviation of values seen one at a time: the mean from
/// `Σ x / n` (the sum in arrival order from −0.0, as `Iterator::sum`), the deviation by
/// Welford's update (B. P. Welford, Technometrics 4(3), 1962; Knuth TAOCP vol. 2,
/// §4.2.2): `δ = x − m̄ₖ₋₁`, `m̄ₖ = m̄ₖ₋₁ + δ/k`, `M₂ += δ (x − m̄ₖ)`, `s² = M₂/(n − 1)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct MeanSd {
    sum: f64,
    count: usize,
    running_mean: f64,
    m2: f64,
}

impl Default for MeanSd {
    fn default() -> Self {
        Self {
            sum: -0.0,
            count: 0,
            running_mean: 0.0,
            m2: 0.0,
        }
    }
}

impl MeanSd {
    /// Adds the next value.
    pub(super) fn add(&mut self, x: f64) {
        self.sum += x;
        self.count += 1;
        let delta = x - self.running_mean;
        self.running_mean += delta / self.count as f64;
        self.m2 += delta * (x - self.running_mean);
    }

    /// The mean (`Σ x / max(n, 1)`) and the sample standard deviation
    /// (`√(M₂ / (max(n, 2) − 1))`; 0 for fewer than two values).
    pub(super) fn mean_sd(&self) -> (f64, f64) {
        let m = self.sum / self.count.max(1) as f64;
        (m, (self.m2 / (self.count.max(2) - 1) as f64).sqrt())
    }
}

impl Sums {
    /// Empty sums for `expected` runs over `times`, the RMS window from `first`.
    pub(super) fn new(times: Vec<f64>, first: usize, expected: usize) -> Self {
        let k = times.len();
        let z = || vec![-0.0; k];
        let z2 = || [z(), z()];
        Self {
            first,
            expected,
            count: 0,
            tail_fixed: [(0.0, 0.0); N],
            tail_smooth: (0.0, 0.0),
            tail_gibbs: (0.0, 0.0),
            nees_smooth: (0.0, 0.0),
            nees_gibbs: (0.0, 0.0),
            tail_multi: [(0.0, 0.0); N],
            tail_vb: [(0.0, 0.0); N],
            tail_ev: [(0.0, 0.0); N],
            tail_df: [(0.0, 0.0); N],
            step_fixed: std::array::from_fn(|_| z()),
            step_multi: std::array::from_fn(|_| z()),
            step_vb: std::array::from_fn(|_| z2()),
            step_ev: std::array::from_fn(|_| z2()),
            step_df: std::array::from_fn(|_| z2()),
            step_mu: vec![[0.0; 3]; k],
            last_multi: [MeanSd::default(); N],
            last_vb: [[MeanSd::default(); 2]; N],
            last_ev: [[MeanSd::default(); 2]; N],
            last_df: [[MeanSd::default(); 2]; N],
            track: Vec::new(),
            times,
        }
    }

    /// Adds the next run (in run order).
    pub(super) fn add(&mut self, r: &RunOut) {
        let f = self.first;
        let n_runs = self.expected as f64;
        for i in 0..N {
            tail(&mut self.tail_fixed[i], &r.fixed_se[i], f);
            tail(&mut self.tail_multi[i], &r.multi_se[i], f);
            tail(&mut self.tail_vb[i], &r.vb_se[i], f);
            tail(&mut self.tail_ev[i], &r.ev_se[i], f);
            tail(&mut self.tail_df[i], &r.df_se[i], f);
            step(&mut self.step_fixed[i], r.fixed_se[i].iter().copied());
            step(&mut self.step_multi[i], r.multi_ratio[i].iter().copied());
            axes(&mut self.step_vb[i], &r.vb_ratio[i]);
            axes(&mut self.step_ev[i], &r.ev_ratio[i]);
            axes(&mut self.step_df[i], &r.df_ratio[i]);
            if let Some(x) = r.multi_ratio[i].last() {
                self.last_multi[i].add(*x);
            }
            finals(&mut self.last_vb[i], &r.vb_ratio[i]);
            finals(&mut self.last_ev[i], &r.ev_ratio[i]);
            finals(&mut self.last_df[i], &r.df_ratio[i]);
        }
        tail(&mut self.tail_smooth, &r.smooth_se, f);
        tail(&mut self.tail_gibbs, &r.gibbs_se, f);
        tail(&mut self.nees_smooth, &r.smooth_nees, 0);
        tail(&mut self.nees_gibbs, &r.gibbs_nees, 0);
        for (m, v) in self.step_mu.iter_mut().zip(&r.mu) {
            for (a, b) in m.iter_mut().zip(v) {
                *a += b / n_runs;
            }
        }
        if self.count == 0 {
            self.track.clone_from(&r.track);
        }
        self.count += 1;
    }

    /// The sums once every run is added.
    ///
    /// # Errors
    /// [`ScenarioError::Degenerate`] if the stream held another number of runs than
    /// announced (a bug, reported).
    pub(super) fn finish(self) -> Result<Self, ScenarioError> {
        if self.count != self.expected {
            return Err(ScenarioError::Degenerate {
                scenario: "gimpo",
                message: format!("{} runs reduced, {} announced", self.count, self.expected),
            });
        }
        Ok(self)
    }

    /// The number of runs as the divisor of the means.
    pub(super) fn n_runs(&self) -> f64 {
        self.count as f64
    }

    /// RMS of a tail sum.
    pub(super) fn rms(t: Tail) -> f64 {
        Self::mean(t).sqrt()
    }

    /// Mean of a tail sum.
    pub(super) fn mean(t: Tail) -> f64 {
        t.0 / t.1.max(1.0)
    }
}

fn lens<'a>(v: impl IntoIterator<Item = &'a Vec<f64>>) -> usize {
    v.into_iter().map(Vec::len).sum()
}

impl Retained for Sums {
    fn footprint(&self) -> Footprint {
        let pairs = |a: &[[Vec<f64>; 2]; N]| lens(a.iter().flatten());
        Footprint {
            fixed: self.times.len()
                + 2 * (4 + 5 * N)
                + lens(&self.step_fixed)
                + lens(&self.step_multi)
                + pairs(&self.step_vb)
                + pairs(&self.step_ev)
                + pairs(&self.step_df)
                + 3 * self.step_mu.len()
                + 6 * self.track.len()
                // The final ratios' accumulators: 5 starts × (1 + 3 × 2), 4 numbers each.
                + 4 * N * 7,
            per_run: 0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::MeanSd;

    #[test]
    fn the_one_pass_mean_and_deviation_equal_the_two_pass_forms() {
        // Ratios near 1 as gimpo's are, spread 0.05, from a fixed sequence.
        let vals: Vec<f64> = (0..1000)
            .map(|k| 1.0 + 0.05 * (f64::from(k) * 0.618_033_988_749_895).fract() - 0.025)
            .collect();
        let mut acc = MeanSd::default();
        vals.iter().for_each(|&x| acc.add(x));
        let (m, sd) = acc.mean_sd();
        // The mean is the same sum in the same order: bit for bit.
        let m2 = vals.iter().sum::<f64>() / vals.len() as f64;
        assert_eq!(m.to_bits(), m2.to_bits());
        // The two-pass deviation; Welford's differs by rounding only (1e-12 relative is
        // ~4 000 ulps, far above the O(n ε) a stable update reaches, far below any digit
        // the report prints).
        let v2 = vals.iter().map(|x| (x - m2).powi(2)).sum::<f64>() / (vals.len() - 1) as f64;
        assert!(
            (sd - v2.sqrt()).abs() <= 1e-12 * v2.sqrt(),
            "{sd} against {}",
            v2.sqrt()
        );
        // No values, one value: mean 0 (or the value), deviation 0, as before.
        assert_eq!(MeanSd::default().mean_sd(), (-0.0, 0.0));
        let mut one = MeanSd::default();
        one.add(1.5);
        assert_eq!(one.mean_sd(), (1.5, 0.0));
    }
}

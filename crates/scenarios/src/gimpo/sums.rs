//! What gimpo's report needs of the runs, accumulated one run at a time in run order, so
//! that a merge of any number of runs holds a few per-step sums and per-run final ratios
//! instead of every run's record. Each sum adds the same numbers in the same order as a
//! pass over all the records would (the per-step sums start at −0.0, as `Iterator::sum`
//! does), so the report is the same bit for bit.

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
    pub(super) tail_smooth: Tail,
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
    /// Per run, the final ratios.
    pub(super) last_multi: [Vec<f64>; N],
    pub(super) last_vb: [[Vec<f64>; 2]; N],
    pub(super) last_ev: [[Vec<f64>; 2]; N],
    pub(super) last_df: [[Vec<f64>; 2]; N],
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

fn finals(acc: &mut [Vec<f64>; 2], v: &[[f64; 2]]) {
    if let Some(x) = v.last() {
        acc[0].push(x[0]);
        acc[1].push(x[1]);
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
            last_multi: std::array::from_fn(|_| Vec::new()),
            last_vb: std::array::from_fn(|_| [Vec::new(), Vec::new()]),
            last_ev: std::array::from_fn(|_| [Vec::new(), Vec::new()]),
            last_df: std::array::from_fn(|_| [Vec::new(), Vec::new()]),
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
                self.last_multi[i].push(*x);
            }
            finals(&mut self.last_vb[i], &r.vb_ratio[i]);
            finals(&mut self.last_ev[i], &r.ev_ratio[i]);
            finals(&mut self.last_df[i], &r.df_ratio[i]);
        }
        tail(&mut self.tail_smooth, &r.smooth_se, f);
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
        (t.0 / t.1.max(1.0)).sqrt()
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
                + 2 * (1 + 5 * N)
                + lens(&self.step_fixed)
                + lens(&self.step_multi)
                + pairs(&self.step_vb)
                + pairs(&self.step_ev)
                + pairs(&self.step_df)
                + 3 * self.step_mu.len()
                + 6 * self.track.len(),
            // The final ratios, one per estimator and axis per run: their mean and
            // standard deviation are computed in two passes over the values.
            per_run: lens(&self.last_multi)
                + pairs(&self.last_vb)
                + pairs(&self.last_ev)
                + pairs(&self.last_df),
        }
    }
}

//! The rbs-landing Monte Carlo statistics per plot time ([`McSummary`]), accumulated one
//! run at a time ([`McSums`]).

use argus_adaptive::AdaptiveError;

use super::experiment::{FILTERS, FilterKind, RbsLandingConfig, RunSeries, simulate_run};

/// Monte Carlo statistics over runs, per plot time.
#[derive(Debug, Clone, PartialEq)]
pub struct McSummary {
    /// Number of runs.
    pub runs: usize,
    /// Plot times, s.
    pub times: Vec<f64>,
    /// RMS position error per filter ([`FilterKind::index`]), per time, per axis (m).
    pub rms: [Vec<[f64; 3]>; FILTERS],
    /// ANEES per filter, per time: the mean NEES over runs divided by 6.
    pub anees: [Vec<f64>; FILTERS],
    /// `√(mean R̂ᵢᵢ)` per adaptive filter ([`ADAPTIVE`](super::experiment::ADAPTIVE) order), per time, per axis (m).
    pub sigma_hat: [Vec<[f64; 3]>; 4],
    /// `√(mean Rᵢᵢ)` of the true plot noise (SNR fluctuation included), per time, per axis (m).
    pub sigma_true: Vec<[f64; 3]>,
    /// `√(mean Rᵢᵢ)` the filters assume, per time, per axis (m).
    pub sigma_assumed: Vec<[f64; 3]>,
    /// CDKF: mean over runs of [`RunSeries::sample_ratio`].
    pub sample_ratio: [[f64; 3]; 2],
}

/// The index range `[from, to)` of the fractions `from_frac..to_frac` of `n` steps.
fn window(n: usize, from_frac: f64, to_frac: f64) -> std::ops::Range<usize> {
    let a = ((n as f64) * from_frac.clamp(0.0, 1.0)).floor() as usize;
    let b = ((n as f64) * to_frac.clamp(0.0, 1.0)).ceil() as usize;
    a.min(n)..b.min(n).max(a.min(n))
}

fn mean_of(v: impl Iterator<Item = f64>) -> f64 {
    let (s, c) = v.fold((0.0, 0usize), |(s, c), x| (s + x, c + 1));
    if c == 0 { f64::NAN } else { s / c as f64 }
}

impl McSummary {
    /// Aggregates runs: a fold through [`McSums`].
    ///
    /// # Errors
    /// [`AdaptiveError::InvalidParameter`] for no runs or runs of different lengths.
    pub fn from_runs(runs: &[RunSeries], dt: f64) -> Result<Self, AdaptiveError> {
        let mut sums = McSums::new(runs.len(), dt);
        for r in runs {
            sums.add(r);
        }
        sums.finish()
    }

    /// Number of plot times.
    #[must_use]
    pub fn len(&self) -> usize {
        self.times.len()
    }

    /// Whether there are no plot times.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }

    /// The ANEES of `kind` averaged over the fraction `from..to` of the approach
    /// (`0.0, 1.0` = whole approach; `0.8, 1.0` = final 20 %).
    #[must_use]
    pub fn time_avg_anees(&self, kind: FilterKind, from: f64, to: f64) -> f64 {
        let a = &self.anees[kind.index()];
        mean_of(window(a.len(), from, to).map(|k| a.get(k).copied().unwrap_or(f64::NAN)))
    }

    /// The RMS error of `kind` on `axis` (0 = x, 1 = y, 2 = z) over the fraction
    /// `from..to`: `√(mean over time of the per-time mean square)`.
    #[must_use]
    pub fn time_rms(&self, kind: FilterKind, axis: usize, from: f64, to: f64) -> f64 {
        let r = &self.rms[kind.index()];
        mean_of(window(r.len(), from, to).map(|k| {
            r.get(k)
                .and_then(|v| v.get(axis))
                .map_or(f64::NAN, |v| v * v)
        }))
        .sqrt()
    }

    /// The time average over `from..to` of `σ̂ / σ_true` on `axis` for the
    /// adaptive filter `adaptive` (index in [`ADAPTIVE`](super::experiment::ADAPTIVE): 0 = ADKF, 1 = ADKF-paper).
    #[must_use]
    pub fn sigma_ratio(&self, adaptive: usize, axis: usize, from: f64, to: f64) -> f64 {
        let Some(h) = self.sigma_hat.get(adaptive) else {
            return f64::NAN;
        };
        mean_of(window(h.len(), from, to).map(|k| {
            match (
                h.get(k).and_then(|v| v.get(axis)),
                self.sigma_true.get(k).and_then(|v| v.get(axis)),
            ) {
                (Some(a), Some(b)) => a / b,
                _ => f64::NAN,
            }
        }))
    }
}

/// Runs `runs` Monte Carlo runs sequentially (run `i` seeded with `seed + i`)
/// and aggregates them.
///
/// # Errors
/// As [`simulate_run`] and [`McSummary::from_runs`].
pub fn run_monte_carlo(
    config: &RbsLandingConfig,
    noise_scale: f64,
    runs: usize,
    seed: u64,
) -> Result<McSummary, AdaptiveError> {
    let series = (0..runs as u64)
        .map(|i| simulate_run(config, noise_scale, seed.wrapping_add(i)))
        .collect::<Result<Vec<_>, _>>()?;
    McSummary::from_runs(&series, config.dt)
}

/// [`McSummary`] accumulated one run at a time, in run order: per-step sums of the
/// squared errors, NEES and noise diagonals, so that aggregating any number of runs holds
/// the same few numbers per step and none per run. Each sum adds the same values in the
/// same order as a pass over all the runs would.
#[derive(Debug, Clone, PartialEq)]
pub struct McSums {
    /// The runs announced (the sample ratios are averaged as `Σ x / m` term by term).
    expected: usize,
    dt: f64,
    runs: usize,
    /// Steps per run (from the first), and whether a run of another length came.
    steps: usize,
    ragged: Option<f64>,
    pos_sq: [Vec<[f64; 3]>; FILTERS],
    nees: [Vec<f64>; FILTERS],
    r_hat: [Vec<[f64; 3]>; 4],
    r_true: Vec<[f64; 3]>,
    r_assumed: Vec<[f64; 3]>,
    sample_ratio: [[f64; 3]; 2],
}

fn add3(acc: &mut [[f64; 3]], v: &[[f64; 3]], f: impl Fn(f64) -> f64) {
    for (a, x) in acc.iter_mut().zip(v) {
        for (a, x) in a.iter_mut().zip(x) {
            *a += f(*x);
        }
    }
}

impl McSums {
    /// No run yet, of the `expected` runs to come, plots every `dt` s.
    #[must_use]
    pub fn new(expected: usize, dt: f64) -> Self {
        Self {
            expected,
            dt,
            runs: 0,
            steps: 0,
            ragged: None,
            pos_sq: std::array::from_fn(|_| Vec::new()),
            nees: std::array::from_fn(|_| Vec::new()),
            r_hat: std::array::from_fn(|_| Vec::new()),
            r_true: Vec::new(),
            r_assumed: Vec::new(),
            sample_ratio: [[0.0; 3]; 2],
        }
    }

    /// Adds the next run.
    pub fn add(&mut self, r: &RunSeries) {
        if self.runs == 0 {
            let n = r.r_true_diag.len();
            self.steps = n;
            self.pos_sq = std::array::from_fn(|_| vec![[0.0; 3]; n]);
            self.nees = std::array::from_fn(|_| vec![-0.0; n]);
            self.r_hat = std::array::from_fn(|_| vec![[0.0; 3]; n]);
            self.r_true = vec![[0.0; 3]; n];
            self.r_assumed = vec![[0.0; 3]; n];
        }
        self.runs += 1;
        let n = self.steps;
        let consistent = r.r_true_diag.len() == n
            && r.r_assumed_diag.len() == n
            && r.pos_err.iter().all(|v| v.len() == n)
            && r.nees.iter().all(|v| v.len() == n)
            && r.r_hat_diag.iter().all(|v| v.len() == n);
        if !consistent {
            self.ragged.get_or_insert(r.r_true_diag.len() as f64);
        }
        if self.ragged.is_some() {
            return;
        }
        for (acc, v) in self.pos_sq.iter_mut().zip(&r.pos_err) {
            add3(acc, v, |e| e * e);
        }
        for (acc, v) in self.nees.iter_mut().zip(&r.nees) {
            for (a, x) in acc.iter_mut().zip(v) {
                *a += x;
            }
        }
        for (acc, v) in self.r_hat.iter_mut().zip(&r.r_hat_diag) {
            add3(acc, v, |x| x);
        }
        add3(&mut self.r_true, &r.r_true_diag, |x| x);
        add3(&mut self.r_assumed, &r.r_assumed_diag, |x| x);
        let m = self.expected as f64;
        for (acc, v) in self.sample_ratio.iter_mut().zip(r.sample_ratio) {
            for (a, x) in acc.iter_mut().zip(v) {
                *a += x / m;
            }
        }
    }

    /// How many numbers the sums hold: `3·(FILTERS + 6) + FILTERS` per step and a fixed
    /// few, whatever the number of runs.
    #[must_use]
    pub fn retained(&self) -> usize {
        let per3 = |v: &Vec<[f64; 3]>| 3 * v.len();
        self.pos_sq.iter().map(per3).sum::<usize>()
            + self.nees.iter().map(Vec::len).sum::<usize>()
            + self.r_hat.iter().map(per3).sum::<usize>()
            + per3(&self.r_true)
            + per3(&self.r_assumed)
            + 6
            + 5
    }

    /// The statistics of the runs added.
    ///
    /// # Errors
    /// [`AdaptiveError::InvalidParameter`] for no runs, runs of different lengths, or
    /// another number of runs than announced.
    pub fn finish(&self) -> Result<McSummary, AdaptiveError> {
        if self.runs == 0 {
            return Err(AdaptiveError::InvalidParameter {
                what: "number of runs",
                value: 0.0,
                reason: "need at least one run",
            });
        }
        if let Some(value) = self.ragged {
            return Err(AdaptiveError::InvalidParameter {
                what: "run length",
                value,
                reason: "runs of different lengths cannot be aggregated",
            });
        }
        if self.runs != self.expected {
            return Err(AdaptiveError::InvalidParameter {
                what: "number of runs",
                value: self.runs as f64,
                reason: "another number of runs than announced was aggregated",
            });
        }
        let m = self.runs as f64;
        let root = |v: &Vec<[f64; 3]>| -> Vec<[f64; 3]> {
            v.iter().map(|a| a.map(|a| (a / m).sqrt())).collect()
        };
        Ok(McSummary {
            runs: self.runs,
            times: (1..=self.steps).map(|k| k as f64 * self.dt).collect(),
            rms: self.pos_sq.each_ref().map(root),
            anees: self
                .nees
                .each_ref()
                .map(|v| v.iter().map(|s| s / (6.0 * m)).collect()),
            sigma_hat: self.r_hat.each_ref().map(root),
            sigma_true: root(&self.r_true),
            sigma_assumed: root(&self.r_assumed),
            sample_ratio: self.sample_ratio,
        })
    }
}

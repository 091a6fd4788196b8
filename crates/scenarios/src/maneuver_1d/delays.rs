//! Detection delays after one switch, counted per plot: the delay of a run is the time
//! of its first detection in `(switch, next switch]` minus the switch time, and that
//! time is a plot time `t_k`, so the delays of any number of runs are the counts of
//! runs per plot index `k` (and of runs that missed the switch). From the counts, the
//! sorted delays — and their mean, nearest-rank quantiles and shares — follow exactly as
//! from a list of every run's delay, with memory independent of the number of runs.

/// The delays of the runs after one switch, as counts per plot.
#[derive(Debug, Clone, PartialEq)]
pub struct DelayCounts {
    /// Per plot index `k`: `t_k − switch` (s), increasing with `k`.
    delays: Vec<f64>,
    /// Per plot index: the runs whose first detection after the switch was at plot `k`.
    counts: Vec<usize>,
    /// Runs without a detection after the switch (before the next one).
    missed: usize,
}

/// The nearest-rank `p`-quantile (`0 ≤ p ≤ 1`) of the values given as `(value, count)`
/// in increasing order: the value at 1-based rank `⌈p·n⌉` (the first for `p = 0`), NaN for
/// no value or a non-finite `p` — as `experiment::quantile` of the sorted list.
pub(super) fn nearest_rank(buckets: impl Iterator<Item = (f64, usize)> + Clone, p: f64) -> f64 {
    let n: usize = buckets.clone().map(|b| b.1).sum();
    if n == 0 || !p.is_finite() {
        return f64::NAN;
    }
    let rank = (p.clamp(0.0, 1.0) * n as f64).ceil() as usize;
    let index = rank.saturating_sub(1);
    let mut seen = 0;
    for (v, c) in buckets {
        seen += c;
        if seen > index {
            return v;
        }
    }
    f64::NAN
}

impl DelayCounts {
    /// No run yet, for a switch at `switch` and plots at `times` (increasing).
    #[must_use]
    pub fn new(switch: f64, times: impl Iterator<Item = f64>) -> Self {
        let delays: Vec<f64> = times.map(|t| t - switch).collect();
        Self {
            counts: vec![0; delays.len()],
            delays,
            missed: 0,
        }
    }

    /// Adds a run whose first detection after the switch was at plot `k` (`None`: missed).
    pub fn add(&mut self, k: Option<usize>) {
        match k.and_then(|k| self.counts.get_mut(k)) {
            Some(c) => *c += 1,
            None => self.missed += 1,
        }
    }

    /// The detected delays as `(delay, runs)`, in increasing delay.
    pub fn detected(&self) -> impl Iterator<Item = (f64, usize)> + Clone + '_ {
        self.delays
            .iter()
            .zip(&self.counts)
            .filter(|(_, c)| **c > 0)
            .map(|(d, c)| (*d, *c))
    }

    /// Runs that detected the switch.
    #[must_use]
    pub fn detected_runs(&self) -> usize {
        self.counts.iter().sum()
    }

    /// Runs that missed it.
    #[must_use]
    pub fn missed(&self) -> usize {
        self.missed
    }

    /// Runs counted.
    #[must_use]
    pub fn runs(&self) -> usize {
        self.detected_runs() + self.missed
    }

    /// Runs that detected the switch within `limit` s.
    #[must_use]
    pub fn within(&self, limit: f64) -> usize {
        self.detected()
            .filter(|(d, _)| *d <= limit + 1e-9)
            .map(|(_, c)| c)
            .sum()
    }

    /// The mean of the detected delays, s (NaN when none): Σ of the sorted delays over
    /// their number, as it was always computed.
    #[must_use]
    pub fn mean(&self) -> f64 {
        let mut s = -0.0;
        for (d, c) in self.detected() {
            for _ in 0..c {
                s += d;
            }
        }
        s / self.detected_runs() as f64
    }

    /// The nearest-rank `p`-quantile of the detected delays, s.
    #[must_use]
    pub fn quantile(&self, p: f64) -> f64 {
        nearest_rank(self.detected(), p)
    }

    /// The nearest-rank `p`-quantile of every run's delay, a missed switch counting as
    /// never detected (`+∞`).
    #[must_use]
    pub fn quantile_with_missed(&self, p: f64) -> f64 {
        nearest_rank(
            self.detected()
                .chain(std::iter::once((f64::INFINITY, self.missed))),
            p,
        )
    }

    /// How many numbers the counts hold (two per plot and one), whatever the runs.
    #[must_use]
    pub fn retained(&self) -> usize {
        self.delays.len() + self.counts.len() + 1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The same f64, bit for bit (the values below are exactly representable).
    fn same(a: f64, b: f64) -> bool {
        a.to_bits() == b.to_bits()
    }

    #[test]
    fn counts_give_the_sorted_list_statistics() {
        // Plots at 1, 2, …, 10 s (index k at k + 1 s), switch at 3 s; runs detecting at
        // indices 5, 3, 5, 9 (6, 4, 6, 10 s) and one missing: delays 3, 1, 3, 7 s (sorted
        // 1, 3, 3, 7), exactly representable.
        let mut d = DelayCounts::new(3.0, (1..=10).map(f64::from));
        for k in [Some(5), Some(3), Some(5), Some(9), None] {
            d.add(k);
        }
        assert_eq!((d.detected_runs(), d.missed(), d.runs()), (4, 1, 5));
        // Mean (1 + 3 + 3 + 7)/4 = 3.5; nearest rank: p = 0.5 → rank 2 → 3; p = 1 → 7;
        // p = 0 → the first, 1; with the miss as +∞ over 5 runs, p = 0.95 → rank 5 → ∞.
        assert!(same(d.mean(), 3.5));
        assert!(same(d.quantile(0.5), 3.0));
        assert!(same(d.quantile(1.0), 7.0));
        assert!(same(d.quantile(0.0), 1.0));
        assert!(same(d.quantile_with_missed(0.95), f64::INFINITY));
        assert!(same(d.quantile_with_missed(0.8), 7.0));
        assert_eq!(d.within(3.0), 3);
        assert!(DelayCounts::new(0.0, std::iter::empty()).mean().is_nan());
    }
}

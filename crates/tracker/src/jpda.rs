//! JPDA association weights for one cluster of tracks that share plots.
//!
//! For tracks `t` and gated plots `j` with likelihood ratios
//! `G_tj = P_D N(ν_tj; 0, S_tj) / λ` and the miss factor `B = 1 − P_D P_G`, a joint event
//! `θ` assigns each track at most one plot and each plot at most one track, with weight
//! `∏_{(t,j)∈θ} G_tj · ∏_{t unassigned} B` (parametric JPDA). The marginal
//! `β_tj = Σ_{θ ∋ (t,j)} w(θ) / Σ_θ w(θ)`, `β_t0 = 1 − Σ_j β_tj`.
//!
//! Clusters with at most `max_events` joint events are enumerated exactly. Larger ones use
//! Fitzgerald's "cheap JPDA" approximation
//! `β_tj = G_tj / (S_t + S^j − G_tj + B)`, `S_t = Σ_j G_tj`, `S^j = Σ_t G_tj`, which is exact
//! for a track alone (it is then the PDA weight `G_j / (S_t + B)`).
//!
//! # References
//! Y. Bar-Shalom, P. Willett, X. Tian, *Tracking and Data Fusion*, YBS 2011, §6.2 (JPDA
//! events and marginals); R. J. Fitzgerald, "Development of practical PDA logic for
//! multitarget tracking by microprocessor", American Control Conference 1986 (cheap JPDA).

/// A gated pair inside a cluster: local row, local column, likelihood ratio `G`.
pub(crate) type Pair = (usize, usize, f64);

/// Marginal weights: `β` per pair (same order as `pairs`) and `β₀` per row.
pub(crate) fn marginals(
    rows: usize,
    cols: usize,
    pairs: &[Pair],
    miss: f64,
    max_events: usize,
) -> (Vec<f64>, Vec<f64>) {
    exact(rows, cols, pairs, miss, max_events).unwrap_or_else(|| cheap(rows, cols, pairs, miss))
}

/// Exact enumeration; `None` when the cluster has more than `max_events` events.
fn exact(
    rows: usize,
    cols: usize,
    pairs: &[Pair],
    miss: f64,
    max_events: usize,
) -> Option<(Vec<f64>, Vec<f64>)> {
    let mut by_row: Vec<Vec<usize>> = vec![Vec::new(); rows];
    for (k, &(r, _, _)) in pairs.iter().enumerate() {
        by_row[r].push(k);
    }
    let mut st = Walk {
        pairs,
        by_row: &by_row,
        miss,
        max_events,
        beta: vec![0.0; pairs.len()],
        total: 0.0,
        taken: vec![false; cols],
        chosen: vec![None; rows],
        events: 0,
    };
    let complete = st.walk(0, 1.0);
    if !complete || !st.total.is_finite() || st.total <= 0.0 {
        return None;
    }
    let total = st.total;
    let mut beta = st.beta;
    for b in &mut beta {
        *b /= total;
    }
    Some(finish(rows, pairs, beta))
}

/// Depth-first enumeration state: each row takes no plot or one free gated plot.
struct Walk<'a> {
    pairs: &'a [Pair],
    by_row: &'a [Vec<usize>],
    miss: f64,
    max_events: usize,
    beta: Vec<f64>,
    total: f64,
    taken: Vec<bool>,
    chosen: Vec<Option<usize>>,
    events: usize,
}

impl Walk<'_> {
    /// Walks rows `r..`; `false` once the event limit is passed.
    fn walk(&mut self, r: usize, weight: f64) -> bool {
        if r == self.by_row.len() {
            self.events += 1;
            if self.events > self.max_events {
                return false;
            }
            self.total += weight;
            for k in self.chosen.iter().flatten() {
                self.beta[*k] += weight;
            }
            return true;
        }
        self.chosen[r] = None;
        if !self.walk(r + 1, weight * self.miss) {
            return false;
        }
        for i in 0..self.by_row[r].len() {
            let k = self.by_row[r][i];
            let (_, c, g) = self.pairs[k];
            if self.taken[c] {
                continue;
            }
            self.taken[c] = true;
            self.chosen[r] = Some(k);
            let ok = self.walk(r + 1, weight * g);
            self.taken[c] = false;
            self.chosen[r] = None;
            if !ok {
                return false;
            }
        }
        true
    }
}

/// Fitzgerald's cheap JPDA.
fn cheap(rows: usize, cols: usize, pairs: &[Pair], miss: f64) -> (Vec<f64>, Vec<f64>) {
    let mut s_row = vec![0.0; rows];
    let mut s_col = vec![0.0; cols];
    for &(r, c, g) in pairs {
        s_row[r] += g;
        s_col[c] += g;
    }
    let beta = pairs
        .iter()
        .map(|&(r, c, g)| g / (s_row[r] + s_col[c] - g + miss))
        .collect();
    finish(rows, pairs, beta)
}

fn finish(rows: usize, pairs: &[Pair], beta: Vec<f64>) -> (Vec<f64>, Vec<f64>) {
    let mut beta0 = vec![1.0; rows];
    for (&(r, _, _), b) in pairs.iter().zip(&beta) {
        beta0[r] -= b;
    }
    for b in &mut beta0 {
        *b = b.max(0.0);
    }
    (beta, beta0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_tracks_two_plots_by_hand() {
        // Tracks a, b; plots 1, 2; G_a1 = 4, G_a2 = 1, G_b1 = 2, G_b2 = 3; B = 0.5.
        // Events and weights: {} B² = 0.25; {a1} 4·0.5 = 2; {a2} 0.5; {b1} 1; {b2} 1.5;
        // {a1,b2} 12; {a2,b1} 2. Total 19.25.
        // β_a1 = (2 + 12)/19.25, β_a2 = (0.5 + 2)/19.25, β_b1 = (1 + 2)/19.25,
        // β_b2 = (1.5 + 12)/19.25; β_a0 = (0.25 + 1 + 1.5)/19.25, β_b0 = (0.25 + 2 + 0.5)/19.25.
        let pairs = [(0, 0, 4.0), (0, 1, 1.0), (1, 0, 2.0), (1, 1, 3.0)];
        let (b, b0) = marginals(2, 2, &pairs, 0.5, 100);
        let t = 19.25;
        let want = [14.0 / t, 2.5 / t, 3.0 / t, 13.5 / t];
        for (x, y) in b.iter().zip(want) {
            assert!((x - y).abs() < 1e-12, "{x} vs {y}");
        }
        assert!((b0[0] - 2.75 / t).abs() < 1e-12);
        assert!((b0[1] - 2.75 / t).abs() < 1e-12);
    }

    #[test]
    fn one_track_is_the_pda_and_cheap_jpda_agrees() {
        // One track, plots with G = 2 and 6, B = 0.1: PDA weights β_j = G_j/(B + ΣG)
        // (Bar-Shalom & Tse 1975) = 2/8.1, 6/8.1, β₀ = 0.1/8.1. The cheap form is exact here.
        let pairs = [(0, 0, 2.0), (0, 1, 6.0)];
        for max_events in [100, 0] {
            let (b, b0) = marginals(1, 2, &pairs, 0.1, max_events);
            assert!((b[0] - 2.0 / 8.1).abs() < 1e-12);
            assert!((b[1] - 6.0 / 8.1).abs() < 1e-12);
            assert!((b0[0] - 0.1 / 8.1).abs() < 1e-12);
        }
    }
}

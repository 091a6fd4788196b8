//! One grid time: tracks assigned to truths, and GOSPA, split into independent clusters.
//!
//! Both the track-to-truth assignment ([`TrackScan::assign`]: minimum `Σ min(d, c)`, pairs
//! closer than `c` kept) and GOSPA with `α = 2` ([`Gospa::distance`]) are maximum-weight
//! matchings whose only useful edges join a truth and a track closer than their cut-off.
//! Such a matching splits exactly over the connected components of the graph of those
//! edges, so each component is solved on its own — with `argus-sim`'s code — and the
//! results are summed. With the cut-offs used here most components hold one truth and
//! one track, which turns one dense `m × n` problem per step into many tiny ones: scoring
//! an hour of 120 aircraft stays in milliseconds. (Ties between equally good assignments
//! may be broken differently from one dense solve; the totals are the same.)

use argus_core_math::Vector;
use argus_sim::{Gospa, TargetId, TrackScan};

use crate::error::ScoreError;
use crate::grid::Kinematic;

/// The GOSPA parts at one time (`p`-th powers, as [`argus_sim::GospaValue`]) and counts.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct GospaParts {
    pub(crate) localisation: f64,
    pub(crate) missed: f64,
    pub(crate) false_targets: f64,
}

/// The assigned `(track index, truth index)` pairs and the GOSPA parts at one time.
pub(crate) struct Step {
    pub(crate) pairs: Vec<(usize, usize)>,
    pub(crate) gospa: GospaParts,
}

/// Disjoint sets over `0..n` (path halving, union by size).
struct Dsu {
    parent: Vec<usize>,
    size: Vec<usize>,
}

impl Dsu {
    fn new(n: usize) -> Self {
        Self {
            parent: (0..n).collect(),
            size: vec![1; n],
        }
    }

    fn find(&mut self, mut x: usize) -> usize {
        while self.parent[x] != x {
            self.parent[x] = self.parent[self.parent[x]];
            x = self.parent[x];
        }
        x
    }

    fn union(&mut self, a: usize, b: usize) {
        let (mut a, mut b) = (self.find(a), self.find(b));
        if a == b {
            return;
        }
        if self.size[a] < self.size[b] {
            std::mem::swap(&mut a, &mut b);
        }
        self.parent[b] = a;
        self.size[a] += self.size[b];
    }
}

/// Assigns `tracks` to `truths` within `cutoff` and computes GOSPA (whose cut-off is
/// `gospa_cutoff`), cluster by cluster.
pub(crate) fn step(
    t: f64,
    truths: &[(usize, Kinematic)],
    tracks: &[(usize, Kinematic)],
    cutoff: f64,
    gospa: &Gospa,
    gospa_cutoff: f64,
    gospa_order: f64,
) -> Result<Step, ScoreError> {
    let (m, n) = (truths.len(), tracks.len());
    let radius = cutoff.max(gospa_cutoff);
    let mut dsu = Dsu::new(m + n);
    // Candidate edges: tracks sorted by x, each truth checks those within ±radius in x.
    let mut by_x: Vec<(f64, usize)> = tracks
        .iter()
        .enumerate()
        .map(|(j, k)| (k.1.pos.x, j))
        .collect();
    by_x.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
    for (i, (_, x)) in truths.iter().enumerate() {
        let from = by_x.partition_point(|&(tx, _)| tx <= x.pos.x - radius);
        for &(tx, j) in &by_x[from..] {
            if tx >= x.pos.x + radius {
                break;
            }
            if (x.pos - tracks[j].1.pos).norm() < radius {
                dsu.union(i, m + j);
            }
        }
    }
    // Members of each component, truths (index < m) then tracks, by root.
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); m + n];
    for v in 0..m + n {
        let r = dsu.find(v);
        members[r].push(v);
    }
    let mut out = Step {
        pairs: Vec::new(),
        gospa: GospaParts::default(),
    };
    let mut lone_truths: Vec<Vector<2>> = Vec::new();
    let mut lone_tracks: Vec<Vector<2>> = Vec::new();
    for group in members.iter().filter(|g| !g.is_empty()) {
        let split = group.partition_point(|&v| v < m);
        let (gt, gk) = group.split_at(split);
        if gk.is_empty() {
            lone_truths.extend(gt.iter().map(|&v| truths[v].1.pos));
            continue;
        }
        if gt.is_empty() {
            lone_tracks.extend(gk.iter().map(|&v| tracks[v - m].1.pos));
            continue;
        }
        if let ([v], [w]) = (gt, gk) {
            // One truth and one track, the common case: both solvers' answer is the pair
            // itself, so it is computed directly (`single_pair`, tested against them).
            let (assigned, parts) = single_pair(
                truths[*v].1.pos,
                tracks[*w - m].1.pos,
                cutoff,
                gospa_cutoff,
                gospa_order,
            );
            if assigned {
                out.pairs.push((*w - m, *v));
            }
            out.gospa.localisation += parts.localisation;
            out.gospa.missed += parts.missed;
            out.gospa.false_targets += parts.false_targets;
            continue;
        }
        let truth_pts: Vec<(TargetId, Vector<2>)> = gt
            .iter()
            .map(|&v| (TargetId(v as u32), truths[v].1.pos))
            .collect();
        let track_pts: Vec<(u64, Vector<2>)> = gk
            .iter()
            .map(|&v| ((v - m) as u64, tracks[v - m].1.pos))
            .collect();
        let scan = TrackScan::assign(t, &truth_pts, &track_pts, cutoff)?;
        out.pairs.extend(
            scan.pairs()
                .iter()
                .map(|&(j, g)| (j as usize, g.0 as usize)),
        );
        let xs: Vec<Vector<2>> = truth_pts.iter().map(|p| p.1).collect();
        let ys: Vec<Vector<2>> = track_pts.iter().map(|p| p.1).collect();
        add(&mut out.gospa, &gospa.distance(&xs, &ys)?);
    }
    add(&mut out.gospa, &gospa.distance(&lone_truths, &[])?);
    add(&mut out.gospa, &gospa.distance::<2>(&[], &lone_tracks)?);
    Ok(out)
}

/// One truth `x` and one track `y`: whether [`TrackScan::assign`] pairs them (`d < cₐ`) and
/// the parts [`Gospa::distance`] gives (`dᵖ` when `d < c`, else `cᵖ/2` missed and
/// `cᵖ/2` false), with the same floating-point operations as those functions.
pub(crate) fn single_pair(
    x: Vector<2>,
    y: Vector<2>,
    cutoff: f64,
    gospa_cutoff: f64,
    gospa_order: f64,
) -> (bool, GospaParts) {
    let d = (x - y).norm();
    let parts = if d < gospa_cutoff {
        GospaParts {
            localisation: d.min(gospa_cutoff).powf(gospa_order),
            ..GospaParts::default()
        }
    } else {
        let half = 0.5 * gospa_cutoff.powf(gospa_order);
        GospaParts {
            localisation: 0.0,
            missed: half,
            false_targets: half,
        }
    };
    (d < cutoff, parts)
}

fn add(parts: &mut GospaParts, v: &argus_sim::GospaValue) {
    parts.localisation += v.localisation;
    parts.missed += v.missed;
    parts.false_targets += v.false_targets;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn single_pair_is_what_the_solvers_give() {
        // Distances on both sides of cₐ = 100 and c = 80, for p = 1, 2, 3: the shortcut
        // must reproduce TrackScan::assign and Gospa::distance bit for bit (same
        // operations), so the totals do not depend on which path a component took.
        let x = Vector::<2>::new(1.0, 2.0);
        for p in [1.0, 2.0, 3.0] {
            let g = Gospa::new(80.0, p).unwrap();
            for d in [0.0, 3.7, 79.999, 80.0, 99.5, 100.0, 250.0] {
                let y = x + Vector::<2>::new(d * 0.6, d * 0.8);
                let (assigned, parts) = single_pair(x, y, 100.0, 80.0, p);
                let scan = TrackScan::assign(0.0, &[(TargetId(0), x)], &[(0, y)], 100.0).unwrap();
                assert_eq!(assigned, !scan.pairs().is_empty(), "d = {d}");
                let v = g.distance(&[x], &[y]).unwrap();
                assert_eq!(
                    parts.localisation.to_bits(),
                    v.localisation.to_bits(),
                    "d = {d}"
                );
                assert_eq!(parts.missed.to_bits(), v.missed.to_bits(), "d = {d}");
                assert_eq!(
                    parts.false_targets.to_bits(),
                    v.false_targets.to_bits(),
                    "d = {d}"
                );
            }
        }
    }
}

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
) -> Result<Step, ScoreError> {
    let (m, n) = (truths.len(), tracks.len());
    let radius = cutoff.max(gospa_cutoff);
    let mut dsu = Dsu::new(m + n);
    for (i, (_, x)) in truths.iter().enumerate() {
        for (j, (_, y)) in tracks.iter().enumerate() {
            if (x.pos - y.pos).norm() < radius {
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

fn add(parts: &mut GospaParts, v: &argus_sim::GospaValue) {
    parts.localisation += v.localisation;
    parts.missed += v.missed;
    parts.false_targets += v.false_targets;
}

//! Truth and tracks sampled on the scoring grid.
//!
//! - A truth path is present at grid time `t` when two of its samples `a`, `b` bracket it
//!   (`a.t ≤ t ≤ b.t`) no more than `max_truth_gap` apart, or a sample falls on `t`
//!   exactly; its state is then the linear interpolation of `x, vx, y, vy` between them.
//! - A track is present at `t` when its last row at or before `t` is `confirmed` and at
//!   most `max_track_age` old; its state is that row's predicted with constant velocity
//!   to `t` (`x + vx (t − tᵣ)`, velocity unchanged). A later `tentative` or `deleted` row
//!   thus ends it, and a track that stops writing rows is dropped after `max_track_age`.
//!
//! Both are swept forward with one cursor per path or track, so sampling a whole grid
//! costs one pass over the rows.

use argus_core_math::Vector;

use crate::input::{TrackHistory, TruthPath};

/// A position and a velocity (m, m/s) in the local plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Kinematic {
    pub(crate) pos: Vector<2>,
    pub(crate) vel: Vector<2>,
}

/// Sweeps truth paths forward in time.
pub(crate) struct TruthCursor<'a> {
    paths: &'a [TruthPath],
    next: Vec<usize>,
    max_gap: f64,
}

impl<'a> TruthCursor<'a> {
    pub(crate) fn new(paths: &'a [TruthPath], max_gap: f64) -> Self {
        Self {
            paths,
            next: vec![0; paths.len()],
            max_gap,
        }
    }

    /// The paths present at `t` (index, state). Times must not decrease between calls.
    pub(crate) fn at(&mut self, t: f64, out: &mut Vec<(usize, Kinematic)>) {
        out.clear();
        for (i, path) in self.paths.iter().enumerate() {
            let s = path.samples();
            // next[i]: the first sample with time > t.
            let n = &mut self.next[i];
            while *n < s.len() && s[*n].t <= t {
                *n += 1;
            }
            if *n == 0 {
                continue;
            }
            let a = s[*n - 1];
            // a.t ≤ t by the cursor, so ≥ means the sample falls on t.
            let state = if a.t >= t {
                Some(Kinematic {
                    pos: Vector::<2>::new(a.x, a.y),
                    vel: Vector::<2>::new(a.vx, a.vy),
                })
            } else if *n < s.len() && s[*n].t - a.t <= self.max_gap {
                let b = s[*n];
                let w = (t - a.t) / (b.t - a.t);
                let lerp = |u: f64, v: f64| u + w * (v - u);
                Some(Kinematic {
                    pos: Vector::<2>::new(lerp(a.x, b.x), lerp(a.y, b.y)),
                    vel: Vector::<2>::new(lerp(a.vx, b.vx), lerp(a.vy, b.vy)),
                })
            } else {
                None
            };
            if let Some(k) = state {
                out.push((i, k));
            }
        }
    }
}

/// Sweeps tracks forward in time, visiting only the tracks that have started and can
/// still be present (so thousands of short false tracks cost little per grid time).
pub(crate) struct TrackCursor<'a> {
    tracks: &'a [TrackHistory],
    /// Track indices by first row time.
    order: Vec<usize>,
    /// Next position in `order` to activate.
    pending: usize,
    /// Active tracks: (index, next row).
    active: Vec<(usize, usize)>,
    max_age: f64,
}

impl<'a> TrackCursor<'a> {
    pub(crate) fn new(tracks: &'a [TrackHistory], max_age: f64) -> Self {
        let mut order: Vec<usize> = (0..tracks.len()).collect();
        order.sort_by(|&a, &b| tracks[a].rows()[0].t.total_cmp(&tracks[b].rows()[0].t));
        Self {
            tracks,
            order,
            pending: 0,
            active: Vec::new(),
            max_age,
        }
    }

    /// The confirmed tracks present at `t` (index, state predicted to `t`), in index order.
    /// Times must not decrease between calls.
    pub(crate) fn at(&mut self, t: f64, out: &mut Vec<(usize, Kinematic)>) {
        out.clear();
        while self.pending < self.order.len()
            && self.tracks[self.order[self.pending]].rows()[0].t <= t
        {
            self.active.push((self.order[self.pending], 0));
            self.pending += 1;
        }
        let (tracks, max_age) = (self.tracks, self.max_age);
        self.active.retain_mut(|(i, n)| {
            let r = tracks[*i].rows();
            while *n < r.len() && r[*n].t <= t {
                *n += 1;
            }
            let row = r[*n - 1];
            let age = t - row.t;
            if row.confirmed && age <= max_age {
                out.push((
                    *i,
                    Kinematic {
                        pos: Vector::<2>::new(row.x + row.vx * age, row.y + row.vy * age),
                        vel: Vector::<2>::new(row.vx, row.vy),
                    },
                ));
            }
            // Keep it while rows remain, or while its last row may still be in date.
            *n < r.len() || (row.confirmed && age <= max_age)
        });
        out.sort_unstable_by_key(|p| p.0);
    }
}

//! Track statistics from a (time, track id, truth id) association: track breaks, id
//! swaps, time to confirm and the false-track rate.
//!
//! A [`TrackScan`] says, at one scan time, which truths exist, which (confirmed) tracks
//! exist, and which track is assigned to which truth. [`TrackScan::assign`] builds one
//! from positions by the optimal assignment with a distance limit; a tracker's own
//! labelling can be fed in directly with [`TrackScan::new`].
//! [`TrackStatistics::from_scans`] reduces a time-ordered run of scans.

use std::collections::{BTreeMap, BTreeSet, HashMap};

use argus_core_math::Vector;

use crate::error::{SimError, positive};
use crate::ospa::optimal_assignment;
use crate::truth::TargetId;

/// One scan of the association between tracks (by the tracker's numeric id) and truths.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackScan {
    time: f64,
    truths: Vec<TargetId>,
    tracks: Vec<u64>,
    pairs: Vec<(u64, TargetId)>,
}

impl TrackScan {
    /// A scan at `time` with the truths and tracks present and the assigned
    /// `(track, truth)` pairs.
    ///
    /// # Errors
    /// [`SimError::InvalidParameter`] for a non-finite time, a duplicated truth or
    /// track, or a pair naming a track or truth not present, or a track or truth used
    /// in two pairs (the value given is the offending id).
    pub fn new(
        time: f64,
        truths: Vec<TargetId>,
        tracks: Vec<u64>,
        pairs: Vec<(u64, TargetId)>,
    ) -> Result<Self, SimError> {
        crate::error::finite("track scan time", time)?;
        let truth_set: BTreeSet<TargetId> = truths.iter().copied().collect();
        if truth_set.len() != truths.len() {
            return Err(invalid_id(
                "track scan truths",
                first_duplicate(&truths).0 as f64,
            ));
        }
        let track_set: BTreeSet<u64> = tracks.iter().copied().collect();
        if track_set.len() != tracks.len() {
            return Err(invalid_id(
                "track scan tracks",
                first_duplicate(&tracks) as f64,
            ));
        }
        let mut used_tracks = BTreeSet::new();
        let mut used_truths = BTreeSet::new();
        for &(track, truth) in &pairs {
            if !track_set.contains(&track) || !used_tracks.insert(track) {
                return Err(invalid_id("track scan pair track", track as f64));
            }
            if !truth_set.contains(&truth) || !used_truths.insert(truth) {
                return Err(invalid_id("track scan pair truth", f64::from(truth.0)));
            }
        }
        Ok(Self {
            time,
            truths,
            tracks,
            pairs,
        })
    }

    /// The scan at `time` whose pairs are the optimal assignment (minimum total distance)
    /// of `tracks` to `truths` by position, keeping only pairs closer than `max_distance`.
    ///
    /// # Errors
    /// [`SimError::InvalidParameter`] for a non-positive `max_distance`, a non-finite
    /// position, or as [`TrackScan::new`].
    pub fn assign<const D: usize>(
        time: f64,
        truths: &[(TargetId, Vector<D>)],
        tracks: &[(u64, Vector<D>)],
        max_distance: f64,
    ) -> Result<Self, SimError> {
        positive("track-to-truth distance limit", max_distance)?;
        let (m, n) = (truths.len(), tracks.len());
        let mut cost = Vec::with_capacity(m * n);
        for (_, x) in truths {
            for (_, y) in tracks {
                let d = (x - y).norm();
                if !d.is_finite() {
                    return Err(SimError::InvalidParameter {
                        what: "track or truth position",
                        value: d,
                        reason: "every coordinate must be finite",
                    });
                }
                cost.push(d.min(max_distance));
            }
        }
        let pairs = optimal_assignment(m, n, &cost)?
            .into_iter()
            .filter(|&(i, j)| cost[i * n + j] < max_distance)
            .map(|(i, j)| (tracks[j].0, truths[i].0))
            .collect();
        Self::new(
            time,
            truths.iter().map(|t| t.0).collect(),
            tracks.iter().map(|t| t.0).collect(),
            pairs,
        )
    }

    /// The scan time.
    #[must_use]
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The assigned `(track, truth)` pairs.
    #[must_use]
    pub fn pairs(&self) -> &[(u64, TargetId)] {
        &self.pairs
    }
}

fn first_duplicate<T: Ord + Copy>(items: &[T]) -> T {
    let mut seen = BTreeSet::new();
    for &x in items {
        if !seen.insert(x) {
            return x;
        }
    }
    items[0]
}

fn invalid_id(what: &'static str, value: f64) -> SimError {
    SimError::InvalidParameter {
        what,
        value,
        reason: "duplicated, or not among the ids present at the scan",
    }
}

/// Track statistics over a run of scans.
///
/// Definitions (after the CLEAR-MOT conventions of Bernardin & Stiefelhagen, 2008):
/// - **track break**: a truth assigned to a track at one scan and present but assigned
///   to no track at the next scan;
/// - **id swap**: a truth assigned to a track different from the last track it was
///   assigned to (at any earlier scan, across gaps);
/// - **time to confirm**: for each truth, the time of its first assignment minus the
///   time it first appears (`None` if never assigned);
/// - **false tracks**: tracks present but assigned to no truth. The rate is the mean
///   number of them per scan; `false_track_ids` counts tracks never assigned at all.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackStatistics {
    /// Number of scans.
    pub scans: usize,
    /// Track breaks summed over truths.
    pub breaks: usize,
    /// Id swaps summed over truths.
    pub id_swaps: usize,
    /// Per truth (in id order): time to confirm (s), `None` if never tracked.
    pub time_to_confirm: Vec<(TargetId, Option<f64>)>,
    /// Sum over scans of the unassigned tracks present.
    pub false_track_scans: usize,
    /// `false_track_scans / scans`: mean number of false tracks per scan.
    pub false_tracks_per_scan: f64,
    /// Distinct tracks never assigned to any truth.
    pub false_track_ids: usize,
    /// Distinct tracks seen.
    pub tracks_seen: usize,
}

impl TrackStatistics {
    /// Reduces a time-ordered run of scans.
    ///
    /// # Errors
    /// [`SimError::Empty`] for no scans; [`SimError::InvalidParameter`] when scan times
    /// do not strictly increase (the value is the offending time).
    pub fn from_scans(scans: &[TrackScan]) -> Result<Self, SimError> {
        if scans.is_empty() {
            return Err(SimError::Empty {
                what: "track scans",
            });
        }
        for w in scans.windows(2) {
            if w[1].time <= w[0].time {
                return Err(SimError::InvalidParameter {
                    what: "track scan time",
                    value: w[1].time,
                    reason: "scan times must strictly increase",
                });
            }
        }
        let mut first_seen: BTreeMap<TargetId, f64> = BTreeMap::new();
        let mut first_tracked: HashMap<TargetId, f64> = HashMap::new();
        let mut last_track: HashMap<TargetId, u64> = HashMap::new();
        let mut tracked_prev: HashMap<TargetId, bool> = HashMap::new();
        let mut ever_assigned: BTreeSet<u64> = BTreeSet::new();
        let mut seen_tracks: BTreeSet<u64> = BTreeSet::new();
        let (mut breaks, mut id_swaps, mut false_track_scans) = (0, 0, 0);
        for scan in scans {
            let assigned: HashMap<TargetId, u64> =
                scan.pairs.iter().map(|&(tr, g)| (g, tr)).collect();
            for &g in &scan.truths {
                first_seen.entry(g).or_insert(scan.time);
                let now = assigned.get(&g).copied();
                if tracked_prev.get(&g).copied().unwrap_or(false) && now.is_none() {
                    breaks += 1;
                }
                if let Some(tr) = now {
                    first_tracked.entry(g).or_insert(scan.time);
                    if let Some(prev) = last_track.insert(g, tr)
                        && prev != tr
                    {
                        id_swaps += 1;
                    }
                }
                tracked_prev.insert(g, now.is_some());
            }
            // A truth absent from this scan starts afresh when it reappears.
            tracked_prev.retain(|g, _| scan.truths.contains(g));
            seen_tracks.extend(scan.tracks.iter().copied());
            ever_assigned.extend(scan.pairs.iter().map(|p| p.0));
            false_track_scans += scan.tracks.len() - scan.pairs.len();
        }
        let time_to_confirm = first_seen
            .iter()
            .map(|(g, &t0)| (*g, first_tracked.get(g).map(|&t| t - t0)))
            .collect();
        Ok(Self {
            scans: scans.len(),
            breaks,
            id_swaps,
            time_to_confirm,
            false_track_scans,
            false_tracks_per_scan: false_track_scans as f64 / scans.len() as f64,
            false_track_ids: seen_tracks.difference(&ever_assigned).count(),
            tracks_seen: seen_tracks.len(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const A: TargetId = TargetId(1);
    const B: TargetId = TargetId(2);

    fn scan(t: f64, truths: &[TargetId], tracks: &[u64], pairs: &[(u64, TargetId)]) -> TrackScan {
        TrackScan::new(t, truths.to_vec(), tracks.to_vec(), pairs.to_vec()).unwrap()
    }

    #[test]
    fn statistics_by_hand() {
        // Scans 5 s apart; truths A (from t = 0) and B (from t = 5).
        // t=0:  A untracked;             track 7 false.
        // t=5:  A←10, B untracked;       7 false.
        // t=10: A←10, B←11.
        // t=15: A untracked (break of A), B←11.
        // t=20: A←12 (swap: last was 10), B←10 (swap: last was 11); 13 false.
        // t=25: A←12, B untracked (break of B); 10 false.
        // Breaks 2, swaps 2; time to confirm A: 5 − 0 = 5 s, B: 10 − 5 = 5 s.
        // False track-scans: 1 + 1 + 0 + 0 + 1 + 1 = 4 over 6 scans; tracks never
        // assigned: {7, 13} → 2 of 5 seen ({7, 10, 11, 12, 13}).
        let scans = [
            scan(0.0, &[A], &[7], &[]),
            scan(5.0, &[A, B], &[7, 10], &[(10, A)]),
            scan(10.0, &[A, B], &[10, 11], &[(10, A), (11, B)]),
            scan(15.0, &[A, B], &[11], &[(11, B)]),
            scan(20.0, &[A, B], &[10, 12, 13], &[(12, A), (10, B)]),
            scan(25.0, &[A, B], &[12, 10], &[(12, A)]),
        ];
        let s = TrackStatistics::from_scans(&scans).unwrap();
        assert_eq!(s.scans, 6);
        assert_eq!(s.breaks, 2);
        assert_eq!(s.id_swaps, 2);
        assert_eq!(s.time_to_confirm, vec![(A, Some(5.0)), (B, Some(5.0))]);
        assert_eq!(s.false_track_scans, 4);
        assert!((s.false_tracks_per_scan - 4.0 / 6.0).abs() < 1e-15);
        assert_eq!(s.false_track_ids, 2);
        assert_eq!(s.tracks_seen, 5);
    }

    #[test]
    fn truth_leaving_is_not_a_break_and_never_tracked_has_no_confirm_time() {
        // A tracked at t=0, gone at t=1 (no break), back untracked at t=2 (no break:
        // it was absent in between). B is never tracked.
        let scans = [
            scan(0.0, &[A, B], &[1], &[(1, A)]),
            scan(1.0, &[B], &[], &[]),
            scan(2.0, &[A, B], &[], &[]),
        ];
        let s = TrackStatistics::from_scans(&scans).unwrap();
        assert_eq!(s.breaks, 0);
        assert_eq!(s.time_to_confirm, vec![(A, Some(0.0)), (B, None)]);
    }

    #[test]
    fn assign_by_position_is_optimal_and_limited() {
        // Truths A at x = 0, B at x = 2; tracks 1 at x = 1.5, 2 at x = 4, 3 at x = 50.
        // Optimal: A↔1 (1.5) and B↔2 (2) = 3.5, not B↔1 (0.5) + A↔2 (4) = 4.5;
        // track 3 is beyond the 10 m limit and stays unassigned.
        let v = |x: f64| Vector::<2>::new(x, 0.0);
        let s = TrackScan::assign(
            0.0,
            &[(A, v(0.0)), (B, v(2.0))],
            &[(1, v(1.5)), (2, v(4.0)), (3, v(50.0))],
            10.0,
        )
        .unwrap();
        let mut pairs = s.pairs().to_vec();
        pairs.sort();
        assert_eq!(pairs, vec![(1, A), (2, B)]);
    }

    #[test]
    fn rejects_bad_scans() {
        assert!(TrackScan::new(f64::NAN, vec![], vec![], vec![]).is_err());
        assert!(TrackScan::new(0.0, vec![A, A], vec![], vec![]).is_err());
        assert!(TrackScan::new(0.0, vec![A], vec![1, 1], vec![]).is_err());
        assert!(TrackScan::new(0.0, vec![A], vec![1], vec![(2, A)]).is_err());
        assert!(TrackScan::new(0.0, vec![A], vec![1, 2], vec![(1, A), (2, A)]).is_err());
        assert!(TrackStatistics::from_scans(&[]).is_err());
        let s = [scan(1.0, &[], &[], &[]), scan(1.0, &[], &[], &[])];
        assert!(matches!(
            TrackStatistics::from_scans(&s),
            Err(SimError::InvalidParameter {
                what: "track scan time",
                ..
            })
        ));
        let p = Vector::<2>::new(f64::NAN, 0.0);
        assert!(TrackScan::assign(0.0, &[(A, p)], &[(1, p)], 1.0).is_err());
        assert!(TrackScan::assign::<2>(0.0, &[], &[], 0.0).is_err());
    }
}

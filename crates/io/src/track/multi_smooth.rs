//! Smoothing the multi-target tracker's tracks (`argus track --smooth` with a `[tracker]`
//! table): every track that was confirmed at some scan is smoothed over its own life,
//! from its rows, by the tracker's one smoother of its tracks
//! ([`argus_tracker::smooth::TrackSmoother`], whose docs say what is smoothed for each
//! estimator and in which sense it is exact). The smoothed mode probabilities go to
//! `mu_1s, mu_2s` (`mu_1s … mu_3s` for the aircraft IMM).
//!
//! Which rows: a smoothed track's rows from its first (the tentative ones included) to
//! its last before deletion; a track's `deleted` row and every row of a track never
//! confirmed have empty smoothed cells.

use std::collections::BTreeMap;

use crate::rows::{Column, TrackRows};
use argus_tracker::smooth::{FilteredRow, SmoothedRow, Smoothing, TrackSmoother};
use argus_tracker::{SensorId, TrackSnapshot, TrackStatus, TrackerConfig};

use super::smooth::SmoothFailure as _;
use super::tally::push_track;
use crate::IoError;

/// The rows of a run kept for smoothing (each track's snapshot with the sensor of its
/// scan), and the tracks' smoother.
#[derive(Debug)]
pub(super) struct Recorded {
    rows: Vec<(SensorId, TrackSnapshot)>,
    smoother: TrackSmoother,
}

impl Recorded {
    /// An empty record for the tracker configured by `c`.
    ///
    /// # Errors
    /// [`IoError::Tracker`] for a bad `sigma_a`, IMM or tuning (already refused by the
    /// configuration).
    pub(super) fn new(c: &TrackerConfig) -> Result<Self, IoError> {
        Ok(Self {
            rows: Vec::new(),
            smoother: TrackSmoother::new(c)?,
        })
    }

    /// The smoothed columns: `xs, vxs, ys, vys, sigma_xs, sigma_ys`, and `mu_1s, mu_2s`
    /// for the IMM (`mu_1s … mu_3s` for the aircraft IMM).
    pub(super) fn columns(&self) -> Vec<Column> {
        Column::smoothed_tracker(self.smoother.mode_count())
    }

    /// Keeps the row of `track` from the scan of `sensor`.
    pub(super) fn push(&mut self, sensor: SensorId, track: TrackSnapshot) {
        self.rows.push((sensor, track));
    }

    /// Smooths every track confirmed at some scan and writes every row, in order, to
    /// `out`; returns the number of tracks smoothed.
    ///
    /// # Errors
    /// [`IoError::Smooth`] naming the track and step of the first failure (nothing is
    /// written).
    pub(super) fn smooth_into(self, how: Smoothing, out: &mut TrackRows) -> Result<usize, IoError> {
        let rows = self.rows;
        let mut by_track: BTreeMap<u64, Vec<usize>> = BTreeMap::new();
        for (i, (_, r)) in rows.iter().enumerate() {
            by_track.entry(r.id.0).or_default().push(i);
        }
        let mut smoothed: Vec<Option<SmoothedRow>> = vec![None; rows.len()];
        let mut count = 0;
        for (id, idx) in by_track {
            if !idx
                .iter()
                .any(|&i| rows[i].1.status == TrackStatus::Confirmed)
            {
                continue;
            }
            let live: Vec<usize> = idx
                .into_iter()
                .filter(|&i| rows[i].1.status != TrackStatus::Deleted)
                .collect();
            let filtered: Vec<FilteredRow<'_>> = live
                .iter()
                .map(|&i| FilteredRow {
                    time: rows[i].1.time,
                    estimate: &rows[i].1.estimate,
                    state: &rows[i].1.state,
                })
                .collect();
            let s = self
                .smoother
                .smooth(&filtered, how)
                .map_err(|f| f.into_cli(id))?;
            for (&i, g) in live.iter().zip(s) {
                smoothed[i] = Some(g);
            }
            count += 1;
        }
        for ((sensor, track), s) in rows.iter().zip(&smoothed) {
            push_track(out, *sensor, track, s.as_ref());
        }
        Ok(count)
    }
}

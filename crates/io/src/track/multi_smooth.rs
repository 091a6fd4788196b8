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

use crate::rows::{Column, Point, TrackRows};
use argus_core_math::Gaussian;
use argus_imm::NoiseVariances;
use argus_tracker::smooth::{FilteredRow, SmoothedRow, Smoothing, TrackSmoother};
use argus_tracker::{
    DeletionReason, EstimatorState, ModeProbabilities, SensorId, TrackSnapshot, TrackStatus,
    TrackerConfig,
};

use super::names::{reason_name, status_name};
use super::smooth::SmoothFailure as _;
use crate::IoError;

/// One row as the tracker gave it.
#[derive(Debug, Clone)]
struct Row {
    sensor: u32,
    track: u64,
    status: TrackStatus,
    reason: Option<DeletionReason>,
    time: f64,
    estimate: Gaussian<4>,
    modes: Option<ModeProbabilities>,
    noise: Option<NoiseVariances>,
    score: f64,
    /// The estimator state (the IMMs' modes), for the smoother.
    state: EstimatorState,
    /// The aircraft IMM's turn rate and its σ (rad/s).
    turn_rate: Option<(f64, f64)>,
}

/// The rows of a run kept for smoothing, and the tracks' smoother.
#[derive(Debug)]
pub(super) struct Recorded {
    rows: Vec<Row>,
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
        let modes = track.mode_probabilities();
        let noise = track.noise_estimate();
        let turn_rate = track.turn_rate();
        self.rows.push(Row {
            sensor: sensor.0,
            track: track.id.0,
            status: track.status,
            reason: track.deletion,
            time: track.time,
            estimate: track.estimate,
            modes,
            noise,
            score: track.score,
            state: track.state,
            turn_rate,
        });
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
        for (i, r) in rows.iter().enumerate() {
            by_track.entry(r.track).or_default().push(i);
        }
        let mut smoothed: Vec<Option<SmoothedRow>> = vec![None; rows.len()];
        let mut count = 0;
        for (id, idx) in by_track {
            if !idx
                .iter()
                .any(|&i| rows[i].status == TrackStatus::Confirmed)
            {
                continue;
            }
            let live: Vec<usize> = idx
                .into_iter()
                .filter(|&i| rows[i].status != TrackStatus::Deleted)
                .collect();
            let filtered: Vec<FilteredRow<'_>> = live
                .iter()
                .map(|&i| FilteredRow {
                    time: rows[i].time,
                    estimate: &rows[i].estimate,
                    state: &rows[i].state,
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
        for (r, s) in rows.iter().zip(&smoothed) {
            let reason = r.reason.map_or("", reason_name);
            let p = Point::new(r.time, &r.estimate)
                .of_track(r.sensor, r.track, status_name(r.status), reason)
                .modes(r.modes.as_ref().map(|m| m.as_slice()))
                .noise(r.noise)
                .turn_rate(r.turn_rate)
                .score(r.score)
                .smoothed(s.as_ref().map(|s| &s.estimate))
                .smoothed_modes(s.as_ref().and_then(|s| s.modes.as_deref()));
            out.push(&p);
        }
        Ok(count)
    }
}

//! What the tracker's reports add up to over a run (the summary's counts), and the rows
//! they give: written to the tracks CSV, or kept for smoothing ([`Recorded`]).

use std::collections::BTreeMap;

use crate::rows::{Point, TrackRows};
use argus_tracker::smooth::SmoothedRow;
use argus_tracker::{Concluded, DeletionReason, SensorId, TrackSnapshot, TrackStatus};

use super::multi_smooth::Recorded;
use super::names::{reason_name, status_name};

/// Every deletion reason, for the summary's zero counts.
const REASONS: [DeletionReason; 5] = [
    DeletionReason::NotConfirmed,
    DeletionReason::Misses,
    DeletionReason::CovarianceGrowth,
    DeletionReason::FilterFailure,
    DeletionReason::Score,
];

/// Track counts over the run, for the summary.
#[derive(Debug, Default, serde::Serialize)]
pub(super) struct Counts {
    pub(super) initiated: usize,
    pub(super) confirmed: usize,
    pub(super) deleted: usize,
    pub(super) deleted_by_reason: BTreeMap<&'static str, usize>,
    pub(super) deleted_after_confirmation: usize,
    pub(super) tentative_at_end: usize,
    pub(super) confirmed_at_end: usize,
}

/// What the reports add up to, and the rows they give.
pub(super) struct Tally<'a> {
    pub(super) out: &'a mut TrackRows,
    /// The smoothing recorder (`--smooth`): rows go there instead.
    recorded: Option<&'a mut Recorded>,
    pub(super) counts: Counts,
    pub(super) scans: usize,
    pub(super) assigned: usize,
}

impl<'a> Tally<'a> {
    /// A tally writing its rows to `out`, or to `recorded` for smoothing.
    pub(super) fn new(out: &'a mut TrackRows, recorded: Option<&'a mut Recorded>) -> Self {
        Self {
            out,
            recorded,
            counts: Counts {
                deleted_by_reason: REASONS.iter().map(|r| (reason_name(*r), 0)).collect(),
                ..Counts::default()
            },
            scans: 0,
            assigned: 0,
        }
    }

    /// Counts one concluded scan or sector and writes its rows (the session's: every
    /// track of a synchronous scan; the tracks a sector visited, initiated and deleted; in
    /// id order).
    pub(super) fn record(&mut self, concluded: Concluded) {
        let Concluded { report, rows } = concluded;
        self.scans += 1;
        self.assigned += report.assigned;
        let counts = &mut self.counts;
        counts.initiated += report.initiated.len();
        counts.confirmed += report.confirmed.len();
        counts.deleted += report.deleted.len();
        for d in rows.iter().filter(|r| r.status == TrackStatus::Deleted) {
            if let Some(r) = d.deletion {
                *counts.deleted_by_reason.entry(reason_name(r)).or_insert(0) += 1;
            }
            if d.confirmed_at.is_some() {
                counts.deleted_after_confirmation += 1;
            }
        }
        for tr in rows {
            row(self.out, self.recorded.as_deref_mut(), report.sensor, tr);
        }
    }

    /// Counts the tracks live at the end.
    pub(super) fn end(&mut self, tracks: &[TrackSnapshot]) {
        for tr in tracks {
            match tr.status {
                TrackStatus::Tentative => self.counts.tentative_at_end += 1,
                TrackStatus::Confirmed => self.counts.confirmed_at_end += 1,
                TrackStatus::Deleted => {}
            }
        }
    }
}

/// One row: the track's state at its time, as produced by the scan of `sensor`; with
/// smoothing, kept until the end of the run ([`Recorded`]).
pub(super) fn row(
    out: &mut TrackRows,
    rec: Option<&mut Recorded>,
    sensor: SensorId,
    track: TrackSnapshot,
) {
    if let Some(rec) = rec {
        rec.push(sensor, track);
        return;
    }
    push_track(out, sensor, &track, None);
}

/// Writes the row of `track` from the scan of `sensor`, with its smoothed values when
/// it was smoothed (empty smoothed cells otherwise).
pub(super) fn push_track(
    out: &mut TrackRows,
    sensor: SensorId,
    track: &TrackSnapshot,
    smoothed: Option<&SmoothedRow>,
) {
    let reason = track.deletion.map_or("", reason_name);
    let mu = track.mode_probabilities();
    let p = Point::new(track.time, &track.estimate)
        .of_track(sensor.0, track.id.0, status_name(track.status), reason)
        .modes(mu.as_ref().map(|m| m.as_slice()))
        .noise(track.noise_estimate())
        .turn_rate(track.turn_rate())
        .score(track.score)
        .smoothed(smoothed.map(|s| &s.estimate))
        .smoothed_modes(smoothed.and_then(|s| s.modes.as_deref()));
    out.push(&p);
}

//! What a [`super::Session`] gives back: a value per concluded scan or sector, with one
//! snapshot per track, and the tracks left at the end.

use argus_core_math::Gaussian;
use argus_imm::NoiseVariances;

use crate::{
    DeletionReason, EstimatorState, ModeProbabilities, Plot, ScanReport, Track, TrackId,
    TrackStatus, Tracker,
};

/// One output value of [`super::Session::push`].
#[derive(Debug, Clone, PartialEq)]
pub enum Output {
    /// A scan or a sector concluded.
    Scan(Concluded),
    /// The end of the stream ([`super::Input::End`]): the live tracks (tentative and
    /// confirmed), in id order; each snapshot's event is its last step's,
    /// [`TrackEvent::Updated`] or [`TrackEvent::Missed`].
    End(Vec<TrackSnapshot>),
}

/// A concluded scan of a synchronous sensor, or sector of a rotating one: the tracker's
/// report and the tracks' rows.
#[derive(Debug, Clone, PartialEq)]
pub struct Concluded {
    /// What the scan or sector did: its sensor, whether it is a sector, its span
    /// (`start`, `time`), the plots assigned, the ids initiated, confirmed, deleted and
    /// (a sector) visited.
    pub report: ScanReport,
    /// One snapshot per track, in id order: every track of a synchronous scan; for a
    /// sector, the tracks it visited (updated or missed), initiated and deleted (a deleted
    /// one in its id's place). Each as the tracker left it after the call that concluded
    /// the scan (when one call concludes several sectors, two radars' sectors ending at
    /// one time or [`super::Input::End`]'s flush, the later ones' steps show in the
    /// earlier one's rows, and the tracks deleted in any of them are among the first's
    /// rows: what `argus track` writes).
    pub rows: Vec<TrackSnapshot>,
}

/// What happened to a track in the step a snapshot shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TrackEvent {
    /// Initiated (from two plots; confirmed at once when `confirm_m = 2`).
    Started,
    /// Updated by a plot.
    Updated,
    /// No plot: it coasts on its prediction.
    Missed,
    /// Confirmed (by this step's plot, or by its score).
    Confirmed,
    /// Deleted ([`TrackSnapshot::deletion`] says why).
    Deleted,
}

/// One track as a scan or sector left it: a value, nothing borrowed from the tracker.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackSnapshot {
    /// Its id.
    pub id: TrackId,
    /// Its status.
    pub status: TrackStatus,
    /// The time of its estimate (s).
    pub time: f64,
    /// The estimate `[x, vx, y, vy]` ([`Track::estimate`]).
    pub estimate: Gaussian<4>,
    /// The estimator's state ([`Track::state`]).
    pub state: EstimatorState,
    /// Its track score ([`Track::score`]).
    pub score: f64,
    /// Why it was deleted, when it was.
    pub deletion: Option<DeletionReason>,
    /// When it was confirmed, if it was.
    pub confirmed_at: Option<f64>,
    /// What happened to it in this step.
    pub event: TrackEvent,
    /// The plot of this step ([`Track::plot`]): the one that updated it, its second
    /// initiating plot when started, `None` after a miss.
    pub plot: Option<Plot>,
}

impl TrackSnapshot {
    /// The snapshot of `track`, whose step was `event`.
    #[must_use]
    pub fn of(track: &Track, event: TrackEvent) -> Self {
        Self {
            id: track.id(),
            status: track.status(),
            time: track.time(),
            estimate: *track.estimate(),
            state: track.state().clone(),
            score: track.score(),
            deletion: track.deletion(),
            confirmed_at: track.confirmed_at(),
            event,
            plot: track.plot().copied(),
        }
    }

    /// The IMM mode probabilities ([`EstimatorState::mode_probabilities`]).
    #[must_use]
    pub fn mode_probabilities(&self) -> Option<ModeProbabilities> {
        self.state.mode_probabilities()
    }

    /// The multi-IMM's noise estimate ([`EstimatorState::noise_estimate`]).
    #[must_use]
    pub fn noise_estimate(&self) -> Option<NoiseVariances> {
        self.state.noise_estimate()
    }

    /// The aircraft IMM's turn rate and its σ ([`EstimatorState::turn_rate`]).
    #[must_use]
    pub fn turn_rate(&self) -> Option<(f64, f64)> {
        self.state.turn_rate()
    }
}

/// The event of `track` in the step of `report`.
fn event(track: &Track, report: &ScanReport) -> TrackEvent {
    if track.status() == TrackStatus::Deleted {
        TrackEvent::Deleted
    } else if report.initiated.contains(&track.id()) {
        TrackEvent::Started
    } else if report.confirmed.contains(&track.id()) {
        TrackEvent::Confirmed
    } else {
        last_step(track)
    }
}

/// A live track's last step: updated or missed.
pub(super) fn last_step(track: &Track) -> TrackEvent {
    if track.plot().is_some() {
        TrackEvent::Updated
    } else {
        TrackEvent::Missed
    }
}

impl Concluded {
    /// The rows of `report`, just returned by `tracker`: its deleted tracks taken
    /// ([`Tracker::take_deleted`]) with the live ones the report concerns.
    pub(super) fn new(tracker: &mut Tracker, report: ScanReport) -> Self {
        let deleted = tracker.take_deleted();
        let mut all: Vec<&Track> = tracker
            .tracks()
            .iter()
            .filter(|tr| {
                !report.sector
                    || report.visited.binary_search(&tr.id()).is_ok()
                    || report.initiated.contains(&tr.id())
            })
            .chain(&deleted)
            .collect();
        all.sort_by_key(|tr| tr.id());
        let rows = all
            .into_iter()
            .map(|tr| TrackSnapshot::of(tr, event(tr, &report)))
            .collect();
        Self { report, rows }
    }
}

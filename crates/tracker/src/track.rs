//! Tracks, their ids and statuses.

use argus_core_math::Gaussian;

use crate::Plot;
use crate::state::EstimatorState;

/// A track's id: numbered from 0 in order of initiation and never reused.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct TrackId(pub u64);

/// Where a track is in its life.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TrackStatus {
    /// Initiated from two plots, not yet confirmed.
    Tentative,
    /// Confirmed by M of N.
    Confirmed,
    /// Deleted; it will never be updated again.
    Deleted,
}

/// Why a track was deleted.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DeletionReason {
    /// A tentative track could no longer reach M hits in its first N opportunities.
    NotConfirmed,
    /// A confirmed track missed `max_misses` scans in a row.
    Misses,
    /// Its position standard deviation exceeded `max_position_sigma`.
    CovarianceGrowth,
    /// Its filter step failed numerically (the other tracks are unaffected).
    FilterFailure,
    /// Its track score fell below the SPRT deletion threshold (tentative) or too far
    /// below its peak (confirmed).
    Score,
}

/// One track: a CV estimate `[x, vx, y, vy]` with its history counters.
#[derive(Debug, Clone, PartialEq)]
pub struct Track {
    pub(crate) id: TrackId,
    pub(crate) status: TrackStatus,
    pub(crate) estimate: Gaussian<4>,
    pub(crate) time: f64,
    pub(crate) initiated: f64,
    pub(crate) confirmed_at: Option<f64>,
    pub(crate) opportunities: u32,
    pub(crate) hits: u32,
    pub(crate) consecutive_misses: u32,
    pub(crate) deletion: Option<DeletionReason>,
    pub(crate) last_hit: bool,
    pub(crate) score: f64,
    pub(crate) peak_score: f64,
    pub(crate) state: EstimatorState,
    /// The plot of its last step ([`Track::plot`]).
    pub(crate) plot: Option<Plot>,
    /// Per sensor index, what rotating sensors know of this track (empty until one
    /// looks at it; missing entries: never looked at).
    pub(crate) looks: Vec<Look>,
    /// Incremented at every change of the estimate (so that a [`Look`]'s hint computed
    /// from an older estimate is not used).
    pub(crate) revision: u64,
}

/// A rotating sensor's memory of one track.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Look {
    /// The time of its last opportunity from the sensor (−∞: none yet).
    pub(crate) visited: f64,
    /// No sector ending at or before this time sweeps its gate (valid for
    /// [`Look::revision`] only).
    pub(crate) quiet_until: f64,
    /// The track's revision when `quiet_until` was computed.
    pub(crate) revision: u64,
}

impl Look {
    /// Nothing known.
    pub(crate) const NONE: Self = Self {
        visited: f64::NEG_INFINITY,
        quiet_until: f64::NEG_INFINITY,
        revision: u64::MAX,
    };
}

impl Track {
    /// Its id.
    #[must_use]
    pub fn id(&self) -> TrackId {
        self.id
    }

    /// Its status.
    #[must_use]
    pub fn status(&self) -> TrackStatus {
        self.status
    }

    /// The estimate `[x, vx, y, vy]` at [`Track::time`] (updated when the last scan
    /// had a plot for it, predicted otherwise; the moment-matched one for an IMM).
    #[must_use]
    pub fn estimate(&self) -> &Gaussian<4> {
        &self.estimate
    }

    /// The time of the estimate (s): the last scan it took part in.
    #[must_use]
    pub fn time(&self) -> f64 {
        self.time
    }

    /// When it was initiated (time of its second plot).
    #[must_use]
    pub fn initiated(&self) -> f64 {
        self.initiated
    }

    /// When it was confirmed, if it was.
    #[must_use]
    pub fn confirmed_at(&self) -> Option<f64> {
        self.confirmed_at
    }

    /// Scans it took part in, counting its two initiating plots.
    #[must_use]
    pub fn opportunities(&self) -> u32 {
        self.opportunities
    }

    /// Plots assigned to it, counting its two initiating plots.
    #[must_use]
    pub fn hits(&self) -> u32 {
        self.hits
    }

    /// Misses since its last plot.
    #[must_use]
    pub fn consecutive_misses(&self) -> u32 {
        self.consecutive_misses
    }

    /// Whether the last scan it took part in gave it a plot.
    #[must_use]
    pub fn last_hit(&self) -> bool {
        self.last_hit
    }

    /// The estimator's state at [`Track::time`] besides [`Track::estimate`] (its mode
    /// probabilities, noise estimate, turn rate, mode-conditioned estimates): a borrow,
    /// nothing copied or allocated.
    #[must_use]
    pub fn state(&self) -> &EstimatorState {
        &self.state
    }

    /// The plot of its last step: the one that updated it (with JPDA, the most probable
    /// of the plots it was weighed with), its second initiating plot in the step that
    /// started it, `None` after a miss.
    #[must_use]
    pub fn plot(&self) -> Option<&Plot> {
        self.plot.as_ref()
    }

    /// Its track score (log-likelihood ratio), kept when
    /// [`crate::TrackerConfig::score`] is set, 0 otherwise.
    #[must_use]
    pub fn score(&self) -> f64 {
        self.score
    }

    /// Why it was deleted, when it was.
    #[must_use]
    pub fn deletion(&self) -> Option<DeletionReason> {
        self.deletion
    }
}

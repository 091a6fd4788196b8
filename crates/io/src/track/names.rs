//! The names a track's status and deletion reason have in the tracks CSV and the summary.

use argus_tracker::{DeletionReason, TrackStatus};

/// The CSV name of a status.
pub(super) fn status_name(s: TrackStatus) -> &'static str {
    match s {
        TrackStatus::Tentative => "tentative",
        TrackStatus::Confirmed => "confirmed",
        TrackStatus::Deleted => "deleted",
    }
}

/// The CSV and JSON name of a deletion reason.
pub(super) fn reason_name(r: DeletionReason) -> &'static str {
    match r {
        DeletionReason::NotConfirmed => "not-confirmed",
        DeletionReason::Misses => "misses",
        DeletionReason::CovarianceGrowth => "covariance-growth",
        DeletionReason::FilterFailure => "filter-failure",
        DeletionReason::Score => "score",
    }
}

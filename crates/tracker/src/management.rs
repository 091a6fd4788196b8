//! Track management: hits and misses, confirmation and deletion (M of N, or the score).

use argus_core_math::Matrix;

use crate::{DeletionReason, Track, TrackStatus, TrackerConfig};

impl Track {
    pub(crate) fn delete(&mut self, reason: DeletionReason) {
        self.status = TrackStatus::Deleted;
        self.deletion = Some(reason);
    }

    /// Counts one opportunity; returns the new status when it changed.
    pub(crate) fn count(&mut self, hit: bool, cfg: &TrackerConfig) -> Option<TrackStatus> {
        self.opportunities += 1;
        self.last_hit = hit;
        if hit {
            self.hits += 1;
            self.consecutive_misses = 0;
        } else {
            self.consecutive_misses += 1;
        }
        if worst_position_sigma(self.estimate.cov()) > cfg.max_position_sigma {
            self.delete(DeletionReason::CovarianceGrowth);
            return Some(TrackStatus::Deleted);
        }
        if let Some(sc) = &cfg.score {
            return self.count_score(sc, cfg);
        }
        match self.status {
            TrackStatus::Tentative => {
                if self.hits >= cfg.confirm_m {
                    self.status = TrackStatus::Confirmed;
                    self.confirmed_at = Some(self.time);
                    Some(TrackStatus::Confirmed)
                } else if i64::from(self.hits) + i64::from(cfg.confirm_n)
                    - i64::from(self.opportunities)
                    < i64::from(cfg.confirm_m)
                {
                    self.delete(DeletionReason::NotConfirmed);
                    Some(TrackStatus::Deleted)
                } else {
                    None
                }
            }
            TrackStatus::Confirmed if self.consecutive_misses >= cfg.max_misses => {
                self.delete(DeletionReason::Misses);
                Some(TrackStatus::Deleted)
            }
            _ => None,
        }
    }
}

impl Track {
    /// Status change by track score (see [`crate::ScoreConfig`]).
    fn count_score(&mut self, sc: &crate::ScoreConfig, cfg: &TrackerConfig) -> Option<TrackStatus> {
        match self.status {
            TrackStatus::Tentative if self.score >= sc.confirm_threshold() => {
                self.status = TrackStatus::Confirmed;
                self.confirmed_at = Some(self.time);
                Some(TrackStatus::Confirmed)
            }
            TrackStatus::Tentative if self.score <= sc.delete_threshold() => {
                self.delete(DeletionReason::Score);
                Some(TrackStatus::Deleted)
            }
            TrackStatus::Confirmed if self.peak_score - self.score >= sc.delete_drop => {
                self.delete(DeletionReason::Score);
                Some(TrackStatus::Deleted)
            }
            TrackStatus::Confirmed if self.consecutive_misses >= cfg.max_misses => {
                self.delete(DeletionReason::Misses);
                Some(TrackStatus::Deleted)
            }
            _ => None,
        }
    }
}

/// Square root of the largest eigenvalue of the position block of `[x, vx, y, vy]`.
fn worst_position_sigma(p: &Matrix<4, 4>) -> f64 {
    let (a, b, c) = (p[(0, 0)], p[(0, 2)], p[(2, 2)]);
    let half = 0.5 * (a - c);
    (0.5 * (a + c) + (half * half + b * b).sqrt()).sqrt()
}

//! `argus track --smooth` (fixed interval), `--smooth-lag N` and `--smooth-lag-seconds S`
//! (fixed lag): the smoothing is `argus_tracker::smooth`'s (what is smoothed, why it is
//! exact, the fixed lag's windows); here, its failure as the command's error.
//!
//! A track is smoothed whole or not at all: a failed step is a [`Failure`] naming the
//! step (0 is the track's first estimate) and its time, and the command stops with
//! [`IoError::Smooth`] naming the track; nothing is written.

use argus_tracker::smooth::Failure;
pub(super) use argus_tracker::smooth::Smoothing;

use crate::IoError;

/// A smoothing [`Failure`] as the command's error.
pub(super) trait SmoothFailure {
    /// The command's error for track `track`.
    fn into_cli(self, track: u64) -> IoError;
}

impl SmoothFailure for Failure {
    fn into_cli(self, track: u64) -> IoError {
        IoError::Smooth {
            track,
            step: self.step(),
            time: self.time(),
            message: self.message().to_owned(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failure_names_the_track_step_and_time() {
        let cli = Failure::new(5, 1.0, "time 1 s does not follow".to_owned())
            .into_cli(7)
            .to_string();
        assert_eq!(
            cli,
            "smoothing track 7: step 5 (t = 1 s): time 1 s does not follow"
        );
    }
}

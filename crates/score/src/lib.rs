//! Scoring tracks against truth as the field does it.
//!
//! On a regular time grid, truth is interpolated linearly and each confirmed track's last
//! row is predicted with constant velocity; confirmed tracks are assigned to truths by the
//! optimal assignment with a distance cut-off (as Stone Soup's SIAP metrics associate
//! tracks to truth); the assignments give completeness, spurious track time, track breaks
//! per aircraft-hour, identity swaps, position and velocity RMSE, the 95th-percentile
//! position error, time to confirm, SIAP's longest segment and rate of track-number change,
//! and GOSPA with its localisation / missed / false parts, in total and over time.
//! Every definition, and where it differs from SIAP, is in `docs/scoring.md`.
//!
//! The assignment ([`argus_sim::TrackScan::assign`]), GOSPA ([`argus_sim::Gospa`]) and the
//! break / swap / time-to-confirm reduction ([`argus_sim::TrackStatistics`]) are
//! `argus-sim`'s, so the surveillance scenario and this crate count the same way.
//!
//! # Example
//! ```
//! use argus_score::{ScoreConfig, Scorer, read_tracks_from, read_truth_from};
//!
//! let truth = "t,target,x,vx,y,vy\n0,A,0,10,0,0\n10,A,100,10,0,0\n";
//! let tracks = "t,track,status,x,vx,y,vy\n0,7,confirmed,3,10,4,0\n";
//! let truth = read_truth_from(truth.as_bytes(), "truth.csv")?;
//! let tracks = read_tracks_from(tracks.as_bytes(), "tracks.csv")?;
//! let scorer = Scorer::new(ScoreConfig { step: 5.0, ..ScoreConfig::default() })?;
//! let score = scorer.score(&tracks, &truth)?;
//! // Grid 0, 5, 10 s; the track (5 m off) is present at 0, 5 and 10 (age ≤ 15 s).
//! assert_eq!(score.summary.completeness, Some(1.0));
//! assert!((score.summary.position_rmse.unwrap() - 5.0).abs() < 1e-9);
//! # Ok::<(), argus_score::ScoreError>(())
//! ```

mod assign;
mod config;
mod error;
mod grid;
mod input;
mod read;
mod report;
mod score;

pub use config::{MAX_GRID_STEPS, ScoreConfig, Scorer};
pub use error::ScoreError;
pub use input::{TrackHistory, TrackRow, TruthPath, TruthSample};
pub use read::{
    Cell, Column, read_tracks, read_tracks_columns, read_tracks_from, read_truth,
    read_truth_columns, read_truth_from,
};
pub use report::{GridPoint, Score, Summary, TruthScore};

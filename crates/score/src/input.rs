//! What is scored: truth paths (time-ordered samples per aircraft) and track histories
//! (time-ordered rows per track), both in the local horizontal plane.

use crate::error::ScoreError;

/// One truth sample: time (s), position (m) and velocity (m/s) in the local plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TruthSample {
    /// Time, s.
    pub t: f64,
    /// East (or local x), m.
    pub x: f64,
    /// x velocity, m/s.
    pub vx: f64,
    /// North (or local y), m.
    pub y: f64,
    /// y velocity, m/s.
    pub vy: f64,
}

/// One aircraft's truth: its name (the file's `target` value) and samples at strictly
/// increasing times.
#[derive(Debug, Clone, PartialEq)]
pub struct TruthPath {
    name: String,
    samples: Vec<TruthSample>,
}

impl TruthPath {
    /// A truth path from its samples.
    ///
    /// # Errors
    /// [`ScoreError::InvalidInput`] for no sample, a non-finite value, or times that do not
    /// strictly increase.
    pub fn new(name: impl Into<String>, samples: Vec<TruthSample>) -> Result<Self, ScoreError> {
        let name = name.into();
        let bad = |reason| ScoreError::InvalidInput {
            what: "truth path",
            name: name.clone(),
            reason,
        };
        if samples.is_empty() {
            return Err(bad("no sample"));
        }
        if samples
            .iter()
            .any(|s| ![s.t, s.x, s.vx, s.y, s.vy].iter().all(|v| v.is_finite()))
        {
            return Err(bad("a sample has a non-finite value"));
        }
        if samples.windows(2).any(|w| w[1].t <= w[0].t) {
            return Err(bad("sample times must strictly increase"));
        }
        Ok(Self { name, samples })
    }

    /// The name (the `target` value).
    #[must_use]
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The samples, in time order.
    #[must_use]
    pub fn samples(&self) -> &[TruthSample] {
        &self.samples
    }
}

/// One row of a track: time, whether the track was confirmed, state `[x, vx, y, vy]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackRow {
    /// Time of the estimate, s.
    pub t: f64,
    /// `true` for `status = confirmed` (or a file without a `status` column).
    pub confirmed: bool,
    /// x, m.
    pub x: f64,
    /// x velocity, m/s.
    pub vx: f64,
    /// y, m.
    pub y: f64,
    /// y velocity, m/s.
    pub vy: f64,
}

/// One track's rows at non-decreasing times (rows at one time: the last one counts).
#[derive(Debug, Clone, PartialEq)]
pub struct TrackHistory {
    name: String,
    rows: Vec<TrackRow>,
}

impl TrackHistory {
    /// A track history from its rows.
    ///
    /// # Errors
    /// [`ScoreError::InvalidInput`] for no row, a non-finite value, or decreasing times.
    pub fn new(name: impl Into<String>, rows: Vec<TrackRow>) -> Result<Self, ScoreError> {
        let name = name.into();
        let bad = |reason| ScoreError::InvalidInput {
            what: "track",
            name: name.clone(),
            reason,
        };
        if rows.is_empty() {
            return Err(bad("no row"));
        }
        if rows
            .iter()
            .any(|r| ![r.t, r.x, r.vx, r.y, r.vy].iter().all(|v| v.is_finite()))
        {
            return Err(bad("a row has a non-finite value"));
        }
        if rows.windows(2).any(|w| w[1].t < w[0].t) {
            return Err(bad("row times must not decrease"));
        }
        Ok(Self { name, rows })
    }

    /// The name (the `track` value).
    #[must_use]
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The rows, in time order.
    #[must_use]
    pub fn rows(&self) -> &[TrackRow] {
        &self.rows
    }
}

//! The scoring parameters, validated once.

use argus_sim::Gospa;

use crate::error::{ScoreError, positive};

/// The largest grid accepted (steps): a day at 10 ms; more is almost surely a unit slip.
pub const MAX_GRID_STEPS: usize = 10_000_000;

/// Scoring parameters. See `docs/scoring.md` for what each one does.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ScoreConfig {
    /// Grid step Δ, s (default 5: seed 000's revolution).
    pub step: f64,
    /// Grid start, s (default: the earliest truth sample).
    pub start: Option<f64>,
    /// Grid end, s (default: the latest truth sample).
    pub end: Option<f64>,
    /// Track-to-truth distance cut-off `c_a`, m: pairs at `d ≥ c_a` are never assigned
    /// (default 1000 m, the surveillance scenario's).
    pub assign_cutoff: f64,
    /// Staleness limit, s: a track's last row older than this at a grid time leaves it
    /// absent (default 15 s: three 5-s revolutions without a row).
    pub max_track_age: f64,
    /// Truth samples further apart than this (s) are not interpolated across: the aircraft
    /// is absent in between (default 10 s; see `docs/scoring.md` for the error bound).
    pub max_truth_gap: f64,
    /// GOSPA cut-off `c`, m (default 1000).
    pub gospa_cutoff: f64,
    /// GOSPA order `p` (default 2).
    pub gospa_order: f64,
}

impl Default for ScoreConfig {
    fn default() -> Self {
        Self {
            step: 5.0,
            start: None,
            end: None,
            assign_cutoff: 1000.0,
            max_track_age: 15.0,
            max_truth_gap: 10.0,
            gospa_cutoff: 1000.0,
            gospa_order: 2.0,
        }
    }
}

/// A validated [`ScoreConfig`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scorer {
    pub(crate) config: ScoreConfig,
    pub(crate) gospa: Gospa,
}

impl Scorer {
    /// Checks every parameter.
    ///
    /// # Errors
    /// [`ScoreError::Parameter`] for a non-positive or non-finite step, cut-off or truth
    /// gap, a negative or non-finite staleness limit, a non-finite start or end, or an end
    /// before the start; [`ScoreError::Sim`] for a GOSPA order below 1.
    pub fn new(config: ScoreConfig) -> Result<Self, ScoreError> {
        positive("step", config.step)?;
        positive("assign_cutoff", config.assign_cutoff)?;
        positive("max_truth_gap", config.max_truth_gap)?;
        if !(config.max_track_age.is_finite() && config.max_track_age >= 0.0) {
            return Err(ScoreError::Parameter {
                what: "max_track_age",
                value: config.max_track_age,
                domain: "must be finite and non-negative",
            });
        }
        for (what, v) in [("start", config.start), ("end", config.end)] {
            if let Some(v) = v
                && !v.is_finite()
            {
                return Err(ScoreError::Parameter {
                    what,
                    value: v,
                    domain: "must be finite",
                });
            }
        }
        if let (Some(a), Some(b)) = (config.start, config.end)
            && b < a
        {
            return Err(ScoreError::Parameter {
                what: "end",
                value: b,
                domain: "must not be before start",
            });
        }
        let gospa = Gospa::new(config.gospa_cutoff, config.gospa_order)?;
        Ok(Self { config, gospa })
    }

    /// The parameters.
    #[must_use]
    pub fn config(&self) -> &ScoreConfig {
        &self.config
    }
}

//! What scoring returns: the summary, per-truth values and the series over the grid.
//!
//! Every ratio whose denominator can be zero is an `Option` (`None`, written `null` in
//! JSON), never a NaN.

use serde::Serialize;

use crate::config::ScoreConfig;

/// The whole score of one tracks file against one truth file.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Score {
    /// The parameters used.
    pub config: ScoreConfig,
    /// The summary numbers.
    pub summary: Summary,
    /// Per truth path, in the truth file's order.
    pub truths: Vec<TruthScore>,
    /// One point per grid time.
    pub series: Vec<GridPoint>,
}

/// The summary numbers (definitions in `docs/scoring.md`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// First grid time, s.
    pub grid_start: f64,
    /// Last grid time, s.
    pub grid_end: f64,
    /// Number of grid times `K`.
    pub grid_times: usize,
    /// Truth paths read.
    pub truths: usize,
    /// Tracks read (any status).
    pub tracks: usize,
    /// Tracks confirmed and present at one grid time at least.
    pub tracks_on_grid: usize,
    /// `Σₖ J(k)`: truth presences on the grid.
    pub truth_points: usize,
    /// `Σₖ N(k)`: confirmed-track presences on the grid.
    pub track_points: usize,
    /// `Σₖ NA(k)`: assigned pairs on the grid.
    pub assigned_points: usize,
    /// Aircraft-hours: `Σₖ J(k) Δ / 3600`.
    pub aircraft_hours: f64,
    /// Completeness `Σ NA / Σ J` (SIAP C with one track per truth).
    pub completeness: Option<f64>,
    /// Spurious confirmed-track time fraction `Σ (N − NA) / Σ N` (SIAP S).
    pub spurious_fraction: Option<f64>,
    /// Mean number of unassigned confirmed tracks per grid time, `Σ (N − NA) / K`.
    pub false_tracks_per_step: f64,
    /// Track breaks (a truth assigned at one grid time, present and unassigned at the next).
    pub breaks: usize,
    /// `breaks / aircraft_hours`.
    pub breaks_per_aircraft_hour: Option<f64>,
    /// Identity swaps (a truth assigned to a different track than the last one).
    pub id_swaps: usize,
    /// Position RMSE over assigned pairs, m.
    pub position_rmse: Option<f64>,
    /// Velocity RMSE over assigned pairs, m/s.
    pub velocity_rmse: Option<f64>,
    /// 95th percentile (nearest rank) of the assigned pairs' position error, m.
    pub position_p95: Option<f64>,
    /// Mean position error over assigned pairs, m (SIAP PA with the Euclidean measure).
    pub position_accuracy: Option<f64>,
    /// Mean velocity error over assigned pairs, m/s (SIAP VA).
    pub velocity_accuracy: Option<f64>,
    /// Mean time to confirm over the truths ever assigned, s.
    pub time_to_confirm_mean: Option<f64>,
    /// Truths present on the grid but never assigned.
    pub truths_never_tracked: usize,
    /// SIAP LS: `Σⱼ TLⱼ / Σⱼ Tⱼ`, the longest single-track segment over the lifetime.
    pub longest_segment: Option<f64>,
    /// SIAP R: `Σⱼ (NUⱼ − 1) / Σⱼ TTⱼ`, track-number changes per second tracked.
    pub track_number_change_rate: Option<f64>,
    /// Mean over grid times of GOSPA (m).
    pub gospa_mean: f64,
    /// Mean over grid times of the localisation part (m^p).
    pub gospa_localisation_mean: f64,
    /// Mean over grid times of the missed-target part (m^p).
    pub gospa_missed_mean: f64,
    /// Mean over grid times of the false-target part (m^p).
    pub gospa_false_mean: f64,
}

/// One truth path's values.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TruthScore {
    /// The `target` name.
    pub name: String,
    /// Grid times at which it is present.
    pub points: usize,
    /// Grid times at which it is assigned.
    pub assigned: usize,
    /// First assignment minus first presence, s (`None` if never assigned).
    pub time_to_confirm: Option<f64>,
    /// Segments (maximal runs of consecutive grid times on one track): SIAP `NUⱼ`.
    pub segments: usize,
    /// Longest segment, s: SIAP `TLⱼ`.
    pub longest_segment: f64,
}

/// The values at one grid time, for figures.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GridPoint {
    /// Grid time, s.
    pub t: f64,
    /// Truths present `J`.
    pub truths: usize,
    /// Confirmed tracks present `N`.
    pub tracks: usize,
    /// Assigned pairs `NA`.
    pub assigned: usize,
    /// `NA / J` (`None` when no truth is present).
    pub completeness: Option<f64>,
    /// GOSPA, m.
    pub gospa: f64,
    /// Localisation part (m^p).
    pub gospa_localisation: f64,
    /// Missed-target part (m^p).
    pub gospa_missed: f64,
    /// False-target part (m^p).
    pub gospa_false: f64,
}

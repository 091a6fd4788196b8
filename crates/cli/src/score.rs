//! `argus score`: a tracks CSV scored against a truth CSV by `argus-score` (regular grid,
//! optimal assignment with a cut-off; definitions in `docs/scoring.md`), written as JSON
//! with the summary, the per-truth scores and the per-time series.

use std::path::Path;

use argus_io::output::write_atomic;
use argus_score::{ScoreConfig, Scorer, read_tracks, read_truth};

use crate::error::CliError;

/// Scores `tracks` against `truth` with the grid `step` (s) and assignment `cutoff` (m),
/// writes the score to `out` (JSON, atomically) and returns the summary's lines for stdout.
///
/// # Errors
/// [`CliError::Score`] for a malformed file (file:line:field) or a bad parameter,
/// [`CliError::Io`] when `out` cannot be written.
pub(crate) fn run(
    tracks: &Path,
    truth: &Path,
    out: &Path,
    step: f64,
    cutoff: f64,
) -> Result<Vec<String>, CliError> {
    let tracks = read_tracks(tracks)?;
    let truth = read_truth(truth)?;
    let config = ScoreConfig {
        step,
        assign_cutoff: cutoff,
        ..ScoreConfig::default()
    };
    let score = Scorer::new(config)?.score(&tracks, &truth)?;
    let json = serde_json::to_string_pretty(&score)
        .map_err(|e| CliError::io(out, std::io::Error::other(e.to_string())))?;
    write_atomic(out, json.as_bytes())?;
    let s = &score.summary;
    let opt = |v: Option<f64>| v.map_or_else(|| "-".to_owned(), |x| format!("{x:.4}"));
    Ok(vec![
        format!("completeness             {}", opt(s.completeness)),
        format!(
            "breaks per aircraft-hour {}",
            opt(s.breaks_per_aircraft_hour)
        ),
        format!("identity swaps           {}", s.id_swaps),
        format!("spurious track fraction  {}", opt(s.spurious_fraction)),
        format!("position RMSE (m)        {}", opt(s.position_rmse)),
        format!("velocity RMSE (m/s)      {}", opt(s.velocity_rmse)),
        format!("position p95 (m)         {}", opt(s.position_p95)),
        format!("time to confirm (s)      {}", opt(s.time_to_confirm_mean)),
    ])
}

//! The tracker configuration pieces that `surveillance` and `real-traffic` read from
//! parameters they both declare under the same keys: the two-mode CV IMM, JPDA's event
//! limit and the track score's confirmation and deletion.

use argus_tracker::{AssociationConfig, EstimatorConfig, ScoreConfig};

use crate::error::ScenarioError;
use crate::params::Params;

/// The two-mode CV IMM per track: white-acceleration σ of the parameters
/// `imm_sigma_low` and `imm_sigma_high` (m/s²), staying probability `imm_p_stay`.
///
/// # Errors
/// A parameter that is not declared (a bug, reported).
pub(crate) fn imm_cv2(p: &Params) -> Result<EstimatorConfig, ScenarioError> {
    Ok(EstimatorConfig::ImmCv2 {
        sigma_a_low: p.get("imm_sigma_low")?,
        sigma_a_high: p.get("imm_sigma_high")?,
        p_stay: p.get("imm_p_stay")?,
    })
}

/// JPDA with detection probability `p_detection` and clutter density `clutter_density`
/// (per m² per scan), enumerating clusters of up to `jpda_max_events` joint events.
///
/// # Errors
/// A parameter that is not declared (a bug, reported).
pub(crate) fn jpda(
    p: &Params,
    p_detection: f64,
    clutter_density: f64,
) -> Result<AssociationConfig, ScenarioError> {
    Ok(AssociationConfig::Jpda {
        p_detection,
        clutter_density,
        max_exact_events: p.get("jpda_max_events")? as usize,
    })
}

/// Confirmation and deletion by the track score with detection probability
/// `p_detection` and clutter density `clutter_density`: the parameters
/// `new_target_density`, `false_confirm` and `delete_drop`, and a 1 % probability of
/// dropping a true tentative track.
///
/// # Errors
/// A parameter that is not declared (a bug, reported).
pub(crate) fn track_score(
    p: &Params,
    p_detection: f64,
    clutter_density: f64,
) -> Result<ScoreConfig, ScenarioError> {
    Ok(ScoreConfig {
        p_detection,
        clutter_density,
        new_target_density: p.get("new_target_density")?,
        false_confirm: p.get("false_confirm")?,
        missed_confirm: 0.01,
        delete_drop: p.get("delete_drop")?,
    })
}

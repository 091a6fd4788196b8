//! The two-mode CV IMM of [`crate::EstimatorConfig::ImmCv2`] and
//! [`crate::EstimatorConfig::MultiImm`], built in one place: for the tracker, and for code
//! that runs the tracker's IMM again over its tracks (a smoother of the recorded tracks).

use argus_filters::Kf;
use argus_imm::{Imm, MarkovMatrix};
use argus_motion_models::Cv2D;

use crate::TrackerError;
use crate::field::{ConfigField, EstimatorField};

/// The tracker's two-mode IMM: a quiet and a manoeuvre CV model on `[x, vx, y, vy]`.
pub type TwoModeImm = Imm<Kf<Cv2D>, 4, 2>;

/// The tracker's two-mode IMM: Kalman filters on the discrete white-noise-acceleration
/// CV models of `sigma_a_low` and `sigma_a_high` (m/s²), with the Markov matrix
/// `[[p, 1 − p], [1 − p, p]]`, `p = p_stay`.
///
/// # Errors
/// [`TrackerError::InvalidConfig`] naming `p_stay` when it does not make a Markov matrix
/// (checked first); [`TrackerError::Motion`] for a negative or non-finite σ.
pub fn two_mode_imm(
    sigma_a_low: f64,
    sigma_a_high: f64,
    p_stay: f64,
) -> Result<TwoModeImm, TrackerError> {
    let markov =
        MarkovMatrix::new([[p_stay, 1.0 - p_stay], [1.0 - p_stay, p_stay]]).map_err(|_| {
            TrackerError::InvalidConfig {
                field: ConfigField::Estimator(EstimatorField::PStay),
                value: p_stay,
                reason: "does not make a Markov matrix",
            }
        })?;
    let filters = [
        Kf::new(Cv2D::discrete(sigma_a_low)?),
        Kf::new(Cv2D::discrete(sigma_a_high)?),
    ];
    Imm::new(filters, markov).map_err(|_| TrackerError::InvalidConfig {
        field: ConfigField::Estimator(EstimatorField::Kind),
        value: p_stay,
        reason: "the IMM rejected it",
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use argus_motion_models::MotionError;

    #[test]
    fn builds_the_configured_models_and_names_bad_values() {
        let imm = two_mode_imm(0.5, 8.0, 0.95).unwrap();
        let pi = imm.markov().matrix();
        // Exact: 1 − 0.95 is formed the same way in both places.
        assert_eq!(pi[(0, 1)].to_bits(), (1.0_f64 - 0.95).to_bits());
        assert_eq!(pi[(1, 1)].to_bits(), 0.95_f64.to_bits());
        assert_eq!(
            imm.filters()[0].model(),
            &Cv2D::discrete(0.5).unwrap(),
            "quiet model first"
        );
        assert_eq!(imm.filters()[1].model(), &Cv2D::discrete(8.0).unwrap());
        assert!(matches!(
            two_mode_imm(0.5, 8.0, 1.5),
            Err(TrackerError::InvalidConfig {
                field: ConfigField::Estimator(EstimatorField::PStay),
                ..
            })
        ));
        // A bad p_stay is named before a bad σ.
        assert!(matches!(
            two_mode_imm(-1.0, 8.0, f64::NAN),
            Err(TrackerError::InvalidConfig { .. })
        ));
        assert!(matches!(
            two_mode_imm(-1.0, 8.0, 0.95),
            Err(TrackerError::Motion(MotionError::Negative { .. }))
        ));
    }
}

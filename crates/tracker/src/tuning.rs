//! The tracker's tunable scalars, declared once: [`TUNABLES`], one [`Tunable`] per field
//! (the typed [`ConfigField`], its allowed range and a one-line help), and
//! [`TrackerConfig::set`], which sets such a field from an `f64`.
//!
//! A front end (a scenario's `--set key=value`, a configuration file) declares its keys
//! from this table instead of writing the ranges and helps again, and applies a value
//! by its field instead of matching its own key back to a field.

use crate::field::{AssociationField, ConfigField, EstimatorField, ScoreField};
use crate::{AssociationConfig, EstimatorConfig, TrackerConfig, TrackerError};

/// One tunable field of [`TrackerConfig`]: which, the values a front end offers for it,
/// and what it is.
///
/// The range is the one offered (`min ..= max`, both inclusive); a value in it may still
/// be refused by [`TrackerConfig::validate`] together with the other fields (e.g.
/// `confirm_m` above `confirm_n`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tunable {
    /// The field.
    pub field: ConfigField,
    /// Smallest value offered (inclusive), in the field's unit.
    pub min: f64,
    /// Largest value offered (inclusive), in the field's unit.
    pub max: f64,
    /// Unit and meaning, one line.
    pub help: &'static str,
}

impl Tunable {
    /// [`TrackerConfig::sigma_a`].
    pub const SIGMA_A: Tunable = Tunable {
        field: ConfigField::SigmaA,
        min: 0.0,
        max: 100.0,
        help: "KF tracks' white-acceleration σ (m/s²)",
    };
    /// [`TrackerConfig::max_speed`].
    pub const MAX_SPEED: Tunable = Tunable {
        field: ConfigField::MaxSpeed,
        min: 1.0,
        max: 2000.0,
        help: "two-point initiation: the fastest aircraft (m/s)",
    };
    /// [`TrackerConfig::confirm_m`].
    pub const CONFIRM_M: Tunable = Tunable {
        field: ConfigField::ConfirmM,
        min: 1.0,
        max: 20.0,
        help: "confirmation: M hits ...",
    };
    /// [`TrackerConfig::confirm_n`].
    pub const CONFIRM_N: Tunable = Tunable {
        field: ConfigField::ConfirmN,
        min: 2.0,
        max: 20.0,
        help: "... in the first N opportunities",
    };
    /// [`TrackerConfig::max_misses`].
    pub const MAX_MISSES: Tunable = Tunable {
        field: ConfigField::MaxMisses,
        min: 1.0,
        max: 100.0,
        help: "a confirmed track is deleted after this many consecutive misses",
    };
    /// [`TrackerConfig::sector_fraction`].
    pub const SECTOR_FRACTION: Tunable = Tunable {
        field: ConfigField::SectorFraction,
        min: 1e-3,
        max: 1.0,
        help: "tracker sector: this fraction of a revolution",
    };
    /// `sigma_a_low` of the IMM estimators.
    pub const IMM_SIGMA_A_LOW: Tunable = Tunable {
        field: ConfigField::Estimator(EstimatorField::SigmaALow),
        min: 0.0,
        max: 100.0,
        help: "IMM quiet mode's white-acceleration σ (m/s²)",
    };
    /// `sigma_a_high` of the IMM estimators.
    pub const IMM_SIGMA_A_HIGH: Tunable = Tunable {
        field: ConfigField::Estimator(EstimatorField::SigmaAHigh),
        min: 0.0,
        max: 100.0,
        help: "IMM manoeuvre mode's white-acceleration σ (m/s²)",
    };
    /// `p_stay` of the IMM estimators.
    pub const IMM_P_STAY: Tunable = Tunable {
        field: ConfigField::Estimator(EstimatorField::PStay),
        min: 1e-3,
        max: 0.999,
        help: "IMM probability of staying in a mode per scan",
    };
    /// `cv_sigma_a[0]` of the aircraft IMM's tuning.
    pub const AIRCRAFT_CV_SIGMA_A_LOW: Tunable = Tunable {
        field: ConfigField::Estimator(EstimatorField::CvSigmaALow),
        min: 0.0,
        max: 100.0,
        help: "aircraft IMM: quiet CV mode's σ_a (m/s²)",
    };
    /// `cv_sigma_a[1]` of the aircraft IMM's tuning.
    pub const AIRCRAFT_CV_SIGMA_A_HIGH: Tunable = Tunable {
        field: ConfigField::Estimator(EstimatorField::CvSigmaAHigh),
        min: 0.0,
        max: 100.0,
        help: "aircraft IMM: manoeuvre CV mode's σ_a (m/s²)",
    };
    /// `ct_sigma_a` of the aircraft IMM's tuning.
    pub const AIRCRAFT_CT_SIGMA_A: Tunable = Tunable {
        field: ConfigField::Estimator(EstimatorField::CtSigmaA),
        min: 0.0,
        max: 100.0,
        help: "aircraft IMM: CT mode's σ_a (m/s²)",
    };
    /// `ct_sigma_omega` of the aircraft IMM's tuning (rad/s²).
    pub const AIRCRAFT_CT_SIGMA_OMEGA: Tunable = Tunable {
        field: ConfigField::Estimator(EstimatorField::CtSigmaOmega),
        min: 1e-9,
        max: 1.0,
        help: "aircraft IMM: CT mode's turn-rate random walk σ_ω (rad/s²)",
    };
    /// [`crate::ScoreConfig::new_target_density`].
    pub const SCORE_NEW_TARGET_DENSITY: Tunable = Tunable {
        field: ConfigField::Score(ScoreField::NewTargetDensity),
        min: 1e-20,
        max: 1e-3,
        help: "track score: new targets per m² per scan",
    };
    /// [`crate::ScoreConfig::false_confirm`].
    pub const SCORE_FALSE_CONFIRM: Tunable = Tunable {
        field: ConfigField::Score(ScoreField::FalseConfirm),
        min: 1e-12,
        max: 0.4,
        help: "track score: probability of confirming a false track",
    };
    /// [`crate::ScoreConfig::delete_drop`].
    pub const SCORE_DELETE_DROP: Tunable = Tunable {
        field: ConfigField::Score(ScoreField::DeleteDrop),
        min: 0.1,
        max: 100.0,
        help: "track score: a confirmed track is deleted this far below its peak score",
    };
    /// `max_exact_events` of [`AssociationConfig::Jpda`].
    pub const JPDA_MAX_EXACT_EVENTS: Tunable = Tunable {
        field: ConfigField::Association(AssociationField::MaxExactEvents),
        min: 1.0,
        max: 1e7,
        help: "JPDA: largest cluster enumerated exactly (joint events)",
    };

    /// The entry of `field` in [`TUNABLES`], `None` for a field that is not tunable.
    #[must_use]
    pub fn of(field: ConfigField) -> Option<&'static Tunable> {
        TUNABLES.iter().find(|t| t.field == field)
    }
}

/// The tracker's tunable fields, one entry per field (the associated constants of
/// [`Tunable`]). The integer fields (`confirm_m`, `confirm_n`, `max_misses`,
/// `max_exact_events`) take the integer part of the value.
pub const TUNABLES: &[Tunable] = &[
    Tunable::SIGMA_A,
    Tunable::MAX_SPEED,
    Tunable::CONFIRM_M,
    Tunable::CONFIRM_N,
    Tunable::MAX_MISSES,
    Tunable::SECTOR_FRACTION,
    Tunable::IMM_SIGMA_A_LOW,
    Tunable::IMM_SIGMA_A_HIGH,
    Tunable::IMM_P_STAY,
    Tunable::AIRCRAFT_CV_SIGMA_A_LOW,
    Tunable::AIRCRAFT_CV_SIGMA_A_HIGH,
    Tunable::AIRCRAFT_CT_SIGMA_A,
    Tunable::AIRCRAFT_CT_SIGMA_OMEGA,
    Tunable::SCORE_NEW_TARGET_DENSITY,
    Tunable::SCORE_FALSE_CONFIRM,
    Tunable::SCORE_DELETE_DROP,
    Tunable::JPDA_MAX_EXACT_EVENTS,
];

impl TrackerConfig {
    /// Sets the tunable `field` (an entry of [`TUNABLES`]) to `value`, an integer field
    /// to its integer part. An estimator field is set only on an estimator that has it
    /// (the IMM fields on [`EstimatorConfig::ImmCv2`] and [`EstimatorConfig::MultiImm`],
    /// the aircraft fields on [`EstimatorConfig::Aircraft`]), a score field only when
    /// [`TrackerConfig::score`] is `Some`, `max_exact_events` only on
    /// [`AssociationConfig::Jpda`]. Nothing else is changed, and nothing is validated
    /// beyond the range ([`TrackerConfig::validate`] does that).
    ///
    /// # Errors
    /// [`TrackerError::InvalidConfig`] naming `field` when it is not tunable, when `value`
    /// is NaN or outside the entry's range, or when the configuration has no such field
    /// (the estimator, score or association named is not the configured one). The
    /// configuration is then unchanged.
    pub fn set(&mut self, field: ConfigField, value: f64) -> Result<(), TrackerError> {
        let bad = |reason| {
            Err(TrackerError::InvalidConfig {
                field,
                value,
                reason,
            })
        };
        let Some(t) = Tunable::of(field) else {
            return bad("is not a tunable field");
        };
        if !(t.min..=t.max).contains(&value) {
            return bad("is outside the field's tunable range");
        }
        let slot: &mut f64 = match field {
            ConfigField::SigmaA => &mut self.sigma_a,
            ConfigField::MaxSpeed => &mut self.max_speed,
            ConfigField::SectorFraction => &mut self.sector_fraction,
            // In range, so the integer parts fit.
            ConfigField::ConfirmM => {
                self.confirm_m = value as u32;
                return Ok(());
            }
            ConfigField::ConfirmN => {
                self.confirm_n = value as u32;
                return Ok(());
            }
            ConfigField::MaxMisses => {
                self.max_misses = value as u32;
                return Ok(());
            }
            ConfigField::Association(AssociationField::MaxExactEvents) => {
                return match &mut self.association {
                    AssociationConfig::Jpda {
                        max_exact_events, ..
                    } => {
                        *max_exact_events = value as usize;
                        Ok(())
                    }
                    AssociationConfig::Gnn => bad("the association is not JPDA"),
                };
            }
            ConfigField::Score(f) => {
                let Some(s) = &mut self.score else {
                    return bad("track-score management is not configured");
                };
                match f {
                    ScoreField::NewTargetDensity => &mut s.new_target_density,
                    ScoreField::FalseConfirm => &mut s.false_confirm,
                    ScoreField::DeleteDrop => &mut s.delete_drop,
                    _ => return bad("is not a tunable field"),
                }
            }
            ConfigField::Estimator(f) => match (f, &mut self.estimator) {
                (
                    EstimatorField::SigmaALow,
                    EstimatorConfig::ImmCv2 { sigma_a_low, .. }
                    | EstimatorConfig::MultiImm { sigma_a_low, .. },
                ) => sigma_a_low,
                (
                    EstimatorField::SigmaAHigh,
                    EstimatorConfig::ImmCv2 { sigma_a_high, .. }
                    | EstimatorConfig::MultiImm { sigma_a_high, .. },
                ) => sigma_a_high,
                (
                    EstimatorField::PStay,
                    EstimatorConfig::ImmCv2 { p_stay, .. }
                    | EstimatorConfig::MultiImm { p_stay, .. },
                ) => p_stay,
                (EstimatorField::CvSigmaALow, EstimatorConfig::Aircraft { tuning }) => {
                    &mut tuning.cv_sigma_a[0]
                }
                (EstimatorField::CvSigmaAHigh, EstimatorConfig::Aircraft { tuning }) => {
                    &mut tuning.cv_sigma_a[1]
                }
                (EstimatorField::CtSigmaA, EstimatorConfig::Aircraft { tuning }) => {
                    &mut tuning.ct_sigma_a
                }
                (EstimatorField::CtSigmaOmega, EstimatorConfig::Aircraft { tuning }) => {
                    &mut tuning.ct_sigma_omega
                }
                _ => return bad("the configured estimator has no such field"),
            },
            _ => return bad("is not a tunable field"),
        };
        *slot = value;
        Ok(())
    }
}

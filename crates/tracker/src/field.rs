//! The configuration fields an error can name, typed: [`ConfigField`] and its parts.
//!
//! [`ConfigField::key`] (and `Display`) give the dotted name of the field in
//! [`crate::TrackerConfig`] (`"confirm_m"`, `"estimator.p_stay"`, `"sensors.id"`), so a
//! front end maps an error to its own input by matching on the enum, not on a string.

use std::fmt;

/// A field of [`crate::TrackerConfig`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum ConfigField {
    /// [`crate::TrackerConfig::sensors`] as a whole (e.g. empty).
    Sensors,
    /// A field of one of [`crate::TrackerConfig::sensors`].
    Sensor(SensorField),
    /// [`crate::TrackerConfig::sigma_a`].
    SigmaA,
    /// [`crate::TrackerConfig::gate_probability`].
    GateProbability,
    /// [`crate::TrackerConfig::max_speed`].
    MaxSpeed,
    /// [`crate::TrackerConfig::velocity_gate_sigmas`].
    VelocityGateSigmas,
    /// [`crate::TrackerConfig::max_initiation_interval`].
    MaxInitiationInterval,
    /// [`crate::TrackerConfig::confirm_m`].
    ConfirmM,
    /// [`crate::TrackerConfig::confirm_n`].
    ConfirmN,
    /// [`crate::TrackerConfig::max_misses`].
    MaxMisses,
    /// [`crate::TrackerConfig::max_position_sigma`].
    MaxPositionSigma,
    /// [`crate::TrackerConfig::grid_cell`].
    GridCell,
    /// [`crate::TrackerConfig::sector_fraction`].
    SectorFraction,
    /// A field of [`crate::TrackerConfig::score`].
    Score(ScoreField),
    /// [`crate::TrackerConfig::estimator`] or one of its parameters.
    Estimator(EstimatorField),
    /// [`crate::TrackerConfig::association`] or one of its parameters.
    Association(AssociationField),
}

/// A field of a [`crate::SensorConfig`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum SensorField {
    /// [`crate::SensorConfig::id`] (e.g. repeated).
    Id,
    /// [`crate::SensorConfig::position`].
    Position,
    /// [`crate::SensorConfig::polar_noise`] as a whole (missing, or refused by a model).
    PolarNoise,
    /// [`crate::PolarNoise::sigma_range`].
    SigmaRange,
    /// [`crate::PolarNoise::sigma_azimuth`].
    SigmaAzimuth,
    /// [`crate::Rotation::period`] (also: a rotation the estimator cannot take).
    RevolutionPeriod,
    /// [`crate::Rotation::north_time`].
    NorthTime,
}

/// A field of a [`crate::ScoreConfig`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum ScoreField {
    /// [`crate::ScoreConfig::p_detection`].
    PDetection,
    /// [`crate::ScoreConfig::clutter_density`].
    ClutterDensity,
    /// [`crate::ScoreConfig::new_target_density`].
    NewTargetDensity,
    /// [`crate::ScoreConfig::false_confirm`].
    FalseConfirm,
    /// [`crate::ScoreConfig::missed_confirm`].
    MissedConfirm,
    /// [`crate::ScoreConfig::delete_drop`].
    DeleteDrop,
}

/// [`crate::EstimatorConfig`] or one of its parameters.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum EstimatorField {
    /// The estimator as a whole (its filters refused the parameters together).
    Kind,
    /// `sigma_a_low` of the IMM estimators.
    SigmaALow,
    /// `sigma_a_high` of the IMM estimators.
    SigmaAHigh,
    /// `p_stay` of the IMM estimators.
    PStay,
    /// `grid_spacing` of [`crate::EstimatorConfig::MultiImm`].
    GridSpacing,
    /// `clip` of [`crate::EstimatorConfig::MultiImm`].
    Clip,
    /// `cv_sigma_a` of [`crate::EstimatorConfig::Aircraft`]'s tuning.
    CvSigmaA,
    /// `cv_sigma_a[0]` of the aircraft tuning: its quiet CV mode's σ_a.
    CvSigmaALow,
    /// `cv_sigma_a[1]` of the aircraft tuning: its manoeuvre CV mode's σ_a.
    CvSigmaAHigh,
    /// `ct_sigma_a` of the aircraft tuning.
    CtSigmaA,
    /// `ct_sigma_omega` of the aircraft tuning.
    CtSigmaOmega,
    /// `markov` of the aircraft tuning.
    Markov,
    /// `start_sigma_omega` of the aircraft tuning.
    StartSigmaOmega,
    /// `start_mu` of the aircraft tuning.
    StartMu,
    /// `augmentation` of the aircraft tuning (its `Fixed` σ).
    Augmentation,
}

/// [`crate::AssociationConfig`] or one of its parameters.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum AssociationField {
    /// The association as a whole (e.g. not built with this estimator).
    Kind,
    /// `p_detection` of [`crate::AssociationConfig::Jpda`].
    PDetection,
    /// `clutter_density` of [`crate::AssociationConfig::Jpda`].
    ClutterDensity,
    /// `max_exact_events` of [`crate::AssociationConfig::Jpda`].
    MaxExactEvents,
}

impl ConfigField {
    /// The field's dotted name in [`crate::TrackerConfig`], e.g. `"estimator.p_stay"`.
    #[must_use]
    pub fn key(self) -> &'static str {
        match self {
            Self::Sensors => "sensors",
            Self::Sensor(f) => match f {
                SensorField::Id => "sensors.id",
                SensorField::Position => "sensors.position",
                SensorField::PolarNoise => "sensors.polar_noise",
                SensorField::SigmaRange => "sensors.polar_noise.sigma_range",
                SensorField::SigmaAzimuth => "sensors.polar_noise.sigma_azimuth",
                SensorField::RevolutionPeriod => "sensors.rotation.period",
                SensorField::NorthTime => "sensors.rotation.north_time",
            },
            Self::SigmaA => "sigma_a",
            Self::GateProbability => "gate_probability",
            Self::MaxSpeed => "max_speed",
            Self::VelocityGateSigmas => "velocity_gate_sigmas",
            Self::MaxInitiationInterval => "max_initiation_interval",
            Self::ConfirmM => "confirm_m",
            Self::ConfirmN => "confirm_n",
            Self::MaxMisses => "max_misses",
            Self::MaxPositionSigma => "max_position_sigma",
            Self::GridCell => "grid_cell",
            Self::SectorFraction => "sector_fraction",
            Self::Score(f) => match f {
                ScoreField::PDetection => "score.p_detection",
                ScoreField::ClutterDensity => "score.clutter_density",
                ScoreField::NewTargetDensity => "score.new_target_density",
                ScoreField::FalseConfirm => "score.false_confirm",
                ScoreField::MissedConfirm => "score.missed_confirm",
                ScoreField::DeleteDrop => "score.delete_drop",
            },
            Self::Estimator(f) => match f {
                EstimatorField::Kind => "estimator",
                EstimatorField::SigmaALow => "estimator.sigma_a_low",
                EstimatorField::SigmaAHigh => "estimator.sigma_a_high",
                EstimatorField::PStay => "estimator.p_stay",
                EstimatorField::GridSpacing => "estimator.grid_spacing",
                EstimatorField::Clip => "estimator.clip",
                EstimatorField::CvSigmaA => "estimator.tuning.cv_sigma_a",
                EstimatorField::CvSigmaALow => "estimator.tuning.cv_sigma_a[0]",
                EstimatorField::CvSigmaAHigh => "estimator.tuning.cv_sigma_a[1]",
                EstimatorField::CtSigmaA => "estimator.tuning.ct_sigma_a",
                EstimatorField::CtSigmaOmega => "estimator.tuning.ct_sigma_omega",
                EstimatorField::Markov => "estimator.tuning.markov",
                EstimatorField::StartSigmaOmega => "estimator.tuning.start_sigma_omega",
                EstimatorField::StartMu => "estimator.tuning.start_mu",
                EstimatorField::Augmentation => "estimator.tuning.augmentation",
            },
            Self::Association(f) => match f {
                AssociationField::Kind => "association",
                AssociationField::PDetection => "association.p_detection",
                AssociationField::ClutterDensity => "association.clutter_density",
                AssociationField::MaxExactEvents => "association.max_exact_events",
            },
        }
    }
}

impl fmt::Display for ConfigField {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.key())
    }
}

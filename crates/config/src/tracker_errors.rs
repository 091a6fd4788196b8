//! The map from the tracker's own checks ([`argus_tracker::TrackerConfig::validate`]),
//! which name a typed [`argus_tracker::ConfigField`], back to the key and line of the file
//! that holds the value: one match on the field, no string names.

use std::ops::Range;

use argus_tracker::{
    AssociationField, ConfigField as F, EstimatorField, ScoreField, SensorField, TrackerError,
};
use toml::Spanned;

use crate::error::ConfigError;
use crate::schema::{File, ScoreTable, Source, TrackerTable};

/// The `[[sensor]]` key of a sensor field the tracker checks again (a missing polar
/// noise is named by `sigma_range`; a field this map does not know by `id`).
fn sensor_key(f: SensorField) -> &'static str {
    match f {
        SensorField::Position => "position",
        SensorField::SigmaRange | SensorField::PolarNoise => "sigma_range",
        SensorField::SigmaAzimuth => "sigma_azimuth_deg",
        SensorField::RevolutionPeriod => "revolution_period",
        SensorField::NorthTime => "north_time",
        SensorField::Id => "id",
        _ => "id",
    }
}

/// Where a value the tracker refuses sits in the file.
enum Place {
    /// A key of `[tracker]` or `[estimator]` and its value's span (`None`: the key is not
    /// written and its default was refused: the `[tracker]` line).
    Key(&'static str, Option<Range<usize>>),
    /// A `[[sensor]]` value, found by the value refused.
    Sensor(SensorField),
    /// No `[[sensor]]` at all.
    NoSensor,
}

/// Maps a [`TrackerError::InvalidConfig`] of the tracker's validation, by its typed
/// [`argus_tracker::ConfigField`], to the key of `file` that holds the value (the `[tracker]` line for a default); any other error names the
/// `[tracker]` table.
pub(crate) fn config_error(
    src: Source<'_>,
    file: &File,
    table: &Spanned<TrackerTable>,
    e: &TrackerError,
) -> ConfigError {
    let TrackerError::InvalidConfig {
        field,
        value,
        reason,
    } = e
    else {
        return ConfigError::input(src.path, None, Some("tracker"), e.to_string());
    };
    let t = table.get_ref();
    let est = &file.estimator;
    let span = |v: &Option<Spanned<toml::Value>>| v.as_ref().map(Spanned::span);
    let score = |f: fn(&ScoreTable) -> &Spanned<toml::Value>| {
        t.score.as_ref().map(|s| f(s.get_ref()).span())
    };
    let place = match *field {
        F::GateProbability => Place::Key("tracker.gate_probability", span(&t.gate_probability)),
        F::MaxSpeed => Place::Key("tracker.max_speed", span(&t.max_speed)),
        F::VelocityGateSigmas => Place::Key(
            "tracker.velocity_gate_sigmas",
            span(&t.velocity_gate_sigmas),
        ),
        F::MaxInitiationInterval => Place::Key(
            "tracker.max_initiation_interval",
            span(&t.max_initiation_interval),
        ),
        F::ConfirmM => Place::Key("tracker.confirm_m", span(&t.confirm_m)),
        F::ConfirmN => Place::Key("tracker.confirm_n", span(&t.confirm_n)),
        F::MaxMisses => Place::Key("tracker.max_misses", span(&t.max_misses)),
        F::MaxPositionSigma => {
            Place::Key("tracker.max_position_sigma", span(&t.max_position_sigma))
        }
        F::GridCell => Place::Key("tracker.grid_cell", span(&t.grid_cell)),
        F::SectorFraction => Place::Key("tracker.sector_fraction", span(&t.sector_fraction)),
        F::Association(a) => match a {
            AssociationField::Kind => Place::Key("tracker.association", span(&t.association)),
            AssociationField::PDetection => Place::Key("tracker.p_detection", span(&t.p_detection)),
            AssociationField::ClutterDensity => {
                Place::Key("tracker.clutter_density", span(&t.clutter_density))
            }
            AssociationField::MaxExactEvents => {
                Place::Key("tracker.max_exact_events", span(&t.max_exact_events))
            }
            _ => Place::Key(field.key(), None),
        },
        F::Score(f) => match f {
            ScoreField::PDetection => {
                Place::Key("tracker.score.p_detection", score(|s| &s.p_detection))
            }
            ScoreField::ClutterDensity => Place::Key(
                "tracker.score.clutter_density",
                score(|s| &s.clutter_density),
            ),
            ScoreField::NewTargetDensity => Place::Key(
                "tracker.score.new_target_density",
                score(|s| &s.new_target_density),
            ),
            ScoreField::FalseConfirm => {
                Place::Key("tracker.score.false_confirm", score(|s| &s.false_confirm))
            }
            ScoreField::MissedConfirm => {
                Place::Key("tracker.score.missed_confirm", score(|s| &s.missed_confirm))
            }
            ScoreField::DeleteDrop => {
                Place::Key("tracker.score.delete_drop", score(|s| &s.delete_drop))
            }
            _ => Place::Key(field.key(), None),
        },
        F::SigmaA => Place::Key("estimator.sigma_a", est.sigma_a.as_ref().map(Spanned::span)),
        F::Estimator(f) => match f {
            EstimatorField::Kind => Place::Key("estimator.kind", Some(est.kind.span())),
            EstimatorField::SigmaALow | EstimatorField::SigmaAHigh => {
                Place::Key("estimator.models", est.models.as_ref().map(Spanned::span))
            }
            EstimatorField::PStay => {
                Place::Key("estimator.markov", est.markov.as_ref().map(Spanned::span))
            }
            EstimatorField::GridSpacing => {
                Place::Key("estimator.p", est.p.as_ref().map(Spanned::span))
            }
            EstimatorField::Clip => {
                Place::Key("estimator.clip", est.clip.as_ref().map(Spanned::span))
            }
            EstimatorField::CvSigmaA => Place::Key(
                "estimator.cv_sigma_a",
                est.cv_sigma_a.as_ref().map(Spanned::span),
            ),
            EstimatorField::CtSigmaA => Place::Key(
                "estimator.ct_sigma_a",
                est.ct_sigma_a.as_ref().map(Spanned::span),
            ),
            EstimatorField::CtSigmaOmega => Place::Key(
                "estimator.ct_sigma_omega_deg",
                est.ct_sigma_omega_deg.as_ref().map(Spanned::span),
            ),
            EstimatorField::Markov => {
                Place::Key("estimator.markov", est.markov.as_ref().map(Spanned::span))
            }
            EstimatorField::StartSigmaOmega => Place::Key(
                "estimator.start_sigma_omega_deg",
                est.start_sigma_omega_deg.as_ref().map(Spanned::span),
            ),
            EstimatorField::StartMu => {
                Place::Key("estimator.initial", est.initial.as_ref().map(Spanned::span))
            }
            EstimatorField::Augmentation => Place::Key(
                "estimator.mixing_sigma_omega_deg",
                est.mixing_sigma_omega_deg.as_ref().map(Spanned::span),
            ),
            _ => Place::Key(field.key(), None),
        },
        F::Sensor(f) => Place::Sensor(f),
        F::Sensors => Place::NoSensor,
        // `ConfigField` is `#[non_exhaustive]`: a field added to the tracker after this
        // map is named as the tracker names it, at the `[tracker]` line.
        _ => Place::Key(field.key(), None),
    };
    match place {
        Place::Key(key, at) => {
            // `association` carries no number of its own.
            let msg = if key == "tracker.association" {
                (*reason).to_owned()
            } else {
                format!("{value}: {reason}")
            };
            let at = at.unwrap_or_else(|| table.span());
            ConfigError::input(src.path, Some(src.line(&at)), Some(key), msg)
        }
        Place::Sensor(f) => sensor_error(src, file, f, *value, reason),
        Place::NoSensor => src.missing("sensor", "the tracker needs at least one [[sensor]]"),
    }
}

/// A sensor value the tracker refuses, at the `[[sensor]]` that holds it (the value
/// reported is the sensor's id for a missing polar noise or a repeated id, else the bad
/// number: the sensor is found by that value).
fn sensor_error(
    src: Source<'_>,
    file: &File,
    field: SensorField,
    value: f64,
    reason: &str,
) -> ConfigError {
    let same = |v: f64| v.to_bits() == value.to_bits();
    let found = file.sensors.iter().find_map(|s| {
        let id = *s.id.get_ref();
        let hit = match field {
            SensorField::Position => s
                .position
                .as_ref()
                .filter(|p| p.get_ref().iter().any(|v| same(*v)))
                .map(Spanned::span),
            SensorField::SigmaRange => s
                .sigma_range
                .as_ref()
                .filter(|v| same(*v.get_ref()))
                .map(Spanned::span),
            SensorField::SigmaAzimuth => s
                .sigma_azimuth_deg
                .as_ref()
                .filter(|v| same(v.get_ref().to_radians()))
                .map(Spanned::span),
            SensorField::RevolutionPeriod => s
                .revolution_period
                .as_ref()
                .filter(|v| same(*v.get_ref()))
                .map(Spanned::span),
            SensorField::NorthTime => s
                .north_time
                .as_ref()
                .filter(|v| same(*v.get_ref()))
                .map(Spanned::span),
            // A missing polar noise, a repeated id: the value is the sensor's id.
            _ => same(f64::from(id)).then(|| s.id.span()),
        };
        hit.map(|span| (id, span))
    });
    let key = sensor_key(field);
    match found {
        Some((id, span)) => ConfigError::input(
            src.path,
            Some(src.line(&span)),
            Some(key),
            format!("sensor {id}: {reason}"),
        ),
        None => src.missing(key, format!("{value}: {reason}")),
    }
}

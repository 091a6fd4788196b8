//! The map from the tracker's own checks ([`argus_tracker::TrackerConfig::validate`]) back to
//! the key of the file that holds the value.

use std::ops::Range;

use argus_tracker::TrackerError;
use toml::Spanned;

use super::schema::{File, ScoreTable, Source, TrackerTable};
use crate::error::CliError;

/// A `[[sensor]]` key the tracker checks again.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum SensorKey {
    Position,
    SigmaRange,
    SigmaAzimuth,
    /// A sensor without polar noise (the multi-IMM needs it): named by its id.
    NoPolarNoise,
    Id,
}

impl SensorKey {
    /// The key as written in `[[sensor]]`.
    fn name(self) -> &'static str {
        match self {
            Self::Position => "position",
            Self::SigmaRange | Self::NoPolarNoise => "sigma_range",
            Self::SigmaAzimuth => "sigma_azimuth_deg",
            Self::Id => "id",
        }
    }
}

/// Where a value the tracker refuses sits in the file.
enum Place {
    /// A key of `[tracker]` or `[estimator]` and its value's span (`None`: the key is not
    /// written and its default was refused: the `[tracker]` line).
    Key(&'static str, Option<Range<usize>>),
    /// A `[[sensor]]` value, found by the value refused.
    Sensor(SensorKey),
    /// No `[[sensor]]` at all.
    NoSensor,
}

/// Maps a [`TrackerError::InvalidConfig`] of the tracker's validation to the key of `file`
/// that holds the value (the `[tracker]` line for a default); any other error names the
/// `[tracker]` table.
pub(super) fn config_error(
    src: Source<'_>,
    file: &File,
    table: &Spanned<TrackerTable>,
    e: &TrackerError,
) -> CliError {
    let TrackerError::InvalidConfig {
        field,
        value,
        reason,
    } = e
    else {
        return CliError::input(src.path, None, Some("tracker"), e.to_string());
    };
    let t = table.get_ref();
    let est = &file.estimator;
    let span = |v: &Option<Spanned<toml::Value>>| v.as_ref().map(Spanned::span);
    let score = |f: fn(&ScoreTable) -> &Spanned<toml::Value>| {
        t.score.as_ref().map(|s| f(s.get_ref()).span())
    };
    let place = match *field {
        "gate_probability" => Place::Key("tracker.gate_probability", span(&t.gate_probability)),
        "max_speed" => Place::Key("tracker.max_speed", span(&t.max_speed)),
        "velocity_gate_sigmas" => Place::Key(
            "tracker.velocity_gate_sigmas",
            span(&t.velocity_gate_sigmas),
        ),
        "max_initiation_interval" => Place::Key(
            "tracker.max_initiation_interval",
            span(&t.max_initiation_interval),
        ),
        "confirm_m" => Place::Key("tracker.confirm_m", span(&t.confirm_m)),
        "confirm_n" => Place::Key("tracker.confirm_n", span(&t.confirm_n)),
        "max_misses" => Place::Key("tracker.max_misses", span(&t.max_misses)),
        "max_position_sigma" => {
            Place::Key("tracker.max_position_sigma", span(&t.max_position_sigma))
        }
        "grid_cell" => Place::Key("tracker.grid_cell", span(&t.grid_cell)),
        "association" => Place::Key("tracker.association", span(&t.association)),
        "association.p_detection" => Place::Key("tracker.p_detection", span(&t.p_detection)),
        "association.clutter_density" => {
            Place::Key("tracker.clutter_density", span(&t.clutter_density))
        }
        "association.max_exact_events" => {
            Place::Key("tracker.max_exact_events", span(&t.max_exact_events))
        }
        "score.p_detection" => Place::Key("tracker.score.p_detection", score(|s| &s.p_detection)),
        "score.clutter_density" => Place::Key(
            "tracker.score.clutter_density",
            score(|s| &s.clutter_density),
        ),
        "score.new_target_density" => Place::Key(
            "tracker.score.new_target_density",
            score(|s| &s.new_target_density),
        ),
        "score.false_confirm" => {
            Place::Key("tracker.score.false_confirm", score(|s| &s.false_confirm))
        }
        "score.missed_confirm" => {
            Place::Key("tracker.score.missed_confirm", score(|s| &s.missed_confirm))
        }
        "score.delete_drop" => Place::Key("tracker.score.delete_drop", score(|s| &s.delete_drop)),
        "sigma_a" => Place::Key("estimator.sigma_a", est.sigma_a.as_ref().map(Spanned::span)),
        "estimator.sigma_a_low" | "estimator.sigma_a_high" => {
            Place::Key("estimator.models", est.models.as_ref().map(Spanned::span))
        }
        "estimator.p_stay" => {
            Place::Key("estimator.markov", est.markov.as_ref().map(Spanned::span))
        }
        "estimator.grid_spacing" => Place::Key("estimator.p", est.p.as_ref().map(Spanned::span)),
        "estimator.clip" => Place::Key("estimator.clip", est.clip.as_ref().map(Spanned::span)),
        "sensors.position" => Place::Sensor(SensorKey::Position),
        "sensors.polar_noise.sigma_range" => Place::Sensor(SensorKey::SigmaRange),
        "sensors.polar_noise.sigma_azimuth" => Place::Sensor(SensorKey::SigmaAzimuth),
        "sensors.polar_noise" => Place::Sensor(SensorKey::NoPolarNoise),
        "sensors.id" => Place::Sensor(SensorKey::Id),
        "sensors" => Place::NoSensor,
        // A field this map does not know: named as the tracker names it, at the
        // `[tracker]` line.
        other => Place::Key(other, None),
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
            CliError::input(src.path, Some(src.line(&at)), Some(key), msg)
        }
        Place::Sensor(key) => sensor_error(src, file, key, *value, reason),
        Place::NoSensor => src.missing("sensor", "the tracker needs at least one [[sensor]]"),
    }
}

/// A sensor value the tracker refuses, at the `[[sensor]]` that holds it (the value
/// reported is the sensor's id for a missing polar noise or a repeated id, else the bad
/// number: the sensor is found by that value).
fn sensor_error(
    src: Source<'_>,
    file: &File,
    key: SensorKey,
    value: f64,
    reason: &str,
) -> CliError {
    let same = |v: f64| v.to_bits() == value.to_bits();
    let found = file.sensors.iter().find_map(|s| {
        let id = *s.id.get_ref();
        let hit = match key {
            SensorKey::Position => s
                .position
                .get_ref()
                .iter()
                .any(|v| same(*v))
                .then(|| s.position.span()),
            SensorKey::SigmaRange => s
                .sigma_range
                .as_ref()
                .filter(|v| same(*v.get_ref()))
                .map(Spanned::span),
            SensorKey::SigmaAzimuth => s
                .sigma_azimuth_deg
                .as_ref()
                .filter(|v| same(v.get_ref().to_radians()))
                .map(Spanned::span),
            SensorKey::NoPolarNoise | SensorKey::Id => same(f64::from(id)).then(|| s.id.span()),
        };
        hit.map(|span| (id, span))
    });
    match found {
        Some((id, span)) => CliError::input(
            src.path,
            Some(src.line(&span)),
            Some(key.name()),
            format!("sensor {id}: {reason}"),
        ),
        None => src.missing(key.name(), format!("{value}: {reason}")),
    }
}

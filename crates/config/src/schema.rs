//! The `argus track` configuration file as written (`docs/FORMATS.md`): `[[sensor]]`,
//! `[estimator]` and the optional `[tracker]`, read once. Every value keeps its place in
//! the file ([`Spanned`]) so that a check made later still names the line; serde rejects
//! unknown keys and wrong types at their line. [`crate::spec`] and
//! [`crate::tracker_config`] turn these tables into checked values.

use std::ops::Range;
use std::path::Path;

use serde::Deserialize;
use toml::Spanned;

use crate::error::ConfigError;

/// The whole file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct File {
    /// `[[sensor]]`, in file order.
    #[serde(rename = "sensor", default)]
    pub(crate) sensors: Vec<SensorTable>,
    /// `[estimator]`.
    pub(crate) estimator: EstimatorTable,
    /// `[tracker]`: present for the multi-target tracker.
    pub(crate) tracker: Option<Spanned<TrackerTable>>,
    /// `[reference]`: the system reference point (geodetic sites, `lat, lon` columns).
    pub(crate) reference: Option<Spanned<ReferenceTable>>,
}

/// `[reference]`: the origin of the local East-North-Up plane, WGS-84 (degrees, metres
/// above the ellipsoid).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ReferenceTable {
    pub(crate) latitude: Spanned<f64>,
    pub(crate) longitude: Spanned<f64>,
    pub(crate) altitude: Option<Spanned<f64>>,
}

/// A `[[sensor]]`: id and position (`[x, y]` or `[x, y, z]`, or a WGS-84 `latitude,
/// longitude, altitude` with a `[reference]`); polar sensors also their noise, spherical
/// ones also the elevation noise; a rotating radar its revolution period, direction and
/// north time (for the multi-target tracker); a radar of an ASTERIX capture its SAC/SIC.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SensorTable {
    pub(crate) id: Spanned<u32>,
    pub(crate) position: Option<Spanned<Vec<f64>>>,
    pub(crate) latitude: Option<Spanned<f64>>,
    pub(crate) longitude: Option<Spanned<f64>>,
    pub(crate) altitude: Option<Spanned<f64>>,
    pub(crate) sigma_range: Option<Spanned<f64>>,
    pub(crate) sigma_azimuth_deg: Option<Spanned<f64>>,
    pub(crate) sigma_elevation_deg: Option<Spanned<f64>>,
    pub(crate) revolution_period: Option<Spanned<f64>>,
    pub(crate) rotation: Option<Spanned<RotationKind>>,
    pub(crate) north_time: Option<Spanned<f64>>,
    /// ASTERIX data source (I048/010): system area code, with `sic`.
    pub(crate) sac: Option<Spanned<u8>>,
    /// ASTERIX data source: system identification code, with `sac`.
    pub(crate) sic: Option<Spanned<u8>>,
}

/// `rotation` of a rotating `[[sensor]]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(crate) enum RotationKind {
    /// North → east (the default).
    Clockwise,
    /// North → west.
    Counterclockwise,
}

/// Estimator kinds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub(crate) enum EstimatorKind {
    /// KF on converted plots (polar plots: unbiased conversion; Cartesian: as reported).
    KfConverted,
    /// EKF on polar plots.
    Ekf,
    /// IMM of CV / fixed-rate CT Kalman filters on converted plots (seed 000).
    Imm,
    /// The multi-IMM measurement-noise estimator of seed 000 eqs (8)–(14) around that IMM.
    MultiImm,
    /// The aircraft IMM (`argus_imm::AircraftImm`): two CV modes and a coordinated turn
    /// with the turn rate as a state, EKFs on one radar's polar plots.
    AircraftImm,
}

impl EstimatorKind {
    /// The name as written in the file (and in the tracker's summary).
    pub(crate) fn name(self) -> &'static str {
        match self {
            Self::KfConverted => "kf-converted",
            Self::Ekf => "ekf",
            Self::Imm => "imm",
            Self::MultiImm => "multi-imm",
            Self::AircraftImm => "aircraft-imm",
        }
    }
}

/// Motion-model kinds of an IMM mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub(crate) enum ModelKind {
    /// Constant velocity.
    Cv,
    /// Coordinated turn at a fixed rate.
    Ct,
}

/// `[estimator]`, flat: which keys a kind needs is checked by [`crate::spec`].
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct EstimatorTable {
    pub(crate) kind: Spanned<EstimatorKind>,
    pub(crate) sigma_a: Option<Spanned<f64>>,
    pub(crate) models: Option<Spanned<Vec<ModelTable>>>,
    pub(crate) markov: Option<Spanned<Vec<Vec<f64>>>>,
    pub(crate) initial: Option<Spanned<Vec<f64>>>,
    pub(crate) n: Option<Spanned<i64>>,
    pub(crate) p: Option<Spanned<f64>>,
    pub(crate) clip: Option<Spanned<f64>>,
    pub(crate) per_axis: Option<Spanned<bool>>,
    pub(crate) cv_sigma_a: Option<Spanned<Vec<f64>>>,
    pub(crate) ct_sigma_a: Option<Spanned<f64>>,
    pub(crate) ct_sigma_omega_deg: Option<Spanned<f64>>,
    pub(crate) start_sigma_omega_deg: Option<Spanned<f64>>,
    pub(crate) mixing: Option<Spanned<Mixing>>,
    pub(crate) mixing_sigma_omega_deg: Option<Spanned<f64>>,
}

/// The aircraft IMM's mixing rule for the turn rate (`argus_imm::Augmentation`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub(crate) enum Mixing {
    /// Granström et al.'s unbiased rule.
    Unbiased,
    /// `ω = 0` with the standard deviation `mixing_sigma_omega_deg`.
    Fixed,
}

/// One motion model of an IMM: `kind = "cv"` or `"ct"` (with `rate_deg`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ModelTable {
    pub(crate) kind: ModelKind,
    pub(crate) sigma_a: Spanned<f64>,
    pub(crate) rate_deg: Option<Spanned<f64>>,
}

/// `[tracker]`: every value is typed by [`crate::tracker_config`] rather than by serde,
/// so that a wrong type names its key (`tracker.<key>`) too.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct TrackerTable {
    pub(crate) association: Option<Spanned<toml::Value>>,
    pub(crate) p_detection: Option<Spanned<toml::Value>>,
    pub(crate) clutter_density: Option<Spanned<toml::Value>>,
    pub(crate) max_exact_events: Option<Spanned<toml::Value>>,
    pub(crate) gate_probability: Option<Spanned<toml::Value>>,
    pub(crate) max_speed: Option<Spanned<toml::Value>>,
    pub(crate) velocity_gate_sigmas: Option<Spanned<toml::Value>>,
    pub(crate) max_initiation_interval: Option<Spanned<toml::Value>>,
    pub(crate) confirm_m: Option<Spanned<toml::Value>>,
    pub(crate) confirm_n: Option<Spanned<toml::Value>>,
    pub(crate) max_misses: Option<Spanned<toml::Value>>,
    pub(crate) max_position_sigma: Option<Spanned<toml::Value>>,
    pub(crate) grid_cell: Option<Spanned<toml::Value>>,
    pub(crate) sector_fraction: Option<Spanned<toml::Value>>,
    pub(crate) score: Option<Spanned<ScoreTable>>,
}

/// `[tracker.score]`: track-score (SPRT) confirmation and deletion instead of M-of-N.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ScoreTable {
    pub(crate) p_detection: Spanned<toml::Value>,
    pub(crate) clutter_density: Spanned<toml::Value>,
    pub(crate) new_target_density: Spanned<toml::Value>,
    pub(crate) false_confirm: Spanned<toml::Value>,
    pub(crate) missed_confirm: Spanned<toml::Value>,
    pub(crate) delete_drop: Spanned<toml::Value>,
}

/// A configuration file: its path and its text, to turn a value's span into a line.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Source<'a> {
    pub(crate) path: &'a Path,
    pub(crate) text: &'a str,
}

impl Source<'_> {
    /// The 1-based line of the span's first byte.
    pub(crate) fn line(&self, span: &Range<usize>) -> u64 {
        self.text
            .get(..span.start)
            .map_or(0, |s| s.matches('\n').count() as u64 + 1)
    }

    /// An input error at the value `v` (its line), field `field`.
    pub(crate) fn at<T>(&self, v: &Spanned<T>, field: &str, msg: impl Into<String>) -> ConfigError {
        ConfigError::input(self.path, Some(self.line(&v.span())), Some(field), msg)
    }

    /// An input error about `field` with no line (a missing key).
    pub(crate) fn missing(&self, field: &str, msg: impl Into<String>) -> ConfigError {
        ConfigError::input(self.path, None, Some(field), msg)
    }
}

/// Parses configuration `text` (the file `path` in errors) into its tables.
///
/// # Errors
/// [`ConfigError::Input`] at the line of a syntax error, an unknown key or
/// a wrong type.
pub(crate) fn parse(text: &str, path: &Path) -> Result<File, ConfigError> {
    toml::from_str(text).map_err(|e| {
        let src = Source { path, text };
        ConfigError::input(
            path,
            e.span().map(|s| src.line(&s)),
            None,
            e.message().to_owned(),
        )
    })
}

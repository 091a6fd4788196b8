//! The `argus track` configuration file as written (`docs/FORMATS.md`): `[[sensor]]`,
//! `[estimator]` and the optional `[tracker]`, read once. Every value keeps its place in
//! the file ([`Spanned`]) so that a check made later still names the line; serde rejects
//! unknown keys and wrong types at their line. [`super::spec`] and
//! [`super::tracker_config`] turn these tables into checked values.

use std::ops::Range;
use std::path::Path;

use serde::Deserialize;
use toml::Spanned;

use crate::error::CliError;

/// The whole file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct File {
    /// `[[sensor]]`, in file order.
    #[serde(rename = "sensor", default)]
    pub(super) sensors: Vec<SensorTable>,
    /// `[estimator]`.
    pub(super) estimator: EstimatorTable,
    /// `[tracker]`: present for the multi-target tracker.
    pub(super) tracker: Option<Spanned<TrackerTable>>,
    /// `[reference]`: the system reference point (geodetic sites, `lat, lon` columns).
    pub(super) reference: Option<Spanned<ReferenceTable>>,
}

/// `[reference]`: the origin of the local East-North-Up plane, WGS-84 (degrees, metres
/// above the ellipsoid).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ReferenceTable {
    pub(super) latitude: Spanned<f64>,
    pub(super) longitude: Spanned<f64>,
    pub(super) altitude: Option<Spanned<f64>>,
}

/// A `[[sensor]]`: id and position (`[x, y]` or `[x, y, z]`, or a WGS-84 `latitude,
/// longitude, altitude` with a `[reference]`); polar sensors also their noise, spherical
/// ones also the elevation noise; a rotating radar its revolution period, direction and
/// north time (for the multi-target tracker); a radar of an ASTERIX capture its SAC/SIC.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SensorTable {
    pub(super) id: Spanned<u32>,
    pub(super) position: Option<Spanned<Vec<f64>>>,
    pub(super) latitude: Option<Spanned<f64>>,
    pub(super) longitude: Option<Spanned<f64>>,
    pub(super) altitude: Option<Spanned<f64>>,
    pub(super) sigma_range: Option<Spanned<f64>>,
    pub(super) sigma_azimuth_deg: Option<Spanned<f64>>,
    pub(super) sigma_elevation_deg: Option<Spanned<f64>>,
    pub(super) revolution_period: Option<Spanned<f64>>,
    pub(super) rotation: Option<Spanned<RotationKind>>,
    pub(super) north_time: Option<Spanned<f64>>,
    /// ASTERIX data source (I048/010): system area code, with `sic`.
    pub(super) sac: Option<Spanned<u8>>,
    /// ASTERIX data source: system identification code, with `sac`.
    pub(super) sic: Option<Spanned<u8>>,
}

/// `rotation` of a rotating `[[sensor]]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum RotationKind {
    /// North → east (the default).
    Clockwise,
    /// North → west.
    Counterclockwise,
}

/// Estimator kinds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub(super) enum EstimatorKind {
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
    pub(super) fn name(self) -> &'static str {
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
pub(super) enum ModelKind {
    /// Constant velocity.
    Cv,
    /// Coordinated turn at a fixed rate.
    Ct,
}

/// `[estimator]`, flat: which keys a kind needs is checked by [`super::spec`].
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct EstimatorTable {
    pub(super) kind: Spanned<EstimatorKind>,
    pub(super) sigma_a: Option<Spanned<f64>>,
    pub(super) models: Option<Spanned<Vec<ModelTable>>>,
    pub(super) markov: Option<Spanned<Vec<Vec<f64>>>>,
    pub(super) initial: Option<Spanned<Vec<f64>>>,
    pub(super) n: Option<Spanned<i64>>,
    pub(super) p: Option<Spanned<f64>>,
    pub(super) clip: Option<Spanned<f64>>,
    pub(super) per_axis: Option<Spanned<bool>>,
    pub(super) cv_sigma_a: Option<Spanned<Vec<f64>>>,
    pub(super) ct_sigma_a: Option<Spanned<f64>>,
    pub(super) ct_sigma_omega_deg: Option<Spanned<f64>>,
    pub(super) start_sigma_omega_deg: Option<Spanned<f64>>,
    pub(super) mixing: Option<Spanned<Mixing>>,
    pub(super) mixing_sigma_omega_deg: Option<Spanned<f64>>,
}

/// The aircraft IMM's mixing rule for the turn rate (`argus_imm::Augmentation`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub(super) enum Mixing {
    /// Granström et al.'s unbiased rule.
    Unbiased,
    /// `ω = 0` with the standard deviation `mixing_sigma_omega_deg`.
    Fixed,
}

/// One motion model of an IMM: `kind = "cv"` or `"ct"` (with `rate_deg`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ModelTable {
    pub(super) kind: ModelKind,
    pub(super) sigma_a: Spanned<f64>,
    pub(super) rate_deg: Option<Spanned<f64>>,
}

/// `[tracker]`: every value is typed by [`super::tracker_config`] rather than by serde,
/// so that a wrong type names its key (`tracker.<key>`) too.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct TrackerTable {
    pub(super) association: Option<Spanned<toml::Value>>,
    pub(super) p_detection: Option<Spanned<toml::Value>>,
    pub(super) clutter_density: Option<Spanned<toml::Value>>,
    pub(super) max_exact_events: Option<Spanned<toml::Value>>,
    pub(super) gate_probability: Option<Spanned<toml::Value>>,
    pub(super) max_speed: Option<Spanned<toml::Value>>,
    pub(super) velocity_gate_sigmas: Option<Spanned<toml::Value>>,
    pub(super) max_initiation_interval: Option<Spanned<toml::Value>>,
    pub(super) confirm_m: Option<Spanned<toml::Value>>,
    pub(super) confirm_n: Option<Spanned<toml::Value>>,
    pub(super) max_misses: Option<Spanned<toml::Value>>,
    pub(super) max_position_sigma: Option<Spanned<toml::Value>>,
    pub(super) grid_cell: Option<Spanned<toml::Value>>,
    pub(super) sector_fraction: Option<Spanned<toml::Value>>,
    pub(super) score: Option<Spanned<ScoreTable>>,
}

/// `[tracker.score]`: track-score (SPRT) confirmation and deletion instead of M-of-N.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ScoreTable {
    pub(super) p_detection: Spanned<toml::Value>,
    pub(super) clutter_density: Spanned<toml::Value>,
    pub(super) new_target_density: Spanned<toml::Value>,
    pub(super) false_confirm: Spanned<toml::Value>,
    pub(super) missed_confirm: Spanned<toml::Value>,
    pub(super) delete_drop: Spanned<toml::Value>,
}

/// A configuration file: its path and its text, to turn a value's span into a line.
#[derive(Debug, Clone, Copy)]
pub(super) struct Source<'a> {
    pub(super) path: &'a Path,
    pub(super) text: &'a str,
}

impl Source<'_> {
    /// The 1-based line of the span's first byte.
    pub(super) fn line(&self, span: &Range<usize>) -> u64 {
        self.text
            .get(..span.start)
            .map_or(0, |s| s.matches('\n').count() as u64 + 1)
    }

    /// An input error at the value `v` (its line), field `field`.
    pub(super) fn at<T>(&self, v: &Spanned<T>, field: &str, msg: impl Into<String>) -> CliError {
        CliError::input(self.path, Some(self.line(&v.span())), Some(field), msg)
    }

    /// An input error about `field` with no line (a missing key).
    pub(super) fn missing(&self, field: &str, msg: impl Into<String>) -> CliError {
        CliError::input(self.path, None, Some(field), msg)
    }
}

/// Reads and parses `path`; returns its text (for the lines of later errors) and tables.
///
/// # Errors
/// [`CliError::Io`]; [`CliError::Input`] at the line of a syntax error, an unknown key or
/// a wrong type.
pub(super) fn read(path: &Path) -> Result<(String, File), CliError> {
    let text = std::fs::read_to_string(path).map_err(|e| CliError::io(path, e))?;
    let file = toml::from_str(&text).map_err(|e| {
        let src = Source { path, text: &text };
        CliError::input(
            path,
            e.span().map(|s| src.line(&s)),
            None,
            e.message().to_owned(),
        )
    })?;
    Ok((text, file))
}

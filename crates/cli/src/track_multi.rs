//! `argus track` with a `[tracker]` table: the multi-target tracker ([`argus_tracker`])
//! over a user's plot file, one CSV row per track per scan with its id and status, and a
//! JSON summary (see `docs/FORMATS.md`).
//!
//! The `[[sensor]]` and `[estimator]` tables are read and checked by `track.rs` first; this
//! module maps them and the `[tracker]` table onto [`TrackerConfig`] (whose
//! [`TrackerConfig::validate`] is the one check of the tracker's values: its field names
//! are mapped back to the file's lines here), groups the plots into scans by
//! `(time, sensor)` in file order and writes every track's state after every scan.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::ops::Range;
use std::path::{Path, PathBuf};

use argus_sensors::Measurement;
use argus_tracker::{
    AssociationConfig, AssociationField, DeletionReason, EstimatorConfig, EstimatorField,
    MULTI_IMM_HYPOTHESES, Plot, PolarNoise, ScoreConfig, ScoreField, SensorConfig, SensorField,
    SensorId, Track, TrackStatus, Tracker, TrackerConfig, TrackerError,
};
use serde::Deserialize;
use toml::Spanned;

use crate::error::CliError;
use crate::output::write_atomic;
use crate::plotfile::FilePlot;
use crate::track::{Sensor, line_of};

/// The parts of the configuration file this module reads (the rest is `track.rs`'s).
#[derive(Debug, Deserialize)]
struct Outer {
    tracker: Option<Spanned<TrackerTable>>,
    estimator: EstimatorKeys,
    #[serde(rename = "sensor", default)]
    sensors: Vec<SensorKeys>,
}

/// The place of a `[[sensor]]`'s values (checked by `track.rs`).
#[derive(Debug, Deserialize)]
struct SensorKeys {
    id: Spanned<u32>,
    position: Spanned<Vec<f64>>,
    sigma_range: Option<Spanned<f64>>,
    sigma_azimuth_deg: Option<Spanned<f64>>,
}

/// The `[tracker]` table as written: every value keeps its place for error messages and
/// is typed here, so that a wrong type names its key too.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct TrackerTable {
    association: Option<Spanned<toml::Value>>,
    p_detection: Option<Spanned<toml::Value>>,
    clutter_density: Option<Spanned<toml::Value>>,
    max_exact_events: Option<Spanned<toml::Value>>,
    gate_probability: Option<Spanned<toml::Value>>,
    max_speed: Option<Spanned<toml::Value>>,
    velocity_gate_sigmas: Option<Spanned<toml::Value>>,
    max_initiation_interval: Option<Spanned<toml::Value>>,
    confirm_m: Option<Spanned<toml::Value>>,
    confirm_n: Option<Spanned<toml::Value>>,
    max_misses: Option<Spanned<toml::Value>>,
    max_position_sigma: Option<Spanned<toml::Value>>,
    grid_cell: Option<Spanned<toml::Value>>,
    score: Option<Spanned<ScoreTable>>,
}

/// `[tracker.score]`: track-score (SPRT) confirmation and deletion instead of M-of-N.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ScoreTable {
    p_detection: Spanned<toml::Value>,
    clutter_density: Spanned<toml::Value>,
    new_target_density: Spanned<toml::Value>,
    false_confirm: Spanned<toml::Value>,
    missed_confirm: Spanned<toml::Value>,
    delete_drop: Spanned<toml::Value>,
}

/// The `[estimator]` keys the tracker maps (already type-checked by `track.rs`).
#[derive(Debug, Deserialize)]
struct EstimatorKeys {
    kind: Spanned<String>,
    sigma_a: Option<Spanned<f64>>,
    models: Option<Spanned<Vec<ModelKeys>>>,
    markov: Option<Spanned<Vec<Vec<f64>>>>,
    initial: Option<Spanned<Vec<f64>>>,
    n: Option<Spanned<i64>>,
    p: Option<Spanned<f64>>,
    clip: Option<Spanned<f64>>,
    per_axis: Option<Spanned<bool>>,
}

/// One IMM model as written.
#[derive(Debug, Deserialize)]
struct ModelKeys {
    kind: String,
    sigma_a: f64,
}

/// A validated multi-target configuration.
#[derive(Debug, Clone)]
pub(crate) struct MultiTarget {
    config: TrackerConfig,
    /// `estimator.kind` as written.
    estimator: String,
}

/// Reads and checks `path` against `[tracker]`: `None` when the file has no `[tracker]`
/// table (one estimator over the file, `track.rs`), else the tracker's configuration.
/// `sensors` are the sensors `track.rs` read from the same file.
///
/// # Errors
/// [`CliError::Input`] naming the file, the line and the field (`tracker.<key>`,
/// `estimator.<key>`) of the first bad value.
pub(crate) fn load(path: &Path, sensors: &[Sensor]) -> Result<Option<MultiTarget>, CliError> {
    let text = std::fs::read_to_string(path).map_err(|e| CliError::io(path, e))?;
    let outer: Outer = toml::from_str(&text).map_err(|e| {
        let line = e.span().map(|s| line_of(&text, s.start));
        CliError::input(path, line, None, e.message().to_owned())
    })?;
    let Some(table) = outer.tracker else {
        return Ok(None);
    };
    let cx = Cx {
        path,
        text: &text,
        table: &table,
        estimator: &outer.estimator,
        sensors: &outer.sensors,
    };
    let config = cx.build(sensors)?;
    config.validate().map_err(|e| cx.config_error(&e))?;
    Ok(Some(MultiTarget {
        config,
        estimator: outer.estimator.kind.get_ref().clone(),
    }))
}

/// What the conversion of the tables needs to name errors.
struct Cx<'a> {
    path: &'a Path,
    text: &'a str,
    table: &'a Spanned<TrackerTable>,
    estimator: &'a EstimatorKeys,
    sensors: &'a [SensorKeys],
}

impl Cx<'_> {
    fn error(&self, span: Option<Range<usize>>, field: &str, msg: impl Into<String>) -> CliError {
        let line = span
            .map(|s| line_of(self.text, s.start))
            .or_else(|| Some(line_of(self.text, self.table.span().start)));
        CliError::input(self.path, line, Some(field), msg)
    }

    /// A number (TOML integer or float).
    fn number(&self, v: &Spanned<toml::Value>, field: &str) -> Result<f64, CliError> {
        match v.get_ref() {
            toml::Value::Float(x) => Ok(*x),
            toml::Value::Integer(i) => Ok(*i as f64),
            other => Err(self.error(Some(v.span()), field, format!("{other} is not a number"))),
        }
    }

    /// An optional number, `default` when absent.
    fn number_or(
        &self,
        v: Option<&Spanned<toml::Value>>,
        field: &str,
        default: f64,
    ) -> Result<f64, CliError> {
        v.map_or(Ok(default), |v| self.number(v, field))
    }

    /// An optional non-negative integer that fits `u32`, `default` when absent.
    fn count_or(
        &self,
        v: Option<&Spanned<toml::Value>>,
        field: &str,
        default: u32,
    ) -> Result<u32, CliError> {
        let Some(v) = v else { return Ok(default) };
        match v.get_ref() {
            toml::Value::Integer(i) => u32::try_from(*i).map_err(|_| {
                self.error(
                    Some(v.span()),
                    field,
                    format!("{i} is not a count (0 … {})", u32::MAX),
                )
            }),
            other => Err(self.error(Some(v.span()), field, format!("{other} is not an integer"))),
        }
    }

    /// The tracker configuration as written (not yet validated).
    fn build(&self, sensors: &[Sensor]) -> Result<TrackerConfig, CliError> {
        let t = self.table.get_ref();
        let mut c = TrackerConfig::new(sensors.iter().map(|s| SensorConfig {
            id: SensorId(s.id),
            position: [s.position[0], s.position[1]],
            polar_noise: s.polar.map(|(sigma_range, sigma_azimuth)| PolarNoise {
                sigma_range,
                sigma_azimuth,
            }),
        }));
        c.gate_probability = self.number_or(
            t.gate_probability.as_ref(),
            "tracker.gate_probability",
            c.gate_probability,
        )?;
        c.max_speed = self.number_or(t.max_speed.as_ref(), "tracker.max_speed", c.max_speed)?;
        c.velocity_gate_sigmas = self.number_or(
            t.velocity_gate_sigmas.as_ref(),
            "tracker.velocity_gate_sigmas",
            c.velocity_gate_sigmas,
        )?;
        c.max_initiation_interval = self.number_or(
            t.max_initiation_interval.as_ref(),
            "tracker.max_initiation_interval",
            c.max_initiation_interval,
        )?;
        c.confirm_m = self.count_or(t.confirm_m.as_ref(), "tracker.confirm_m", c.confirm_m)?;
        c.confirm_n = self.count_or(t.confirm_n.as_ref(), "tracker.confirm_n", c.confirm_n)?;
        c.max_misses = self.count_or(t.max_misses.as_ref(), "tracker.max_misses", c.max_misses)?;
        c.max_position_sigma = self.number_or(
            t.max_position_sigma.as_ref(),
            "tracker.max_position_sigma",
            c.max_position_sigma,
        )?;
        c.grid_cell = self.number_or(t.grid_cell.as_ref(), "tracker.grid_cell", c.grid_cell)?;
        if let Some(s) = &t.score {
            let s = s.get_ref();
            c.score = Some(ScoreConfig {
                p_detection: self.number(&s.p_detection, "tracker.score.p_detection")?,
                clutter_density: self
                    .number(&s.clutter_density, "tracker.score.clutter_density")?,
                new_target_density: self
                    .number(&s.new_target_density, "tracker.score.new_target_density")?,
                false_confirm: self.number(&s.false_confirm, "tracker.score.false_confirm")?,
                missed_confirm: self.number(&s.missed_confirm, "tracker.score.missed_confirm")?,
                delete_drop: self.number(&s.delete_drop, "tracker.score.delete_drop")?,
            });
        }
        c.association = self.association()?;
        self.estimator_into(&mut c)?;
        Ok(c)
    }

    /// `association` and its JPDA keys (which GNN refuses rather than ignores).
    fn association(&self) -> Result<AssociationConfig, CliError> {
        let t = self.table.get_ref();
        let name = match &t.association {
            None => "gnn".to_owned(),
            Some(v) => match v.get_ref() {
                toml::Value::String(s) => s.clone(),
                other => {
                    return Err(self.error(
                        Some(v.span()),
                        "tracker.association",
                        format!("{other} is not a string: \"gnn\" or \"jpda\""),
                    ));
                }
            },
        };
        let jpda_keys = [
            (&t.p_detection, "tracker.p_detection"),
            (&t.clutter_density, "tracker.clutter_density"),
            (&t.max_exact_events, "tracker.max_exact_events"),
        ];
        match name.as_str() {
            "gnn" => {
                if let Some((Some(v), field)) = jpda_keys.iter().find(|(v, _)| v.is_some()) {
                    return Err(self.error(
                        Some(v.span()),
                        field,
                        "used by association = \"jpda\" only (association is \"gnn\")",
                    ));
                }
                Ok(AssociationConfig::Gnn)
            }
            "jpda" => {
                let need = |v: &Option<Spanned<toml::Value>>, field: &str| {
                    v.as_ref().map_or_else(
                        || Err(self.error(None, field, "required by association = \"jpda\"")),
                        |v| self.number(v, field),
                    )
                };
                let max_exact_events = self.count_or(
                    t.max_exact_events.as_ref(),
                    "tracker.max_exact_events",
                    DEFAULT_MAX_EXACT_EVENTS,
                )?;
                Ok(AssociationConfig::Jpda {
                    p_detection: need(&t.p_detection, "tracker.p_detection")?,
                    clutter_density: need(&t.clutter_density, "tracker.clutter_density")?,
                    max_exact_events: max_exact_events as usize,
                })
            }
            other => Err(self.error(
                t.association.as_ref().map(Spanned::span),
                "tracker.association",
                format!("unknown association \"{other}\": \"gnn\" or \"jpda\""),
            )),
        }
    }

    /// The per-track estimator from `[estimator]`: `kf-converted` is the tracker's KF,
    /// `ekf` its EKF, `imm` its two-mode CV IMM, `multi-imm` its multi-IMM around that IMM
    /// (five hypotheses on one common scale).
    fn estimator_into(&self, c: &mut TrackerConfig) -> Result<(), CliError> {
        let e = self.estimator;
        let at = |s: Range<usize>| Some(line_of(self.text, s.start));
        let sigma_a = e.sigma_a.as_ref().map(|v| *v.get_ref());
        c.estimator = match e.kind.get_ref().as_str() {
            "kf-converted" => {
                c.sigma_a = sigma_a.unwrap_or(c.sigma_a);
                EstimatorConfig::Kf
            }
            "ekf" => {
                c.sigma_a = sigma_a.unwrap_or(c.sigma_a);
                EstimatorConfig::Ekf
            }
            "imm" => {
                let (sigma_a_low, sigma_a_high, p_stay) = self.imm_cv2()?;
                EstimatorConfig::ImmCv2 {
                    sigma_a_low,
                    sigma_a_high,
                    p_stay,
                }
            }
            "multi-imm" => {
                let (sigma_a_low, sigma_a_high, p_stay) = self.imm_cv2()?;
                if let Some(n) = &e.n
                    && usize::try_from(*n.get_ref()).ok() != Some(MULTI_IMM_HYPOTHESES)
                {
                    return Err(CliError::input(
                        self.path,
                        at(n.span()),
                        Some("estimator.n"),
                        format!(
                            "the tracker's multi-IMM has n = {MULTI_IMM_HYPOTHESES} hypotheses (seed 000), not {}",
                            n.get_ref()
                        ),
                    ));
                }
                if let Some(pa) = &e.per_axis
                    && *pa.get_ref()
                {
                    return Err(CliError::input(
                        self.path,
                        at(pa.span()),
                        Some("estimator.per_axis"),
                        "the tracker's multi-IMM scales range and azimuth by one factor (per_axis = false)",
                    ));
                }
                EstimatorConfig::MultiImm {
                    sigma_a_low,
                    sigma_a_high,
                    p_stay,
                    // track.rs's defaults: the paper's p = 0.1 and ±5 % clip; 0 = no clip.
                    grid_spacing: e.p.as_ref().map_or(0.1, |p| *p.get_ref()),
                    clip: match e.clip.as_ref().map(|v| *v.get_ref()) {
                        None => Some(0.05),
                        Some(v) if v > 0.0 => Some(v),
                        Some(_) => None,
                    },
                }
            }
            other => {
                return Err(CliError::input(
                    self.path,
                    at(e.kind.span()),
                    Some("estimator.kind"),
                    format!("kind \"{other}\" is not built for the multi-target tracker"),
                ));
            }
        };
        Ok(())
    }

    /// The tracker's IMM: two CV models, a symmetric Markov matrix, uniform start.
    fn imm_cv2(&self) -> Result<(f64, f64, f64), CliError> {
        let e = self.estimator;
        let at = |s: Range<usize>| Some(line_of(self.text, s.start));
        let models = e.models.as_ref().ok_or_else(|| {
            CliError::input(
                self.path,
                None,
                Some("estimator.models"),
                "required by kind \"imm\"",
            )
        })?;
        let [m1, m2] = models.get_ref().as_slice() else {
            return Err(CliError::input(
                self.path,
                at(models.span()),
                Some("estimator.models"),
                format!(
                    "the tracker's IMM has two CV models (quiet, manoeuvre), not {}",
                    models.get_ref().len()
                ),
            ));
        };
        if m1.kind != "cv" || m2.kind != "cv" {
            return Err(CliError::input(
                self.path,
                at(models.span()),
                Some("estimator.models"),
                "the tracker's IMM has two CV models (quiet, manoeuvre); CT models are not built per track",
            ));
        }
        let markov = e.markov.as_ref().ok_or_else(|| {
            CliError::input(
                self.path,
                None,
                Some("estimator.markov"),
                "required by kind \"imm\"",
            )
        })?;
        let m = markov.get_ref();
        let p_stay = m
            .first()
            .and_then(|r| r.first())
            .copied()
            .unwrap_or(f64::NAN);
        let q_stay = m.get(1).and_then(|r| r.get(1)).copied().unwrap_or(f64::NAN);
        if (p_stay - q_stay).abs() > 1e-12 {
            return Err(CliError::input(
                self.path,
                at(markov.span()),
                Some("estimator.markov"),
                format!(
                    "the tracker's IMM stays in either mode with one probability: markov = [[p, 1 − p], [1 − p, p]] (here {p_stay} and {q_stay})"
                ),
            ));
        }
        if let Some(init) = &e.initial
            && init.get_ref().iter().any(|mu| (mu - 0.5).abs() > 1e-12)
        {
            return Err(CliError::input(
                self.path,
                at(init.span()),
                Some("estimator.initial"),
                "the tracker starts both modes at 0.5: leave initial out or write [0.5, 0.5]",
            ));
        }
        Ok((m1.sigma_a, m2.sigma_a, p_stay))
    }

    /// A sensor value the tracker refuses: the `[[sensor]]` that holds it (the value
    /// reported is the sensor's id for a missing polar noise or a repeated id, else the
    /// bad number).
    fn sensor_error(&self, field: SensorField, value: f64, reason: &str) -> CliError {
        let same = |v: f64| v.to_bits() == value.to_bits();
        let found = self.sensors.iter().find_map(|s| {
            let id = *s.id.get_ref();
            let hit = match field {
                SensorField::Position => s
                    .position
                    .get_ref()
                    .iter()
                    .any(|v| same(*v))
                    .then(|| s.position.span()),
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
                _ => same(f64::from(id)).then(|| s.id.span()),
            };
            hit.map(|span| (id, span))
        });
        let key = match field {
            SensorField::Position => "position",
            SensorField::SigmaRange => "sigma_range",
            SensorField::SigmaAzimuth => "sigma_azimuth_deg",
            SensorField::PolarNoise => "sigma_range",
            _ => "id",
        };
        match found {
            Some((id, span)) => CliError::input(
                self.path,
                Some(line_of(self.text, span.start)),
                Some(key),
                format!("sensor {id}: {reason}"),
            ),
            None => CliError::input(self.path, None, Some(key), format!("{value}: {reason}")),
        }
    }

    /// Maps a [`TrackerError::InvalidConfig`] from [`TrackerConfig::validate`] to the key
    /// of the file that holds the value (the `[tracker]` line for a default).
    fn config_error(&self, e: &TrackerError) -> CliError {
        let TrackerError::InvalidConfig {
            field,
            value,
            reason,
        } = e
        else {
            return CliError::input(self.path, None, Some("tracker"), e.to_string());
        };
        let t = self.table.get_ref();
        let span = |v: &Option<Spanned<toml::Value>>| v.as_ref().map(Spanned::span);
        let score = |f: fn(&ScoreTable) -> &Spanned<toml::Value>| {
            t.score.as_ref().map(|s| f(s.get_ref()).span())
        };
        let est = self.estimator;
        use argus_tracker::ConfigField as F;
        let (name, at): (String, Option<Range<usize>>) = match *field {
            F::GateProbability => (format!("tracker.{field}"), span(&t.gate_probability)),
            F::MaxSpeed => (format!("tracker.{field}"), span(&t.max_speed)),
            F::VelocityGateSigmas => (format!("tracker.{field}"), span(&t.velocity_gate_sigmas)),
            F::MaxInitiationInterval => {
                (format!("tracker.{field}"), span(&t.max_initiation_interval))
            }
            F::ConfirmM => (format!("tracker.{field}"), span(&t.confirm_m)),
            F::ConfirmN => (format!("tracker.{field}"), span(&t.confirm_n)),
            F::MaxMisses => (format!("tracker.{field}"), span(&t.max_misses)),
            F::MaxPositionSigma => (format!("tracker.{field}"), span(&t.max_position_sigma)),
            F::GridCell => (format!("tracker.{field}"), span(&t.grid_cell)),
            F::Association(AssociationField::Kind) => {
                ("tracker.association".into(), span(&t.association))
            }
            F::Association(AssociationField::PDetection) => {
                ("tracker.p_detection".into(), span(&t.p_detection))
            }
            F::Association(AssociationField::ClutterDensity) => {
                ("tracker.clutter_density".into(), span(&t.clutter_density))
            }
            F::Association(AssociationField::MaxExactEvents) => {
                ("tracker.max_exact_events".into(), span(&t.max_exact_events))
            }
            F::Score(ScoreField::PDetection) => {
                (format!("tracker.{field}"), score(|s| &s.p_detection))
            }
            F::Score(ScoreField::ClutterDensity) => {
                (format!("tracker.{field}"), score(|s| &s.clutter_density))
            }
            F::Score(ScoreField::NewTargetDensity) => {
                (format!("tracker.{field}"), score(|s| &s.new_target_density))
            }
            F::Score(ScoreField::FalseConfirm) => {
                (format!("tracker.{field}"), score(|s| &s.false_confirm))
            }
            F::Score(ScoreField::MissedConfirm) => {
                (format!("tracker.{field}"), score(|s| &s.missed_confirm))
            }
            F::Score(ScoreField::DeleteDrop) => {
                (format!("tracker.{field}"), score(|s| &s.delete_drop))
            }
            F::SigmaA => (
                "estimator.sigma_a".into(),
                est.sigma_a.as_ref().map(Spanned::span),
            ),
            F::Estimator(EstimatorField::SigmaALow | EstimatorField::SigmaAHigh) => (
                "estimator.models".into(),
                est.models.as_ref().map(Spanned::span),
            ),
            F::Estimator(EstimatorField::PStay) => (
                "estimator.markov".into(),
                est.markov.as_ref().map(Spanned::span),
            ),
            F::Estimator(EstimatorField::Kind) => ("estimator.kind".into(), Some(est.kind.span())),
            F::Estimator(EstimatorField::GridSpacing) => {
                ("estimator.p".into(), est.p.as_ref().map(Spanned::span))
            }
            F::Estimator(EstimatorField::Clip) => (
                "estimator.clip".into(),
                est.clip.as_ref().map(Spanned::span),
            ),
            F::Sensor(f) => {
                return self.sensor_error(f, *value, reason);
            }
            F::Sensors => {
                return CliError::input(
                    self.path,
                    None,
                    Some("sensor"),
                    "the tracker needs at least one [[sensor]]",
                );
            }
            other => (other.key().to_owned(), None),
        };
        // "association" carries no number of its own.
        let msg = if *field == F::Association(AssociationField::Kind) {
            (*reason).to_owned()
        } else {
            format!("{value}: {reason}")
        };
        self.error(at, &name, msg)
    }
}

/// `max_exact_events` when `association = "jpda"` does not give it (the default of
/// `argus run surveillance`'s `jpda_max_events`).
pub(crate) const DEFAULT_MAX_EXACT_EVENTS: u32 = 1000;

/// Where the run's inputs and outputs are, for errors and the summary.
pub(crate) struct Files<'a> {
    /// The configuration.
    pub(crate) config: &'a Path,
    /// The plot file.
    pub(crate) plots: &'a Path,
    /// The tracks CSV to write.
    pub(crate) out: &'a Path,
}

/// The tracker's plot of a file plot: polar plots go in as they are (the tracker converts
/// them with its sensor's noise, or the EKF and multi-IMM use them directly), Cartesian
/// reports with their covariance.
fn tracker_plot(files: &Files<'_>, p: &FilePlot) -> Result<Plot, CliError> {
    match p.measurement() {
        Measurement::Cartesian2(_) | Measurement::Polar(_) => Ok(p.plot),
        Measurement::Spherical(_) | Measurement::Cartesian3(_) => Err(CliError::input(
            files.plots,
            Some(p.line),
            None,
            "the multi-target tracker ([tracker]) tracks 2-D plots (polar or x, y); this plot is 3-D",
        )),
    }
}

/// A [`TrackerError`] about plot `index` of the scan starting at file plot `start`, at
/// that plot's line.
fn plot_error(files: &Files<'_>, plots: &[FilePlot], start: usize, e: TrackerError) -> CliError {
    let (index, field) = match &e {
        TrackerError::TimeOrder { index, .. } => (*index, Some("t")),
        TrackerError::UnknownSensor { index, .. } => (*index, Some("sensor")),
        TrackerError::NoPolarNoise { index, .. } | TrackerError::NotPolar { index, .. } => {
            (*index, Some("sensor"))
        }
        TrackerError::NonPositiveRange { index, .. } | TrackerError::Conversion { index, .. } => {
            (*index, Some("range"))
        }
        TrackerError::NonFinite { index, .. }
        | TrackerError::PlotCovariance { index, .. }
        | TrackerError::MixedScan { index, .. } => (*index, None),
        _ => return CliError::Tracker(e),
    };
    let line = plots.get(start + index).map(|p| p.line);
    CliError::input(files.plots, line, field, format!("tracker: {e}"))
}

/// The CSV name of a status.
fn status_name(s: TrackStatus) -> &'static str {
    match s {
        TrackStatus::Tentative => "tentative",
        TrackStatus::Confirmed => "confirmed",
        TrackStatus::Deleted => "deleted",
    }
}

/// The CSV and JSON name of a deletion reason.
fn reason_name(r: DeletionReason) -> &'static str {
    match r {
        DeletionReason::NotConfirmed => "not-confirmed",
        DeletionReason::Misses => "misses",
        DeletionReason::CovarianceGrowth => "covariance-growth",
        DeletionReason::FilterFailure => "filter-failure",
        DeletionReason::Score => "score",
    }
}

/// Every deletion reason, for the summary's zero counts.
const REASONS: [DeletionReason; 5] = [
    DeletionReason::NotConfirmed,
    DeletionReason::Misses,
    DeletionReason::CovarianceGrowth,
    DeletionReason::FilterFailure,
    DeletionReason::Score,
];

/// The CSV columns for a configuration.
fn header(c: &TrackerConfig) -> String {
    let mut h = String::from("t,sensor,track,status,reason,x,vx,y,vy,sigma_x,sigma_y");
    match c.estimator {
        EstimatorConfig::ImmCv2 { .. } => h.push_str(",mu_1,mu_2"),
        EstimatorConfig::MultiImm { .. } => h.push_str(",mu_1,mu_2,sigma_range,sigma_azimuth_deg"),
        EstimatorConfig::Kf | EstimatorConfig::Ekf => {}
    }
    if c.score.is_some() {
        h.push_str(",score");
    }
    h.push('\n');
    h
}

/// One CSV row: the track's state at its time, as produced by scan `sensor`.
fn row(out: &mut String, c: &TrackerConfig, sensor: SensorId, track: &Track) {
    let g = track.estimate();
    let (m, p) = (g.mean(), g.cov());
    let reason = track.deletion().map_or("", reason_name);
    let _ = write!(
        out,
        "{},{},{},{},{reason},{},{},{},{},{},{}",
        track.time(),
        sensor.0,
        track.id().0,
        status_name(track.status()),
        m[0],
        m[1],
        m[2],
        m[3],
        p[(0, 0)].sqrt(),
        p[(2, 2)].sqrt(),
    );
    if matches!(
        c.estimator,
        EstimatorConfig::ImmCv2 { .. } | EstimatorConfig::MultiImm { .. }
    ) {
        match track.mode_probabilities() {
            Some([a, b]) => {
                let _ = write!(out, ",{a},{b}");
            }
            None => out.push_str(",,"),
        }
    }
    if matches!(c.estimator, EstimatorConfig::MultiImm { .. }) {
        match track.noise_estimate() {
            Some(v) => {
                let _ = write!(
                    out,
                    ",{},{}",
                    v.range().sqrt(),
                    v.azimuth().sqrt().to_degrees()
                );
            }
            None => out.push_str(",,"),
        }
    }
    if c.score.is_some() {
        let _ = write!(out, ",{}", track.score());
    }
    out.push('\n');
}

/// Track counts over the run, for the summary.
#[derive(Debug, Default, serde::Serialize)]
struct Counts {
    initiated: usize,
    confirmed: usize,
    deleted: usize,
    deleted_by_reason: BTreeMap<&'static str, usize>,
    deleted_after_confirmation: usize,
    tentative_at_end: usize,
    confirmed_at_end: usize,
}

/// `<out>.summary.json`.
#[derive(Debug, serde::Serialize)]
struct Summary<'a> {
    command: &'static str,
    config: String,
    plots_file: String,
    tracks_file: String,
    estimator: &'a str,
    association: &'static str,
    confirmation: String,
    plots: usize,
    scans: usize,
    plots_assigned: usize,
    rows: usize,
    tracks: Counts,
}

/// The summary's path beside the tracks file: `<stem>.summary.json`.
pub(crate) fn summary_path(out: &Path) -> PathBuf {
    out.with_extension("summary.json")
}

/// Runs the tracker over `plots` (already read and checked by `plotfile`): every plot is
/// converted before the first scan, so a bad plot stops the run before any track exists
/// and nothing is written. Writes the tracks CSV and the summary atomically; returns the
/// number of rows.
///
/// # Errors
/// [`CliError::Input`] naming the plot file's line for a plot the tracker rejects;
/// [`CliError::Io`].
pub(crate) fn run(
    m: &MultiTarget,
    files: &Files<'_>,
    plots: &[FilePlot],
) -> Result<usize, CliError> {
    let converted = plots
        .iter()
        .map(|p| tracker_plot(files, p))
        .collect::<Result<Vec<_>, _>>()?;
    let c = &m.config;
    let mut tracker = Tracker::new(c.clone())?;
    let mut text = header(c);
    let mut counts = Counts {
        deleted_by_reason: REASONS.iter().map(|r| (reason_name(*r), 0)).collect(),
        ..Counts::default()
    };
    let (mut rows, mut scans, mut assigned) = (0, 0, 0);
    let mut start = 0;
    while start < converted.len() {
        let (t, s) = (converted[start].time(), converted[start].sensor());
        let len = converted[start..]
            .iter()
            .take_while(|p| p.sensor() == s && p.time().total_cmp(&t).is_eq())
            .count();
        let report = tracker
            .process_scan(t, s, &converted[start..start + len])
            .map_err(|e| plot_error(files, plots, start, e))?;
        scans += 1;
        assigned += report.assigned;
        counts.initiated += report.initiated.len();
        counts.confirmed += report.confirmed.len();
        counts.deleted += report.deleted.len();
        let deleted = tracker.take_deleted();
        for d in &deleted {
            if let Some(r) = d.deletion() {
                *counts.deleted_by_reason.entry(reason_name(r)).or_insert(0) += 1;
            }
            if d.confirmed_at().is_some() {
                counts.deleted_after_confirmation += 1;
            }
        }
        // One row per track of this scan, in id order (live tracks are in id order; a
        // deleted one goes in its place).
        let mut all: Vec<&Track> = tracker.tracks().iter().chain(&deleted).collect();
        all.sort_by_key(|tr| tr.id());
        for tr in all {
            row(&mut text, c, s, tr);
            rows += 1;
        }
        start += len;
    }
    for tr in tracker.tracks() {
        match tr.status() {
            TrackStatus::Tentative => counts.tentative_at_end += 1,
            TrackStatus::Confirmed => counts.confirmed_at_end += 1,
            TrackStatus::Deleted => {}
        }
    }
    write_atomic(files.out, text.as_bytes())?;
    let summary = Summary {
        command: "track",
        config: files.config.display().to_string(),
        plots_file: files.plots.display().to_string(),
        tracks_file: files.out.display().to_string(),
        estimator: &m.estimator,
        association: match c.association {
            AssociationConfig::Gnn => "gnn",
            AssociationConfig::Jpda { .. } => "jpda",
        },
        confirmation: match &c.score {
            Some(_) => "score".to_owned(),
            None => format!("m-of-n {}/{}", c.confirm_m, c.confirm_n),
        },
        plots: plots.len(),
        scans,
        plots_assigned: assigned,
        rows,
        tracks: counts,
    };
    let path = summary_path(files.out);
    let json = serde_json::to_string_pretty(&summary)
        .map_err(|e| CliError::io(&path, std::io::Error::other(e.to_string())))?;
    write_atomic(&path, json.as_bytes())?;
    println!("wrote {}", path.display());
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Loads `text` as `track.rs` then this module would.
    fn load_text(text: &str) -> Result<Option<MultiTarget>, CliError> {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("m.toml");
        std::fs::write(&p, text).unwrap();
        let sensors = [Sensor {
            id: 1,
            position: [10.0, 20.0, 0.0],
            polar: Some((50.0, 1e-3)),
            sigma_elevation: None,
        }];
        load(&p, &sensors)
    }

    const HEAD: &str = "[[sensor]]\nid = 1\nposition = [10.0, 20.0]\n\n[estimator]\nkind = \"kf-converted\"\nsigma_a = 1.5\n";

    #[test]
    fn every_key_reaches_its_field() {
        // Distinct values per key, so that a key mapped to the wrong field shows.
        let text = format!(
            "{HEAD}[tracker]\nassociation = \"jpda\"\np_detection = 0.8\nclutter_density = 2e-9\nmax_exact_events = 77\ngate_probability = 0.95\nmax_speed = 400\nvelocity_gate_sigmas = 2.5\nmax_initiation_interval = 11.0\nconfirm_m = 4\nconfirm_n = 6\nmax_misses = 5\nmax_position_sigma = 3000.0\ngrid_cell = 1500.0\n[tracker.score]\np_detection = 0.7\nclutter_density = 3e-9\nnew_target_density = 4e-10\nfalse_confirm = 0.01\nmissed_confirm = 0.2\ndelete_drop = 6.0\n"
        );
        let m = load_text(&text).unwrap().unwrap();
        let c = &m.config;
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-15 * b.abs();
        assert!(close(c.sigma_a, 1.5));
        assert!(close(c.gate_probability, 0.95));
        assert!(close(c.max_speed, 400.0));
        assert!(close(c.velocity_gate_sigmas, 2.5));
        assert!(close(c.max_initiation_interval, 11.0));
        assert_eq!((c.confirm_m, c.confirm_n, c.max_misses), (4, 6, 5));
        assert!(close(c.max_position_sigma, 3000.0));
        assert!(close(c.grid_cell, 1500.0));
        let AssociationConfig::Jpda {
            p_detection,
            clutter_density,
            max_exact_events,
        } = c.association
        else {
            panic!("not JPDA: {:?}", c.association);
        };
        assert!(close(p_detection, 0.8) && close(clutter_density, 2e-9));
        assert_eq!(max_exact_events, 77);
        let s = c.score.unwrap();
        assert!(close(s.p_detection, 0.7) && close(s.clutter_density, 3e-9));
        assert!(close(s.new_target_density, 4e-10) && close(s.delete_drop, 6.0));
        assert!(close(s.false_confirm, 0.01) && close(s.missed_confirm, 0.2));
        assert_eq!(c.estimator, EstimatorConfig::Kf);
        // The sensor with its position and polar noise.
        assert_eq!(c.sensors.len(), 1);
        assert_eq!(c.sensors[0].id, SensorId(1));
        let n = c.sensors[0].polar_noise.unwrap();
        assert!(close(n.sigma_range, 50.0) && close(n.sigma_azimuth, 1e-3));
        assert!(close(c.sensors[0].position[0], 10.0) && close(c.sensors[0].position[1], 20.0));
    }

    #[test]
    fn no_tracker_table_is_single_target_and_defaults_are_the_libraries() {
        assert!(load_text(HEAD).unwrap().is_none());
        let m = load_text(&format!("{HEAD}[tracker]\n")).unwrap().unwrap();
        let mut expected = TrackerConfig::new(m.config.sensors.clone());
        expected.sigma_a = 1.5;
        assert_eq!(m.config, expected);
        // JPDA's max_exact_events defaults to the CLI's constant.
        let m = load_text(&format!(
            "{HEAD}[tracker]\nassociation = \"jpda\"\np_detection = 0.9\nclutter_density = 1e-9\n"
        ))
        .unwrap()
        .unwrap();
        assert!(matches!(
            m.config.association,
            AssociationConfig::Jpda { max_exact_events, .. } if max_exact_events == DEFAULT_MAX_EXACT_EVENTS as usize
        ));
    }
}

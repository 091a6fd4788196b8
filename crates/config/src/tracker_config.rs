//! The multi-target job: the checked sensors and estimator and the `[tracker]` table
//! mapped onto [`TrackerConfig`], whose [`TrackerConfig::validate`] is the one check of
//! the tracker's values (its fields are mapped back to the file's keys by
//! [`crate::tracker_errors::config_error`]).

use std::ops::Range;

use argus_tracker::{
    AssociationConfig, EstimatorConfig, MULTI_IMM_HYPOTHESES, PolarNoise, ScoreConfig,
    SensorConfig, SensorId, TrackerConfig,
};
use toml::Spanned;

use crate::error::ConfigError;
use crate::schema::{EstimatorTable, File, ModelKind, Source, TrackerTable};
use argus_tracker::single::EstimatorSpec;

use crate::spec::Sensor;
use crate::tracker_errors::config_error;

/// `max_exact_events` when `association = "jpda"` does not give it (the default of
/// `argus run surveillance`'s `jpda_max_events`).
pub const DEFAULT_MAX_EXACT_EVENTS: u32 = 1000;

/// A checked multi-target configuration.
#[derive(Debug, Clone)]
pub struct MultiTarget {
    /// The tracker's configuration, validated.
    pub config: TrackerConfig,
    /// `estimator.kind` as written.
    pub estimator: &'static str,
}

/// Maps `file`'s `[tracker]` table (`table`), the checked `sensors` and `estimator` onto
/// the tracker's configuration and validates it.
///
/// # Errors
/// [`ConfigError::Input`] naming the file, the line and the field (`tracker.<key>`,
/// `estimator.<key>`, a `[[sensor]]` key) of the first bad value.
pub(crate) fn build(
    src: Source<'_>,
    file: &File,
    table: &Spanned<TrackerTable>,
    sensors: &[Sensor],
    estimator: &EstimatorSpec,
) -> Result<MultiTarget, ConfigError> {
    let cx = Cx {
        src,
        table,
        estimator: &file.estimator,
    };
    let config = cx.config(sensors, estimator)?;
    config
        .validate()
        .map_err(|e| config_error(src, file, table, &e))?;
    Ok(MultiTarget {
        config,
        estimator: file.estimator.kind.get_ref().name(),
    })
}

/// What the mapping needs to name errors.
struct Cx<'a> {
    src: Source<'a>,
    table: &'a Spanned<TrackerTable>,
    estimator: &'a EstimatorTable,
}

impl Cx<'_> {
    /// An error at `span`, or at the `[tracker]` line.
    fn error(
        &self,
        span: Option<Range<usize>>,
        field: &str,
        msg: impl Into<String>,
    ) -> ConfigError {
        let at = span.unwrap_or_else(|| self.table.span());
        ConfigError::input(self.src.path, Some(self.src.line(&at)), Some(field), msg)
    }

    /// A number (TOML integer or float).
    fn number(&self, v: &Spanned<toml::Value>, field: &str) -> Result<f64, ConfigError> {
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
    ) -> Result<f64, ConfigError> {
        v.map_or(Ok(default), |v| self.number(v, field))
    }

    /// An optional non-negative integer that fits `u32`, `default` when absent.
    fn count_or(
        &self,
        v: Option<&Spanned<toml::Value>>,
        field: &str,
        default: u32,
    ) -> Result<u32, ConfigError> {
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

    /// The tracker configuration as written (not yet validated); the library's defaults
    /// for every key not written.
    fn config(
        &self,
        sensors: &[Sensor],
        estimator: &EstimatorSpec,
    ) -> Result<TrackerConfig, ConfigError> {
        let t = self.table.get_ref();
        let mut c = TrackerConfig::new(sensors.iter().map(|s| SensorConfig {
            id: SensorId(s.id),
            position: [s.position[0], s.position[1]],
            polar_noise: s.polar.map(|(sigma_range, sigma_azimuth)| PolarNoise {
                sigma_range,
                sigma_azimuth,
            }),
            rotation: s.rotation,
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
        c.sector_fraction = self.number_or(
            t.sector_fraction.as_ref(),
            "tracker.sector_fraction",
            c.sector_fraction,
        )?;
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
        self.estimator_into(&mut c, estimator)?;
        Ok(c)
    }

    /// `association` and its JPDA keys (which GNN refuses rather than ignores).
    fn association(&self) -> Result<AssociationConfig, ConfigError> {
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

    /// The per-track estimator: `kf-converted` is the tracker's KF, `ekf` its EKF, `imm`
    /// its two-mode CV IMM, `multi-imm` its multi-IMM around that IMM (five hypotheses on
    /// one common scale; grid spacing and clip as checked, defaults included, by
    /// [`crate::spec`]), `aircraft-imm` its aircraft IMM with the tuning checked there.
    fn estimator_into(
        &self,
        c: &mut TrackerConfig,
        estimator: &EstimatorSpec,
    ) -> Result<(), ConfigError> {
        let e = self.estimator;
        c.estimator = match estimator {
            EstimatorSpec::KfConverted(sigma_a) => {
                c.sigma_a = *sigma_a;
                EstimatorConfig::Kf
            }
            EstimatorSpec::Ekf(sigma_a) => {
                c.sigma_a = *sigma_a;
                EstimatorConfig::Ekf
            }
            EstimatorSpec::Imm(_) => {
                let (sigma_a_low, sigma_a_high, p_stay) = self.imm_cv2()?;
                EstimatorConfig::ImmCv2 {
                    sigma_a_low,
                    sigma_a_high,
                    p_stay,
                }
            }
            EstimatorSpec::MultiImm(_, multi) => {
                let (sigma_a_low, sigma_a_high, p_stay) = self.imm_cv2()?;
                if multi.n != MULTI_IMM_HYPOTHESES {
                    let msg = format!(
                        "the tracker's multi-IMM has n = {MULTI_IMM_HYPOTHESES} hypotheses (seed 000), not {}",
                        multi.n
                    );
                    return Err(match &e.n {
                        Some(n) => self.src.at(n, "estimator.n", msg),
                        None => self.src.missing("estimator.n", msg),
                    });
                }
                if multi.per_axis {
                    let msg = "the tracker's multi-IMM scales range and azimuth by one factor (per_axis = false)";
                    return Err(match &e.per_axis {
                        Some(pa) => self.src.at(pa, "estimator.per_axis", msg),
                        None => self.src.missing("estimator.per_axis", msg),
                    });
                }
                EstimatorConfig::MultiImm {
                    sigma_a_low,
                    sigma_a_high,
                    p_stay,
                    grid_spacing: multi.p,
                    clip: multi.clip,
                }
            }
            EstimatorSpec::Aircraft(tuning) => EstimatorConfig::Aircraft { tuning: *tuning },
        };
        Ok(())
    }

    /// The tracker's IMM: two CV models, a symmetric Markov matrix, uniform start.
    fn imm_cv2(&self) -> Result<(f64, f64, f64), ConfigError> {
        let e = self.estimator;
        let src = self.src;
        let models = e
            .models
            .as_ref()
            .ok_or_else(|| src.missing("estimator.models", "required by kind \"imm\""))?;
        let [m1, m2] = models.get_ref().as_slice() else {
            return Err(src.at(
                models,
                "estimator.models",
                format!(
                    "the tracker's IMM has two CV models (quiet, manoeuvre), not {}",
                    models.get_ref().len()
                ),
            ));
        };
        if m1.kind != ModelKind::Cv || m2.kind != ModelKind::Cv {
            return Err(src.at(
                models,
                "estimator.models",
                "the tracker's IMM has two CV models (quiet, manoeuvre); CT models are not built per track",
            ));
        }
        let markov = e
            .markov
            .as_ref()
            .ok_or_else(|| src.missing("estimator.markov", "required by kind \"imm\""))?;
        // Two models: the Markov matrix is 2 × 2 (checked by `spec`).
        let m = markov.get_ref();
        let (Some(&p_stay), Some(&q_stay)) = (
            m.first().and_then(|r| r.first()),
            m.get(1).and_then(|r| r.get(1)),
        ) else {
            return Err(src.at(
                markov,
                "estimator.markov",
                "must be 2 × 2 (one row and column per model)",
            ));
        };
        if (p_stay - q_stay).abs() > 1e-12 {
            return Err(src.at(
                markov,
                "estimator.markov",
                format!(
                    "the tracker's IMM stays in either mode with one probability: markov = [[p, 1 − p], [1 − p, p]] (here {p_stay} and {q_stay})"
                ),
            ));
        }
        if let Some(init) = &e.initial
            && init.get_ref().iter().any(|mu| (mu - 0.5).abs() > 1e-12)
        {
            return Err(src.at(
                init,
                "estimator.initial",
                "the tracker starts both modes at 0.5: leave initial out or write [0.5, 0.5]",
            ));
        }
        Ok((*m1.sigma_a.get_ref(), *m2.sigma_a.get_ref(), p_stay))
    }
}

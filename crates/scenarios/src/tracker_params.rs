//! The scenario parameters that are tracker fields, declared once from the tracker's
//! table ([`argus_tracker::TUNABLES`]): each [`TrackerParam`] is a key with its
//! [`Tunable`] (field, range, help), and [`TrackerParam::spec`] gives its [`ParamSpec`]
//! with the scenario's default. A scenario may spell the key or the help its own way or
//! narrow the range ([`TrackerParam::key`], [`TrackerParam::help`],
//! [`TrackerParam::range`]). Values are applied to a [`TrackerConfig`] by field
//! ([`TrackerConfig::set`]), not by matching the key back to a field.
//!
//! Also the configuration pieces `surveillance` and `real-traffic` both build from
//! these: the two-mode CV IMM, JPDA, the track score and the aircraft IMM.

use argus_tracker::{
    AircraftTuning, AssociationConfig, EstimatorConfig, ScoreConfig, TrackerConfig, Tunable,
};

use crate::error::ScenarioError;
use crate::params::{ParamSpec, Params};

/// A scenario parameter that sets one tracker field.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct TrackerParam {
    /// The `--set` key.
    key: &'static str,
    /// The field, its range and help (unless overridden below).
    tunable: Tunable,
    /// The scenario's own range, if it is not the tracker's.
    range: Option<(f64, f64)>,
    /// The scenario's own help, if it is not the tracker's.
    help: Option<&'static str>,
    /// The key's value is in degrees, the field in radians.
    degrees: bool,
}

impl TrackerParam {
    /// The key `key` for `tunable`, with its range and help.
    const fn new(key: &'static str, tunable: Tunable) -> Self {
        Self {
            key,
            tunable,
            range: None,
            help: None,
            degrees: false,
        }
    }

    /// This parameter under another key.
    pub(crate) const fn key(self, key: &'static str) -> Self {
        Self { key, ..self }
    }

    /// This parameter with the scenario's own help.
    pub(crate) const fn help(self, help: &'static str) -> Self {
        Self {
            help: Some(help),
            ..self
        }
    }

    /// This parameter with the scenario's own range.
    pub(crate) const fn range(self, min: f64, max: f64) -> Self {
        Self {
            range: Some((min, max)),
            ..self
        }
    }

    /// This parameter given in degrees (the field is in radians).
    const fn degrees(self) -> Self {
        Self {
            degrees: true,
            ..self
        }
    }

    /// Its spec with the scenario's `default`.
    pub(crate) fn spec(&self, default: f64) -> ParamSpec {
        let (min, max) = self.range.unwrap_or((self.tunable.min, self.tunable.max));
        ParamSpec::new(
            self.key,
            default,
            min,
            max,
            self.help.unwrap_or(self.tunable.help),
        )
    }

    /// Sets its field of `config` to its value in `p`.
    ///
    /// # Errors
    /// An undeclared key (a bug, reported), or the tracker refusing the value for this
    /// configuration ([`TrackerConfig::set`]).
    pub(crate) fn apply(
        &self,
        p: &Params,
        config: &mut TrackerConfig,
    ) -> Result<(), ScenarioError> {
        let v = p.get(self.key)?;
        let v = if self.degrees { v.to_radians() } else { v };
        Ok(config.set(self.tunable.field, v)?)
    }
}

/// [`TrackerConfig::sigma_a`] of the KF tracks.
pub(crate) const KF_SIGMA_A: TrackerParam = TrackerParam::new("kf_sigma_a", Tunable::SIGMA_A);
/// The two-mode IMM's quiet mode σ_a.
pub(crate) const IMM_SIGMA_LOW: TrackerParam =
    TrackerParam::new("imm_sigma_low", Tunable::IMM_SIGMA_A_LOW);
/// The two-mode IMM's manoeuvre mode σ_a.
pub(crate) const IMM_SIGMA_HIGH: TrackerParam =
    TrackerParam::new("imm_sigma_high", Tunable::IMM_SIGMA_A_HIGH);
/// The two-mode IMM's staying probability.
pub(crate) const IMM_P_STAY: TrackerParam = TrackerParam::new("imm_p_stay", Tunable::IMM_P_STAY);
/// The aircraft IMM's quiet CV mode σ_a.
pub(crate) const AC_CV_SIGMA_LOW: TrackerParam =
    TrackerParam::new("ac_cv_sigma_low", Tunable::AIRCRAFT_CV_SIGMA_A_LOW);
/// The aircraft IMM's manoeuvre CV mode σ_a.
pub(crate) const AC_CV_SIGMA_HIGH: TrackerParam =
    TrackerParam::new("ac_cv_sigma_high", Tunable::AIRCRAFT_CV_SIGMA_A_HIGH);
/// The aircraft IMM's CT mode σ_a.
pub(crate) const AC_CT_SIGMA_A: TrackerParam =
    TrackerParam::new("ac_ct_sigma_a", Tunable::AIRCRAFT_CT_SIGMA_A);
/// The aircraft IMM's turn-rate random walk, in deg/s² (its own range and help: the
/// tracker's are in rad/s²).
pub(crate) const AC_CT_SIGMA_OMEGA_DEG: TrackerParam =
    TrackerParam::new("ac_ct_sigma_omega_deg", Tunable::AIRCRAFT_CT_SIGMA_OMEGA)
        .degrees()
        .range(1e-6, 10.0)
        .help("aircraft IMM: CT mode's turn-rate random walk σ_ω (deg/s²)");
/// [`TrackerConfig::max_misses`].
pub(crate) const MAX_MISSES: TrackerParam = TrackerParam::new("max_misses", Tunable::MAX_MISSES);
/// The track score's `α`.
pub(crate) const FALSE_CONFIRM: TrackerParam =
    TrackerParam::new("false_confirm", Tunable::SCORE_FALSE_CONFIRM);
/// The track score's deletion drop.
pub(crate) const DELETE_DROP: TrackerParam =
    TrackerParam::new("delete_drop", Tunable::SCORE_DELETE_DROP);
/// The track score's `β_NT`.
pub(crate) const NEW_TARGET_DENSITY: TrackerParam =
    TrackerParam::new("new_target_density", Tunable::SCORE_NEW_TARGET_DENSITY);
/// JPDA's largest exactly enumerated cluster.
pub(crate) const JPDA_MAX_EVENTS: TrackerParam =
    TrackerParam::new("jpda_max_events", Tunable::JPDA_MAX_EXACT_EVENTS);
/// [`TrackerConfig::confirm_m`].
pub(crate) const CONFIRM_M: TrackerParam = TrackerParam::new("confirm_m", Tunable::CONFIRM_M);
/// [`TrackerConfig::confirm_n`].
pub(crate) const CONFIRM_N: TrackerParam = TrackerParam::new("confirm_n", Tunable::CONFIRM_N);
/// [`TrackerConfig::max_speed`].
pub(crate) const MAX_SPEED: TrackerParam = TrackerParam::new("max_speed", Tunable::MAX_SPEED);
/// [`TrackerConfig::sector_fraction`].
pub(crate) const SECTOR_FRACTION: TrackerParam =
    TrackerParam::new("sector_fraction", Tunable::SECTOR_FRACTION);

/// Applies each of `params` to `config`.
///
/// # Errors
/// As [`TrackerParam::apply`].
pub(crate) fn apply_all(
    params: &[TrackerParam],
    p: &Params,
    config: &mut TrackerConfig,
) -> Result<(), ScenarioError> {
    params.iter().try_for_each(|t| t.apply(p, config))
}

/// The two-mode CV IMM per track: [`IMM_SIGMA_LOW`], [`IMM_SIGMA_HIGH`], [`IMM_P_STAY`]
/// (set on `base`'s copy; its other fields do not matter).
///
/// # Errors
/// As [`TrackerParam::apply`].
pub(crate) fn imm_cv2(p: &Params, base: &TrackerConfig) -> Result<EstimatorConfig, ScenarioError> {
    let mut c = base.clone();
    // Each NaN is set below (one left would fail validation).
    c.estimator = EstimatorConfig::ImmCv2 {
        sigma_a_low: f64::NAN,
        sigma_a_high: f64::NAN,
        p_stay: f64::NAN,
    };
    apply_all(&[IMM_SIGMA_LOW, IMM_SIGMA_HIGH, IMM_P_STAY], p, &mut c)?;
    Ok(c.estimator)
}

/// JPDA with detection probability `p_detection` and clutter density `clutter_density`
/// (per m² per scan), enumerating clusters of up to [`JPDA_MAX_EVENTS`] joint events.
///
/// # Errors
/// As [`TrackerParam::apply`].
pub(crate) fn jpda(
    p: &Params,
    base: &TrackerConfig,
    p_detection: f64,
    clutter_density: f64,
) -> Result<AssociationConfig, ScenarioError> {
    let mut c = base.clone();
    c.association = AssociationConfig::Jpda {
        p_detection,
        clutter_density,
        max_exact_events: 0,
    };
    JPDA_MAX_EVENTS.apply(p, &mut c)?;
    Ok(c.association)
}

/// Sets `config`'s confirmation and deletion by the track score with detection
/// probability `p_detection` and clutter density `clutter_density`:
/// [`NEW_TARGET_DENSITY`], [`FALSE_CONFIRM`] and [`DELETE_DROP`], and a 1 % probability
/// of dropping a true tentative track.
///
/// # Errors
/// As [`TrackerParam::apply`].
pub(crate) fn set_track_score(
    p: &Params,
    config: &mut TrackerConfig,
    p_detection: f64,
    clutter_density: f64,
) -> Result<(), ScenarioError> {
    // Each NaN is set below (one left would fail validation).
    config.score = Some(ScoreConfig {
        p_detection,
        clutter_density,
        new_target_density: f64::NAN,
        false_confirm: f64::NAN,
        missed_confirm: 0.01,
        delete_drop: f64::NAN,
    });
    apply_all(&[NEW_TARGET_DENSITY, FALSE_CONFIRM, DELETE_DROP], p, config)
}

/// The aircraft IMM: [`AircraftTuning::default`] with `params` (of the `AC_` ones) set.
///
/// # Errors
/// As [`TrackerParam::apply`].
pub(crate) fn aircraft(
    p: &Params,
    base: &TrackerConfig,
    params: &[TrackerParam],
) -> Result<EstimatorConfig, ScenarioError> {
    let mut c = base.clone();
    c.estimator = EstimatorConfig::Aircraft {
        tuning: AircraftTuning::default(),
    };
    apply_all(params, p, &mut c)?;
    Ok(c.estimator)
}

#[cfg(test)]
mod tests {
    use argus_tracker::{ConfigField, EstimatorField, SensorId, TUNABLES};

    use super::*;

    /// Every shared declaration.
    const ALL: [TrackerParam; 17] = [
        KF_SIGMA_A,
        IMM_SIGMA_LOW,
        IMM_SIGMA_HIGH,
        IMM_P_STAY,
        AC_CV_SIGMA_LOW,
        AC_CV_SIGMA_HIGH,
        AC_CT_SIGMA_A,
        AC_CT_SIGMA_OMEGA_DEG,
        MAX_MISSES,
        FALSE_CONFIRM,
        DELETE_DROP,
        NEW_TARGET_DENSITY,
        JPDA_MAX_EVENTS,
        CONFIRM_M,
        CONFIRM_N,
        MAX_SPEED,
        SECTOR_FRACTION,
    ];

    fn specs(name: &str) -> Vec<ParamSpec> {
        crate::registry::find(name)
            .map(|s| s.params())
            .unwrap_or_default()
    }

    #[test]
    fn the_tables_ranges_and_helps_are_the_scenarios_specs() {
        let (surv, real) = (specs("surveillance"), specs("real-traffic"));
        assert!(!surv.is_empty() && !real.is_empty());
        let mut from_table = 0;
        for t in ALL {
            assert!(TUNABLES.contains(&t.tunable), "{}", t.key);
            for s in surv.iter().chain(&real).filter(|s| s.key == t.key) {
                if t.range.is_none() && t.help.is_none() && s.help == t.tunable.help {
                    assert_eq!(s.min.to_bits(), t.tunable.min.to_bits(), "{}", t.key);
                    assert_eq!(s.max.to_bits(), t.tunable.max.to_bits(), "{}", t.key);
                    from_table += 1;
                }
            }
        }
        // Those taken whole from the tracker's table in at least one scenario.
        assert!(from_table >= 14, "{from_table}");
        let spec = |v: &[ParamSpec], key| v.iter().find(|s| s.key == key).copied();
        assert_eq!(
            spec(&real, "confirm_n"),
            Some(ParamSpec::new(
                "confirm_n",
                4.0,
                2.0,
                20.0,
                "... in the first N opportunities"
            ))
        );
        assert_eq!(
            spec(&surv, "kf_sigma_a"),
            Some(ParamSpec::new(
                "kf_sigma_a",
                3.0,
                0.0,
                100.0,
                "KF tracks' white-acceleration σ (m/s²)"
            ))
        );
        assert_eq!(
            spec(&real, "kf_sigma_a").map(|s| s.default.to_bits()),
            Some(5.0_f64.to_bits())
        );
        // The scenario's own key spelling.
        assert!(spec(&surv, "default_max_misses").is_some());
        assert!(spec(&surv, "max_misses").is_none());
    }

    #[test]
    fn applying_a_parameter_sets_exactly_its_field() -> Result<(), ScenarioError> {
        let specs = [AC_CT_SIGMA_OMEGA_DEG.spec(0.2), CONFIRM_M.spec(3.0)];
        let p = Params::from_settings(
            &specs,
            &[
                "ac_ct_sigma_omega_deg=2".to_owned(),
                "confirm_m=2".to_owned(),
            ],
        )?;
        let base = TrackerConfig::new(vec![SensorId(0)]);
        let est = aircraft(&p, &base, &[AC_CT_SIGMA_OMEGA_DEG])?;
        let tuning = AircraftTuning {
            ct_sigma_omega: 2.0_f64.to_radians(),
            ..AircraftTuning::default()
        };
        assert_eq!(est, EstimatorConfig::Aircraft { tuning });
        let mut c = base.clone();
        CONFIRM_M.apply(&p, &mut c)?;
        assert_eq!(
            c,
            TrackerConfig {
                confirm_m: 2,
                ..base.clone()
            }
        );
        // Refused by the tracker (no IMM configured): a typed error naming the field.
        let mut c = base.clone();
        let specs = [IMM_P_STAY.spec(0.95)];
        let p = Params::from_settings(&specs, &[])?;
        match IMM_P_STAY.apply(&p, &mut c) {
            Err(ScenarioError::Tracker(argus_tracker::TrackerError::InvalidConfig {
                field,
                ..
            })) => assert_eq!(field, ConfigField::Estimator(EstimatorField::PStay)),
            other => panic!("{other:?}"),
        }
        assert_eq!(c, base);
        Ok(())
    }
}

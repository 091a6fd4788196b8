//! The tunable-field table and `TrackerConfig::set`.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use argus_tracker::{
    AircraftTuning, AssociationConfig, AssociationField, ConfigField, EstimatorConfig,
    EstimatorField, ScoreConfig, ScoreField, SensorId, TUNABLES, TrackerConfig, TrackerError,
    Tunable,
};

/// A configuration that has every tunable field, for the estimator `estimator`.
fn config(estimator: EstimatorConfig) -> TrackerConfig {
    let mut c = TrackerConfig::new(vec![SensorId(0)]);
    c.estimator = estimator;
    c.association = AssociationConfig::Jpda {
        p_detection: 0.9,
        clutter_density: 1e-9,
        max_exact_events: 100,
    };
    c.score = Some(ScoreConfig {
        p_detection: 0.9,
        clutter_density: 1e-9,
        new_target_density: 1e-11,
        false_confirm: 1e-4,
        missed_confirm: 0.01,
        delete_drop: 9.0,
    });
    c
}

fn imm() -> EstimatorConfig {
    EstimatorConfig::ImmCv2 {
        sigma_a_low: 0.5,
        sigma_a_high: 10.0,
        p_stay: 0.95,
    }
}

fn aircraft() -> EstimatorConfig {
    EstimatorConfig::Aircraft {
        tuning: AircraftTuning::default(),
    }
}

/// `c` with `field` set to `v` by hand (the test's own map from field to place).
fn by_hand(mut c: TrackerConfig, field: ConfigField, v: f64) -> TrackerConfig {
    let score = c.score.as_mut();
    match field {
        ConfigField::SigmaA => c.sigma_a = v,
        ConfigField::MaxSpeed => c.max_speed = v,
        ConfigField::ConfirmM => c.confirm_m = v as u32,
        ConfigField::ConfirmN => c.confirm_n = v as u32,
        ConfigField::MaxMisses => c.max_misses = v as u32,
        ConfigField::SectorFraction => c.sector_fraction = v,
        ConfigField::Score(f) => {
            let s = score.into_iter().next();
            if let Some(s) = s {
                match f {
                    ScoreField::NewTargetDensity => s.new_target_density = v,
                    ScoreField::FalseConfirm => s.false_confirm = v,
                    ScoreField::DeleteDrop => s.delete_drop = v,
                    other => unreachable!("{other:?} is not in the table"),
                }
            }
        }
        ConfigField::Association(AssociationField::MaxExactEvents) => {
            if let AssociationConfig::Jpda {
                max_exact_events, ..
            } = &mut c.association
            {
                *max_exact_events = v as usize;
            }
        }
        ConfigField::Estimator(f) => match (&mut c.estimator, f) {
            (EstimatorConfig::ImmCv2 { sigma_a_low, .. }, EstimatorField::SigmaALow) => {
                *sigma_a_low = v;
            }
            (EstimatorConfig::ImmCv2 { sigma_a_high, .. }, EstimatorField::SigmaAHigh) => {
                *sigma_a_high = v;
            }
            (EstimatorConfig::ImmCv2 { p_stay, .. }, EstimatorField::PStay) => *p_stay = v,
            (EstimatorConfig::Aircraft { tuning }, EstimatorField::CvSigmaALow) => {
                tuning.cv_sigma_a[0] = v;
            }
            (EstimatorConfig::Aircraft { tuning }, EstimatorField::CvSigmaAHigh) => {
                tuning.cv_sigma_a[1] = v;
            }
            (EstimatorConfig::Aircraft { tuning }, EstimatorField::CtSigmaA) => {
                tuning.ct_sigma_a = v;
            }
            (EstimatorConfig::Aircraft { tuning }, EstimatorField::CtSigmaOmega) => {
                tuning.ct_sigma_omega = v;
            }
            other => unreachable!("{other:?}"),
        },
        other => unreachable!("{other:?} is not in the table"),
    }
    c
}

fn is_aircraft(field: ConfigField) -> bool {
    matches!(
        field,
        ConfigField::Estimator(
            EstimatorField::CvSigmaALow
                | EstimatorField::CvSigmaAHigh
                | EstimatorField::CtSigmaA
                | EstimatorField::CtSigmaOmega
        )
    )
}

#[test]
fn setting_a_field_changes_exactly_that_field() {
    for t in TUNABLES {
        let before = config(if is_aircraft(t.field) {
            aircraft()
        } else {
            imm()
        });
        // A value inside the range, neither end, and (for the integers) whole.
        let v = (t.min + 0.37 * (t.max - t.min)).max(t.min);
        let v = if matches!(
            t.field,
            ConfigField::ConfirmM
                | ConfigField::ConfirmN
                | ConfigField::MaxMisses
                | ConfigField::Association(AssociationField::MaxExactEvents)
        ) {
            v.floor()
        } else {
            v
        };
        let mut after = before.clone();
        after.set(t.field, v).expect("in range");
        assert_ne!(after, before, "{}: nothing changed", t.field);
        assert_eq!(after, by_hand(before, t.field, v), "{}", t.field);
    }
}

#[test]
fn integer_fields_take_the_integer_part() {
    let mut c = config(imm());
    c.set(ConfigField::ConfirmM, 2.9).expect("in range");
    assert_eq!(c.confirm_m, 2);
    c.set(
        ConfigField::Association(AssociationField::MaxExactEvents),
        50.5,
    )
    .expect("in range");
    assert!(matches!(
        c.association,
        AssociationConfig::Jpda {
            max_exact_events: 50,
            ..
        }
    ));
}

#[test]
fn out_of_range_values_are_refused_and_change_nothing() {
    for t in TUNABLES {
        let before = config(if is_aircraft(t.field) {
            aircraft()
        } else {
            imm()
        });
        for v in [t.max * 2.0 + 1.0, t.min - 1.0, f64::NAN] {
            let mut c = before.clone();
            let e = c.set(t.field, v).expect_err("out of range");
            assert!(
                matches!(e, TrackerError::InvalidConfig { field, .. } if field == t.field),
                "{}: {e}",
                t.field
            );
            assert_eq!(c, before, "{}", t.field);
        }
    }
}

#[test]
fn a_field_the_configuration_lacks_is_refused() {
    // The IMM's p_stay on a KF configuration, the aircraft's on the IMM's, a score field
    // without the score, JPDA's events with GNN, and a field that is not tunable.
    let mut kf = TrackerConfig::new(vec![SensorId(0)]);
    let before = kf.clone();
    for (field, v) in [
        (ConfigField::Estimator(EstimatorField::PStay), 0.9),
        (ConfigField::Estimator(EstimatorField::CtSigmaA), 1.0),
        (ConfigField::Score(ScoreField::DeleteDrop), 5.0),
        (
            ConfigField::Association(AssociationField::MaxExactEvents),
            5.0,
        ),
        (ConfigField::GateProbability, 0.5),
    ] {
        let e = kf.set(field, v).expect_err("no such field here");
        assert!(
            matches!(e, TrackerError::InvalidConfig { field: f, .. } if f == field),
            "{e}"
        );
        assert_eq!(kf, before);
    }
    let mut c = config(imm());
    let e = c.set(ConfigField::Estimator(EstimatorField::CvSigmaALow), 1.0);
    assert!(e.is_err());
}

#[test]
fn the_table_has_one_entry_per_field_with_a_range_and_a_help() {
    for (i, t) in TUNABLES.iter().enumerate() {
        assert!(
            TUNABLES[..i].iter().all(|o| o.field != t.field),
            "{} twice",
            t.field
        );
        assert!(t.min < t.max, "{}", t.field);
        assert!(!t.help.is_empty() && !t.help.contains('\n'), "{}", t.field);
        assert_eq!(Tunable::of(t.field), Some(t));
    }
    assert_eq!(Tunable::of(ConfigField::GateProbability), None);
    assert_eq!(
        Tunable::SIGMA_A.help,
        "KF tracks' white-acceleration σ (m/s²)"
    );
}

//! Seed 001 "drag-bearing" on a reduced Monte Carlo count (the full count runs through
//! `argus run drag-bearing`): EKF and truncated second-order filter, plain and with GLRT
//! detection + MRAS input estimation, on a quadratic-drag target seen in bearing only.
//! Scenario and every chosen parameter: `argus_scenarios::experiments::drag_bearing` docs.
#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use argus_adaptive::AdaptiveError;
use argus_scenarios::experiments::drag_bearing::{
    DragBearingConfig, DragFilter, McSummary, simulate_run,
};

fn summary(cfg: &DragBearingConfig, runs: u64) -> McSummary {
    let r: Vec<_> = (0..runs).map(|s| simulate_run(cfg, s).unwrap()).collect();
    McSummary::from_runs(cfg, &r).unwrap()
}

fn print(cfg: &DragBearingConfig, s: &McSummary) {
    let end = cfg.duration;
    for f in DragFilter::ALL {
        eprintln!(
            "{:>15}: RMS pos 0-{:.0} s {:7.1} m, after {:7.1} m, final 10 s {:7.1} m (range {:7.1} m); detections before turn {}, delay mean {:.2} s, missed {}, failed {}, |û-Δu| {:.2} m/s²",
            f.name(),
            cfg.turn_time,
            s.time_rms_position(f, 0.0, cfg.turn_time),
            s.time_rms_position(f, cfg.turn_time, end),
            s.time_rms_position(f, end - 10.0, end),
            s.time_rms_range(f, end - 10.0, end),
            s.false_detections[f.index()],
            s.mean_delay(f),
            s.missed(f),
            s.failures[f.index()],
            s.final_input_rms[f.index()],
        );
    }
}

const RUNS: u64 = 40;

#[test]
fn input_estimation_ends_with_a_smaller_position_error_than_without() {
    let cfg = DragBearingConfig::default();
    let s = summary(&cfg, RUNS);
    print(&cfg, &s);
    let end = cfg.duration;
    let last10 = |f| s.time_rms_position(f, end - 10.0, end);
    // Issue 8: the filters with input estimation end with a smaller position error than
    // without. Measured (40 runs): plain ≈ 4200 m (range collapse towards the sensor),
    // with GLRT + MRAS ≈ 600 m. Asserted: below half of the plain filter's.
    for (plain, adaptive) in [
        (DragFilter::Ekf, DragFilter::EkfGlrtMras),
        (DragFilter::Tsof, DragFilter::TsofGlrtMras),
    ] {
        assert!(
            last10(adaptive) < 0.5 * last10(plain),
            "{}: {} vs {}",
            adaptive.name(),
            last10(adaptive),
            last10(plain)
        );
        // Before the turn the detector must stay silent (η = 20 on a χ²(2) statistic:
        // exceedance e^{-10} ≈ 4.5e-5 per onset hypothesis) and the adaptive filter is
        // then the plain one, to round-off.
        assert_eq!(s.false_detections[adaptive.index()], 0);
        let before = |f| s.time_rms_position(f, 0.0, cfg.turn_time);
        assert!((before(adaptive) - before(plain)).abs() < 1e-6 * before(plain));
        // Every run detects the turn within the window M = 20 s, and no filter fails.
        assert_eq!(s.missed(adaptive), 0);
        assert!(s.delay_max[adaptive.index()] <= 20.0);
        assert_eq!(s.failures[adaptive.index()], 0);
    }
}

#[test]
fn runs_are_reproducible_from_their_seed() {
    // A run is a pure function of (configuration, seed).
    let cfg = DragBearingConfig {
        duration: 60.0,
        ..DragBearingConfig::default()
    };
    assert_eq!(
        simulate_run(&cfg, 3).unwrap(),
        simulate_run(&cfg, 3).unwrap()
    );
    assert_ne!(
        simulate_run(&cfg, 3).unwrap(),
        simulate_run(&cfg, 4).unwrap()
    );
}

#[test]
fn bad_configurations_are_rejected_with_the_field_named() {
    let d = DragBearingConfig::default();
    let cases = [
        ("dt", DragBearingConfig { dt: 0.0, ..d }),
        ("dt", DragBearingConfig { dt: f64::NAN, ..d }),
        ("alpha", DragBearingConfig { alpha: -0.1, ..d }),
        (
            "q",
            DragBearingConfig {
                q: f64::INFINITY,
                ..d
            },
        ),
        (
            "sigma_bearing",
            DragBearingConfig {
                sigma_bearing: 0.0,
                ..d
            },
        ),
        (
            "sigma_input",
            DragBearingConfig {
                sigma_input: -1.0,
                ..d
            },
        ),
        (
            "turn_time",
            DragBearingConfig {
                turn_time: 200.0,
                ..d
            },
        ),
        ("substeps", DragBearingConfig { substeps: 0, ..d }),
    ];
    for (field, cfg) in cases {
        match simulate_run(&cfg, 0) {
            Err(AdaptiveError::InvalidParameter { what, .. }) => assert_eq!(what, field),
            other => panic!("{field}: {other:?}"),
        }
    }
    let window = DragBearingConfig { min_age: 30, ..d };
    assert!(matches!(
        simulate_run(&window, 0),
        Err(AdaptiveError::InvalidWindow { .. })
    ));
    assert!(McSummary::from_runs(&d, &[]).is_err());
}

/// Exploration of the open choices (not a check): `cargo test -- --ignored --nocapture`.
#[test]
#[ignore = "exploration, prints only"]
fn explore_parameters() {
    let d = DragBearingConfig::default();
    for (name, cfg) in [
        ("default", d),
        (
            "sigma_input 1",
            DragBearingConfig {
                sigma_input: 1.0,
                ..d
            },
        ),
        (
            "sigma_input 5",
            DragBearingConfig {
                sigma_input: 5.0,
                ..d
            },
        ),
        ("eta 10", DragBearingConfig { eta: 10.0, ..d }),
        (
            "sigma 0.5 deg",
            DragBearingConfig {
                sigma_bearing: 0.5_f64.to_radians(),
                ..d
            },
        ),
        ("alpha 0.002", DragBearingConfig { alpha: 0.002, ..d }),
        ("N 5", DragBearingConfig { min_age: 5, ..d }),
    ] {
        eprintln!("== {name}");
        print(&cfg, &summary(&cfg, 40));
    }
}

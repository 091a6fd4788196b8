//! Polar plots into the tracker: converted once per scan (unbiased conversion), so a KF
//! tracker fed polar plots is the tracker fed the same plots converted beforehand; bad
//! polar plots are typed errors naming the plot.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use argus_core_math::Vector;
use argus_sensors::{ConversionMethod, Measurement, convert_polar};
use argus_sim::{ChaCha8Rng, run_rng};
use argus_tracker::{
    AssociationConfig, EstimatorConfig, Plot, SensorConfig, SensorId, TrackStatus, Tracker,
    TrackerConfig, TrackerError,
};
use rand::RngExt;
use rand_distr::{Distribution, StandardNormal};

const S0: SensorId = SensorId(0);
const T: f64 = 5.0;
const SENSOR: [f64; 2] = [1_000.0, -2_000.0];
const SIGMA_R: f64 = 30.0;
const SIGMA_AZ: f64 = 2e-3;

/// A noisy polar plot of the point `p` seen from `SENSOR`.
fn polar(rng: &mut ChaCha8Rng, t: f64, p: Vector<2>) -> Plot {
    let d = p - Vector::<2>::new(SENSOR[0], SENSOR[1]);
    let nr: f64 = StandardNormal.sample(rng);
    let na: f64 = StandardNormal.sample(rng);
    Plot::polar(
        t,
        S0,
        d.norm() + SIGMA_R * nr,
        d[1].atan2(d[0]) + SIGMA_AZ * na,
    )
    .unwrap()
}

/// The same plot converted by the caller (unbiased conversion, plus the sensor position).
fn converted(p: &Plot) -> Plot {
    let Measurement::Polar(m) = p.measurement() else {
        panic!("not polar");
    };
    let (range, azimuth) = (m.range(), m.azimuth());
    let c = convert_polar(
        range,
        azimuth,
        SIGMA_R,
        SIGMA_AZ,
        ConversionMethod::Unbiased,
    )
    .unwrap();
    Plot::cartesian(
        p.time(),
        p.sensor(),
        c.position + Vector::<2>::new(SENSOR[0], SENSOR[1]),
        c.covariance,
    )
    .unwrap()
}

/// Three targets 20–40 km out and a few uniform false plots per scan.
fn scans(seed: u64, n: u32) -> Vec<Vec<Plot>> {
    let mut rng = run_rng(41, seed);
    (0..n)
        .map(|k| {
            let t = T * f64::from(k);
            let mut plots = vec![
                polar(&mut rng, t, Vector::<2>::new(20_000.0 + 200.0 * t, 5_000.0)),
                polar(
                    &mut rng,
                    t,
                    Vector::<2>::new(-15_000.0, 30_000.0 - 150.0 * t),
                ),
                polar(
                    &mut rng,
                    t,
                    Vector::<2>::new(25_000.0 - 100.0 * t, -20_000.0 + 100.0 * t),
                ),
            ];
            for _ in 0..3 {
                let p = Vector::<2>::new(
                    60_000.0 * rng.random::<f64>() - 30_000.0,
                    60_000.0 * rng.random::<f64>() - 30_000.0,
                );
                plots.push(polar(&mut rng, t, p));
            }
            plots
        })
        .collect()
}

fn same_tracks(a: &Tracker, b: &Tracker, what: &str) {
    assert_eq!(a.tracks().len(), b.tracks().len(), "{what}");
    for (x, y) in a.tracks().iter().zip(b.tracks()) {
        assert_eq!((x.id(), x.status()), (y.id(), y.status()), "{what}");
        // Both run the same arithmetic on the same converted plots; 1e-9 relative leaves
        // room for nothing but rounding.
        let dm = (x.estimate().mean() - y.estimate().mean()).norm();
        let dp = (x.estimate().cov() - y.estimate().cov()).norm();
        assert!(
            dm <= 1e-9 * x.estimate().mean().norm() && dp <= 1e-9 * x.estimate().cov().norm(),
            "{what}: {dm} {dp}"
        );
    }
}

#[test]
fn polar_plots_give_the_tracks_of_preconverted_cartesian_plots() {
    for association in [
        AssociationConfig::Gnn,
        AssociationConfig::Jpda {
            p_detection: 0.9,
            clutter_density: 1e-9,
            max_exact_events: 100,
        },
    ] {
        let mut cfg = TrackerConfig::new([SensorConfig::polar(S0, SENSOR, SIGMA_R, SIGMA_AZ)]);
        cfg.association = association;
        let mut with_polar = Tracker::new(cfg.clone()).unwrap();
        // The Cartesian tracker's sensor has no polar noise: the plots are its own.
        cfg.sensors = vec![SensorConfig::cartesian(S0)];
        let mut with_cartesian = Tracker::new(cfg).unwrap();
        let mut confirmed = 0;
        for scan in scans(0, 20) {
            let t = scan[0].time();
            let conv: Vec<Plot> = scan.iter().map(converted).collect();
            let ra = with_polar.process_scan(t, S0, &scan).unwrap();
            let rb = with_cartesian.process_scan(t, S0, &conv).unwrap();
            assert_eq!(ra, rb);
            same_tracks(
                &with_polar,
                &with_cartesian,
                &format!("{association:?} t = {t}"),
            );
            confirmed = with_polar
                .tracks()
                .iter()
                .filter(|tr| tr.status() == TrackStatus::Confirmed)
                .count();
        }
        // The three targets are held by confirmed tracks at the end.
        assert!(confirmed >= 3, "{association:?}: {confirmed}");
    }
}

/// What a bad plot's error must look like.
type Check = fn(&TrackerError) -> bool;

#[test]
fn bad_polar_plots_are_rejected_with_their_place_and_change_nothing() {
    let cfg = TrackerConfig::new([
        SensorConfig::polar(S0, SENSOR, SIGMA_R, SIGMA_AZ),
        SensorConfig::cartesian(SensorId(1)),
    ]);
    let mut tracker = Tracker::new(cfg).unwrap();
    let all = scans(1, 5);
    for scan in &all[..4] {
        tracker.process(scan).unwrap();
    }
    let before = tracker.tracks().to_vec();
    let t = all[4][0].time();
    let good = all[4][0];
    // A non-finite range or azimuth, or a negative range, is not a plot (argus_sensors
    // refuses to build it); a range of zero is one, which the tracker refuses.
    assert!(Plot::polar(t, S0, f64::NAN, 0.1).is_err());
    assert!(Plot::polar(t, S0, 1000.0, f64::INFINITY).is_err());
    assert!(Plot::polar(t, S0, -5.0, 0.1).is_err());
    let cases: [(Plot, Check); 3] = [
        (
            Plot::polar(t, S0, 0.0, 0.1).unwrap(),
            |e| matches!(e, TrackerError::NonPositiveRange { index: 1, range, .. } if range.total_cmp(&0.0).is_eq()),
        ),
        (Plot::polar(t, SensorId(1), 1000.0, 0.1).unwrap(), |e| {
            matches!(
                e,
                TrackerError::NoPolarNoise {
                    index: 1,
                    sensor: SensorId(1),
                    ..
                }
            )
        }),
        (Plot::polar(t, SensorId(7), 1000.0, 0.1).unwrap(), |e| {
            matches!(
                e,
                TrackerError::UnknownSensor {
                    index: 1,
                    sensor: SensorId(7),
                    ..
                }
            )
        }),
    ];
    for (bad, ok) in cases {
        let err = tracker.process(&[good, bad]).unwrap_err();
        assert!(ok(&err), "{err:?}");
        if bad.sensor() == S0 {
            let err = tracker.process_scan(t, S0, &[good, bad]).unwrap_err();
            assert!(ok(&err), "{err:?}");
        }
        assert_eq!(tracker.tracks(), &before[..]);
        assert_eq!(tracker.time(), Some(T * 3.0));
    }
    // The scan itself goes through afterwards.
    tracker.process(&all[4]).unwrap();
    assert_eq!(tracker.time(), Some(t));
}

#[test]
fn bad_sensor_configs_name_the_field() {
    let field = |cfg: TrackerConfig| match Tracker::new(cfg) {
        Err(TrackerError::InvalidConfig { field, .. }) => field.key(),
        other => panic!("expected InvalidConfig, got {other:?}"),
    };
    let polar = |sr, sa| TrackerConfig::new([SensorConfig::polar(S0, SENSOR, sr, sa)]);
    assert_eq!(field(polar(0.0, 1e-3)), "sensors.polar_noise.sigma_range");
    assert_eq!(
        field(polar(30.0, f64::NAN)),
        "sensors.polar_noise.sigma_azimuth"
    );
    assert_eq!(
        field(TrackerConfig::new([SensorConfig::polar(
            S0,
            [f64::INFINITY, 0.0],
            30.0,
            1e-3
        )])),
        "sensors.position"
    );
    assert_eq!(
        field(TrackerConfig::new([
            SensorConfig::cartesian(S0),
            SensorConfig::polar(S0, SENSOR, 30.0, 1e-3)
        ])),
        "sensors.id"
    );
    // EKF: accepted with polar or Cartesian sensors.
    let mut ekf = polar(30.0, 1e-3);
    ekf.estimator = EstimatorConfig::Ekf;
    assert!(Tracker::new(ekf).is_ok());
}

#[test]
fn a_polar_plot_the_conversion_cannot_take_is_a_typed_error() {
    // σ_θ = 40 rad: λ = e^{−σ_θ²/2} underflows to 0 and the unbiased conversion divides by
    // it, so the converted position is not finite; the tracker names the plot.
    let mut tracker = Tracker::new(TrackerConfig::new([SensorConfig::polar(
        S0, SENSOR, 30.0, 40.0,
    )]))
    .unwrap();
    let err = tracker
        .process(&[Plot::polar(0.0, S0, 10_000.0, 0.3).unwrap()])
        .unwrap_err();
    assert!(
        matches!(
            err,
            TrackerError::Conversion {
                index: 0,
                sensor: S0,
                ..
            }
        ),
        "{err:?}"
    );
    assert_eq!(tracker.time(), None);
}

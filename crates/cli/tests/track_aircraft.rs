//! `argus track` with `kind = "aircraft-imm"`, driving the real binary: the single-target
//! estimator of `docs/examples/aircraft.toml` (its columns, its keys = the defaults, its
//! position RMSE against seed 000's IMM on the same plots), the aircraft IMM per track
//! under `[tracker]`, and bad configurations named at their file and line.

// Test helpers outside #[test] functions may unwrap: a failure is a test failure.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};

use argus_core_math::Vector;
use argus_sensors::Measurement;
use argus_sim::{
    FlightEnvelope, Schedule, SensorId, SensorKind, SensorSpec, Trajectory, Truth, generate_plots,
    random_flight, run_rng,
};

mod common;
use common::{argus, assert_error, col, simulate_gimpo};

/// `docs/examples/aircraft.toml` in the repository.
fn example() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/examples/aircraft.toml")
}

const SENSOR: &str = r#"[[sensor]]
id = 1
position = [0.0, 0.0]
sigma_range = 70.0
sigma_azimuth_deg = 0.08
"#;

/// Seed 000's IMM (docs/papers/000-gimpo.md: CV σ 0.1 m/s², CT ±3 °/s σ 0.5 m/s², eq
/// (20)) with the true R, as in the gimpo scenario.
fn seed000_imm() -> String {
    format!(
        r#"{SENSOR}
[estimator]
kind = "imm"
models = [
  {{ kind = "cv", sigma_a = 0.1 }},
  {{ kind = "ct", sigma_a = 0.5, rate_deg = 3.0 }},
  {{ kind = "ct", sigma_a = 0.5, rate_deg = -3.0 }},
]
markov = [
  [0.95, 0.025, 0.025],
  [0.05, 0.95, 0.0],
  [0.05, 0.0, 0.95],
]
"#
    )
}

/// Runs `argus track --config cfg --plots plots --out out` in `dir`; (exit code,
/// stderr, tracks text).
fn track(dir: &Path, cfg: &Path, plots: &str, out: &str) -> (Option<i32>, String, String) {
    let _ = std::fs::remove_file(dir.join(out));
    let o = argus(
        &[
            "track",
            "--config",
            cfg.to_str().unwrap(),
            "--plots",
            plots,
            "--out",
            out,
        ],
        dir,
    );
    let text = std::fs::read_to_string(dir.join(out)).unwrap_or_default();
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
        text,
    )
}

/// Writes `cfg` to `dir/name` and runs it.
fn track_cfg(dir: &Path, name: &str, cfg: &str, plots: &str) -> (Option<i32>, String, String) {
    std::fs::write(dir.join(name), cfg).unwrap();
    track(dir, &dir.join(name), plots, "tracks.csv")
}

/// (header, rows) of a CSV text whose cells are numbers (or names, read as NaN).
fn table(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut lines = text.lines();
    let head = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_owned)
        .collect();
    let rows = lines
        .map(|l| {
            l.split(',')
                .map(|v| v.parse().unwrap_or(f64::NAN))
                .collect()
        })
        .collect();
    (head, rows)
}

/// Position errors² of a single-target tracks file against `truth` (`t → [x, y]`),
/// leaving out the first `WARMUP` rows (the two-point start's transient).
fn squared_errors(text: &str, truth: &dyn Fn(f64) -> [f64; 2]) -> Vec<f64> {
    const WARMUP: usize = 6;
    let (head, rows) = table(text);
    let (t, x, y) = (col(&head, "t"), col(&head, "x"), col(&head, "y"));
    rows.iter()
        .skip(WARMUP)
        .map(|r| {
            let p = truth(r[t]);
            (r[x] - p[0]).powi(2) + (r[y] - p[1]).powi(2)
        })
        .collect()
}

fn rmse(se: &[f64]) -> f64 {
    (se.iter().sum::<f64>() / se.len() as f64).sqrt()
}

/// The truth file's `t → [x, y]` (exact times: the truth is written at every plot time).
fn truth_file(dir: &Path) -> impl Fn(f64) -> [f64; 2] {
    let (head, rows) = table(&std::fs::read_to_string(dir.join("sim.truth.csv")).unwrap());
    let (t, x, y) = (col(&head, "t"), col(&head, "x"), col(&head, "y"));
    let at: Vec<(f64, [f64; 2])> = rows.iter().map(|r| (r[t], [r[x], r[y]])).collect();
    move |time| {
        at.iter()
            .find(|(s, _)| s.to_bits() == time.to_bits())
            .map(|(_, p)| *p)
            .unwrap()
    }
}

#[test]
fn the_example_tracks_a_gimpo_flight_with_modes_and_turn_rate() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    simulate_gimpo(d, 4);
    let (code, err, text) = track(d, &example(), "sim.csv", "tracks.csv");
    assert_eq!(code, Some(0), "{err}");
    let (head, rows) = table(&text);
    assert_eq!(
        head.join(","),
        "t,track,x,vx,y,vy,var_x,var_vx,var_y,var_vy,mu_1,mu_2,mu_3,turn_rate_deg,sigma_turn_rate_deg"
    );
    // One row per plot from the second: the beam sees the target ≈ 1019 / 5 ≈ 204 times.
    assert!((195..=210).contains(&rows.len()), "{}", rows.len());
    let (m1, w) = (col(&head, "mu_1"), col(&head, "turn_rate_deg"));
    for r in &rows {
        let s: f64 = r[m1..m1 + 3].iter().sum();
        assert!((s - 1.0).abs() < 1e-9, "probabilities sum to {s}");
    }
    // The first row is the start: μ₀ and the turn-rate prior 0 ± 2 °/s.
    assert_eq!(&rows[0][m1..m1 + 3], &[0.6, 0.2, 0.2]);
    assert_eq!(&rows[0][w..w + 2], &[0.0, 2.0]);
    // Table 1 of seed 000: a +1.5 °/s turn from 330 to 393 s after straight flight. Over
    // the turn's second half the CT mode (mu_3) holds more weight than over the last
    // 80 s of straight flight, and its turn rate is within 0.75 °/s of the truth
    // (half the rate: the turn is found, sign included, at 2 σ of one step's σ_ω ≈ 0.4).
    let mean = |a: f64, b: f64, c: usize| {
        let v: Vec<f64> = rows
            .iter()
            .filter(|r| r[0] >= a && r[0] < b)
            .map(|r| r[c])
            .collect();
        v.iter().sum::<f64>() / v.len() as f64
    };
    let (before, during) = (mean(250.0, 330.0, m1 + 2), mean(362.0, 393.0, m1 + 2));
    assert!(
        during > before + 0.2,
        "CT {before} before, {during} in the turn"
    );
    let rate = mean(362.0, 393.0, w);
    assert!(
        (rate - 1.5).abs() < 0.75,
        "turn rate {rate} °/s in a 1.5 °/s turn"
    );

    // The example's values are the defaults: a config with the kind alone gives the same
    // file, byte for byte.
    let bare = format!("{SENSOR}\n[estimator]\nkind = \"aircraft-imm\"\n");
    let (code, err, bare_text) = track_cfg(d, "bare.toml", &bare, "sim.csv");
    assert_eq!(code, Some(0), "{err}");
    assert_eq!(bare_text, text);
}

/// One issue-18 flight (seeds `run_rng(18_202, run)`): the default envelope
/// ([`FlightEnvelope`]: legs of 40–150 s at 120–250 m/s, then a ±1–3 °/s turn of 30–120 s
/// (65 %) or a ±0.5–1.5 m/s² speed change of 20–60 s, for 900 s, 20–150 km from the radar)
/// without its slowing down of fast flights.
fn flight(run: u64) -> Trajectory {
    let envelope = FlightEnvelope {
        slow_down_above: None,
        ..FlightEnvelope::default()
    };
    random_flight(&mut run_rng(18_202, run), &envelope).unwrap()
}

/// The flight's plots from seed 000's radar (rotating beam, 5 s, σr 70 m, σθ 0.08°,
/// P_D = 1, no clutter) into `dir/flight.csv` as `t,sensor,range,azimuth`.
fn write_flight(dir: &Path, traj: &Trajectory, run: u64) {
    let mut truth = Truth::new();
    truth.add(traj.clone());
    let radar = SensorSpec::new(
        SensorId(1),
        Vector::<3>::zeros(),
        SensorKind::Polar {
            sigma_range: 70.0,
            sigma_azimuth: 0.08_f64.to_radians(),
        },
        Schedule::RotatingBeam {
            period: 5.0,
            azimuth_at_zero: 0.0,
        },
    )
    .unwrap();
    let mut rng = run_rng(18_203, run);
    let mut text = String::from("t,sensor,range,azimuth\n");
    for p in generate_plots(&truth, &[radar], &mut rng).unwrap() {
        if let Measurement::Polar(m) = p.plot.measurement() {
            text.push_str(&format!(
                "{},1,{},{}\n",
                p.plot.time(),
                m.range(),
                m.azimuth()
            ));
        }
    }
    std::fs::write(dir.join("flight.csv"), text).unwrap();
}

/// Issue 18's goal for single flights is ≤ 0.8 × seed 000's IMM (CV + CT ±3 °/s, true R)
/// on the same plots. Measured here on simulated flights and reported in
/// docs/aircraft-imm.md whatever the ratios are; on the issue-18 flights asserted below
/// 1 (measured 0.627), on gimpo's only within 10 % (measured 1.044).
#[test]
fn the_example_beats_seed_000s_imm_on_simulated_flights() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("imm.toml"), seed000_imm()).unwrap();
    // Seed 000's own scenario (gimpo: one ±1.5 °/s turn per flight), 5 seeds.
    let (mut se_air, mut se_imm) = (Vec::new(), Vec::new());
    for seed in 0..5 {
        simulate_gimpo(d, seed);
        let truth = truth_file(d);
        let (code, err, air) = track(d, &example(), "sim.csv", "air.csv");
        assert_eq!(code, Some(0), "{err}");
        let (code, err, imm) = track(d, &d.join("imm.toml"), "sim.csv", "imm.csv");
        assert_eq!(code, Some(0), "{err}");
        se_air.extend(squared_errors(&air, &truth));
        se_imm.extend(squared_errors(&imm, &truth));
    }
    let (a, i) = (rmse(&se_air), rmse(&se_imm));
    println!(
        "gimpo, 5 seeds: aircraft IMM {a:.1} m, seed 000's IMM {i:.1} m, ratio {:.3}",
        a / i
    );
    // Not below it on seed 000's own scenario: its flight is 330 s of exactly constant
    // velocity, then one 1.5 °/s turn, which the IMM's CV σ = 0.1 m/s² mode fits better
    // than the aircraft IMM's quiet mode (0.3 m/s²). Measured 1.044 ×; asserted within
    // 10 % (a regression guard, not the goal).
    assert!(a < 1.1 * i, "{a:.1} m vs {i:.1} m");

    // Issue-18 flights (turns of 1–3 °/s, speed changes), 10 flights of 900 s.
    let (mut se_air, mut se_imm) = (Vec::new(), Vec::new());
    for run in 0..10 {
        let traj = flight(run);
        write_flight(d, &traj, run);
        let truth = |t: f64| {
            let s = traj.state_at(t).unwrap();
            [s.position.x, s.position.y]
        };
        let (code, err, air) = track(d, &example(), "flight.csv", "air.csv");
        assert_eq!(code, Some(0), "{err}");
        let (code, err, imm) = track(d, &d.join("imm.toml"), "flight.csv", "imm.csv");
        assert_eq!(code, Some(0), "{err}");
        se_air.extend(squared_errors(&air, &truth));
        se_imm.extend(squared_errors(&imm, &truth));
    }
    let (a, i) = (rmse(&se_air), rmse(&se_imm));
    println!(
        "issue-18 flights, 10 runs: aircraft IMM {a:.1} m, seed 000's IMM {i:.1} m, ratio {:.3}",
        a / i
    );
    // Seed 000's IMM cannot follow the speed changes (CV σ = 0.1 m/s²) and its fixed
    // ±3 °/s turns miss 1–2 °/s turns (docs/aircraft-imm.md).
    assert!(a < i, "{a:.1} m vs {i:.1} m");
}

#[test]
fn the_tracker_runs_the_aircraft_imm_per_track() {
    tracker_equals_single_target(SENSOR);
}

/// gimpo's radar is a rotating one (counter-clockwise, the beam east at t = 0, so north at
/// 1.25 s): tracked as such, by sectors, each plot at its own time, the track must still be
/// the single-target estimator row by row (the sector's look prediction must not leak
/// into the update at the plot's time).
#[test]
fn the_tracker_runs_the_aircraft_imm_per_track_on_a_rotating_radar() {
    let rotating = format!(
        "{SENSOR}revolution_period = 5.0\nrotation = \"counterclockwise\"\nnorth_time = 1.25\n"
    );
    tracker_equals_single_target(&rotating);
}

fn tracker_equals_single_target(sensor: &str) {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    simulate_gimpo(d, 4);
    let cfg =
        format!("{sensor}\n[estimator]\nkind = \"aircraft-imm\"\n\n[tracker]\nconfirm_m = 3\n");
    let (code, err, text) = track_cfg(d, "trk.toml", &cfg, "sim.csv");
    assert_eq!(code, Some(0), "{err}");
    let (head, rows) = table(&text);
    assert_eq!(
        head.join(","),
        "t,sensor,track,status,reason,x,vx,y,vy,sigma_x,sigma_y,mu_1,mu_2,mu_3,turn_rate_deg,sigma_turn_rate_deg"
    );
    // One target, no clutter: one track from the second plot to the end, confirmed at
    // the third, never deleted.
    let tr = col(&head, "track");
    assert!(rows.iter().all(|r| r[tr] == 0.0));
    assert!((195..=210).contains(&rows.len()), "{}", rows.len());
    assert!(text.lines().skip(2).all(|l| l.contains(",confirmed,")));
    let summary = std::fs::read_to_string(d.join("tracks.summary.json")).unwrap();
    assert!(
        summary.contains("\"estimator\": \"aircraft-imm\""),
        "{summary}"
    );
    // Every plot is assigned, so the track is the single-target estimator, row by row
    // (the tracker starts from the same converted plots' two-point estimate): equal to
    // round-off (1e-9 relative).
    // A rotating sensor's rows are its initiation row (at the track's second plot, as
    // the single-target estimator's first row) and then its updates and misses: the
    // same rows as the single-target estimator's, scan or sectors.
    let single = track(d, &example(), "sim.csv", "single.csv").2;
    let (sh, srows) = table(&single);
    assert_eq!(rows.len(), srows.len(), "rows against the single-target's");
    let (x, sx) = (col(&head, "x"), col(&sh, "x"));
    let (t, st) = (col(&head, "t"), col(&sh, "t"));
    for (r, s) in rows.iter().zip(&srows) {
        assert_eq!(r[t].to_bits(), s[st].to_bits(), "row times");
        for k in 0..4 {
            let (a, b) = (r[x + k], s[sx + k]);
            assert!((a - b).abs() <= 1e-9 * (1.0 + b.abs()), "{a} vs {b}");
        }
    }
}

#[test]
fn bad_aircraft_configs_name_file_line_and_field() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let plots = "t,sensor,range,azimuth\n0,1,50000,0.5\n5,1,50010,0.51\n10,1,50020,0.52\n";
    std::fs::write(d.join("p.csv"), plots).unwrap();
    // The estimator table starts at line 7 of these files (after SENSOR and a blank).
    let cfg = |extra: &str| format!("{SENSOR}\n[estimator]\nkind = \"aircraft-imm\"\n{extra}\n");
    let cases: [(String, &[&str]); 8] = [
        (cfg("ct_sigma_omega = 0.1"), &["a.toml:9", "unknown field"]),
        (
            cfg("cv_sigma_a = [0.3]"),
            &["a.toml:9", "field 'cv_sigma_a'", "2 values"],
        ),
        (
            cfg("ct_sigma_a = -0.5"),
            &["a.toml:9", "field 'ct_sigma_a'"],
        ),
        (
            cfg("\n\nmarkov = [[0.9, 0.1], [0.1, 0.9]]"),
            &["a.toml:11", "field 'markov'"],
        ),
        (
            cfg("initial = [0.5, 0.5, 0.5]"),
            &["a.toml:9", "field 'initial'"],
        ),
        (
            cfg("mixing = \"fixed\""),
            &["field 'mixing_sigma_omega_deg'", "required"],
        ),
        (cfg("mixing = \"zero\""), &["a.toml:9", "unknown variant"]),
        (
            cfg("sigma_a = 2.0"),
            &["a.toml:9", "field 'sigma_a'", "not used"],
        ),
    ];
    for (c, needles) in &cases {
        let (code, err, _) = track_cfg(d, "a.toml", c, "p.csv");
        assert_error(code, &err, needles);
    }
    // Under [tracker]: JPDA runs (IMM-JPDA), a bad JPDA key is named at its line, and a
    // Cartesian plot is refused at its line.
    let jpda =
        cfg("\n[tracker]\nassociation = \"jpda\"\np_detection = 0.9\nclutter_density = 1e-9");
    let (code, err, text) = track_cfg(d, "a.toml", &jpda, "p.csv");
    assert_eq!(code, Some(0), "{err}");
    assert!(
        text.lines().last().unwrap().contains(",confirmed,"),
        "{text}"
    );
    let (code, err, _) = track_cfg(d, "a.toml", &jpda.replace("0.9", "1.5"), "p.csv");
    assert_error(code, &err, &["a.toml:12", "field 'tracker.p_detection'"]);
    let cart = "t,sensor,x,y,r_xx,r_xy,r_yy\n0,1,0,0,100,0,100\n5,1,50,0,100,0,100\n";
    std::fs::write(d.join("cart.csv"), cart).unwrap();
    let (code, err, _) = track_cfg(d, "a.toml", &cfg("\n[tracker]"), "cart.csv");
    assert_error(
        code,
        &err,
        &[
            "cart.csv:2",
            "field 'sensor'",
            "aircraft IMM needs polar plots",
        ],
    );
    // Smoothing is built for it (single target and tracker; tests/smooth_aircraft_tracks.rs
    // checks the values): the smoothed mode probabilities are written.
    for extra in ["", "\n[tracker]"] {
        std::fs::write(d.join("a.toml"), cfg(extra)).unwrap();
        let o = argus(
            &[
                "track", "--config", "a.toml", "--plots", "p.csv", "--out", "s.csv", "--smooth",
            ],
            d,
        );
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(0), "{extra:?}: {err}");
        let out = std::fs::read_to_string(d.join("s.csv")).unwrap();
        assert!(
            out.lines().next().unwrap().ends_with("mu_1s,mu_2s,mu_3s"),
            "{out}"
        );
    }
    // Single-target: a Cartesian report, and a plot of another sensor.
    let (code, err, _) = track_cfg(d, "a.toml", &cfg(""), "cart.csv");
    assert_error(code, &err, &["cart.csv:2", "field 'sensor'", "polar plots"]);
    let two = format!(
        "{SENSOR}\n[[sensor]]\nid = 2\nposition = [1.0, 0.0]\nsigma_range = 70.0\nsigma_azimuth_deg = 0.08\n\n[estimator]\nkind = \"aircraft-imm\"\n"
    );
    let mixed = "t,sensor,range,azimuth\n0,1,50000,0.5\n5,1,50010,0.51\n10,2,50020,0.52\n";
    std::fs::write(d.join("mixed.csv"), mixed).unwrap();
    let (code, err, _) = track_cfg(d, "a.toml", &two, "mixed.csv");
    assert_error(
        code,
        &err,
        &["mixed.csv:4", "field 'sensor'", "sensor 2 after sensor 1"],
    );
}

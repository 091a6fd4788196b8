//! Drives the real `argus` binary on good and bad files.

// Test helpers outside #[test] functions may unwrap: a failure is a test failure.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};

mod common;
use common::{argus, ok, read};

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

const CONFIG: &str = r#"
[[sensor]]
id = 1
position = [0.0, 0.0]
sigma_range = 50.0
sigma_azimuth_deg = 1.0

[estimator]
kind = "kf-converted"
sigma_a = 0.5
"#;

const PLOTS: &str = "t,sensor,range,azimuth\n\
0,1,10000,0.5\n\
2,1,10010,0.51\n\
4,1,10020,0.52\n\
6,1,10030,0.53\n";

/// Runs `argus track` with the given config and plots; returns (exit code, stderr).
fn track(dir: &Path, config: &str, plots: &str) -> (Option<i32>, String) {
    write(dir, "filter.toml", config);
    write(dir, "plots.csv", plots);
    let o = argus(
        &[
            "track",
            "--config",
            "filter.toml",
            "--plots",
            "plots.csv",
            "--out",
            "tracks.csv",
        ],
        dir,
    );
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
fn scenarios_lists_cv_polar() {
    let dir = tempfile::tempdir().unwrap();
    let o = argus(&["scenarios"], dir.path());
    assert!(o.status.success());
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.lines().any(|l| l.starts_with("cv-polar ")), "{out}");
}

#[test]
fn track_good_file_writes_tracks() {
    let dir = tempfile::tempdir().unwrap();
    let (code, err) = track(dir.path(), CONFIG, PLOTS);
    assert_eq!(code, Some(0), "{err}");
    let text = std::fs::read_to_string(dir.path().join("tracks.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("t,track,x,vx,y,vy,var_x,var_vx,var_y,var_vy")
    );
    // One row from the two-point start (t = 2) and one per later plot.
    assert_eq!(lines.count(), 3);
    // The two-point start at t = 2 puts x at the converted second plot:
    // x = r cos θ / λ with λ = exp(−σθ²/2), σθ = 1° (Mo Longbin et al. 1998).
    let row2: Vec<f64> = text
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    let lam = (-0.5 * 1f64.to_radians().powi(2)).exp();
    let x = 10010.0 * 0.51f64.cos() / lam;
    assert!((row2[2] - x).abs() < 1e-6 * x, "{row2:?}");
}

#[test]
fn track_ekf_on_polar_plots() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = CONFIG.replace("kf-converted", "ekf");
    let (code, err) = track(dir.path(), &cfg, PLOTS);
    assert_eq!(code, Some(0), "{err}");
}

/// Asserts exit code 2, a single `error:` line naming the file, and `needles` in it.
fn assert_error(code: Option<i32>, err: &str, needles: &[&str]) {
    assert_eq!(code, Some(2), "{err}");
    assert!(
        !err.contains("panicked") && !err.contains("backtrace"),
        "{err}"
    );
    assert_eq!(err.lines().count(), 1, "one message expected: {err}");
    assert!(err.starts_with("error: "), "{err}");
    for n in needles {
        assert!(err.contains(n), "missing '{n}' in: {err}");
    }
}

#[test]
fn bad_plot_files_name_file_line_and_field() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&str, &[&str]); 6] = [
        // Malformed row: too few fields on line 3.
        (
            "t,sensor,range,azimuth\n0,1,10000,0.5\n2,1,10010\n",
            &["plots.csv:3", "malformed row"],
        ),
        // Unknown column in the header.
        (
            "t,sensor,range,azimuth,colour\n0,1,10000,0.5,red\n",
            &["plots.csv:1", "field 'colour'", "unknown column"],
        ),
        // Non-numeric value.
        (
            "t,sensor,range,azimuth\n0,1,10000,0.5\n2,1,ten,0.51\n",
            &["plots.csv:3", "field 'range'", "not a number"],
        ),
        // Non-finite value.
        (
            "t,sensor,range,azimuth\n0,1,10000,0.5\n2,1,10010,NaN\n",
            &["plots.csv:3", "field 'azimuth'", "not finite"],
        ),
        // Time going backwards.
        (
            "t,sensor,range,azimuth\n0,1,10000,0.5\n2,1,10010,0.51\n1,1,10020,0.52\n",
            &["plots.csv:4", "field 't'", "backwards"],
        ),
        // Unknown sensor.
        (
            "t,sensor,range,azimuth\n0,1,10000,0.5\n2,7,10010,0.51\n",
            &["plots.csv:3", "field 'sensor'", "unknown sensor 7"],
        ),
    ];
    for (plots, needles) in cases {
        let (code, err) = track(dir.path(), CONFIG, plots);
        assert_error(code, &err, needles);
    }
}

#[test]
fn bad_configs_name_file_line_and_field() {
    let dir = tempfile::tempdir().unwrap();
    // Negative variance (σ) on line 6.
    let neg = CONFIG.replace("sigma_azimuth_deg = 1.0", "sigma_azimuth_deg = -1.0");
    let (code, err) = track(dir.path(), &neg, PLOTS);
    assert_error(
        code,
        &err,
        &["filter.toml:6", "field 'sigma_azimuth_deg'", "non-negative"],
    );
    // Non-stochastic Markov matrix (row 2 sums to 1.1), on line 13.
    let imm = r#"
[[sensor]]
id = 1
position = [0.0, 0.0]
sigma_range = 50.0
sigma_azimuth_deg = 1.0

[estimator]
kind = "imm"
models = [{ kind = "cv", sigma_a = 0.1 }, { kind = "ct", sigma_a = 0.5, rate_deg = 3.0 }]
markov = [
  [0.95, 0.05],
  [0.20, 0.90],
]
"#;
    let (code, err) = track(dir.path(), imm, PLOTS);
    assert_error(
        code,
        &err,
        &[
            "filter.toml:11",
            "field 'markov'",
            "row 2 is not stochastic",
        ],
    );
    // Unknown key: toml's own message with the line.
    let unknown = CONFIG.replace("sigma_a = 0.5", "sigma_a = 0.5\nsigma_b = 1.0");
    let (code, err) = track(dir.path(), &unknown, PLOTS);
    assert_error(code, &err, &["filter.toml:", "sigma_b"]);
}

#[test]
fn failed_run_keeps_previous_output() {
    let dir = tempfile::tempdir().unwrap();
    let (code, err) = track(dir.path(), CONFIG, PLOTS);
    assert_eq!(code, Some(0), "{err}");
    let good = std::fs::read_to_string(dir.path().join("tracks.csv")).unwrap();
    // A bad row late in the file: the run fails, tracks.csv is the good one, no temp left.
    let bad = format!("{PLOTS}8,1,10040,inf\n");
    let (code, err) = track(dir.path(), CONFIG, &bad);
    assert_error(code, &err, &["plots.csv:6", "field 'azimuth'"]);
    assert_eq!(
        std::fs::read_to_string(dir.path().join("tracks.csv")).unwrap(),
        good
    );
    let leftovers: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().contains(".tmp-"))
        .collect();
    assert!(leftovers.is_empty());
}

#[test]
fn run_cv_polar_small_campaign_writes_everything() {
    let dir = tempfile::tempdir().unwrap();
    let stdout = ok(
        &[
            "run",
            "cv-polar",
            "--runs",
            "0..8",
            "--seed",
            "3",
            "--out",
            "res",
            "--set",
            "duration=60",
        ],
        dir.path(),
    );
    assert!(stdout.contains("ANEES (time average)"), "{stdout}");
    for f in ["summary.json", "per_step.csv", "rmse_pos.svg", "anees.svg"] {
        assert!(dir.path().join("res").join(f).exists(), "{f} missing");
    }
    let json = std::fs::read_to_string(dir.path().join("res/summary.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["runs"], serde_json::json!([0, 8]));
    assert!(v["results"]["anees"]["ours"].as_f64().unwrap().is_finite());
    // Bad --set: unknown key and out-of-range value, exit code 2.
    let o = argus(&["run", "cv-polar", "--set", "speed=3"], dir.path());
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("unknown parameter"));
    let o = argus(&["run", "cv-polar", "--runs", "5..2"], dir.path());
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn cv_polar_is_consistent_on_a_reduced_campaign() {
    // Matched filter in the near-linear regime (the defaults): the time-averaged ANEES must
    // lie in the per-step 95 % interval of 40 runs of a 4-dim NEES, χ²₁₆₀(0.025, 0.975)/40
    // = [3.16, 4.94] (a time average varies less than one step, so this is conservative).
    let dir = tempfile::tempdir().unwrap();
    ok(
        &[
            "run", "cv-polar", "--runs", "40", "--seed", "11", "--out", "r",
        ],
        dir.path(),
    );
    let json = std::fs::read_to_string(dir.path().join("r/summary.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let anees = v["results"]["anees"]["ours"].as_f64().unwrap();
    assert!((3.16..=4.94).contains(&anees), "ANEES {anees}");
    // ANIS of a 2-dim NIS over 40 runs and ~75 steps: same reasoning, χ²₈₀/40 = [1.44, 2.63].
    let anis = v["results"]["anis"]["ours"].as_f64().unwrap();
    assert!((1.44..=2.63).contains(&anis), "ANIS {anis}");
}

#[test]
fn simulate_then_track_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    ok(
        &[
            "simulate",
            "cv-polar",
            "--seed",
            "9",
            "--out",
            "sim.csv",
            "--set",
            "duration=20",
        ],
        dir.path(),
    );
    let plots = std::fs::read_to_string(dir.path().join("sim.csv")).unwrap();
    // duration 20 s, period 2 s, P_D = 1: 11 plots + header.
    assert_eq!(plots.lines().count(), 12, "{plots}");
    assert!(dir.path().join("sim.truth.csv").exists());
    // The same seed gives the same file.
    ok(
        &[
            "simulate",
            "cv-polar",
            "--seed",
            "9",
            "--out",
            "sim2.csv",
            "--set",
            "duration=20",
        ],
        dir.path(),
    );
    assert_eq!(
        std::fs::read_to_string(dir.path().join("sim2.csv")).unwrap(),
        plots
    );
    write(dir.path(), "filter.toml", CONFIG);
    ok(
        &[
            "track",
            "--config",
            "filter.toml",
            "--plots",
            "sim.csv",
            "--out",
            "t.csv",
        ],
        dir.path(),
    );
}

#[test]
fn merge_of_split_campaign_equals_whole_run() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    ok(&["run", "cv-polar", "--runs", "0..40", "--out", "a"], d);
    ok(&["run", "cv-polar", "--runs", "40..100", "--out", "b"], d);
    ok(&["run", "cv-polar", "--runs", "100", "--out", "whole"], d);
    let out = ok(&["merge", "cv-polar", "a", "b", "--out", "m"], d);
    assert!(out.contains("--runs 0..100 (2 files)"), "{out}");
    // Exactly the same numbers: per-step CSV, per-run file and every summary result.
    assert_eq!(read(d, "whole/per_step.csv"), read(d, "m/per_step.csv"));
    assert_eq!(
        read(d, "whole/runs/0-100.jsonl"),
        read(d, "m/runs/0-100.jsonl")
    );
    let j = |f: &str| serde_json::from_str::<serde_json::Value>(&read(d, f)).unwrap();
    let (w, m) = (j("whole/summary.json"), j("m/summary.json"));
    for k in ["results", "runs", "seed", "params", "scenario"] {
        assert_eq!(w[k], m[k], "{k}");
    }
    assert!(w["files"].to_string().contains("runs/0-100.jsonl"), "{w}");
    // The pieces differ from the whole (a real merge, not a copy).
    assert_ne!(read(d, "a/per_step.csv"), read(d, "m/per_step.csv"));
    // A merged directory merges again with a later piece.
    ok(&["run", "cv-polar", "--runs", "100..120", "--out", "c"], d);
    ok(&["merge", "cv-polar", "m", "c", "--out", "m2"], d);
    ok(&["run", "cv-polar", "--runs", "120", "--out", "whole2"], d);
    assert_eq!(read(d, "whole2/per_step.csv"), read(d, "m2/per_step.csv"));
}

#[test]
fn merge_rejects_overlap_gap_and_mismatch() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let runs = |r: &str, out: &str, seed: &str| {
        ok(
            &[
                "run",
                "cv-polar",
                "--runs",
                r,
                "--out",
                out,
                "--seed",
                seed,
                "--set",
                "duration=20",
            ],
            d,
        );
    };
    runs("0..4", "a", "1");
    runs("2..6", "b", "1");
    runs("5..8", "c", "1");
    runs("4..8", "s2", "2");
    let err = |args: &[&str]| {
        let o = argus(args, d);
        (
            o.status.code(),
            String::from_utf8_lossy(&o.stderr).into_owned(),
        )
    };
    let (code, e) = err(&["merge", "cv-polar", "a", "b", "--out", "m"]);
    assert_error(
        code,
        &e,
        &["runs 2..4 are in both", "0-4.jsonl", "2-6.jsonl"],
    );
    let (code, e) = err(&["merge", "cv-polar", "a", "c", "--out", "m"]);
    assert_error(
        code,
        &e,
        &["runs 4..5 are in no per-run file", "re-submit index 4..5"],
    );
    let (code, e) = err(&["merge", "cv-polar", "a", "s2", "--out", "m"]);
    assert_error(code, &e, &["4-8.jsonl:1", "field 'seed'"]);
    let (code, e) = err(&["merge", "cv-polar", "a", "--out", "a"]);
    assert_error(code, &e, &["one of the merged directories"]);
    // A truncated per-run file is named with its line count.
    let f = d.join("b/runs/2-6.jsonl");
    let text = std::fs::read_to_string(&f).unwrap();
    let cut: Vec<&str> = text.lines().take(3).collect();
    std::fs::write(&f, cut.join("\n")).unwrap();
    let (code, e) = err(&["merge", "cv-polar", "b", "--out", "m"]);
    assert_error(code, &e, &["2-6.jsonl", "2 run lines for runs 2..6"]);
    // No merged output was left behind by the failures.
    assert!(!d.join("m").exists());
}

#[test]
fn figures_are_written_as_svg_and_png() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    ok(
        &[
            "run",
            "cv-polar",
            "--runs",
            "4",
            "--out",
            "r",
            "--set",
            "duration=20",
        ],
        d,
    );
    for stem in ["rmse_pos", "anees"] {
        let png = std::fs::read(d.join(format!("r/{stem}.png"))).unwrap();
        // PNG signature, then IHDR with width 800 and height 500 (big-endian).
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
        assert_eq!(&png[16..24], &[0, 0, 3, 32, 0, 0, 1, 244]);
        let svg = read(d, &format!("r/{stem}.svg"));
        assert!(svg.contains("time (s)"), "x label missing in {stem}.svg");
    }
    assert!(read(d, "r/rmse_pos.svg").contains("position error (m)"));
}

/// A 3-D CV target: x₀ = (20 km, 5 km, 3 km), v = (−100, 50, 10) m/s, plots every 2 s.
fn truth3(t: f64) -> [f64; 3] {
    [20_000.0 - 100.0 * t, 5_000.0 + 50.0 * t, 3_000.0 + 10.0 * t]
}

const CONFIG3: &str = r#"
[[sensor]]
id = 1
position = [100.0, 200.0, 10.0]
sigma_range = 1.0
sigma_azimuth_deg = 0.001
sigma_elevation_deg = 0.001

[[sensor]]
id = 2
position = [0.0, 0.0]

[estimator]
kind = "kf-converted"
sigma_a = 0.0
"#;

fn rows(text: &str) -> Vec<Vec<f64>> {
    text.lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect()
}

#[test]
fn track_3d_cartesian_reports_match_least_squares() {
    let dir = tempfile::tempdir().unwrap();
    let mut plots = String::from("t,sensor,x,y,z,r_xx,r_xy,r_xz,r_yy,r_yz,r_zz\n");
    for k in 0..6 {
        let t = 2.0 * f64::from(k);
        let [x, y, z] = truth3(t);
        plots.push_str(&format!("{t},2,{x},{y},{z},100,10,0,100,0,100\n"));
    }
    let (code, err) = track(dir.path(), CONFIG3, &plots);
    assert_eq!(code, Some(0), "{err}");
    let text = read(dir.path(), "tracks.csv");
    assert_eq!(
        text.lines().next(),
        Some("t,track,x,vx,y,vy,z,vz,var_x,var_vx,var_y,var_vy,var_z,var_vz")
    );
    let r = rows(&text);
    assert_eq!(r.len(), 5);
    let last = &r[4];
    // Exact plots of a CV target and no process noise: the KF stays on the truth.
    let [x, y, z] = truth3(10.0);
    for (got, want) in [
        (last[2], x),
        (last[3], -100.0),
        (last[4], y),
        (last[5], 50.0),
        (last[6], z),
        (last[7], 10.0),
    ] {
        assert!((got - want).abs() < 1e-6, "{last:?}");
    }
    // Without process noise the KF is least squares on t = 0, 2, …, 10 (n = 6, t̄ = 5,
    // Sxx = 70): var(x(10)) = R (1/n + (10 − t̄)²/Sxx) = 100 · 0.52381, var(v) = R/Sxx.
    for axis in 0..3 {
        assert!((last[8 + 2 * axis] - 100.0 * (1.0 / 6.0 + 25.0 / 70.0)).abs() < 1e-9);
        assert!((last[9 + 2 * axis] - 100.0 / 70.0).abs() < 1e-9);
    }
}

#[test]
fn track_3d_spherical_plots_kf_and_ekf() {
    let dir = tempfile::tempdir().unwrap();
    // Noise-free spherical plots of the 3-D target from sensor 1 at (100, 200, 10).
    let mut plots = String::from("t,sensor,range,azimuth,elevation\n");
    for k in 0..6 {
        let t = 2.0 * f64::from(k);
        let [x, y, z] = truth3(t);
        let (dx, dy, dz) = (x - 100.0, y - 200.0, z - 10.0);
        let r = (dx * dx + dy * dy + dz * dz).sqrt();
        plots.push_str(&format!(
            "{t},1,{r},{},{}\n",
            dy.atan2(dx),
            dz.atan2(dx.hypot(dy))
        ));
    }
    for kind in ["kf-converted", "ekf"] {
        let cfg = CONFIG3.replace("kf-converted", kind);
        let (code, err) = track(dir.path(), &cfg, &plots);
        assert_eq!(code, Some(0), "{kind}: {err}");
        let r = rows(&read(dir.path(), "tracks.csv"));
        let last = &r[4];
        // Exact plots: the only error is the unbiased conversion's 1/λ range scaling in
        // the start, λ⁻¹ − 1 ≈ σψ²/2 + σθ²/2 ≈ 3e-10 of 20 km ≈ 6 µm; allow 1 mm.
        let [x, y, z] = truth3(10.0);
        assert!((last[2] - x).abs() < 1e-3, "{kind} {last:?}");
        assert!((last[4] - y).abs() < 1e-3, "{kind} {last:?}");
        assert!((last[6] - z).abs() < 1e-3, "{kind} {last:?}");
        assert!((last[3] + 100.0).abs() < 1e-3, "{kind} {last:?}");
    }
    // Bad 3-D input: a sensor without elevation σ, an elevation beyond π/2, a
    // covariance that is not positive definite.
    let no_el = CONFIG3.replace("sigma_elevation_deg = 0.001\n", "");
    let (code, err) = track(dir.path(), &no_el, &plots);
    assert_error(
        code,
        &err,
        &["filter.toml", "field 'sigma_elevation_deg'", "sensor 1"],
    );
    let bad_el = "t,sensor,range,azimuth,elevation\n0,1,1000,0.1,0.2\n2,1,1000,0.1,1.7\n";
    let (code, err) = track(dir.path(), CONFIG3, bad_el);
    assert_error(code, &err, &["plots.csv:3", "field 'elevation'"]);
    let bad_cov = "t,sensor,x,y,z,r_xx,r_xy,r_xz,r_yy,r_yz,r_zz\n0,2,1,2,3,1,2,0,1,0,1\n";
    let (code, err) = track(dir.path(), CONFIG3, bad_cov);
    assert_error(code, &err, &["plots.csv:2", "not positive definite"]);
    let missing = "t,sensor,x,y,z,r_xx,r_xy,r_yy\n0,2,1,2,3,1,0,1\n";
    let (code, err) = track(dir.path(), CONFIG3, missing);
    assert_error(code, &err, &["plots.csv:1", "field 'r_xz'", "missing"]);
}

#[test]
fn track_3d_noisy_spherical_plots_are_consistent() {
    use rand::SeedableRng;
    use rand_distr::{Distribution, StandardNormal};
    // 30 seeded runs of 20 noisy spherical plots (σr = 20 m, σψ = σθ = 0.2°, r ≈ 20 km:
    // r σ² / σr ≈ 0.012, the near-linear regime) of the CV target, no process noise
    // in truth or filter. At the last plot each axis' normalised squared position error
    // e²/var is χ²₁ for a consistent filter; the mean of 90 of them lies in
    // χ²₉₀(0.025, 0.975)/90 (axes treated as independent, which they nearly are here).
    let dir = tempfile::tempdir().unwrap();
    let cfg = CONFIG3
        .replace("sigma_range = 1.0", "sigma_range = 20.0")
        .replace("sigma_azimuth_deg = 0.001", "sigma_azimuth_deg = 0.2")
        .replace("sigma_elevation_deg = 0.001", "sigma_elevation_deg = 0.2");
    let (sr, sa) = (20.0, 0.2f64.to_radians());
    let lo = argus_core_math::chi2_quantile(0.025, 90.0).unwrap() / 90.0;
    let hi = argus_core_math::chi2_quantile(0.975, 90.0).unwrap() / 90.0;
    for kind in ["kf-converted", "ekf"] {
        let cfg = cfg.replace("kf-converted", kind);
        let mut sum = 0.0;
        for run in 0..30u64 {
            let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1000 + run);
            let mut n = || -> f64 { StandardNormal.sample(&mut rng) };
            let mut plots = String::from("t,sensor,range,azimuth,elevation\n");
            for k in 0..20 {
                let t = 2.0 * f64::from(k);
                let [x, y, z] = truth3(t);
                let (dx, dy, dz) = (x - 100.0, y - 200.0, z - 10.0);
                let r = (dx * dx + dy * dy + dz * dz).sqrt() + sr * n();
                let az = dy.atan2(dx) + sa * n();
                let el = dz.atan2(dx.hypot(dy)) + sa * n();
                plots.push_str(&format!("{t},1,{r},{az},{el}\n"));
            }
            let (code, err) = track(dir.path(), &cfg, &plots);
            assert_eq!(code, Some(0), "{kind}: {err}");
            let r = rows(&read(dir.path(), "tracks.csv"));
            let last = r.last().unwrap();
            let truth = truth3(38.0);
            for axis in 0..3 {
                let e = last[2 + 2 * axis] - truth[axis];
                sum += e * e / last[8 + 2 * axis];
            }
        }
        let mean = sum / 90.0;
        println!("{kind}: mean e²/var {mean:.4} in [{lo:.4}, {hi:.4}]");
        assert!(
            (lo..=hi).contains(&mean),
            "{kind}: {mean} not in [{lo}, {hi}]"
        );
    }
}

/// A reader that stops reading (`argus run … | head -1`) closes the pipe: the command
/// must neither panic nor lose its files (it used to panic in `println!`).
#[test]
fn a_closed_stdout_is_no_panic_and_the_files_are_written() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_argus"))
        .args([
            "run",
            "cv-polar",
            "--runs",
            "4",
            "--set",
            "duration=20",
            "--out",
        ])
        .arg(&out)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let done = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&done.stderr);
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(done.status.code(), Some(0), "{err}");
    assert!(out.join("summary.json").is_file());
}

//! `argus track` with the IMM and multi-IMM estimators, driving the real binary on plots
//! that `argus simulate gimpo` writes (seed 000's approach, σr = 70 m, σθ = 0.08°).

// Test helpers outside #[test] functions may unwrap: a failure is a test failure.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;

mod common;
use common::{argus, assert_error, col, simulate_gimpo};

/// The paper's IMM (seed 000 eqs (15)–(20)) for a radar with the given σ.
fn config(kind: &str, sigma_range: f64, sigma_az_deg: f64, extra: &str) -> String {
    format!(
        r#"[[sensor]]
id = 1
position = [0.0, 0.0]
sigma_range = {sigma_range}
sigma_azimuth_deg = {sigma_az_deg}

[estimator]
kind = "{kind}"
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
{extra}
"#
    )
}

/// Runs `argus track` with `cfg` on `plots`; returns (exit code, stderr, tracks text).
fn track(dir: &Path, cfg: &str, plots: &str) -> (Option<i32>, String, String) {
    std::fs::write(dir.join("imm.toml"), cfg).unwrap();
    let _ = std::fs::remove_file(dir.join("tracks.csv"));
    let o = argus(
        &[
            "track",
            "--config",
            "imm.toml",
            "--plots",
            plots,
            "--out",
            "tracks.csv",
        ],
        dir,
    );
    let text = std::fs::read_to_string(dir.join("tracks.csv")).unwrap_or_default();
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
        text,
    )
}

/// (header, rows) of a CSV text.
fn table(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut lines = text.lines();
    let head = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_owned)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    (head, rows)
}

#[test]
fn imm_track_has_mode_probabilities_that_follow_the_turn() {
    let dir = tempfile::tempdir().unwrap();
    simulate_gimpo(dir.path(), 4);
    let (code, err, text) = track(dir.path(), &config("imm", 70.0, 0.08, ""), "sim.csv");
    assert_eq!(code, Some(0), "{err}");
    let (head, rows) = table(&text);
    assert_eq!(
        head.join(","),
        "t,track,x,vx,y,vy,var_x,var_vx,var_y,var_vy,mu_1,mu_2,mu_3"
    );
    // One row per plot from the second on: the beam (5 s period) sees the target about
    // 1019 / 5 ≈ 204 times.
    assert!((195..=210).contains(&rows.len()), "{}", rows.len());
    let (m1, m2) = (col(&head, "mu_1"), col(&head, "mu_2"));
    for r in &rows {
        let s: f64 = r[m1..m1 + 3].iter().sum();
        assert!((s - 1.0).abs() < 1e-9, "probabilities sum to {s}");
    }
    // Table 1: CV until 330 s, then a +1.5 °/s turn until 393 s. The CT+ model (mu_2) must
    // gain in the turn: its mean over the turn's second half is above its mean over the
    // last 80 s of straight flight before it (paper Fig. 4; ours, 100-run mean: ≈ 0.1 → 0.5).
    let mean = |a: f64, b: f64, c: usize| {
        let v: Vec<f64> = rows
            .iter()
            .filter(|r| r[0] >= a && r[0] < b)
            .map(|r| r[c])
            .collect();
        v.iter().sum::<f64>() / v.len() as f64
    };
    let before = mean(250.0, 330.0, m2);
    let during = mean(362.0, 393.0, m2);
    assert!(
        during > before + 0.1,
        "CT+ {before} before, {during} in the turn"
    );
    assert!(
        mean(250.0, 330.0, m1) > 0.5,
        "CV dominates the straight leg"
    );
}

/// The multi-IMM started at 2 × the true variance. Issue 4's reference (100 runs, p = 0.1,
/// ±5 % clip): the final ratio from 2.0 is 1.07 on average with a per-run sd of 0.11, so one
/// run is within 1.07 ± 0.33 (3 sd). The paper's grid scales both variances by one factor:
/// range and azimuth ratios are equal.
#[test]
fn multi_imm_track_estimates_the_noise() {
    let dir = tempfile::tempdir().unwrap();
    simulate_gimpo(dir.path(), 5);
    let s2 = 2f64.sqrt();
    let cfg = config(
        "multi-imm",
        70.0 * s2,
        0.08 * s2,
        "n = 5\np = 0.1\nclip = 0.05\n",
    );
    let (code, err, text) = track(dir.path(), &cfg, "sim.csv");
    assert_eq!(code, Some(0), "{err}");
    let (head, rows) = table(&text);
    assert_eq!(
        head.join(","),
        "t,track,x,vx,y,vy,var_x,var_vx,var_y,var_vy,mu_1,mu_2,mu_3,sigma_range,sigma_azimuth_deg"
    );
    let (sr, sa) = (col(&head, "sigma_range"), col(&head, "sigma_azimuth_deg"));
    // The first row is the start: the configured σ.
    assert!((rows[0][sr] - 70.0 * s2).abs() < 1e-9);
    // Per step the reference moves by at most 5 % (the clip).
    for w in rows.windows(2) {
        let q = (w[1][sr] / w[0][sr]).powi(2);
        assert!((0.95 - 1e-12..=1.05 + 1e-12).contains(&q), "step ratio {q}");
    }
    let last = rows.last().unwrap();
    let ratio_r = (last[sr] / 70.0).powi(2);
    let ratio_a = (last[sa] / 0.08).powi(2);
    assert!(
        (0.74..=1.40).contains(&ratio_r),
        "final range ratio {ratio_r}"
    );
    assert!((ratio_r - ratio_a).abs() < 1e-9, "{ratio_r} vs {ratio_a}");

    // With per_axis = true the two ratios are estimated separately.
    let cfg = config(
        "multi-imm",
        70.0 * s2,
        0.08 * s2,
        "n = 3\np = 0.1\nper_axis = true\n",
    );
    let (code, err, text) = track(dir.path(), &cfg, "sim.csv");
    assert_eq!(code, Some(0), "{err}");
    let (head, rows) = table(&text);
    let (sr, sa) = (col(&head, "sigma_range"), col(&head, "sigma_azimuth_deg"));
    let last = rows.last().unwrap();
    let ratio_r = (last[sr] / 70.0).powi(2);
    let ratio_a = (last[sa] / 0.08).powi(2);
    assert!((ratio_r - ratio_a).abs() > 1e-6, "{ratio_r} vs {ratio_a}");
    // A 3 × 3 grid with p = 0.1 moves each axis by at most 10 % per step and, with a fresh
    // uniform prior each step, slowly: from 2.0 both ratios must have come down (this run:
    // 1.56 and 1.62 at the end), not necessarily reached the truth.
    assert!(
        ratio_r < 1.8 && ratio_a < 1.8,
        "{ratio_r}, {ratio_a} from 2.0"
    );
}

#[test]
fn bad_imm_configs_name_file_line_and_field() {
    let dir = tempfile::tempdir().unwrap();
    let plots = "t,sensor,range,azimuth\n0,1,10000,0.5\n5,1,10010,0.51\n10,1,10020,0.52\n";
    std::fs::write(dir.path().join("p.csv"), plots).unwrap();
    let cases: [(String, &[&str]); 7] = [
        (
            config("imm", 70.0, 0.08, "initial = [0.5, 0.5, 0.5]"),
            &["imm.toml:19", "field 'initial'", "sum = 1.5"],
        ),
        (
            config("multi-imm", 70.0, 0.08, "n = 4"),
            &["imm.toml:19", "field 'n'"],
        ),
        (
            config("multi-imm", 70.0, 0.08, "n = 5\np = 0.6"),
            &["imm.toml:20", "field 'p'"],
        ),
        (
            config("multi-imm", 70.0, 0.08, "clip = 1.5"),
            &["imm.toml:19", "field 'clip'"],
        ),
        (
            config("multi-imm", 70.0, 0.08, "n = 7\nper_axis = true"),
            &["field 'n'", "per_axis"],
        ),
        (
            config("imm", 70.0, 0.08, "").replace("rate_deg = 3.0", "rate_deg = 0.0"),
            &["imm.toml:11", "field 'rate_deg'"],
        ),
        (
            config("imm", 70.0, 0.08, "").replace("sigma_a = 0.1", "sigma_a = -0.1"),
            &["imm.toml:10", "field 'sigma_a'"],
        ),
    ];
    for (cfg, needles) in &cases {
        let (code, err, _) = track(dir.path(), cfg, "p.csv");
        assert_error(code, &err, needles);
    }
    // The multi-IMM needs increasing times: a repeated time is an error at its plot line.
    let same = "t,sensor,range,azimuth\n0,1,10000,0.5\n5,1,10010,0.51\n5,1,10020,0.52\n";
    std::fs::write(dir.path().join("same.csv"), same).unwrap();
    let (code, err, _) = track(dir.path(), &config("multi-imm", 70.0, 0.08, ""), "same.csv");
    assert_error(code, &err, &["same.csv:4", "dt = 0"]);
    // ... which the plain IMM accepts (plots of one instant are applied in turn).
    let (code, err, text) = track(dir.path(), &config("imm", 70.0, 0.08, ""), "same.csv");
    assert_eq!(code, Some(0), "{err}");
    assert_eq!(text.lines().count(), 3);
    // Cartesian reports cannot feed the multi-IMM (it estimates polar noise).
    let cart = "t,sensor,x,y,r_xx,r_xy,r_yy\n0,1,0,0,100,0,100\n5,1,50,0,100,0,100\n10,1,100,0,100,0,100\n";
    std::fs::write(dir.path().join("cart.csv"), cart).unwrap();
    let (code, err, _) = track(dir.path(), &config("multi-imm", 70.0, 0.08, ""), "cart.csv");
    assert_error(code, &err, &["cart.csv:2", "field 'sensor'", "Cartesian"]);
    // 3-D plots: the IMMs are 2-D.
    let sph = "t,sensor,range,azimuth,elevation\n0,1,10000,0.5,0.1\n5,1,10010,0.51,0.1\n";
    std::fs::write(dir.path().join("sph.csv"), sph).unwrap();
    let cfg = config("imm", 70.0, 0.08, "").replace(
        "sigma_azimuth_deg = 0.08",
        "sigma_azimuth_deg = 0.08\nsigma_elevation_deg = 0.1",
    );
    let (code, err, _) = track(dir.path(), &cfg, "sph.csv");
    assert_error(code, &err, &["field 'estimator.kind'", "2-D"]);
}

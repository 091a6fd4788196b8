//! `argus run surveillance` on a reduced campaign: the command works end to end and
//! the trackers beat "no tracks" by a wide margin without many false tracks.

// Test helpers may unwrap: a failure is a test failure.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::process::Command;

/// Keys of the tracker configurations in `summary.json` (`default` first).
const CONFIGS: [&str; 5] = ["default", "gnn_kf", "gnn_imm", "jpda_kf", "jpda_imm"];

/// Runs `argus run surveillance` with `args` in a temporary directory and returns the
/// output directory's `summary.json`, parsed, with the directory (kept alive).
fn campaign(args: &[&str]) -> (serde_json::Value, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_argus"))
        .args(["run", "surveillance", "--out", "res"])
        .args(args)
        .current_dir(dir.path())
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    let json = std::fs::read_to_string(dir.path().join("res").join("summary.json")).unwrap();
    (serde_json::from_str(&json).unwrap(), dir)
}

/// The summary row `key`'s value.
fn ours(v: &serde_json::Value, key: &str) -> f64 {
    v["results"][key]["ours"]
        .as_f64()
        .unwrap_or_else(|| panic!("row {key} missing in {v}"))
}

#[test]
fn default_configuration_keeps_clutter_tracks_below_one_per_scan() {
    // Issue 18's goal for the default configuration: ≤ 1 confirmed false track per scan at
    // the scenario's default clutter density (500 plots per scan over the 200 km disc).
    // False tracks are born of clutter and do not depend on the traffic, so 20 aircraft
    // over 100 s (2 runs, seed 5) carry the full density's false tracks: the M-of-N
    // IMM configurations keep 12.7–13.0 per scan here (measured), the default 0.0. The
    // bound is the goal's (a requirement, not a derived value); its second goal, ≤ 5
    // breaks per run at the full default, is not reached (11.05, docs/surveillance.md)
    // and is not checked.
    let (v, _dir) = campaign(&[
        "--runs",
        "2",
        "--seed",
        "5",
        "--set",
        "targets=20",
        "--set",
        "duration=100",
    ]);
    let rate = ours(&v, "default_false_track_rate");
    assert!(rate <= 1.0, "default: false-track rate {rate} per scan");
    let false_after = ours(&v, "default_false");
    assert!(
        false_after <= 1.0,
        "default: {false_after} false tracks per scan"
    );
}

#[test]
fn reduced_campaign_beats_no_tracks_with_few_false_tracks() {
    // 20 aircraft, 2 runs, scans at 0, 5, …, 100 s, and the default's clutter per
    // aircraft (500 plots per scan for 200 aircraft → 50 for 20); every other parameter at
    // its default (200 km coverage, P_D = 0.9, c = 1000 m, p = 2, averages over t ≥ 30 s).
    // Clutter is scaled with the traffic because false tracks born of clutter do not
    // depend on the traffic (and grow about ∝ clutter³: pairs through the velocity gate
    // ∝ clutter², confirmation ∝ density): 500 plots per scan give ≈ 5 false tracks per
    // scan (measured, 2 runs), 2.5 % of 200 aircraft but 25 % of 20.
    let targets = 20.0_f64;
    let dir = tempfile::tempdir().unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_argus"))
        .args([
            "run",
            "surveillance",
            "--runs",
            "2",
            "--seed",
            "5",
            "--out",
            "res",
            "--set",
            "targets=20",
            "--set",
            "duration=100",
            "--set",
            "clutter=50",
        ])
        .current_dir(dir.path())
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    let res = dir.path().join("res");
    for f in [
        "summary.json",
        "per_scan.csv",
        "ospa.svg",
        "gospa.svg",
        "gospa.png",
        "missed_false.svg",
    ] {
        assert!(res.join(f).exists(), "{f} missing");
    }
    let json = std::fs::read_to_string(res.join("summary.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let ours = |key: &str| -> f64 {
        v["results"][key]["ours"]
            .as_f64()
            .unwrap_or_else(|| panic!("row {key} missing in {json}"))
    };

    // GOSPA (α = 2) of an empty estimate set: no pair is assigned, each of the n truths
    // is a missed target costing c^p/2 (Rahmathullah, García-Fernández & Svensson 2017,
    // Proposition 1), so d^p = n c^p / 2 and d = c (n/2)^{1/p} = 1000 · √10 = 3162.3 m.
    let (c, p) = (1000.0_f64, 2.0_f64);
    let no_tracks = c * (targets / 2.0).powf(1.0 / p);
    assert!(
        (ours("gospa_no_tracks") - no_tracks).abs() < 1e-9,
        "{}",
        ours("gospa_no_tracks")
    );

    for key in CONFIGS {
        // "Well below": after the confirmation period the mean GOSPA must be at most half
        // the no-track value, i.e. d^p at most a quarter of n c^p/2 — the cost of fewer
        // than a quarter of the targets missed (or as many false tracks), with every
        // tracked target's error counted on top.
        let gospa = ours(&format!("{key}_gospa"));
        assert!(
            gospa <= 0.5 * no_tracks,
            "{key}: mean GOSPA {gospa} m against no tracks {no_tracks} m"
        );
        // Stated bound on false tracks (a requirement we set, not a derived value): on
        // average at most 5 % of the number of targets, i.e. ≤ 1 false confirmed track
        // per scan for 20 aircraft, over the whole run including the start-up.
        let rate = ours(&format!("{key}_false_track_rate"));
        assert!(
            rate <= 0.05 * targets,
            "{key}: false-track rate {rate} per scan"
        );
        // Every row is a finite number.
        for row in [
            "ospa",
            "localisation",
            "missed",
            "false",
            "breaks",
            "id_swaps",
            "time_to_confirm",
        ] {
            let x = ours(&format!("{key}_{row}"));
            assert!(x.is_finite() && x >= 0.0, "{key}_{row} = {x}");
        }
    }
}

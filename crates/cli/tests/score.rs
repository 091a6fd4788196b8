//! `argus score` drives argus-score on files: the numbers Stone Soup 1.9.1's SIAP gave on the
//! same pair of files (crates/score/tests/stonesoup_siap.py, quoted in docs/scoring.md), and a
//! malformed file named at its line and field.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::PathBuf;

mod common;
use common::argus;

fn data(name: &str) -> String {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../score/tests/data")
        .join(name);
    p.display().to_string()
}

#[test]
fn scores_a_file_pair_as_stone_soup_does() {
    let dir = tempfile::tempdir().unwrap();
    let o = argus(
        &[
            "score",
            "--tracks",
            &data("surv-kf-gnn.tracks.csv"),
            "--truth",
            &data("surv.truth.csv"),
            "--out",
            "score.json",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("score.json")).unwrap())
            .unwrap();
    let s = &v["summary"];
    // Stone Soup 1.9.1, SIAP with a one-to-one assignment on the same grid: completeness
    // 0.900000, spuriousness 0.013477, position accuracy 169.328159 m (printed to 6 digits:
    // tolerance half a unit of the last digit).
    let close = |key: &str, want: f64, tol: f64| {
        let got = s[key].as_f64().unwrap();
        assert!((got - want).abs() <= tol, "{key}: {got} vs {want}");
    };
    close("completeness", 0.900_000, 5e-7);
    close("spurious_fraction", 0.013_477, 5e-7);
    close("position_accuracy", 169.328_159, 5e-7);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("completeness"), "{stdout}");
}

#[test]
fn a_malformed_tracks_file_is_named_at_its_line_and_field() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("bad.csv"),
        "t,track,status,x,vx,y,vy\n0,1,confirmed,abc,0,0,0\n",
    )
    .unwrap();
    let o = argus(
        &[
            "score",
            "--tracks",
            "bad.csv",
            "--truth",
            &data("surv.truth.csv"),
            "--out",
            "s.json",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("bad.csv:2: field 'x'"), "{err}");
    assert!(!dir.path().join("s.json").exists(), "no output on error");
}

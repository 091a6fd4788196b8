//! Issues 19 and 18 on real traffic (the hour's first five minutes, seed 1): the Kalman
//! and two-mode IMM trackers' tracks smoothed over their lives (`*_smooth_rms_ratio`) and every
//! configuration's NEES against the RTS-smoothed ADS-B truth
//! (`*_nees_cv_vs_smoothed_truth`).

// Test helpers outside #[test] functions may unwrap: a failure is a test failure.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use argus_scenarios::{NoProgress, Params, find};

#[test]
fn smoothed_tracks_and_nees_against_the_smoothed_truth() {
    let sc = find("real-traffic").unwrap();
    let params = Params::from_settings(&sc.params(), &["duration=300".to_owned()]).unwrap();
    let out = argus_scenarios::run(sc.as_ref(), 0..1, 1, params, &NoProgress).unwrap();
    let row = |key: &str| {
        out.report
            .rows
            .iter()
            .find(|r| r.key == key)
            .map(|r| r.ours)
    };
    for c in ["gnn_kf", "jpda_kf", "gnn_imm", "jpda_imm"] {
        let ratio = row(&format!("{c}_smooth_rms_ratio")).unwrap();
        // Measured 0.518 / 0.518 (KF), 0.505 / 0.505 (two-mode IMM, argus_imm's IMM
        // smoother); whole hour, seed 3: 0.513 (KF), 0.506 (IMM). Upper side: the smoother uses the
        // later plots too, so it must gain clearly (< 0.9); lower side: a sanity bound
        // (0.3 would be below the ADS-B jitter's share of the error, docs/real-traffic.md).
        assert!((0.3..0.9).contains(&ratio), "{c}: smooth_rms_ratio {ratio}");
    }
    for c in ["gnn_aircraft", "jpda_aircraft"] {
        // The aircraft-IMM smoother (argus_imm::aircraft_smooth). Measured 0.477 / 0.476
        // (GNN / JPDA). Bounds as for the KF and the two-mode IMM.
        let ratio = row(&format!("{c}_smooth_rms_ratio")).unwrap();
        assert!((0.3..0.9).contains(&ratio), "{c}: smooth_rms_ratio {ratio}");
    }
    for c in [
        "gnn_kf",
        "gnn_imm",
        "jpda_kf",
        "jpda_imm",
        "gnn_aircraft",
        "jpda_aircraft",
    ] {
        let nees = row(&format!("{c}_nees_cv_vs_smoothed_truth")).unwrap();
        // Reported, not a goal: measured 2.7 (KF, two-CV IMM) and 3.6 (aircraft IMM).
        // Outside 0.5–20 would mean the covariance or the truth matching is broken.
        assert!((0.5..20.0).contains(&nees), "{c}: NEES {nees}");
    }
}

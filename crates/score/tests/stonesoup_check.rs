//! argus-score against Stone Soup 1.9.1's own SIAP and GOSPA on one file: the
//! surveillance scenario (seed 7, 20 aircraft, 300 s) tracked by GNN + KF
//! (`tests/data/`). The reference values were printed by `tests/stonesoup_siap.py`
//! (quoted in full in docs/scoring.md):
//!
//! ```text
//! one-to-one optimal assignment per grid time (SciPy), SIAPMetrics' per-time sums
//!   sums: J 1220, JT 1098, NA 1098, N 1113
//!   SIAP Completeness: 0.900000
//!   SIAP Spuriousness: 0.013477
//!   SIAP Position Accuracy: 169.328159
//!   SIAP Velocity Accuracy: 23.184210
//! GOSPA mean distance over 61 times: 1411.608159
//! GOSPA mean localisation over 61 times: 1044275.881682
//! GOSPA mean missed over 61 times: 1000000.000000
//! GOSPA mean false over 61 times: 122950.819672
//! ```
//!
//! Tolerance: half a unit of the printed sixth decimal. With Stone Soup's `TrackToTruth`
//! associator instead (nearest truth per track, two consecutive matches to start) it gave
//! C 0.899180, S 0.014376, PA 169.450088, VA 23.202637, R 0.012008, LS 0.413333; LS is
//! checked against that run too (same segments), the rest differ by the association.

#![allow(clippy::unwrap_used, missing_docs)]

use std::path::Path;

use argus_score::{ScoreConfig, Scorer, read_tracks, read_truth};

fn near(a: f64, b: f64, decimals: i32) -> bool {
    (a - b).abs() <= 0.5 * 10f64.powi(-decimals)
}

#[test]
fn matches_stone_soup_siap_and_gospa() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let tracks = read_tracks(&dir.join("surv-kf-gnn.tracks.csv")).unwrap();
    let truth = read_truth(&dir.join("surv.truth.csv")).unwrap();
    let s = Scorer::new(ScoreConfig::default())
        .unwrap()
        .score(&tracks, &truth)
        .unwrap()
        .summary;
    assert_eq!(
        (s.truth_points, s.assigned_points, s.track_points),
        (1220, 1098, 1113)
    );
    assert!(near(s.completeness.unwrap(), 0.900000, 6));
    assert!(near(s.spurious_fraction.unwrap(), 0.013477, 6));
    assert!(near(s.position_accuracy.unwrap(), 169.328159, 6));
    assert!(near(s.velocity_accuracy.unwrap(), 23.184210, 6));
    assert!(near(s.longest_segment.unwrap(), 0.413333, 6));
    assert!(near(s.gospa_mean, 1411.608159, 6));
    assert!(near(s.gospa_localisation_mean, 1044275.881682, 6));
    assert!(near(s.gospa_missed_mean, 1000000.0, 6));
    assert!(near(s.gospa_false_mean, 122950.819672, 6));
}

//! `argus track --smooth` / `--smooth-lag` for the aircraft IMM (`aircraft-imm`): the
//! real binary on a simulated gimpo flight (one target, no clutter), the multi-target
//! tracker's GNN track (by scans, and by sectors of the rotating radar) checked row by
//! row against the single-target `aircraft-imm` smoother of the same plots, and the
//! smoothed error against the truth.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;
use common::{Row, gimpo_rmse_pair, num, rows, simulate_gimpo, smoothed_track, track};

const SENSOR: &str =
    "[[sensor]]\nid = 1\nposition = [0.0, 0.0]\nsigma_range = 70.0\nsigma_azimuth_deg = 0.08\n\n";
const ESTIMATOR: &str = "[estimator]\nkind = \"aircraft-imm\"\n";

fn single() -> String {
    format!("{SENSOR}{ESTIMATOR}")
}

/// gimpo's radar as a rotating one (counter-clockwise, the beam east at t = 0, so north
/// at 1.25 s; tests/track_aircraft.rs): the tracker then runs by sectors.
const ROTATION: &str =
    "revolution_period = 5.0\nrotation = \"counterclockwise\"\nnorth_time = 1.25\n";

/// The tracker's configuration, its sensor `rotation` (nothing or [`ROTATION`]).
fn tracker(rotation: &str) -> String {
    let sensor = SENSOR.trim_end();
    format!("{sensor}\n{rotation}\n{ESTIMATOR}\n[tracker]\nconfirm_m = 3\n")
}

/// The rows of the scene's one track (track 0), deleted row excluded.
fn the_track(csv: &str) -> Vec<Row> {
    assert!(rows(csv).iter().all(|r| r["track"] == "0"));
    smoothed_track::the_track(csv)
}

/// The worst relative difference between the tracker's smoothed columns and the
/// single-target ones, row by row: both start at the second plot (the two-point start's
/// estimate, the tracker's initiation row) and take every later plot.
fn worst_difference(multi: &[Row], single: &[Row]) -> f64 {
    smoothed_track::worst_difference(multi, single, &[], 3)
}

#[test]
fn a_gnn_aircraft_track_smooths_as_the_single_target_aircraft_imm() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    simulate_gimpo(d, 4);
    let plots = d.join("sim.csv");
    let cases = [
        ("", &["--smooth"][..]),
        ("", &["--smooth-lag", "3"][..]),
        (ROTATION, &["--smooth"][..]),
        (ROTATION, &["--smooth-lag", "3"][..]),
    ];
    for (rotation, flags) in cases {
        let path = if rotation.is_empty() {
            "scan"
        } else {
            "sectors"
        };
        let case = (path, flags);
        let (code, err, multi) = track(d, &tracker(rotation), &plots, flags);
        assert_eq!(code, Some(0), "{case:?}: {err}");
        let (code, err, single) = track(d, &single(), &plots, flags);
        assert_eq!(code, Some(0), "{case:?}: {err}");
        let header = single.lines().next().unwrap();
        assert!(
            header.ends_with(
                "turn_rate_deg,sigma_turn_rate_deg,xs,vxs,ys,vys,var_xs,var_vxs,var_ys,var_vys,mu_1s,mu_2s,mu_3s"
            ),
            "{header}"
        );
        let header = multi.lines().next().unwrap();
        assert!(
            header.ends_with(
                "turn_rate_deg,sigma_turn_rate_deg,xs,vxs,ys,vys,sigma_xs,sigma_ys,mu_1s,mu_2s,mu_3s"
            ),
            "{header}"
        );
        let (m, s) = (the_track(&multi), rows(&single));
        assert!(m.len() > 190, "{}", m.len());
        let worst = worst_difference(&m, &s);
        // 1e-9 relative: the same arithmetic on the same posteriors (the tracker's GNN
        // track is the single-target estimator row by row, tests/track_aircraft.rs),
        // printed at full precision.
        println!("{case:?}: worst relative difference {worst:e}");
        assert!(worst < 1e-9, "{case:?}: {worst:e}");
        for r in &s {
            let mu: f64 = ["mu_1s", "mu_2s", "mu_3s"].iter().map(|k| num(r, k)).sum();
            // Three printed probabilities of a normalised distribution.
            assert!((mu - 1.0).abs() < 1e-9, "{mu}");
        }
    }
    // A lag as long as the track is the fixed-interval smoother.
    smoothed_track::long_lag_is_interval(d, &single(), &plots, "10000");
}

#[test]
fn the_smoothed_aircraft_track_is_closer_to_the_truth() {
    let dir = tempfile::tempdir().unwrap();
    let (f, s) = gimpo_rmse_pair(dir.path(), &single());
    // Measured: filtered 53.9 m, smoothed 27.5 m, ratio 0.510. Bound: 0.51 ± 0.1,
    // two-sided (one flight: the margin is for changes of the forward filter's round-off
    // and tuning, not for a smoother that stops helping).
    assert!((0.41..0.61).contains(&(s / f)), "{f} {s}");
}

//! `argus track --smooth` for the multi-target tracker's two-mode IMM tracks
//! (`estimator.kind = "imm"` under `[tracker]`): the real binary on a small scene of
//! Cartesian reports, checked against the single-target `imm` smoother of the same plots
//! and against a reference built here from `argus_imm` alone.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::Path;

use argus_core_math::{Matrix, Vector};
use argus_filters::{Kf, two_point_cv2};
use argus_imm::{Imm, ImmEstimate, ImmTrack, MarkovMatrix};
use argus_motion_models::Cv2D;
use argus_sensors::CartesianPosition;

mod common;
use common::smoothed_track::{
    compare_smoothed, long_lag_is_interval, relative_difference, the_track,
};
use common::{num, rows, track};

/// The IMM's parameters, the same in every configuration below.
const SIGMA_LOW: f64 = 0.5;
const SIGMA_HIGH: f64 = 8.0;
const P_STAY: f64 = 0.95;
/// The reports' noise: `r_xx = r_yy = 400 m²`, `r_xy = 30 m²`.
const R: [f64; 3] = [400.0, 30.0, 400.0];

// The multi-IMM's tracks are smoothed too: tests/smooth_multi_imm_tracks.rs.
const SENSOR: &str = "[[sensor]]\nid = 1\nposition = [0.0, 0.0]\n\n";

fn estimator() -> String {
    format!(
        "[estimator]\nkind = \"imm\"\nmodels = [{{ kind = \"cv\", sigma_a = {SIGMA_LOW} }}, {{ kind = \"cv\", sigma_a = {SIGMA_HIGH} }}]\nmarkov = [[{P_STAY}, {q}], [{q}, {P_STAY}]]\n",
        q = 1.0 - P_STAY
    )
}

fn tracker(association: &str) -> String {
    format!(
        "{SENSOR}{}\n[tracker]\n{association}confirm_m = 3\nconfirm_n = 4\nmax_misses = 3\ngate_probability = 0.99\nmax_speed = 350.0\n",
        estimator()
    )
}

/// One target: 100 m/s east, then a 3g-ish turn north from t = 30 s; scans every 2 s
/// (irregular at the end), deterministic offsets of ±25 m (no random numbers: the test
/// compares two computations of one value). `(t, x, y)` per plot.
fn target() -> Vec<(f64, f64, f64)> {
    let times: Vec<f64> = (0..30)
        .map(|k| 2.0 * f64::from(k))
        .chain([61.0, 64.5, 66.0])
        .collect();
    times
        .iter()
        .enumerate()
        .map(|(k, &t)| {
            let (mut x, mut y) = (10_000.0 + 100.0 * t.min(30.0), 5_000.0);
            if t > 30.0 {
                // A turn of 0.05 rad/s at 100 m/s (radius 2 km).
                let a = 0.05 * (t - 30.0);
                x += 2_000.0 * a.sin();
                y += 2_000.0 * (1.0 - a.cos());
            }
            let off = [25.0, -15.0, 5.0, -25.0, 10.0][k % 5];
            (t, x + off, y - 0.6 * off)
        })
        .collect()
}

fn plot_line(t: f64, x: f64, y: f64) -> String {
    format!("{t},1,{x},{y},{},{},{}\n", R[0], R[1], R[2])
}

/// Writes the plots; `miss_at`: the scan whose target plot is replaced by a plot 150 km
/// away (the track misses it; the far plot never pairs into a track).
fn write_plots(path: &Path, miss_at: Option<usize>) -> Vec<(f64, Option<Vector<2>>)> {
    let mut text = "t,sensor,x,y,r_xx,r_xy,r_yy\n".to_owned();
    let mut scans = Vec::new();
    for (k, (t, x, y)) in target().into_iter().enumerate() {
        if Some(k) == miss_at {
            text.push_str(&plot_line(t, 150_000.0, -150_000.0));
            scans.push((t, None));
        } else {
            text.push_str(&plot_line(t, x, y));
            scans.push((t, Some(Vector::<2>::new(x, y))));
        }
    }
    std::fs::write(path, text).unwrap();
    scans
}

/// |a − b| ≤ tol · max(1, |b|).
fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * b.abs().max(1.0)
}

/// The smoothed columns the two outputs share.
const SMOOTHED: [&str; 8] = [
    "xs", "vxs", "ys", "vys", "sigma_xs", "sigma_ys", "mu_1s", "mu_2s",
];

#[test]
fn a_gnn_imm_track_smooths_as_the_single_target_imm_of_its_plots() {
    let dir = tempfile::tempdir().unwrap();
    let plots = dir.path().join("p.csv");
    write_plots(&plots, None);
    let (code, err, multi) = track(dir.path(), &tracker(""), &plots, &["--smooth"]);
    assert_eq!(code, Some(0), "{err}");
    let (code, err, single) = track(
        dir.path(),
        &format!("{SENSOR}{}", estimator()),
        &plots,
        &["--smooth"],
    );
    assert_eq!(code, Some(0), "{err}");
    let (multi, single) = (the_track(&multi), rows(&single));
    // Both start at the second plot (two-point differencing) and take every later plot.
    assert_eq!(multi.len(), single.len());
    assert_eq!(multi.len(), target().len() - 1);
    let mut worst = 0.0_f64;
    compare_smoothed(&multi, &single, &["x", "vy"], 2, |m, a, b| {
        // 1e-9 relative: two evaluations of the same arithmetic (the tracker's IMM and
        // the single-target one), printed at full precision.
        assert!(close(a, b, 1e-9), "t = {}: {a} against {b}", m["t"]);
        worst = worst.max(relative_difference(a, b));
    });
    // Both sides can fail: the smoothed track is not the filtered one (the turn).
    let moved = multi
        .iter()
        .map(|r| (num(r, "xs") - num(r, "x")).abs())
        .fold(0.0, f64::max);
    assert!(moved > 1.0, "smoothing moved x by at most {moved} m");
    assert!(worst <= 1e-9);
}

/// The reference of a track with a miss: `argus_imm`'s own forward pass
/// ([`ImmTrack::step`], the prediction for the miss) from the two-point start, smoothed.
fn reference(scans: &[(f64, Option<Vector<2>>)]) -> Vec<argus_imm::ImmSmoothed<4, 2>> {
    let imm = Imm::new(
        [
            Kf::new(Cv2D::discrete(SIGMA_LOW).unwrap()),
            Kf::new(Cv2D::discrete(SIGMA_HIGH).unwrap()),
        ],
        MarkovMatrix::new([[P_STAY, 1.0 - P_STAY], [1.0 - P_STAY, P_STAY]]).unwrap(),
    )
    .unwrap();
    let r = Matrix::<2, 2>::new(R[0], R[1], R[1], R[2]);
    let meas = CartesianPosition::<4, 2>::cv(r).unwrap();
    let (t0, z0) = (scans[0].0, scans[0].1.unwrap());
    let (t1, z1) = (scans[1].0, scans[1].1.unwrap());
    let start = two_point_cv2(&z0, &r, &z1, &r, t1 - t0).unwrap();
    let mut tr = ImmTrack::new(
        *imm.markov(),
        t1,
        ImmEstimate::from_common(start, [0.5, 0.5]).unwrap(),
    )
    .unwrap();
    let mut t = t1;
    for (tn, z) in &scans[2..] {
        match z {
            Some(z) => {
                tr.step(&imm, *tn, &meas, z).unwrap();
            }
            None => {
                let p = imm.predict(tr.latest(), tn - t).unwrap();
                tr.push(&imm, *tn, p.into_estimate()).unwrap();
            }
        }
        t = *tn;
    }
    tr.smooth().unwrap()
}

#[test]
fn a_missed_scan_is_smoothed_as_the_imm_prediction_it_is() {
    let dir = tempfile::tempdir().unwrap();
    let plots = dir.path().join("p.csv");
    let scans = write_plots(&plots, Some(20));
    let (code, err, csv) = track(dir.path(), &tracker(""), &plots, &["--smooth"]);
    assert_eq!(code, Some(0), "{err}");
    let rows = the_track(&csv);
    let want = reference(&scans);
    assert_eq!(rows.len(), want.len());
    for (r, w) in rows.iter().zip(&want) {
        let g = &w.combined;
        let expect = [
            g.mean()[0],
            g.mean()[1],
            g.mean()[2],
            g.mean()[3],
            g.cov()[(0, 0)].sqrt(),
            g.cov()[(2, 2)].sqrt(),
            w.mode_probabilities[0],
            w.mode_probabilities[1],
        ];
        for (k, e) in SMOOTHED.iter().zip(expect) {
            // 1e-9 relative: the same recursion evaluated by the tracker + CLI record
            // and by `ImmTrack::step` here.
            assert!(
                close(num(r, k), e, 1e-9),
                "t = {}: {k} {} against {e}",
                r["t"],
                r[*k]
            );
        }
    }
    // The missed scan's row: coasted (the far plot started nothing confirmed).
    let miss = &rows[19];
    assert_eq!(num(miss, "t").to_bits(), scans[20].0.to_bits());
}

#[test]
fn imm_jpda_tracks_smooth_and_shrink_their_sigmas() {
    let dir = tempfile::tempdir().unwrap();
    let plots = dir.path().join("p.csv");
    write_plots(&plots, Some(20));
    let config = tracker("association = \"jpda\"\np_detection = 0.9\nclutter_density = 1e-10\n");
    let (code, err, csv) = track(dir.path(), &config, &plots, &["--smooth"]);
    assert_eq!(code, Some(0), "{err}");
    let rows = the_track(&csv);
    assert!(!rows.is_empty());
    for r in &rows {
        for (s, f) in [("sigma_xs", "sigma_x"), ("sigma_ys", "sigma_y")] {
            // The smoothed σ is at most the filtered one (round-off margin 1e-9).
            assert!(
                num(r, s) <= num(r, f) * (1.0 + 1e-9),
                "t = {}: {s} > {f}",
                r["t"]
            );
        }
        assert!(close(num(r, "mu_1s") + num(r, "mu_2s"), 1.0, 1e-12));
    }
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("t.summary.json")).unwrap())
            .unwrap();
    assert_eq!(summary["smoothed_tracks"], 1);
}

#[test]
fn a_fixed_lag_as_long_as_the_track_is_the_fixed_interval_smoother() {
    let dir = tempfile::tempdir().unwrap();
    let plots = dir.path().join("p.csv");
    write_plots(&plots, Some(20));
    let interval = long_lag_is_interval(dir.path(), &tracker(""), &plots, "100");
    let (_, _, lag2) = track(dir.path(), &tracker(""), &plots, &["--smooth-lag", "2"]);
    assert_ne!(interval, lag2);
}

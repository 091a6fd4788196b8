//! `argus track --smooth` / `--smooth-lag N` / `--smooth-lag-seconds S`, and the
//! `[reference]` point's `lat, lon` columns: the real binary on plot files of
//! `argus simulate cv-polar` (fixed seeds) and on docs/examples.

// Test helpers outside #[test] functions may unwrap: a failure is a test failure.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use argus_geo::{Geodetic, LocalFrame};

mod common;
use common::{argus, num, rows, track};

/// A single-target configuration of one polar radar at the origin (cv-polar's σ: 50 m,
/// 0.1°).
const KF: &str = "[[sensor]]\nid = 1\nposition = [0.0, 0.0]\nsigma_range = 50.0\nsigma_azimuth_deg = 0.1\n\n[estimator]\nkind = \"kf-converted\"\nsigma_a = 0.5\n";

/// `argus simulate cv-polar --seed 11 --run <run>` into `dir`: the plots' path.
fn simulate(dir: &Path, run: u32) -> PathBuf {
    let plots = dir.join(format!("p{run}.csv"));
    let o = argus(
        &[
            "simulate",
            "cv-polar",
            "--seed",
            "11",
            "--run",
            &run.to_string(),
            "--out",
            plots.to_str().unwrap(),
        ],
        dir,
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    plots
}

/// The truth `(x, y)` by time.
fn truth(plots: &Path) -> BTreeMap<u64, (f64, f64)> {
    let text = std::fs::read_to_string(plots.with_extension("truth.csv")).unwrap();
    rows(&text)
        .iter()
        .map(|r| (num(r, "t").to_bits(), (num(r, "x"), num(r, "y"))))
        .collect()
}

#[test]
fn smoothing_beats_the_filter_and_shrinks_every_variance() {
    let dir = tempfile::tempdir().unwrap();
    let (mut se_f, mut se_s, mut tr_f, mut tr_s) = (0.0, 0.0, 0.0, 0.0);
    for run in 0..4 {
        let plots = simulate(dir.path(), run);
        let (code, err, plain) = track(dir.path(), KF, &plots, &[]);
        assert_eq!(code, Some(0), "{err}");
        let (code, err, csv) = track(dir.path(), KF, &plots, &["--smooth"]);
        assert_eq!(code, Some(0), "{err}");
        let truth = truth(&plots);
        let (plain, smooth) = (rows(&plain), rows(&csv));
        assert_eq!(plain.len(), smooth.len());
        let (mut f_run, mut s_run) = (0.0, 0.0);
        for (p, r) in plain.iter().zip(&smooth) {
            // The filtered columns are the run's without --smooth, to the bit.
            for (k, v) in p {
                assert_eq!(&r[k], v, "column {k} changed by --smooth");
            }
            let (x, y) = truth[&num(r, "t").to_bits()];
            f_run += (num(r, "x") - x).powi(2) + (num(r, "y") - y).powi(2);
            s_run += (num(r, "xs") - x).powi(2) + (num(r, "ys") - y).powi(2);
            tr_f += num(r, "var_x") + num(r, "var_y");
            tr_s += num(r, "var_xs") + num(r, "var_ys");
            // Smoothed ≤ filtered: every diagonal entry (the written part of
            // P − Pˢ ⪰ 0; the eigenvalues of the whole difference are checked on the
            // full matrices in the unit tests of src/track/smooth.rs). Tolerance:
            // 1e-9 relative, round-off of the backward pass.
            for c in ["x", "vx", "y", "vy"] {
                let (v, vs) = (num(r, &format!("var_{c}")), num(r, &format!("var_{c}s")));
                assert!(
                    vs <= v * (1.0 + 1e-9),
                    "t = {}: var_{c}s {vs} > {v}",
                    r["t"]
                );
            }
        }
        // Seeded: every run's smoothed error is below its filtered error (measured
        // ratios of squared errors 0.16–0.31 at seed 11, RMS 14–27 m against 34–49 m).
        assert!(
            s_run < f_run,
            "run {run}: smoothed {s_run} ≥ filtered {f_run}"
        );
        se_f += f_run;
        se_s += s_run;
    }
    // Derived: the expected ratio of squared position errors is the ratio of the
    // covariances' position traces (each estimator consistent: the filter's ANEES on
    // cv-polar, and the smoother's in the library test, sit inside their bands). The
    // pooled measured ratio over 4 runs of 100 strongly correlated rows scatters
    // around it; a factor 2 covers that scatter (measured: 0.234 against 0.268 expected).
    let measured = se_s / se_f;
    let expected = tr_s / tr_f;
    assert!(
        measured < 2.0 * expected && measured < 0.6,
        "smoothed / filtered squared position error {measured:.3}, expected {expected:.3}"
    );
}

#[test]
fn the_ekf_smooths_polar_plots() {
    let dir = tempfile::tempdir().unwrap();
    let plots = simulate(dir.path(), 2);
    let ekf = KF.replace("kf-converted", "ekf");
    let (code, err, csv) = track(dir.path(), &ekf, &plots, &["--smooth"]);
    assert_eq!(code, Some(0), "{err}");
    let truth = truth(&plots);
    let (mut f, mut s) = (0.0, 0.0);
    for r in rows(&csv) {
        let (x, y) = truth[&num(&r, "t").to_bits()];
        f += (num(&r, "x") - x).powi(2) + (num(&r, "y") - y).powi(2);
        s += (num(&r, "xs") - x).powi(2) + (num(&r, "ys") - y).powi(2);
        assert!(num(&r, "var_ys") <= num(&r, "var_y") * (1.0 + 1e-9));
    }
    // Seeded (seed 11 run 2): the extended RTS gains as the RTS does (measured ratio of
    // squared errors 0.20; the RTS runs above measured 0.16–0.31).
    assert!(s < 0.6 * f, "smoothed {s} against filtered {f}");
}

/// The smoothed columns of a CSV, by row.
fn smoothed(csv: &str) -> Vec<Vec<f64>> {
    let keys = [
        "xs", "vxs", "ys", "vys", "var_xs", "var_vxs", "var_ys", "var_vys",
    ];
    rows(csv)
        .iter()
        .map(|r| keys.iter().map(|k| num(r, k)).collect())
        .collect()
}

/// The largest relative difference of two tables.
fn max_rel(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .flatten()
        .zip(b.iter().flatten())
        .map(|(x, y)| (x - y).abs() / x.abs().max(y.abs()).max(1e-300))
        .fold(0.0, f64::max)
}

#[test]
fn a_lag_as_long_as_the_track_is_the_fixed_interval_smoother() {
    let dir = tempfile::tempdir().unwrap();
    let plots = simulate(dir.path(), 0);
    let (_, err, interval) = track(dir.path(), KF, &plots, &["--smooth"]);
    let interval = smoothed(&interval);
    assert!(!interval.is_empty(), "{err}");
    // 100 rows: lags of 100 and 1000 steps, and 1000 s (the track lasts 198 s).
    for flags in [
        ["--smooth-lag", "100"],
        ["--smooth-lag", "1000"],
        ["--smooth-lag-seconds", "1000"],
    ] {
        let (code, err, csv) = track(dir.path(), KF, &plots, &flags);
        assert_eq!(code, Some(0), "{err}");
        // Tolerance 1e-9 relative (issue 19): the same backward steps, in windows.
        let d = max_rel(&interval, &smoothed(&csv));
        assert!(d <= 1e-9, "{flags:?}: differs from --smooth by {d:e}");
    }
    // A short lag is not the fixed-interval smoother (the early rows miss most plots),
    // and its last row, smoothed with nothing after it, is the filter's.
    let (_, _, lag3) = track(dir.path(), KF, &plots, &["--smooth-lag", "3"]);
    let lag3_rows = rows(&lag3);
    assert!(max_rel(&interval, &smoothed(&lag3)) > 1e-3);
    let last = lag3_rows.last().unwrap();
    assert_eq!(last["x"], last["xs"]);
    assert_eq!(last["var_vy"], last["var_vys"]);
}

#[test]
fn bad_smoothing_flags_are_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let plots = simulate(dir.path(), 0);
    let cases: [(&[&str], &str); 5] = [
        (&["--smooth-lag", "0"], "--smooth-lag"),
        (&["--smooth", "--smooth-lag", "3"], "cannot be used with"),
        (
            &["--smooth-lag", "3", "--smooth-lag-seconds", "5"],
            "cannot be used with",
        ),
        (&["--smooth-lag-seconds", "-1"], "positive"),
        (&["--smooth-lag-seconds", "inf"], "positive"),
    ];
    for (flags, msg) in cases {
        let (code, err, csv) = track(dir.path(), KF, &plots, flags);
        assert_eq!(code, Some(2), "{flags:?}");
        assert!(err.contains(msg), "{flags:?}: {err}");
        assert!(csv.is_empty(), "{flags:?} wrote a file");
    }
    // Every 2-D kind smooths (the multi-IMM: tests/smooth_multi_imm_tracks.rs).
}

#[test]
fn the_imm_smooths_with_mode_probabilities() {
    let dir = tempfile::tempdir().unwrap();
    let plots = simulate(dir.path(), 0);
    let imm = |models: &str, markov: &str| {
        KF.replace(
            "kind = \"kf-converted\"\nsigma_a = 0.5\n",
            &format!("kind = \"imm\"\nmodels = {models}\nmarkov = {markov}\n"),
        )
    };
    // One CV mode: argus_imm's smoother of the recorded IMM is the RTS smoother of the
    // same KF (tolerance 1e-9 relative: round-off of the mode mixtures of weight 1).
    let one = imm("[{ kind = \"cv\", sigma_a = 0.5 }]", "[[1.0]]");
    let (code, err, csv) = track(dir.path(), &one, &plots, &["--smooth"]);
    assert_eq!(code, Some(0), "{err}");
    let (_, _, kf) = track(dir.path(), KF, &plots, &["--smooth"]);
    let d = max_rel(&smoothed(&kf), &smoothed(&csv));
    assert!(d <= 1e-9, "one-mode IMM smoother against the RTS: {d:e}");
    for r in rows(&csv) {
        assert!((num(&r, "mu_1s") - 1.0).abs() < 1e-12);
    }
    // Two modes: smoothed mode probabilities in every row, summing to one (1e-12: the
    // log-sum-exp normalisation). Their accuracy is the library's (docs/smoothing.md).
    let two = imm(
        "[{ kind = \"cv\", sigma_a = 0.1 }, { kind = \"cv\", sigma_a = 3.0 }]",
        "[[0.95, 0.05], [0.05, 0.95]]",
    );
    let (code, err, csv) = track(dir.path(), &two, &plots, &["--smooth-lag", "5"]);
    assert_eq!(code, Some(0), "{err}");
    for r in rows(&csv) {
        let mu = num(&r, "mu_1s") + num(&r, "mu_2s");
        assert!((mu - 1.0).abs() < 1e-12, "{mu}");
        assert!(num(&r, "var_xs").is_finite());
    }
}

/// docs/examples, from the crate directory.
fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../docs/examples")
        .join(name)
}

#[test]
fn the_tracker_smooths_each_confirmed_track_over_its_life() {
    let dir = tempfile::tempdir().unwrap();
    let config = std::fs::read_to_string(example("tracker.toml")).unwrap();
    let plots = example("two-targets.csv");
    let (code, err, plain) = track(dir.path(), &config, &plots, &[]);
    assert_eq!(code, Some(0), "{err}");
    let (code, err, csv) = track(dir.path(), &config, &plots, &["--smooth"]);
    assert_eq!(code, Some(0), "{err}");
    let (plain, smooth) = (rows(&plain), rows(&csv));
    assert_eq!(plain.len(), smooth.len());
    let confirmed: std::collections::BTreeSet<&str> = smooth
        .iter()
        .filter(|r| r["status"] == "confirmed")
        .map(|r| r["track"].as_str())
        .collect();
    assert!(!confirmed.is_empty());
    let keys = ["xs", "vxs", "ys", "vys", "sigma_xs", "sigma_ys"];
    for (p, r) in plain.iter().zip(&smooth) {
        for (k, v) in p {
            assert_eq!(&r[k], v, "column {k} changed by --smooth");
        }
        let want = confirmed.contains(r["track"].as_str()) && r["status"] != "deleted";
        for k in keys {
            assert_eq!(
                !r[k].is_empty(),
                want,
                "track {} {}: {k}",
                r["track"],
                r["status"]
            );
        }
        if want {
            for (s, f) in [("sigma_xs", "sigma_x"), ("sigma_ys", "sigma_y")] {
                assert!(num(r, s) <= num(r, f) * (1.0 + 1e-9), "{s} > {f}");
            }
        }
    }
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("t.summary.json")).unwrap())
            .unwrap();
    assert_eq!(summary["smoothing"], "fixed-interval");
    assert_eq!(summary["smoothed_tracks"], confirmed.len());
    // The tracker's IMM tracks smooth too (tests/smooth_imm_tracks.rs), with their
    // smoothed mode probabilities.
    let imm = config.replace(
        "kind = \"kf-converted\"      # or \"ekf\", \"imm\", \"multi-imm\" (see docs/FORMATS.md)\nsigma_a = 2.0              # m/s²\n",
        "kind = \"imm\"\nmodels = [{ kind = \"cv\", sigma_a = 0.5 }, { kind = \"cv\", sigma_a = 5.0 }]\nmarkov = [[0.9, 0.1], [0.1, 0.9]]\n",
    );
    assert_ne!(imm, config);
    let (code, err, csv) = track(dir.path(), &imm, &plots, &["--smooth-lag", "2"]);
    assert_eq!(code, Some(0), "{err}");
    let imm_rows = rows(&csv);
    assert!(imm_rows.iter().any(|r| !r["mu_1s"].is_empty()));
    // The multi-IMM is refused: tests/smooth_imm_tracks.rs.
}

#[test]
fn lat_lon_of_a_track_row_round_trips_to_its_x_y() {
    let dir = tempfile::tempdir().unwrap();
    let plots = simulate(dir.path(), 1);
    // The reference at Paris CDG (issue 18), 120 m above the ellipsoid; the radar on it.
    let head = "[reference]\nlatitude = 49.0097\nlongitude = 2.5479\naltitude = 120.0\n\n";
    let cfg = format!(
        "{head}{}",
        KF.replace(
            "position = [0.0, 0.0]",
            "latitude = 49.0097\nlongitude = 2.5479\naltitude = 120.0"
        )
    );
    let (code, err, csv) = track(dir.path(), &cfg, &plots, &[]);
    assert_eq!(code, Some(0), "{err}");
    let frame = LocalFrame::wgs84(Geodetic::from_degrees(49.0097, 2.5479, 120.0).unwrap());
    let located = rows(&csv);
    assert!(located.len() > 50);
    for r in &located {
        // lat, lon at the reference's altitude, back through the closed-form forward
        // map: east, north within 1 mm of x, y (issue 18; the iteration stops at a
        // height error of 1 µm).
        let g = Geodetic::from_degrees(num(r, "lat"), num(r, "lon"), 120.0).unwrap();
        let enu = frame.geodetic_to_enu(&g);
        let d = (enu.east - num(r, "x")).hypot(enu.north - num(r, "y"));
        assert!(d < 1e-3, "t = {}: {d} m", r["t"]);
    }
    // The same radar given by position = [0, 0]: the same track to the bit (a site at
    // the reference point is at ENU (0, 0, 0) to round-off of the ECEF difference, and
    // the tracker ignores z in 2-D).
    let (_, _, plain) = track(dir.path(), KF, &plots, &[]);
    for (a, b) in rows(&plain).iter().zip(&located) {
        let d = (num(a, "x") - num(b, "x")).abs();
        assert!(d < 1e-6, "x differs by {d}");
    }
    // position and latitude together: an error naming the line.
    let both = cfg.replace(
        "latitude = 49.0097\nlongitude = 2.5479\naltitude = 120.0\nsigma",
        "position = [0.0, 0.0]\nlatitude = 49.0097\nlongitude = 2.5479\nsigma",
    );
    assert_ne!(both, cfg);
    let (code, err, _) = track(dir.path(), &both, &plots, &[]);
    assert_eq!(code, Some(2));
    assert!(
        err.contains("c.toml:8") && err.contains("not both"),
        "{err}"
    );
}

#[test]
fn smoothed_normalised_errors_sit_in_their_chi_square_band() {
    // cv-polar's target moves at constant velocity: the KF with σa = 0 is the exact model
    // (as the library's smoothed-NEES test, crates/filters/tests/smoothing.rs). The CSV
    // holds the covariance's diagonal, so each position axis is checked on its own:
    // (xs − x)² / var_xs ~ χ²(1), averaged over the runs per row.
    const RUNS: u32 = 30;
    let dir = tempfile::tempdir().unwrap();
    let kf0 = KF.replace("sigma_a = 0.5", "sigma_a = 0.0");
    let mut sums: Vec<[f64; 4]> = Vec::new();
    for run in 0..RUNS {
        let plots = simulate(dir.path(), run);
        let (code, err, csv) = track(dir.path(), &kf0, &plots, &["--smooth"]);
        assert_eq!(code, Some(0), "{err}");
        let truth = truth(&plots);
        let rows = rows(&csv);
        sums.resize(rows.len(), [0.0; 4]);
        for (r, s) in rows.iter().zip(sums.iter_mut()) {
            let (x, y) = truth[&num(r, "t").to_bits()];
            s[0] += (num(r, "xs") - x).powi(2) / num(r, "var_xs");
            s[1] += (num(r, "ys") - y).powi(2) / num(r, "var_ys");
            s[2] += (num(r, "x") - x).powi(2) / num(r, "var_x");
            s[3] += (num(r, "y") - y).powi(2) / num(r, "var_y");
        }
    }
    let n = f64::from(RUNS);
    // Per row: the two-sided 99 % interval of χ²(RUNS) / RUNS (Bar-Shalom, Li &
    // Kirubarajan 2001 §5.4.2).
    let band = argus_core_math::anees_interval(1, RUNS as usize, 0.99).unwrap();
    let inside = |i: usize| {
        sums.iter().filter(|s| band.contains(s[i] / n)).count() as f64 / sums.len() as f64
    };
    let mean = |i: usize| sums.iter().map(|s| s[i] / n).sum::<f64>() / sums.len() as f64;
    for (i, what) in [(0, "xs"), (1, "ys"), (2, "x"), (3, "y")] {
        // A consistent estimator has 99 % of the rows inside; the rows of one run are
        // correlated (an excursion lasts several rows), so ≥ 90 % is asked, and the
        // mean over the rows within the band of one row's average (measured, band
        // [0.46, 1.79]: smoothed xs / ys 100 % / 100 % inside, means 1.06 / 0.79;
        // filtered x / y 100 % / 100 %, 1.07 / 1.07).
        assert!(
            inside(i) >= 0.9,
            "{what}: {:.0} % inside",
            100.0 * inside(i)
        );
        assert!(band.contains(mean(i)), "{what}: mean {}", mean(i));
    }
}

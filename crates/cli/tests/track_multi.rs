//! `argus track --config` with a `[tracker]` table: the multi-target tracker over a plot
//! file, driving the real binary on plot files written here (fixed seeds or literally).

// Test helpers outside #[test] functions may unwrap: a failure is a test failure.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::collections::BTreeSet;
use std::path::Path;

use rand::{RngExt as _, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal, Poisson};

mod common;
use common::tracker_run::{self, Run, assert_config_error};
use common::{Row, argus, num, rows as parse_rows};

/// Runs `argus track --config multi.toml --plots plots.csv --out tracks.csv` in `dir`.
fn track(dir: &Path, config: &str, plots: &str) -> Run {
    tracker_run::run(dir, "multi.toml", config, plots)
}

/// A polar radar at the origin, σr = 50 m, σθ = 0.06° (≈ 1 mrad), and the tables given.
fn config(estimator: &str, tracker: &str) -> String {
    format!(
        "[[sensor]]\nid = 1\nposition = [0.0, 0.0]\nsigma_range = 50.0\nsigma_azimuth_deg = 0.06\n\n[estimator]\n{estimator}\n[tracker]\n{tracker}"
    )
}

const KF: &str = "kind = \"kf-converted\"\nsigma_a = 2.0\n";
const EKF: &str = "kind = \"ekf\"\nsigma_a = 2.0\n";
const IMM: &str = "kind = \"imm\"\nmodels = [{ kind = \"cv\", sigma_a = 0.5 }, { kind = \"cv\", sigma_a = 10.0 }]\nmarkov = [[0.95, 0.05], [0.05, 0.95]]\n";

/// Two constant-velocity targets (position at t = 0, velocity), well apart.
const TARGETS: [([f64; 2], [f64; 2]); 2] = [
    ([30_000.0, 10_000.0], [-200.0, 0.0]),
    ([20_000.0, -15_000.0], [0.0, 150.0]),
];
const SCANS: u32 = 20;
const PERIOD: f64 = 5.0;

fn truth(k: usize, t: f64) -> [f64; 2] {
    let (p, v) = TARGETS[k];
    [p[0] + v[0] * t, p[1] + v[1] * t]
}

/// Polar plots of both targets every 5 s (P_D = 1, no clutter), noise drawn with a fixed
/// seed at the configured σ.
fn two_target_plots(seed: u64) -> String {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (nr, na) = (
        Normal::new(0.0, 50.0).unwrap(),
        Normal::new(0.0, 0.06_f64.to_radians()).unwrap(),
    );
    let mut s = String::from("t,sensor,range,azimuth\n");
    for i in 0..SCANS {
        let t = PERIOD * f64::from(i);
        for k in 0..2 {
            let [x, y] = truth(k, t);
            let r = x.hypot(y) + nr.sample(&mut rng);
            let a = y.atan2(x) + na.sample(&mut rng);
            s.push_str(&format!("{t},1,{r},{a}\n"));
        }
    }
    s
}

/// Checks a run over [`two_target_plots`]: two tracks, never more; both confirmed at the
/// third scan (M-of-N 3/4: the two initiating plots and the third are three hits); at the
/// last scan each within 3σ of its target per axis, σ being the track's own standard
/// deviation in the file (a consistent filter's error is N(0, σ²) per axis, outside 3σ with
/// probability 0.27 %).
fn check_two_tracks(run: &Run) {
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    let rows = parse_rows(&run.csv);
    let ids: BTreeSet<&str> = rows.iter().map(|r| r["track"].as_str()).collect();
    assert_eq!(ids.len(), 2, "track ids {ids:?}");
    for id in &ids {
        let mine: Vec<&Row> = rows.iter().filter(|r| r["track"] == *id).collect();
        let first_confirmed = mine.iter().find(|r| r["status"] == "confirmed").unwrap();
        assert!((num(first_confirmed, "t") - 2.0 * PERIOD).abs() < 1e-9);
        let last = mine.last().unwrap();
        assert_eq!(last["status"], "confirmed");
        let t_end = PERIOD * f64::from(SCANS - 1);
        assert!((num(last, "t") - t_end).abs() < 1e-9);
        // The target it follows: the nearer truth.
        let (x, y) = (num(last, "x"), num(last, "y"));
        let k = (0..2)
            .min_by(|&a, &b| {
                let d = |k| {
                    let p = truth(k, t_end);
                    (p[0] - x).hypot(p[1] - y)
                };
                d(a).total_cmp(&d(b))
            })
            .unwrap();
        let p = truth(k, t_end);
        let (sx, sy) = (num(last, "sigma_x"), num(last, "sigma_y"));
        assert!(
            (x - p[0]).abs() <= 3.0 * sx && (y - p[1]).abs() <= 3.0 * sy,
            "track {id}: error ({}, {}) m, 3σ ({}, {}) m",
            x - p[0],
            y - p[1],
            3.0 * sx,
            3.0 * sy
        );
    }
    // The two tracks follow different targets.
    let last_xy: Vec<(f64, f64)> = rows
        .iter()
        .rev()
        .take(2)
        .map(|r| (num(r, "x"), num(r, "y")))
        .collect();
    assert!((last_xy[0].0 - last_xy[1].0).hypot(last_xy[0].1 - last_xy[1].1) > 10_000.0);
    let tr = &run.summary["tracks"];
    assert_eq!(tr["initiated"], 2);
    assert_eq!(tr["confirmed"], 2);
    assert_eq!(tr["deleted"], 0);
    assert_eq!(tr["confirmed_at_end"], 2);
    assert_eq!(run.summary["scans"], SCANS);
    // Every plot after the two initiating scans went to a track.
    assert_eq!(run.summary["plots_assigned"], 2 * (SCANS - 2));
}

#[test]
fn two_targets_give_two_confirmed_tracks_near_the_truth() {
    let dir = tempfile::tempdir().unwrap();
    let run = track(dir.path(), &config(KF, ""), &two_target_plots(11));
    check_two_tracks(&run);
    let rows = parse_rows(&run.csv);
    assert!(
        run.csv
            .starts_with("t,sensor,track,status,reason,x,vx,y,vy,sigma_x,sigma_y\n")
    );
    // One row per track per scan from its initiation (the second scan): 2 × 19.
    assert_eq!(rows.len(), 2 * (SCANS as usize - 1));
    assert_eq!(run.summary["association"], "gnn");
    assert_eq!(run.summary["confirmation"], "m-of-n 3/4");
}

#[test]
fn jpda_ekf_imm_and_multi_imm_variants_track_both_targets() {
    let dir = tempfile::tempdir().unwrap();
    let plots = two_target_plots(12);
    let jpda = "association = \"jpda\"\np_detection = 0.9\nclutter_density = 1e-9\nmax_exact_events = 100\n";
    let run = track(dir.path(), &config(KF, jpda), &plots);
    check_two_tracks(&run);
    assert_eq!(run.summary["association"], "jpda");

    let run = track(dir.path(), &config(IMM, ""), &plots);
    check_two_tracks(&run);
    assert!(
        run.csv
            .starts_with("t,sensor,track,status,reason,x,vx,y,vy,sigma_x,sigma_y,mu_1,mu_2\n")
    );
    for r in parse_rows(&run.csv) {
        let s = num(&r, "mu_1") + num(&r, "mu_2");
        assert!((s - 1.0).abs() < 1e-9, "mode probabilities sum to {s}");
    }

    // IMM-JPDA.
    let run = track(dir.path(), &config(IMM, jpda), &plots);
    check_two_tracks(&run);

    let run = track(dir.path(), &config(EKF, ""), &plots);
    check_two_tracks(&run);
    let run = track(dir.path(), &config(EKF, jpda), &plots);
    check_two_tracks(&run);

    // Track-score (SPRT) management: the score column, both targets confirmed, nothing
    // deleted.
    let score = "[tracker.score]\np_detection = 0.9\nclutter_density = 1e-9\nnew_target_density = 1e-10\nfalse_confirm = 1e-3\nmissed_confirm = 0.1\ndelete_drop = 8.0\n";
    let run = track(dir.path(), &config(KF, score), &plots);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert!(run.csv.lines().next().unwrap().ends_with(",score"));
    assert_eq!(run.summary["confirmation"], "score");
    assert_eq!(run.summary["tracks"]["confirmed_at_end"], 2);
    assert_eq!(run.summary["tracks"]["deleted"], 0);
    assert!(
        parse_rows(&run.csv)
            .iter()
            .all(|r| num(r, "score").is_finite())
    );

    // The multi-IMM: each track's noise reference starts at the sensor's configured σ
    // (50 m, 0.06°) and moves by at most the clip (5 % in variance) per plot.
    let multi = format!(
        "{}p = 0.1\nclip = 0.05\n",
        IMM.replace("\"imm\"", "\"multi-imm\"")
    );
    let run = track(dir.path(), &config(&multi, ""), &plots);
    check_two_tracks(&run);
    assert!(run.csv.starts_with(
        "t,sensor,track,status,reason,x,vx,y,vy,sigma_x,sigma_y,mu_1,mu_2,sigma_range,sigma_azimuth_deg\n"
    ));
    let rows = parse_rows(&run.csv);
    for id in ["0", "1"] {
        let mine: Vec<&Row> = rows.iter().filter(|r| r["track"] == id).collect();
        assert!((num(mine[0], "sigma_range") - 50.0).abs() < 1e-9);
        assert!((num(mine[0], "sigma_azimuth_deg") - 0.06).abs() < 1e-12);
        for w in mine.windows(2) {
            let q = (num(w[1], "sigma_range") / num(w[0], "sigma_range")).powi(2);
            assert!((0.95 - 1e-9..=1.05 + 1e-9).contains(&q), "step ratio {q}");
        }
    }
}

/// Cartesian plots, σ = 50 m per axis, from one sensor.
fn cartesian(plots: &[(f64, f64, f64)]) -> String {
    let mut s = String::from("t,sensor,x,y,r_xx,r_xy,r_yy\n");
    for (t, x, y) in plots {
        s.push_str(&format!("{t},1,{x},{y},2500,0,2500\n"));
    }
    s
}

#[test]
fn a_clutter_pair_alone_is_deleted_unconfirmed_under_3_of_4() {
    let dir = tempfile::tempdir().unwrap();
    // Two plots 500 m apart in 5 s start a tentative track (velocity gate 350 m/s × 5 s);
    // the later plots are 70 km and more away from it and from each other, so it misses
    // its 3rd and 4th opportunities: 2 hits of 4 < 3, deleted at t = 15.
    let far = [
        (10.0, 50_000.0, 50_000.0),
        (15.0, -50_000.0, 50_000.0),
        (20.0, 50_000.0, -50_000.0),
    ];
    let mut plots = vec![(0.0, 0.0, 0.0), (5.0, 500.0, 0.0)];
    plots.extend(far);
    let run = track(dir.path(), &config(KF, ""), &cartesian(&plots));
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    let rows = parse_rows(&run.csv);
    let statuses: Vec<(f64, &str, &str)> = rows
        .iter()
        .map(|r| (num(r, "t"), r["status"].as_str(), r["reason"].as_str()))
        .collect();
    assert_eq!(
        statuses,
        vec![
            (5.0, "tentative", ""),
            (10.0, "tentative", ""),
            (15.0, "deleted", "not-confirmed")
        ]
    );
    let tr = &run.summary["tracks"];
    assert_eq!(tr["confirmed"], 0);
    assert_eq!(tr["deleted_by_reason"]["not-confirmed"], 1);

    // Control: a third plot on the pair's line (1 000 m at t = 10) is its third hit and
    // confirms it at t = 10.
    plots[2] = (10.0, 1000.0, 0.0);
    let run = track(dir.path(), &config(KF, ""), &cartesian(&plots));
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    let rows = parse_rows(&run.csv);
    assert_eq!(rows[1]["status"], "confirmed");
    assert!((num(&rows[1], "t") - 10.0).abs() < 1e-9);
}

/// Clutter only: Poisson, 5 plots per scan on average, uniform over 100 km × 100 km
/// (λ = 5e-10 per m²), 60 scans 5 s apart, σ = 50 m.
///
/// Expected numbers (defaults: v_max = 350 m/s, 3σ velocity-gate allowance, initiators
/// kept 12 s, P_G = 0.99 so γ = 9.21): an unused plot meets a second plot within
/// 350·Δt + 3·√(4·2500) m after Δt = 5 s and 10 s, areas 1.3e7 and 4.5e7 m², so ≈ 5 ×
/// 5.8e7 × 5e-10 ≈ 0.15 tentative tracks per scan, ≈ 9 in the run. A tentative track's gate
/// one scan later has S ≈ (2500 + 2·5·500 + 25·200 + 625 + 2500) I ≈ 1.6e4 I m² (two-point
/// start: velocity variance 2σ²/Δt², cross term σ²/Δt), area π γ √det S ≈ 4.5e5 m²; two
/// scans later ≈ 1e6 m²: P(a third hit in its next two scans) ≈ 5e-10 × 1.5e6 ≈ 7.5e-4, so
/// ≈ 0.007 false confirmations are expected in the run. None may occur.
#[test]
fn clutter_alone_never_confirms_under_3_of_4() {
    let dir = tempfile::tempdir().unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(21);
    let count = Poisson::new(5.0).unwrap();
    let mut plots = Vec::new();
    for i in 0..60 {
        let t = PERIOD * f64::from(i);
        let n = count.sample(&mut rng) as usize;
        for _ in 0..n {
            plots.push((
                t,
                rng.random_range(0.0..100_000.0),
                rng.random_range(0.0..100_000.0),
            ));
        }
    }
    let run = track(dir.path(), &config(KF, ""), &cartesian(&plots));
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    let rows = parse_rows(&run.csv);
    assert!(rows.iter().all(|r| r["status"] != "confirmed"));
    let tr = &run.summary["tracks"];
    assert_eq!(tr["confirmed"], 0);
    // Every tentative track that ended was deleted for not being confirmed.
    let initiated = tr["initiated"].as_u64().unwrap();
    assert!(
        initiated > 0,
        "no tentative track: the test exercised nothing"
    );
    assert_eq!(
        tr["deleted_by_reason"]["not-confirmed"].as_u64().unwrap()
            + tr["tentative_at_end"].as_u64().unwrap(),
        initiated
    );
}

/// Asserts exit code 2, that stderr names `at` (file:line) and the field, and that no
/// tracks file was written.
#[test]
fn config_errors_name_file_line_and_field() {
    let dir = tempfile::tempdir().unwrap();
    let plots = two_target_plots(13);
    // Line numbers: 1–5 sensor, 7–9 estimator (KF: kind, sigma_a; IMM: kind, models,
    // markov), 11 [tracker], 12 on the tracker keys.
    let run = track(dir.path(), &config(KF, "association = \"foo\"\n"), &plots);
    assert_config_error(&run, "multi.toml:12", "tracker.association");
    let run = track(
        dir.path(),
        &config(KF, "confirm_n = 4\nconfirm_m = 5\n"),
        &plots,
    );
    assert_config_error(&run, "multi.toml:13", "tracker.confirm_m");
    // confirm_n alone below the default confirm_m = 3: the [tracker] line names the default.
    let run = track(dir.path(), &config(KF, "confirm_n = 2\n"), &plots);
    assert_config_error(&run, "multi.toml:11", "tracker.confirm_m");
    let run = track(dir.path(), &config(KF, "confirm_m = -1\n"), &plots);
    assert_config_error(&run, "multi.toml:12", "tracker.confirm_m");
    let run = track(dir.path(), &config(KF, "max_speed = \"fast\"\n"), &plots);
    assert_config_error(&run, "multi.toml:12", "tracker.max_speed");
    let run = track(dir.path(), &config(KF, "gate_probability = 1.0\n"), &plots);
    assert_config_error(&run, "multi.toml:12", "tracker.gate_probability");
    // JPDA keys under GNN are refused, not ignored; JPDA without them too.
    let run = track(dir.path(), &config(KF, "p_detection = 0.9\n"), &plots);
    assert_config_error(&run, "multi.toml:12", "tracker.p_detection");
    let run = track(
        dir.path(),
        &config(
            KF,
            "association = \"jpda\"\np_detection = 0.9\nclutter_density = -1.0\n",
        ),
        &plots,
    );
    assert_config_error(&run, "multi.toml:14", "tracker.clutter_density");
    let run = track(
        dir.path(),
        &config(
            KF,
            "\n[tracker.score]\np_detection = 0.9\nclutter_density = 1e-9\nnew_target_density = 1e-10\nfalse_confirm = 0.6\nmissed_confirm = 0.1\ndelete_drop = 5.0\n",
        ),
        &plots,
    );
    assert_config_error(&run, "multi.toml:17", "tracker.score.false_confirm");
    // The IMM the tracker runs per track: two CV modes, one stay probability.
    let three = IMM
        .replace(
            "{ kind = \"cv\", sigma_a = 10.0 }]",
            "{ kind = \"cv\", sigma_a = 10.0 }, { kind = \"ct\", sigma_a = 1.0, rate_deg = 3.0 }]",
        )
        .replace(
            "[[0.95, 0.05], [0.05, 0.95]]",
            "[[0.9, 0.05, 0.05], [0.05, 0.9, 0.05], [0.05, 0.05, 0.9]]",
        );
    let run = track(dir.path(), &config(&three, ""), &plots);
    assert_config_error(&run, "multi.toml:9", "estimator.models");
    // The multi-IMM per track has seed 000's five hypotheses on one scale, and no JPDA.
    let multi = IMM.replace("\"imm\"", "\"multi-imm\"");
    let run = track(dir.path(), &config(&format!("{multi}n = 3\n"), ""), &plots);
    assert_config_error(&run, "multi.toml:11", "estimator.n");
    let run = track(
        dir.path(),
        &config(
            &multi,
            "association = \"jpda\"\np_detection = 0.9\nclutter_density = 1e-9\n",
        ),
        &plots,
    );
    assert_config_error(&run, "multi.toml:13", "tracker.association");
    let skew = IMM.replace("[0.05, 0.95]]", "[0.1, 0.9]]");
    let run = track(dir.path(), &config(&skew, ""), &plots);
    assert_config_error(&run, "multi.toml:10", "estimator.markov");
    // A sensor σ the tracker cannot use (it needs σ > 0) names the sensor's line.
    let zero = config(KF, "").replace("sigma_range = 50.0", "sigma_range = 0.0");
    let run = track(dir.path(), &zero, &plots);
    assert_config_error(&run, "multi.toml:4", "sigma_range");
    // An unknown key in [tracker].
    let run = track(dir.path(), &config(KF, "confirm_k = 3\n"), &plots);
    assert_eq!(run.code, Some(2));
    assert!(
        run.stderr.contains("multi.toml:12") && run.stderr.contains("confirm_k"),
        "{}",
        run.stderr
    );
}

#[test]
fn out_of_order_plots_name_the_line() {
    let dir = tempfile::tempdir().unwrap();
    let plots = cartesian(&[(0.0, 0.0, 0.0), (10.0, 1000.0, 0.0), (5.0, 500.0, 0.0)]);
    let run = track(dir.path(), &config(KF, ""), &plots);
    assert_config_error(&run, "plots.csv:4", "t");
    // A plot of an unknown sensor stops the run before any track exists.
    let plots = "t,sensor,x,y,r_xx,r_xy,r_yy\n0,1,0,0,2500,0,2500\n5,7,500,0,2500,0,2500\n";
    let run = track(dir.path(), &config(KF, ""), plots);
    assert_config_error(&run, "plots.csv:3", "sensor");
    // A polar plot, in the third scan, from a sensor configured without σ: the tracker's
    // error is reported at the plot's line, and a previous tracks file stays as it was
    // (written atomically).
    let good = track(dir.path(), &config(KF, ""), &two_target_plots(14));
    assert_eq!(good.code, Some(0), "{}", good.stderr);
    let cfg = format!(
        "[[sensor]]\nid = 1\nposition = [0.0, 0.0]\nsigma_range = 50.0\nsigma_azimuth_deg = 0.06\n\n[[sensor]]\nid = 2\nposition = [0.0, 0.0]\n\n[estimator]\n{KF}\n[tracker]\n"
    );
    let plots =
        "t,sensor,range,azimuth\n0,1,10000,0.1\n5,1,10500,0.1\n10,1,11000,0.1\n10,2,11000,0.1\n";
    std::fs::write(dir.path().join("multi.toml"), &cfg).unwrap();
    std::fs::write(dir.path().join("plots.csv"), plots).unwrap();
    let o = argus(
        &[
            "track",
            "--config",
            "multi.toml",
            "--plots",
            "plots.csv",
            "--out",
            "tracks.csv",
        ],
        dir.path(),
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("plots.csv:5: field 'sensor'"), "{err}");
    assert_eq!(
        std::fs::read_to_string(dir.path().join("tracks.csv")).unwrap(),
        good.csv
    );
}

/// The example of `docs/FORMATS.md` (`docs/examples/tracker.toml` on
/// `docs/examples/two-targets.csv`: the two targets above with 2 clutter plots per scan, one
/// missed detection, 12 scans) runs as documented: both targets confirmed, and a clutter
/// track that was never confirmed ends with one `deleted` row and its reason.
#[test]
fn documented_example_runs() {
    let docs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/examples");
    let dir = tempfile::tempdir().unwrap();
    let config = std::fs::read_to_string(docs.join("tracker.toml")).unwrap();
    let plots = std::fs::read_to_string(docs.join("two-targets.csv")).unwrap();
    let run = track(dir.path(), &config, &plots);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    let tr = &run.summary["tracks"];
    assert_eq!(tr["confirmed_at_end"], 2);
    assert_eq!(tr["deleted_after_confirmation"], 0);
    let rows = parse_rows(&run.csv);
    let deleted: Vec<&Row> = rows.iter().filter(|r| r["status"] == "deleted").collect();
    assert_eq!(deleted.len(), tr["deleted"].as_u64().unwrap() as usize);
    assert!(!deleted.is_empty());
    assert!(deleted.iter().all(|r| r["reason"] == "not-confirmed"));
    // A deleted track has no row after its deletion.
    for d in &deleted {
        let later = rows
            .iter()
            .filter(|r| r["track"] == d["track"] && num(r, "t") > num(d, "t"));
        assert_eq!(later.count(), 0);
    }
}

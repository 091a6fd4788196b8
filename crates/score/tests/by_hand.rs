//! Every metric on small constructed cases, against values worked out by hand in the
//! comments. Tolerances are round-off (1e-9 on numbers of order 1–100).

#![allow(clippy::unwrap_used, missing_docs)]

use argus_score::{ScoreConfig, Scorer, read_tracks_from, read_truth_from};

const TOL: f64 = 1e-9;

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= TOL
}

fn some_close(a: Option<f64>, b: f64) -> bool {
    a.is_some_and(|a| close(a, b))
}

/// The main case. Grid 0, 10, …, 40 s (the truth's span), cut-off 100 m, GOSPA c = 100,
/// p = 1 (so c^p/2 = 50), staleness 15 s, truth gaps up to 50 s interpolated.
///
/// Truth: A moves along x at 10 m/s from (0, 0) at t = 0 to (400, 0) at t = 40 (two
/// samples, interpolated); B sits at (0, 1000) from t = 10 to t = 40.
/// Tracks:
/// - 1: tentative at 0, confirmed at 10 at (103, 4) with A's velocity, no row after:
///   predicted to (203, 4) at 20 (age 10 ≤ 15), absent at 30 (age 20 > 15);
/// - 2: confirmed at 40 at (400, 8), velocity (13, 4);
/// - 3: still at (0, 1000) at 10, (0, 1150) at 20 (150 m ≥ 100 from B: not assigned),
///   (0, 1010) at 30, deleted at 40;
/// - 4: confirmed at 0 at (5000, 5000), no row after: false at 0 and 10, gone at 20.
///
/// | t  | truths | tracks  | pairs (error m)    | GOSPA loc + missed + false |
/// |----|--------|---------|--------------------|----------------------------|
/// | 0  | A      | 4       | —                  | 0 + 50 + 50 = 100          |
/// | 10 | A, B   | 1, 3, 4 | A–1 (5), B–3 (0)   | 5 + 0 + 50 = 55            |
/// | 20 | A, B   | 1, 3    | A–1 (5)            | 5 + 50 + 50 = 105          |
/// | 30 | A, B   | 3       | B–3 (10)           | 10 + 50 + 0 = 60           |
/// | 40 | A, B   | 2       | A–2 (8, vel 5)     | 8 + 50 + 0 = 58            |
const TRUTH: &str = "\
t,target,x,vx,y,vy,z,vz
0,A,0,10,0,0,0,0
10,B,0,0,1000,0,0,0
40,A,400,10,0,0,0,0
40,B,0,0,1000,0,0,0
";

const TRACKS: &str = "\
t,sensor,track,status,reason,x,vx,y,vy,sigma_x,sigma_y
0,1,1,tentative,,0,10,0,0,1,1
0,1,4,confirmed,,5000,0,5000,0,1,1
10,1,1,confirmed,,103,10,4,0,1,1
10,1,3,confirmed,,0,0,1000,0,1,1
20,1,3,confirmed,,0,0,1150,0,1,1
30,1,3,confirmed,,0,0,1010,0,1,1
40,1,2,confirmed,,400,13,8,4,1,1
40,1,3,deleted,misses,0,0,1010,0,1,1
";

fn config() -> ScoreConfig {
    ScoreConfig {
        step: 10.0,
        assign_cutoff: 100.0,
        max_track_age: 15.0,
        max_truth_gap: 50.0,
        gospa_cutoff: 100.0,
        gospa_order: 1.0,
        ..ScoreConfig::default()
    }
}

fn score_main() -> argus_score::Score {
    let truth = read_truth_from(TRUTH.as_bytes(), "truth.csv").unwrap();
    let tracks = read_tracks_from(TRACKS.as_bytes(), "tracks.csv").unwrap();
    Scorer::new(config())
        .unwrap()
        .score(&tracks, &truth)
        .unwrap()
}

#[test]
fn counts_completeness_and_spuriousness() {
    let s = score_main().summary;
    assert_eq!(s.grid_times, 5);
    assert!(close(s.grid_start, 0.0) && close(s.grid_end, 40.0));
    assert_eq!((s.truths, s.tracks, s.tracks_on_grid), (2, 4, 4));
    // ΣJ = 1 + 2 + 2 + 2 + 2 = 9, ΣN = 1 + 3 + 2 + 1 + 1 = 8, ΣNA = 0 + 2 + 1 + 1 + 1 = 5.
    assert_eq!(
        (s.truth_points, s.track_points, s.assigned_points),
        (9, 8, 5)
    );
    assert!(some_close(s.completeness, 5.0 / 9.0));
    assert!(some_close(s.spurious_fraction, 3.0 / 8.0));
    assert!(close(s.false_tracks_per_step, 3.0 / 5.0));
    // 9 presences × 10 s = 90 s = 0.025 h.
    assert!(close(s.aircraft_hours, 0.025));
}

#[test]
fn breaks_swaps_and_time_to_confirm() {
    let s = score_main();
    let m = &s.summary;
    // Breaks: A at 20 → 30; B at 10 → 20 and at 30 → 40. Swap: A from track 1 to 2.
    assert_eq!(m.breaks, 3);
    assert!(some_close(m.breaks_per_aircraft_hour, 3.0 / 0.025));
    assert_eq!(m.id_swaps, 1);
    // A: first present 0, first assigned 10 → 10 s; B: 10 and 10 → 0 s; mean 5 s.
    assert_eq!(s.truths[0].name, "A");
    assert_eq!(s.truths[0].time_to_confirm, Some(10.0));
    assert_eq!(s.truths[1].time_to_confirm, Some(0.0));
    assert!(some_close(m.time_to_confirm_mean, 5.0));
    assert_eq!(m.truths_never_tracked, 0);
}

#[test]
fn errors_rmse_percentile_and_siap_accuracy() {
    let m = score_main().summary;
    // Position errors 5, 0, 5, 10, 8: Σe² = 214, RMSE = √(214/5); mean 28/5.
    assert!(some_close(m.position_rmse, (214.0f64 / 5.0).sqrt()));
    assert!(some_close(m.position_accuracy, 28.0 / 5.0));
    // Nearest rank: ⌈0.95 · 5⌉ = 5th of (0, 5, 5, 8, 10) = 10.
    assert!(some_close(m.position_p95, 10.0));
    // Velocity errors 0, 0, 0, 0, |(3, 4)| = 5: RMSE √(25/5) = √5, mean 1.
    assert!(some_close(m.velocity_rmse, 5f64.sqrt()));
    assert!(some_close(m.velocity_accuracy, 1.0));
}

#[test]
fn siap_longest_segment_and_track_number_changes() {
    let s = score_main();
    // A: segments [10, 20] on track 1 (10 s) and [40] on 2 (0 s); B: [10] and [30] on 3
    // (0 s each: a gap splits a segment). Lifetimes 40 s (A) and 30 s (B).
    // LS = (10 + 0) / (40 + 30) = 1/7; R = ((2 − 1) + (2 − 1)) / (10 + 0) = 0.2 /s.
    assert_eq!((s.truths[0].segments, s.truths[1].segments), (2, 2));
    assert!(close(s.truths[0].longest_segment, 10.0));
    assert!(some_close(s.summary.longest_segment, 1.0 / 7.0));
    assert!(some_close(s.summary.track_number_change_rate, 0.2));
}

#[test]
fn gospa_parts_and_series() {
    let s = score_main();
    let g: Vec<f64> = s.series.iter().map(|p| p.gospa).collect();
    let want = [100.0, 55.0, 105.0, 60.0, 58.0];
    for (a, b) in g.iter().zip(want) {
        assert!(close(*a, b), "{g:?}");
    }
    let loc: Vec<f64> = s.series.iter().map(|p| p.gospa_localisation).collect();
    assert!(
        loc.iter()
            .zip([0.0, 5.0, 5.0, 10.0, 8.0])
            .all(|(a, b)| close(*a, b))
    );
    let m = &s.summary;
    assert!(close(m.gospa_mean, 378.0 / 5.0));
    assert!(close(m.gospa_localisation_mean, 28.0 / 5.0));
    assert!(close(m.gospa_missed_mean, 200.0 / 5.0));
    assert!(close(m.gospa_false_mean, 150.0 / 5.0));
    let c: Vec<Option<f64>> = s.series.iter().map(|p| p.completeness).collect();
    assert_eq!(
        c,
        vec![Some(0.0), Some(1.0), Some(0.5), Some(0.5), Some(0.5)]
    );
}

fn one_truth_one_track(track_rows: &str, cfg: ScoreConfig) -> argus_score::Summary {
    // A still truth at the origin sampled at 0 and 100 s.
    let truth = "t,target,x,vx,y,vy\n0,A,0,0,0,0\n100,A,0,0,0,0\n";
    let truth = read_truth_from(truth.as_bytes(), "truth.csv").unwrap();
    let tracks = read_tracks_from(track_rows.as_bytes(), "tracks.csv").unwrap();
    Scorer::new(cfg)
        .unwrap()
        .score(&tracks, &truth)
        .unwrap()
        .summary
}

#[test]
fn cutoff_both_sides() {
    // Cut-off 100 m: a track 99.999 m off is assigned, one 100 m off is not (d < c).
    let cfg = ScoreConfig {
        step: 100.0,
        assign_cutoff: 100.0,
        max_truth_gap: 200.0,
        ..ScoreConfig::default()
    };
    let near = "t,track,x,vx,y,vy\n0,1,99.999,0,0,0\n100,1,99.999,0,0,0\n";
    let at = "t,track,x,vx,y,vy\n0,1,100,0,0,0\n100,1,100,0,0,0\n";
    assert!(some_close(one_truth_one_track(near, cfg).completeness, 1.0));
    let s = one_truth_one_track(at, cfg);
    assert!(some_close(s.completeness, 0.0));
    assert!(some_close(s.spurious_fraction, 1.0));
    assert_eq!(s.position_rmse, None);
}

#[test]
fn staleness_both_sides_and_prediction() {
    // Grid 0, 5, …, 100; one confirmed row at t = 0 at (−50, 0) moving +10 m/s in x: at
    // 5 s it is predicted to (0, 0) — error 0 — at 10 s to (50, 0) and at 15 s to
    // (100, 0), all within the 1000 m cut-off, so the age limit alone decides: at 15 s it
    // is present at 0, 5, 10, 15 (4 grid times, age 15 ≤ 15); at 14.9 s at 0, 5, 10 (3).
    let rows = "t,track,x,vx,y,vy\n0,1,-50,10,0,0\n";
    let base = ScoreConfig {
        step: 5.0,
        max_truth_gap: 200.0,
        ..ScoreConfig::default()
    };
    let s = one_truth_one_track(
        rows,
        ScoreConfig {
            max_track_age: 15.0,
            ..base
        },
    );
    assert_eq!(s.track_points, 4);
    // Errors 50, 0, 50, 100: Σe² = 15000 → RMSE √3750.
    assert!(some_close(s.position_rmse, 3750f64.sqrt()));
    let s = one_truth_one_track(
        rows,
        ScoreConfig {
            max_track_age: 14.9,
            ..base
        },
    );
    assert_eq!(s.track_points, 3);
    // Assigned at 0..10, then present and unassigned: one break.
    assert_eq!(s.breaks, 1);
}

#[test]
fn truth_interpolation_and_gaps() {
    // Samples at 0 (x 0, vx 0) and 10 (x 100, vx 20): at 5 s, x = 50 and vx = 10.
    // A track exactly there has zero error in both.
    let truth = "t,target,x,vx,y,vy\n0,A,0,0,0,0\n10,A,100,20,0,0\n";
    let truth = read_truth_from(truth.as_bytes(), "truth.csv").unwrap();
    let tracks = "t,track,x,vx,y,vy\n5,1,50,10,0,0\n";
    let tracks = read_tracks_from(tracks.as_bytes(), "tracks.csv").unwrap();
    let cfg = ScoreConfig {
        step: 5.0,
        start: Some(5.0),
        end: Some(5.0),
        ..ScoreConfig::default()
    };
    let s = Scorer::new(cfg)
        .unwrap()
        .score(&tracks, &truth)
        .unwrap()
        .summary;
    assert_eq!(s.grid_times, 1);
    assert!(some_close(s.position_rmse, 0.0));
    assert!(some_close(s.velocity_rmse, 0.0));
    // The same samples with a 9 s gap limit: not interpolated across, the truth is
    // absent at 5 s (present only on its samples), so nothing is scored there.
    let cfg = ScoreConfig {
        max_truth_gap: 9.0,
        ..cfg
    };
    let s = Scorer::new(cfg)
        .unwrap()
        .score(&tracks, &truth)
        .unwrap()
        .summary;
    assert_eq!(s.truth_points, 0);
    assert_eq!(s.completeness, None);
}

#[test]
fn assignment_is_optimal_not_greedy() {
    // Truths A at x = 0 and B at x = 2; tracks at 1.5 and 4 (cut-off 10). Optimal pairs
    // A–1.5, B–4: errors 1.5 and 2, Σe² = 6.25; greedy (B–1.5 first) would give 16.25.
    let truth = "t,target,x,vx,y,vy\n0,A,0,0,0,0\n0,B,2,0,0,0\n";
    let tracks = "t,track,x,vx,y,vy\n0,1,1.5,0,0,0\n0,2,4,0,0,0\n";
    let truth = read_truth_from(truth.as_bytes(), "truth.csv").unwrap();
    let tracks = read_tracks_from(tracks.as_bytes(), "tracks.csv").unwrap();
    let cfg = ScoreConfig {
        assign_cutoff: 10.0,
        gospa_cutoff: 10.0,
        ..ScoreConfig::default()
    };
    let s = Scorer::new(cfg)
        .unwrap()
        .score(&tracks, &truth)
        .unwrap()
        .summary;
    assert!(some_close(s.position_rmse, (6.25f64 / 2.0).sqrt()));
    // GOSPA p = 2 on the same optimal pairs: √(1.5² + 2²) = 2.5.
    assert!(close(s.gospa_mean, 2.5));
}

#[test]
fn rejects_bad_parameters() {
    let d = ScoreConfig::default();
    for bad in [
        ScoreConfig { step: 0.0, ..d },
        ScoreConfig {
            step: f64::NAN,
            ..d
        },
        ScoreConfig {
            assign_cutoff: -1.0,
            ..d
        },
        ScoreConfig {
            max_track_age: -1.0,
            ..d
        },
        ScoreConfig {
            max_truth_gap: 0.0,
            ..d
        },
        ScoreConfig {
            gospa_cutoff: 0.0,
            ..d
        },
        ScoreConfig {
            gospa_order: 0.5,
            ..d
        },
        ScoreConfig {
            start: Some(f64::INFINITY),
            ..d
        },
        ScoreConfig {
            start: Some(10.0),
            end: Some(5.0),
            ..d
        },
    ] {
        assert!(Scorer::new(bad).is_err(), "{bad:?}");
    }
    // A grid of 10¹⁰ steps is refused rather than allocated.
    let truth = "t,target,x,vx,y,vy\n0,A,0,0,0,0\n1e10,A,0,0,0,0\n";
    let truth = read_truth_from(truth.as_bytes(), "truth.csv").unwrap();
    let scorer = Scorer::new(ScoreConfig { step: 1.0, ..d }).unwrap();
    assert!(matches!(
        scorer.score(&[], &truth),
        Err(argus_score::ScoreError::GridTooLong { .. })
    ));
}

//! Every scenario's campaign split by run index and merged gives exactly the report of
//! one whole run (issue 22): the table, the series, the figures and the notes, compared
//! bit for bit through their `Debug` text (which prints every f64 exactly, NaN included).
//! Reduced run counts and short flights keep each case within a few seconds.

// Test helpers outside #[test] functions may unwrap: a failure is a test failure.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use argus_scenarios::{NoProgress, Params, RecordText, Report, find, in_process, merge, run};

/// `report` with its computing-time values zeroed: bias-32's cost per plot (rows
/// `*cost_per_plot`, the sweep series' `us_per_plot` column) is a measured time, the one
/// value that differs between two runs of the same records' computation.
fn without_timing(mut report: Report) -> Report {
    for r in &mut report.rows {
        if r.key.ends_with("cost_per_plot") {
            r.ours = 0.0;
        }
    }
    for s in &mut report.series {
        if let Some(c) = s.columns.iter().position(|c| c == "us_per_plot") {
            for row in &mut s.rows {
                row[c] = 0.0;
            }
        }
    }
    report
}

/// Runs `name` over `0..n` whole and in the shards `cuts` (`[0, a, b, n]`), merges the
/// shards' records in run order and asserts the two reports are identical.
fn split_equals_whole(name: &str, settings: &[&str], cuts: &[u64]) {
    let sc = find(name).unwrap();
    let settings: Vec<String> = settings.iter().map(|s| (*s).to_owned()).collect();
    let params = Params::from_settings(&sc.params(), &settings).unwrap();
    let n = *cuts.last().unwrap();
    let whole = run(sc.as_ref(), 0..n, 5, params.clone(), &NoProgress).unwrap();
    let mut records: Vec<String> = Vec::new();
    for w in cuts.windows(2) {
        let part = run(sc.as_ref(), w[0]..w[1], 5, params.clone(), &NoProgress).unwrap();
        let recs = part
            .records
            .expect("a splittable scenario returns its records");
        assert_eq!(recs.len() as u64, w[1] - w[0], "{name}: one record per run");
        records.extend(recs);
    }
    // The shards' records are the whole run's, byte for byte (each run has its own
    // generator) … except bias-32's measured computing times.
    if name != "bias-32" {
        assert_eq!(Some(&records), whole.records.as_ref(), "{name}: records");
    }
    // … and the merge reduces them to the same report, exactly (tolerance: none).
    let mut stream = in_process(&records, &(0..n));
    let merged = without_timing(merge(sc.as_ref(), &params, n, &mut stream).unwrap());
    assert_eq!(
        format!("{merged:?}"),
        format!("{:?}", without_timing(whole.report)),
        "{name}: merged report differs from the whole run's"
    );
    assert!(!merged.rows.is_empty(), "{name}: the report has rows");
}

#[test]
fn a_record_that_does_not_parse_is_refused_with_its_place() {
    let sc = find("gimpo").unwrap();
    let params = Params::from_settings(&sc.params(), &[]).unwrap();
    let bad = RecordText {
        json: "{\"fixed_se\": 3}".into(),
        file: "x/runs/0-1.jsonl".into(),
        line: 2,
    };
    let e = merge(sc.as_ref(), &params, 1, &mut std::iter::once(Ok(bad))).unwrap_err();
    assert!(e.to_string().contains("x/runs/0-1.jsonl"), "{e}");
}

#[test]
fn cv_polar_split_equals_whole() {
    split_equals_whole("cv-polar", &["duration=40"], &[0, 3, 5, 8]);
}

#[test]
fn surveillance_split_equals_whole() {
    split_equals_whole("surveillance", &["duration=40", "targets=5"], &[0, 1, 3]);
}

#[test]
fn gimpo_split_equals_whole() {
    split_equals_whole("gimpo", &[], &[0, 1, 3]);
}

#[test]
fn launch_split_equals_whole() {
    split_equals_whole("launch", &["period=2"], &[0, 2, 5]);
}

#[test]
fn clutter_split_equals_whole() {
    split_equals_whole("clutter", &["steps=20"], &[0, 2, 3, 5]);
}

#[test]
fn rbs_landing_split_equals_whole() {
    split_equals_whole("rbs-landing", &[], &[0, 1, 3]);
}

#[test]
fn maneuver_1d_split_equals_whole() {
    // Detection delays and their percentiles come from the runs' detection indices.
    split_equals_whole("maneuver-1d", &[], &[0, 2, 3, 5]);
}

#[test]
fn drag_bearing_split_equals_whole() {
    split_equals_whole("drag-bearing", &[], &[0, 1, 3]);
}

#[test]
fn bias_32_split_equals_whole() {
    split_equals_whole("bias-32", &["duration=30"], &[0, 2, 4]);
}

#[test]
fn bias_32_sweep_split_equals_whole() {
    split_equals_whole(
        "bias-32",
        &["duration=20", "sensors=2,3", "targets=4"],
        &[0, 1, 3],
    );
}

#[test]
fn real_traffic_split_equals_whole() {
    // Three noise realisations of the hour's first five minutes.
    split_equals_whole("real-traffic", &["duration=300"], &[0, 1, 3]);
}

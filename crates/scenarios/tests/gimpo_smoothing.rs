//! Issue 19 on seed 000's trajectory: `argus run gimpo` reports the fixed-interval smoothed
//! IMM's RMS position error against the filtered IMM's (true R) as `smooth_rms_ratio`.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use argus_scenarios::{NoProgress, Params, find, run};

#[test]
fn gimpo_reports_the_smoothed_over_filtered_rms_ratio() {
    let s = find("gimpo").unwrap();
    let params = Params::from_settings(&s.params(), &[]).unwrap();
    // 20 runs (the CLI's default is 100): fixed seed.
    let out = run(s.as_ref(), 0..20, 7, params, &NoProgress).unwrap();
    let row = out
        .report
        .rows
        .iter()
        .find(|r| r.key == "smooth_rms_ratio")
        .expect("gimpo writes smooth_rms_ratio");
    // Upper side: a smoother that also uses the later plots must do better than the filter
    // (< 1; 100 runs at seed 3 read 0.630, the library test's 30 runs 0.653; before the
    // backward-likelihood weights 0.941 and 0.952). Lower side: a
    // loose sanity bound, not a derived one (0.33 would be far below anything measured; the
    // issue's goal is 0.6) — a value under it would mean the truth leaked into the estimate.
    assert!(
        row.ours > 0.33 && row.ours < 1.0,
        "smooth_rms_ratio = {}",
        row.ours
    );
}

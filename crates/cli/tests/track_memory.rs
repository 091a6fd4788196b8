//! Issue 18: `argus track` runs a long plot file in the memory of a short one. The
//! real-traffic scenario's hour of plots (seed 1) replayed with its times shifted by whole
//! hours (a multiple of the 5-s revolution, so the beam's phase is kept) is written as one
//! plot file of 1 hour and one of 4 hours, and tracked by `docs/examples/real-traffic.toml`
//! through `argus_cli::track_files` (the command's own pipeline) in this process. The peak
//! resident set after the 4-hour file must be within 10 % of that after the 1-hour file
//! (the bound, for 24 h against 1 h): plots are read one at a time and rows written
//! as the sectors conclude. Before the stream, both were held whole (the plots ~100 B each,
//! the rows ~150 B of text), which grows by ~40 MB per hour here.
//!
//! This file holds one test so that its process measures nothing else.

// Test helpers outside #[test] functions may unwrap: a failure is a test failure.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::fmt::Write as _;
use std::path::Path;

use argus_scenarios::{Params, find};
use argus_sensors::Measurement;

/// Peak resident set size of this process (kB), from `/proc/self/status`.
fn peak_rss_kb() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// Writes `hours` replays of `hour` (time, range, azimuth) as a polar plot file of sensor 1.
fn write_plots(path: &Path, hour: &[(f64, f64, f64)], hours: u32) {
    let mut text = String::from("t,sensor,range,azimuth\n");
    let mut file = std::fs::File::create(path).unwrap();
    for h in 0..hours {
        let offset = 3600.0 * f64::from(h);
        for &(t, r, a) in hour {
            writeln!(text, "{},1,{r},{a}", t + offset).unwrap();
        }
        std::io::Write::write_all(&mut file, text.as_bytes()).unwrap();
        text.clear();
    }
}

#[test]
fn a_long_plot_file_is_tracked_in_the_memory_of_a_short_one() {
    let sc = find("real-traffic").unwrap();
    let params = Params::from_settings(&sc.params(), &[]).unwrap();
    let sim = sc.simulated(&params, 1, 0).unwrap().unwrap();
    let hour: Vec<(f64, f64, f64)> = sim
        .plots
        .iter()
        .filter_map(|l| match l.plot.measurement() {
            Measurement::Polar(m) => Some((l.plot.time(), m.range(), m.azimuth())),
            _ => None,
        })
        .collect();
    assert!(hour.len() > 20_000, "{} plots", hour.len());
    drop(sim);
    let dir = tempfile::tempdir().unwrap();
    let config =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/examples/real-traffic.toml");
    let run = |hours: u32| {
        let plots = dir.path().join(format!("plots-{hours}h.csv"));
        write_plots(&plots, &hour, hours);
        let out = dir.path().join(format!("tracks-{hours}h.csv"));
        let (rows, _) = argus_cli::track_files(&config, &plots, &out, None).unwrap();
        std::fs::remove_file(&plots).unwrap();
        std::fs::remove_file(&out).unwrap();
        rows
    };
    let rows_1h = run(1);
    let after_1h = peak_rss_kb().unwrap();
    let rows_4h = run(4);
    let after_4h = peak_rss_kb().unwrap();
    eprintln!("peak RSS: {after_1h} kB after 1 h, {after_4h} kB after 4 h");
    // The same traffic four times: about four times the rows (the tracks of one replay
    // end before the next begins; ±2 % for the few that meet across an hour's seam).
    let ratio = rows_4h as f64 / rows_1h as f64;
    assert!(
        (3.92..=4.08).contains(&ratio),
        "rows {rows_1h} then {rows_4h}"
    );
    assert!(
        after_4h as f64 <= 1.10 * after_1h as f64,
        "peak RSS {after_1h} kB after the 1-hour file, {after_4h} kB after the 4-hour file"
    );
}

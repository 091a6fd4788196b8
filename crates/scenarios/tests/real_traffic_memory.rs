//! Issue 18: a day of plots with flat memory. The quickstart hour's plots (the real-traffic
//! scenario's radar, seed 1) replayed 24 times with their times shifted by whole hours (a
//! multiple of the 5-s revolution, so the beam's phase is kept) go through the real-traffic
//! tracker (`gnn_aircraft`, docs/examples/real-traffic.toml) as a stream; deleted tracks
//! are taken out after every chunk, as a caller that keeps nothing does. The process's
//! peak resident set after the first hour and after the 24th must agree within 10 %
//! (the bound): nothing grows with the length of the stream.
//!
//! This file holds one test so that its process measures nothing else.

// Test helpers outside #[test] functions may unwrap: a failure is a test failure.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use argus_scenarios::{Params, find};
use argus_sensors::{Measurement, Plot};
use argus_tracker::Tracker;

/// Peak resident set size of this process (kB), from `/proc/self/status`.
fn peak_rss_kb() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

#[test]
fn a_day_of_plots_runs_in_the_memory_of_an_hour() {
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
    let sensor = sim.plots[0].plot.sensor();
    let config = argus_scenarios::experiments::real_traffic::trackers(&params)
        .unwrap()
        .into_iter()
        .find(|(name, _)| *name == "gnn_aircraft")
        .unwrap()
        .1;
    let mut tracker = Tracker::new(config).unwrap();
    let mut chunk: Vec<Plot> = Vec::with_capacity(512);
    let mut after_first = None;
    let mut deleted = 0usize;
    for h in 0..24 {
        let offset = 3600.0 * f64::from(h);
        for (k, &(t, r, a)) in hour.iter().enumerate() {
            chunk.push(Plot::polar(t + offset, sensor, r, a).unwrap());
            if chunk.len() == 256 || k + 1 == hour.len() {
                tracker.process(&chunk).unwrap();
                deleted += tracker.take_deleted().len();
                chunk.clear();
            }
        }
        if h == 0 {
            after_first = peak_rss_kb();
        }
    }
    tracker.flush();
    deleted += tracker.take_deleted().len();
    // Every hour ends all its tracks (the aircraft of 13:33 are not those of 14:32), so
    // about 24 × the hour's tracks were created and deleted.
    assert!(deleted > 24 * 100, "{deleted} tracks deleted");
    assert!(
        tracker.tracks().len() < 200,
        "{} live tracks",
        tracker.tracks().len()
    );
    if let (Some(first), Some(day)) = (after_first, peak_rss_kb()) {
        let growth = day as f64 / first as f64;
        eprintln!("peak RSS: {first} kB after 1 h, {day} kB after 24 h ({deleted} tracks deleted)");
        assert!(
            growth <= 1.10,
            "peak RSS {first} kB after 1 h, {day} kB after 24 h"
        );
    }
}

//! The reader and the cleaning on the committed extract (data/real-traffic/).
//!
//! Expected counts from the independent pandas implementation of the rules,
//! data/real-traffic/cleaning_counts.py (pandas 3.1.1, numpy 2.4.6, in a venv with
//! traffic 2.13), which printed:
//!   records 109262, aircraft 123, missing_position 0, on_ground 19574,
//!   missing_altitude 316, altitude_out_of_bounds 158, duplicate_time 0,
//!   stale_position 5763, gap_splits 15, position_spike 0, altitude_spike 45,
//!   short_segment 24, kept 83382, flights 118, aircraft_kept 114.
//! Exact integers: the tolerance is zero.

#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use std::path::PathBuf;

use argus_adsb::{CleaningConfig, CleaningReport, read_path};
use argus_geo::{Geodetic, LocalFrame};

fn extract() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/real-traffic/quickstart-busiest-hour.csv.gz")
}

#[test]
fn counts_match_the_independent_computation() {
    let records = read_path(&extract(), None).unwrap();
    let (flights, report) = argus_adsb::clean(&records, &CleaningConfig::default()).unwrap();
    let want = CleaningReport {
        records: 109_262,
        aircraft: 123,
        missing_position: 0,
        on_ground: 19_574,
        missing_altitude: 316,
        altitude_out_of_bounds: 158,
        duplicate_time: 0,
        stale_position: 5_763,
        gap_splits: 15,
        position_spike: 0,
        altitude_spike: 45,
        short_segment: 24,
        kept: 83_382,
        flights: 118,
        aircraft_kept: 114,
    };
    assert_eq!(report, want);
    // Every record is accounted for once.
    let dropped = report.missing_position
        + report.on_ground
        + report.missing_altitude
        + report.altitude_out_of_bounds
        + report.duplicate_time
        + report.stale_position
        + report.position_spike
        + report.altitude_spike
        + report.short_segment;
    assert_eq!(dropped + report.kept, report.records);
    // The busiest hour: 13:33:00 to 14:33:00 UTC on 2021-10-07 (1633613580 s).
    let t0 = records.iter().map(|r| r.time).fold(f64::INFINITY, f64::min);
    let t1 = records
        .iter()
        .map(|r| r.time)
        .fold(f64::NEG_INFINITY, f64::max);
    assert!((t0 - 1_633_613_580.0).abs() < 1e-9 && t1 < t0 + 3600.0);
    for f in &flights {
        assert!(
            f.samples.windows(2).all(|w| w[1].time > w[0].time),
            "{}",
            f.icao24
        );
    }
}

#[test]
fn enu_around_paris_cdg() {
    let records = read_path(&extract(), None).unwrap();
    let (flights, _) = argus_adsb::clean(&records, &CleaningConfig::default()).unwrap();
    // Paris-CDG aerodrome reference point, 49°00′35″N 2°32′52″E (AIP France).
    let frame = LocalFrame::wgs84(Geodetic::from_degrees(49.0097, 2.5478, 0.0).unwrap());
    let mut max_range: f64 = 0.0;
    let mut max_speed: f64 = 0.0;
    for f in &flights {
        for s in f.to_enu(&frame).unwrap() {
            max_range = max_range.max(s.position.east.hypot(s.position.north));
            if let Some(v) = s.velocity {
                max_speed = max_speed.max(v.east.hypot(v.north));
            }
        }
    }
    // The sample covers lat 47.7–50.0°, lon 0.9–4.1° (pandas describe()):
    // within ~200 km of CDG; the fastest ground speed is 539 kt = 277.3 m/s
    // (rotation into the CDG frame changes a horizontal speed by < 0.1 %).
    assert!(max_range > 50e3 && max_range < 200e3, "{max_range}");
    assert!(
        (max_speed - 539.0 * 1852.0 / 3600.0).abs() < 0.3,
        "{max_speed}"
    );
}

//! Each cleaning rule on a small hand-made track, and the readers' typed errors.

#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use argus_adsb::{AdsbError, CleaningConfig, EpochUnit, Location, clean, read_csv, read_json};

const HEADER: &str = "timestamp,icao24,latitude,longitude,altitude,groundspeed,track,vertical_rate,callsign,onground\n";

/// A straight eastbound track at 49° N: 0.001° of longitude is 73.0 m, so one step
/// per second is 73 m/s, well under the 350 m/s limit.
fn row(t: u32, lon_step: f64, alt: &str, onground: bool) -> String {
    let lon = 2.0 + 0.001 * lon_step;
    format!("{t},abc123,49.0,{lon},{alt},140,90,0,TEST1,{onground}\n")
}

fn run(rows: &[String], min_samples: usize) -> argus_adsb::CleaningReport {
    let csv = format!("{HEADER}{}", rows.concat());
    let records = read_csv(csv.as_bytes(), EpochUnit::Seconds).unwrap();
    let config = CleaningConfig {
        min_samples,
        ..CleaningConfig::default()
    };
    clean(&records, &config).unwrap().1
}

#[test]
fn each_rule_counts_what_it_drops() {
    let mut rows: Vec<String> = (0..20)
        .map(|t| row(t, f64::from(t), "10000", false))
        .collect();
    rows[3] = row(3, 3.0, "", false); // missing altitude
    rows[5] = row(5, 5.0, "10000", true); // on ground
    rows[7] = row(7, 6.0, "10000", false); // stale: the position of t = 6
    rows[9] = row(9, 9.0, "70000", false); // out of bounds
    rows[11] = row(11, 40.0, "10000", false); // position spike: 2.2 km in 1 s
    rows[13] = row(13, 13.0, "12000", false); // altitude spike: 610 m in 1 s
    rows.push(row(19, 19.0, "10000", false)); // duplicate time
    let r = run(&rows, 2);
    assert_eq!(
        (
            r.missing_altitude,
            r.on_ground,
            r.stale_position,
            r.altitude_out_of_bounds
        ),
        (1, 1, 1, 1)
    );
    assert_eq!(
        (r.position_spike, r.altitude_spike, r.duplicate_time),
        (1, 1, 1)
    );
    assert_eq!((r.kept, r.flights, r.gap_splits), (14, 1, 0));
}

#[test]
fn gaps_split_and_short_segments_go() {
    // 12 samples, a 61 s gap, then 5 samples: two segments, the second too short.
    let mut rows: Vec<String> = (0..12)
        .map(|t| row(t, f64::from(t), "10000", false))
        .collect();
    rows.extend((0..5).map(|k| row(72 + k, 72.0 + f64::from(k), "10000", false)));
    let r = run(&rows, 10);
    assert_eq!(
        (r.gap_splits, r.flights, r.kept, r.short_segment),
        (1, 1, 12, 5)
    );
}

#[test]
fn a_genuine_jump_is_kept() {
    // The track shifts by 2.2 km and stays there: each side agrees with itself, so
    // neither is a spike (a single outlier would disagree with both neighbours).
    let rows: Vec<String> = (0..10)
        .map(|t| {
            row(
                t,
                f64::from(t) + if t >= 5 { 30.0 } else { 0.0 },
                "10000",
                false,
            )
        })
        .collect();
    let r = run(&rows, 2);
    assert_eq!((r.position_spike, r.kept), (0, 10));
    // A spike at the first record is found through the next pair.
    let mut rows: Vec<String> = (0..10)
        .map(|t| row(t, f64::from(t), "10000", false))
        .collect();
    rows[0] = row(0, -40.0, "10000", false);
    assert_eq!(run(&rows, 2).position_spike, 1);
}

#[test]
fn json_records_and_lines() {
    // The traffic package's JSON sample layout: epoch milliseconds, nulls.
    let array = r#"[{"altitude":13650.0,"callsign":"MSR799","groundspeed":325.0,"icao24":"0101de",
        "latitude":48.48,"longitude":3.83,"onground":false,"squawk":"1000",
        "timestamp":1633608773000,"track":311.1,"vertical_rate":-896.0},
        {"altitude":null,"callsign":"MSR799","groundspeed":null,"icao24":"0101de",
        "latitude":48.49,"longitude":3.82,"onground":true,"timestamp":"2021-10-07T12:12:54Z",
        "track":null,"vertical_rate":null}]"#;
    let r = read_json(array.as_bytes(), EpochUnit::Milliseconds).unwrap();
    assert_eq!(r.len(), 2);
    assert!(
        (r[0].time - 1_633_608_773.0).abs() < 1e-9 && (r[1].time - 1_633_608_774.0).abs() < 1e-9
    );
    // 13 650 ft = 4 160.52 m; 325 kt = 167.19 m/s; −896 ft/min = −4.5517 m/s (exact factors).
    assert!((r[0].altitude_m().unwrap() - 4160.52).abs() < 1e-9);
    assert!((r[0].groundspeed_mps().unwrap() - 325.0 * 1852.0 / 3600.0).abs() < 1e-12);
    assert!((r[0].vertical_rate_mps().unwrap() + 896.0 * 0.3048 / 60.0).abs() < 1e-12);
    assert_eq!((r[1].altitude_ft, r[1].onground), (None, Some(true)));
    let lines = "{\"timestamp\":1,\"icao24\":\"ABC123\",\"latitude\":1.0,\"longitude\":2.0}\n\n{\"timestamp\":2,\"icao24\":\"abc123\",\"latitude\":1.0,\"longitude\":2.1}\n";
    let r = read_json(lines.as_bytes(), EpochUnit::Seconds).unwrap();
    assert_eq!((r.len(), r[0].icao24.as_str()), (2, "abc123"));
}

#[test]
fn errors_name_the_line_or_record_and_field() {
    let bad = format!(
        "{HEADER}0,abc123,49.0,2.0,10000,140,90,0,X,false\n1,abc123,95.0,2.0,10000,140,90,0,X,false\n"
    );
    match read_csv(bad.as_bytes(), EpochUnit::Seconds) {
        Err(AdsbError::Field {
            at: Location::Line(3),
            field: "latitude",
            ..
        }) => {}
        other => panic!("{other:?}"),
    }
    let bad = format!("{HEADER}0,abc123,49.0,2.0,high,140,90,0,X,false\n");
    let e = read_csv(bad.as_bytes(), EpochUnit::Seconds).unwrap_err();
    assert_eq!(
        e.to_string(),
        "line 2: field 'altitude': 'high' is not a finite number"
    );
    let bad = format!("{HEADER}2021-10-07T25:00:00Z,abc123,49.0,2.0,1,1,1,1,X,false\n");
    assert!(matches!(
        read_csv(bad.as_bytes(), EpochUnit::Seconds),
        Err(AdsbError::Field {
            at: Location::Line(2),
            field: "timestamp",
            ..
        })
    ));
    let bad = "timestamp,icao24,latitude\n0,abc123,1\n";
    assert!(matches!(
        read_csv(bad.as_bytes(), EpochUnit::Seconds),
        Err(AdsbError::MissingColumn {
            column: "longitude"
        })
    ));
    let bad = r#"[{"timestamp":0,"icao24":"zz9","latitude":1,"longitude":2}]"#;
    assert!(matches!(
        read_json(bad.as_bytes(), EpochUnit::Seconds),
        Err(AdsbError::Field {
            at: Location::Record(0),
            field: "icao24",
            ..
        })
    ));
    let bad = r#"[{"timestamp":0,"icao24":"abc","latitude":1,"longitude":2,"onground":"yes"}]"#;
    assert!(matches!(
        read_json(bad.as_bytes(), EpochUnit::Seconds),
        Err(AdsbError::Field {
            field: "onground",
            ..
        })
    ));
    let config = CleaningConfig {
        max_gap_s: f64::NAN,
        ..CleaningConfig::default()
    };
    assert!(matches!(
        clean(&[], &config),
        Err(AdsbError::Parameter {
            what: "max_gap_s",
            ..
        })
    ));
}

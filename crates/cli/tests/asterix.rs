//! ASTERIX in and out of the command: `argus simulate` writing CAT048 + CAT034, `argus
//! track --plots capture.pcap` and `argus convert`, the round trip of the real-traffic
//! hour, and every bad-input path (truncated capture, a link type without IP, bad
//! ASTERIX inside, an unknown SAC/SIC, half a data source in the configuration).

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;

use argus_asterix::{ItemId, MeasuredPolar, TimeOfDay};

mod common;
use common::argus;

const CONFIG: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../docs/examples/real-traffic.toml"
);

fn ok(args: &[&str], cwd: &Path) -> String {
    let out = argus(args, cwd);
    assert!(
        out.status.success(),
        "argus {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap() + &String::from_utf8(out.stderr).unwrap()
}

fn fails(args: &[&str], cwd: &Path) -> String {
    let out = argus(args, cwd);
    assert_eq!(out.status.code(), Some(2), "argus {args:?} should fail");
    String::from_utf8(out.stderr).unwrap()
}

/// The plot CSV `t,sensor,range,azimuth[,origin]` quantised as ASTERIX holds it, from
/// the codec's own primitives (not the reader under test): I048/140 to 1/128 s, RHO to
/// 1/256 NM, θ to 360°/2^16 and back to Argus's azimuth.
fn quantised(csv: &str) -> String {
    let item = ItemId {
        cat: 48,
        name: "140",
    };
    let mut out = String::from("t,sensor,range,azimuth\n");
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let t: f64 = f[0].parse().unwrap();
        let (range, az): (f64, f64) = (f[2].parse().unwrap(), f[3].parse().unwrap());
        let tq = TimeOfDay::from_seconds(item, t).unwrap().seconds();
        let p = MeasuredPolar::from_range_azimuth(range, az).unwrap();
        out.push_str(&format!(
            "{tq},{},{},{}\n",
            f[1],
            p.range_m(),
            p.theta.argus()
        ));
    }
    out
}

/// The summary without the file names.
fn summary(path: &Path) -> String {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| !l.contains("_file"))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn real_traffic_tracked_from_its_capture_equals_the_quantised_csv() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    ok(&["simulate", "real-traffic", "--out", "P.csv"], d);
    let said = ok(&["simulate", "real-traffic", "--out", "P.pcap"], d);
    assert!(said.contains("22593 plots"), "{said}");
    let csv = std::fs::read_to_string(d.join("P.csv")).unwrap();
    std::fs::write(d.join("Q.csv"), quantised(&csv)).unwrap();
    ok(
        &[
            "track", "--config", CONFIG, "--plots", "Q.csv", "--out", "TQ.csv",
        ],
        d,
    );
    ok(
        &[
            "track", "--config", CONFIG, "--plots", "P.pcap", "--out", "TP.csv",
        ],
        d,
    );
    // Same plots (after the codec's quantisation) and the same sectors (CAT034 gives
    // the 5-s period and north at phase 0, the configuration's): the same tracks, bit
    // for bit, and the same summary.
    let tq = std::fs::read(d.join("TQ.csv")).unwrap();
    assert!(tq.len() > 1_000_000);
    assert!(tq == std::fs::read(d.join("TP.csv")).unwrap());
    assert_eq!(
        summary(&d.join("TQ.summary.json")),
        summary(&d.join("TP.summary.json"))
    );
    // Without a rotation in the configuration the capture's CAT034 messages make the
    // radar a rotating one with the same sectors: the same tracks again.
    let config = std::fs::read_to_string(CONFIG).unwrap();
    let bare: String = config
        .lines()
        .filter(|l| {
            !["revolution_period", "rotation", "north_time"]
                .iter()
                .any(|k| l.starts_with(k))
        })
        .map(|l| format!("{l}\n"))
        .collect();
    assert!(!bare.contains("revolution_period"));
    std::fs::write(d.join("bare.toml"), bare).unwrap();
    ok(
        &[
            "track",
            "--config",
            "bare.toml",
            "--plots",
            "P.pcap",
            "--out",
            "TB.csv",
        ],
        d,
    );
    assert!(tq == std::fs::read(d.join("TB.csv")).unwrap());
    // The raw-block file holds the same records: the same tracks.
    ok(&["simulate", "real-traffic", "--out", "P.ast"], d);
    ok(
        &[
            "track", "--config", CONFIG, "--plots", "P.ast", "--out", "TA.csv",
        ],
        d,
    );
    assert!(tq == std::fs::read(d.join("TA.csv")).unwrap());
    // convert gives the quantised plot file itself: every value is the codec's, printed
    // by Rust's shortest round-trip formatting in both.
    let said = ok(&["convert", "P.pcap", "C.csv"], d);
    assert!(said.contains("22593 plots"), "{said}");
    assert_eq!(
        std::fs::read_to_string(d.join("C.csv")).unwrap(),
        quantised(&csv)
    );
}

#[test]
fn convert_round_trips_across_midnight_and_counts_the_messages() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Times across midnight (86 400 s), on the 1/128-s grid so nothing is rounded;
    // ranges on the 1/256-NM grid, azimuths on the 2^-16-turn grid.
    let rho = 1852.0 / 256.0;
    let mut text = String::from("t,sensor,range,azimuth\n");
    for k in 0..40u32 {
        let t = 86_390.0 + f64::from(k) * 0.5;
        let az = argus_asterix::Azimuth16(u16::try_from(k * 1000).unwrap()).argus();
        text.push_str(&format!("{t},1,{},{az}\n", f64::from(1000 + k) * rho));
    }
    std::fs::write(d.join("in.csv"), &text).unwrap();
    let said = ok(
        &["convert", "in.csv", "out.ast", "--revolution-period", "4"],
        d,
    );
    // A 4-s radar in 8 sectors: a boundary every 0.5 s, from the first plot's time
    // (86 390 s, itself a boundary) to the last plot's (86 409.5 s): 40 messages.
    assert!(
        said.contains("40 CAT048 reports, 40 CAT034 messages"),
        "{said}"
    );
    ok(&["convert", "out.ast", "back.csv"], d);
    assert_eq!(std::fs::read_to_string(d.join("back.csv")).unwrap(), text);
    // CSV to CSV and ASTERIX to ASTERIX are refused.
    assert!(fails(&["convert", "in.csv", "x.csv"], d).contains("give an ASTERIX output"));
    assert!(fails(&["convert", "out.ast", "x.pcap"], d).contains("ASTERIX already"));
    // A negative time has no time of day.
    std::fs::write(d.join("neg.csv"), "t,sensor,range,azimuth\n-1,1,1000,0\n").unwrap();
    assert!(fails(&["convert", "neg.csv", "x.pcap"], d).contains("t ≥ 0"));
}

/// A pcap from `argus convert` of a few plots of sensor `sensor` (SAC 0, SIC `sensor`).
fn small_capture(d: &Path, sensor: u32) -> Vec<u8> {
    let mut text = String::from("t,sensor,range,azimuth\n");
    for k in 0..10 {
        text.push_str(&format!("{},{sensor},{},0.5\n", k, 20_000 + 100 * k));
    }
    std::fs::write(d.join("s.csv"), text).unwrap();
    ok(&["convert", "s.csv", "s.pcap"], d);
    std::fs::read(d.join("s.pcap")).unwrap()
}

#[test]
fn bad_captures_are_refused_or_skipped_with_their_reason() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let bytes = small_capture(d, 1);
    // Ten scan times: ten datagrams of one CAT048 record each.
    // Truncated inside the last packet: nine plots kept, the tail counted.
    std::fs::write(d.join("cut.pcap"), &bytes[..bytes.len() - 5]).unwrap();
    let said = ok(&["convert", "cut.pcap", "cut.csv"], d);
    assert!(said.contains("skipped 1 packets"), "{said}");
    assert!(said.contains("truncated pcap record"), "{said}");
    assert!(said.contains("wrote cut.csv (9 plots"), "{said}");
    // A link type without IP (105, IEEE 802.11): refused whole.
    let mut wifi = bytes.clone();
    wifi[20..24].copy_from_slice(&105u32.to_le_bytes());
    std::fs::write(d.join("wifi.pcap"), wifi).unwrap();
    let e = fails(&["convert", "wifi.pcap", "w.csv"], d);
    assert!(e.contains("link type 105"), "{e}");
    // Bad ASTERIX inside a datagram: the first CAT048 record's FSPEC (after the 24-byte
    // file header, the 16-byte record header, 42 bytes of Ethernet/IPv4/UDP headers and
    // the 3-byte block header) set to FX bits that never end: that record skipped with
    // its reason, the other nine kept.
    let mut bad = bytes.clone();
    let at = 24 + 16 + 42 + 3;
    bad[at..at + 4].copy_from_slice(&[0xff; 4]);
    std::fs::write(d.join("bad.pcap"), bad).unwrap();
    let said = ok(&["convert", "bad.pcap", "bad.csv"], d);
    assert!(said.contains("1 ASTERIX blocks or records"), "{said}");
    assert!(said.contains("wrote bad.csv (9 plots"), "{said}");
}

#[test]
fn plots_of_an_unknown_radar_and_half_a_data_source_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    small_capture(d, 7);
    let base = std::fs::read_to_string(CONFIG).unwrap();
    std::fs::write(d.join("c.toml"), &base).unwrap();
    // Sensor 1 answers to SAC 0 / SIC 1; the capture's radar is SAC 0 / SIC 7.
    let e = fails(
        &[
            "track", "--config", "c.toml", "--plots", "s.pcap", "--out", "t.csv",
        ],
        d,
    );
    assert!(e.contains("I048/010 SAC 0 SIC 7 is no [[sensor]]"), "{e}");
    assert!(e.contains("known SAC/SIC: 0/1"), "{e}");
    assert!(e.contains("record 1"), "{e}");
    // With sac = 0, sic = 7 the same sensor takes them.
    let keyed = base.replacen("id = 1\n", "id = 1\nsac = 0\nsic = 7\n", 1);
    std::fs::write(d.join("k.toml"), &keyed).unwrap();
    ok(
        &[
            "track", "--config", "k.toml", "--plots", "s.pcap", "--out", "t.csv",
        ],
        d,
    );
    // sac without sic: an error at its line.
    let half = base.replacen("id = 1\n", "id = 1\nsac = 0\n", 1);
    std::fs::write(d.join("h.toml"), &half).unwrap();
    let e = fails(
        &[
            "track", "--config", "h.toml", "--plots", "s.pcap", "--out", "t.csv",
        ],
        d,
    );
    assert!(e.contains("h.toml:") && e.contains("sac needs sic"), "{e}");
    // A SAC outside 0..=255: refused by the configuration's types.
    let big = base.replacen("id = 1\n", "id = 1\nsac = 256\nsic = 1\n", 1);
    std::fs::write(d.join("b.toml"), &big).unwrap();
    fails(
        &[
            "track", "--config", "b.toml", "--plots", "s.pcap", "--out", "t.csv",
        ],
        d,
    );
}

#[test]
fn tracks_csv_round_trips_through_cat062() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Values on CAT062's grids (t 1/128 s, x, y 0.5 m, v 0.25 m/s) come back exactly;
    // the tentative row is not written (CAT062 carries the system's confirmed tracks).
    let rows = "t,sensor,track,status,x,vx,y,vy\n\
        0.5,1,3,tentative,10,1,20,2\n\
        5.5,1,3,confirmed,-1000.5,100.25,2000,-7.75\n\
        5.5,1,12,confirmed,400000,0,-300000.5,250.5\n\
        10.0078125,1,3,confirmed,-500,100.25,1961.5,-7.75\n";
    std::fs::write(d.join("t.csv"), rows).unwrap();
    let said = ok(&["convert", "t.csv", "t.pcap"], d);
    assert!(said.contains("3 CAT062 records"), "{said}");
    ok(&["convert", "t.pcap", "back.csv"], d);
    assert_eq!(
        std::fs::read_to_string(d.join("back.csv")).unwrap(),
        "t,track,x,vx,y,vy,status\n\
         5.5,3,-1000.5,100.25,2000,-7.75,confirmed\n\
         5.5,12,400000,0,-300000.5,250.5,confirmed\n\
         10.0078125,3,-500,100.25,1961.5,-7.75,confirmed\n"
    );
    // A track name CAT062 cannot number, and a speed past I062/185's 16 bits: errors.
    std::fs::write(d.join("n.csv"), "t,track,x,vx,y,vy\n0,a7,0,0,0,0\n").unwrap();
    assert!(fails(&["convert", "n.csv", "n.ast"], d).contains("not a CAT062 track number"));
    std::fs::write(d.join("v.csv"), "t,track,x,vx,y,vy\n0,1,0,9000,0,0\n").unwrap();
    assert!(fails(&["convert", "v.csv", "v.ast"], d).contains("vx 9000"));
}

#[test]
fn cat021_reports_convert_to_the_adsb_csv_the_adsb_reader_reads() {
    use argus_asterix::{Cat021, DataSource, LatLon, Quality, QualityExt};
    // Three reports: high-resolution position and NACp 9 (EPU 30 m: σ = 30 / 2.4477 =
    // 12.26 m per axis), the coarse position only and no NACp, and one without a target
    // address (not converted, counted).
    let hr = LatLon {
        lat_deg: 400_000_000.0 * LatLon::LSB_131_DEG,
        lon_deg: 10_000_000.0 * LatLon::LSB_131_DEG,
    };
    let coarse = LatLon {
        lat_deg: 2_000_000.0 * LatLon::LSB_130_DEG,
        lon_deg: -300_000.0 * LatLon::LSB_130_DEG,
    };
    let a = Cat021 {
        source: Some(DataSource { sac: 1, sic: 2 }),
        t_position: Some(TimeOfDay(128 * 36_000)),
        position: Some(coarse),
        position_hr: Some(hr),
        target_address: Some(0x3c_4a_5b),
        quality: Some(Quality {
            nac_v: 1,
            nic: 8,
            extension: Some(QualityExt {
                nic_baro: true,
                sil: 3,
                nac_p: 9,
            }),
        }),
        ..Cat021::default()
    };
    let b = Cat021 {
        t_position: Some(TimeOfDay(128 * 36_001 + 64)),
        position_hr: None,
        quality: None,
        target_address: Some(0x00_00_0f),
        ..a
    };
    let c = Cat021 {
        target_address: None,
        ..a
    };
    let mut bytes = Vec::new();
    argus_asterix::encode_block(&[a, b, c], &mut bytes)
        .map_err(|e| e.to_string())
        .unwrap();
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("adsb.ast"), &bytes).unwrap();
    let o = argus(&["convert", "adsb.ast", "adsb.csv"], dir.path());
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        stdout.contains("2 ADS-B rows") && stdout.contains("1 incomplete CAT021"),
        "{stdout}"
    );
    let text = std::fs::read_to_string(dir.path().join("adsb.csv")).unwrap();
    let rows = argus_adsb::read_csv(text.as_bytes(), argus_adsb::EpochUnit::Seconds).unwrap();
    assert_eq!(rows.len(), 2);
    assert_eq!(rows[0].icao24, "3c4a5b");
    assert_eq!(rows[1].icao24, "00000f");
    // Times of applicability in seconds (1/128 s LSB: exact), positions exactly the
    // items' grid values (the high-resolution one when present).
    assert_eq!(rows[0].time.to_bits(), 36_000.0_f64.to_bits());
    assert_eq!(rows[1].time.to_bits(), 36_001.5_f64.to_bits());
    assert_eq!(rows[0].latitude.unwrap().to_bits(), hr.lat_deg.to_bits());
    assert_eq!(rows[0].longitude.unwrap().to_bits(), hr.lon_deg.to_bits());
    assert_eq!(
        rows[1].latitude.unwrap().to_bits(),
        coarse.lat_deg.to_bits()
    );
    assert_eq!(
        rows[1].longitude.unwrap().to_bits(),
        coarse.lon_deg.to_bits()
    );
    // σ from NACp 9 (EPU < 30 m, DO-242A), empty without NACp.
    let sigma: Vec<&str> = text
        .lines()
        .skip(1)
        .map(|l| l.rsplit(',').next().unwrap())
        .collect();
    let s0: f64 = sigma[0].parse().unwrap();
    assert!((s0 - 30.0 / 2.447_746_830_680_816).abs() < 1e-9, "{s0}");
    assert_eq!(sigma[1], "");
}

//! CAT062 (ed. 1.18) core items: a hand-built vector from the LSBs, and a
//! proptest round trip.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use argus_asterix::{
    Cartesian062, Cat062, DataSource, Record, TimeOfDay, Velocity062, Wgs84Position, decode,
    encode_block,
};
use proptest::option::of;
use proptest::prelude::*;

fn tracks(bytes: &[u8]) -> Vec<Cat062> {
    decode(bytes)
        .records
        .into_iter()
        .filter_map(|r| {
            if let Record::Cat062(c) = r {
                Some(c)
            } else {
                None
            }
        })
        .collect()
}

#[test]
fn cat062_values_from_lsbs() {
    let block: &[u8] = &[
        62, 0, 34, //
        // FSPEC: FRN 1, 4, 5, 6, 7 → 0x9e | FX; FRN 11 (380), 12 (040) → 0x18.
        0x9f, 0x18, //
        0x01, 0x02, // I062/010
        0x00, 0x00, 0x80, // I062/070 1 s × 128 = 128
        0x00, 0x80, 0x00, 0x00, // I062/105 lat 45° × 2^25/180 = 2^23
        0xff, 0x00, 0x00, 0x00, // lon −90° = −2^24
        0xff, 0xf8, 0x30, // I062/100 x −1000 m / 0.5 = −2000 = 2^24 − 2000 = 0xfff830
        0x00, 0x03, 0xe9, // y 500.5 m / 0.5 = 1001
        0x01, 0x90, 0xff,
        0x38, // I062/185 vx 100 m/s / 0.25 = 400, vy −50 → −200 = 0xff38
        0x80, 0x4c, 0xa1, 0x23, // I062/380 compound, ADR subfield only (skipped)
        0x12, 0x34, // I062/040
    ];
    let d = decode(block);
    assert!(d.skipped.is_empty(), "{:?}", d.skipped);
    let t = tracks(block);
    assert_eq!(t.len(), 1);
    let t = t[0];
    assert_eq!(t.source, Some(DataSource { sac: 1, sic: 2 }));
    assert_eq!(t.time, Some(TimeOfDay(128)));
    // Exact: the LSBs are dyadic.
    let (lat, lon) = t.wgs84.unwrap().degrees();
    assert!((lat - 45.0).abs() < 1e-12 && (lon + 90.0).abs() < 1e-12);
    let (x, y) = t.cartesian.unwrap().metres();
    assert!((x + 1000.0).abs() < 1e-12 && (y - 500.5).abs() < 1e-12);
    let (vx, vy) = t.velocity.unwrap().mps();
    assert!((vx - 100.0).abs() < 1e-12 && (vy + 50.0).abs() < 1e-12);
    assert_eq!(t.track_number, Some(0x1234));
    // Spare FRN 2 set: length unknown, typed error.
    let d = decode(&[62, 0, 6, 0x40, 0, 0]);
    assert!(matches!(
        d.skipped[0].error,
        argus_asterix::DecodeError::UndefinedFrn {
            offset: 3,
            cat: 62,
            frn: 2
        }
    ));
}

fn cat062() -> impl Strategy<Value = Cat062> {
    (
        of((any::<u8>(), any::<u8>()).prop_map(|(sac, sic)| DataSource { sac, sic })),
        of((0u32..1 << 24).prop_map(TimeOfDay)),
        of((any::<i32>(), any::<i32>()).prop_map(|(lat, lon)| Wgs84Position { lat, lon })),
        of((-(1i32 << 23)..1 << 23, -(1i32 << 23)..1 << 23)
            .prop_map(|(x, y)| Cartesian062 { x, y })),
        of((any::<i16>(), any::<i16>()).prop_map(|(vx, vy)| Velocity062 { vx, vy })),
        of(any::<u16>()),
    )
        .prop_map(
            |(source, time, wgs84, cartesian, velocity, track_number)| Cat062 {
                source,
                time,
                wgs84,
                cartesian,
                velocity,
                track_number,
            },
        )
        .prop_filter("at least one item", |r| *r != Cat062::default())
}

proptest! {
    #[test]
    fn cat062_round_trip(records in proptest::collection::vec(cat062(), 1..20)) {
        let mut bytes = Vec::new();
        encode_block(&records, &mut bytes).unwrap();
        let d = decode(&bytes);
        prop_assert!(d.skipped.is_empty(), "{:?}", d.skipped);
        prop_assert_eq!(tracks(&bytes), records);
    }
}

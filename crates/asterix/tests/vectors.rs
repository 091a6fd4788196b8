//! Hand-built byte vectors, their expected values computed from the items' LSBs
//! (CAT048 ed. 1.31, CAT034 ed. 1.29).

#![allow(clippy::unwrap_used, clippy::expect_used)]

use argus_asterix::{
    Cat034, Cat048, DecodeError, MessageType, Record, TimeOfDay, decode, encode_block,
};

/// One CAT048 record with every decoded item, then one with skipped items.
fn cat048_block() -> Vec<u8> {
    let rec1: &[u8] = &[
        // FSPEC: FRN 1-6 → 0b1111_1100 | FX; FRN 8, 11, 12, 13, 14 → 0x80|0x10|0x08|0x04|0x02.
        0xfd, 0x9e, //
        0x19, 0xc9, // I048/010 SAC 25, SIC 201
        0x54, 0x60, 0x40, // I048/140 43200.5 s × 128 = 5 529 664 = 0x546040
        0xa4, // I048/020 TYP 5 (101), SPI → 1010_0100
        0x32, 0x00, 0x40,
        0x00, // I048/040 RHO 50 NM × 256 = 0x3200, θ 90° × 2^16/360 = 0x4000
        0x0e, 0x00, // I048/070 code 0o7000 = 0xe00
        0x05, 0x78, // I048/090 FL 350 × 4 = 1400 = 0x578
        0x4c, 0xa1, 0x23, // I048/220
        0xfa, 0xbc, // I048/161 spare bits set (ignored), track 0xabc
        0xfb, 0x00, 0x0a,
        0x00, // I048/042 x −10 NM × 128 = −1280 = 0xfb00, y 20 NM = 2560
        0x08, 0x00, 0x80, 0x00, // I048/200 0.125 NM/s × 2^14 = 2048, heading 180° = 0x8000
        0x4b, 0x40, // I048/170 RAD 2, MAH, CDM 1, FX | GHO
    ];
    let rec2: &[u8] = &[
        // FSPEC: FRN 1, 6, 7 → 0x86|FX; FRN 10 → 0x20|FX; none → FX; FRN 27 → 0x04.
        0x87, 0x21, 0x01, 0x04, //
        0x01, 0x02, // I048/010
        0x7f, 0xd8, // I048/090 G, FL −10 → −40 in 14 bits = 16344 = 0x3fd8, | G 0x4000
        0xc0, 0x11, 0x22, // I048/130 SRL, SRR present (skipped)
        0x01, 1, 2, 3, 4, 5, 6, 7, 8, // I048/250 REP 1 × 8 (skipped)
        0x03, 0xaa, 0xbb, // SP, LEN 3 (skipped)
    ];
    let len = 3 + rec1.len() + rec2.len();
    let mut b = vec![48, 0, u8::try_from(len).unwrap_or(0)];
    b.extend_from_slice(rec1);
    b.extend_from_slice(rec2);
    b
}

fn cat048s(bytes: &[u8]) -> Vec<Cat048> {
    decode(bytes)
        .records
        .into_iter()
        .filter_map(|r| {
            if let Record::Cat048(c) = r {
                Some(c)
            } else {
                None
            }
        })
        .collect()
}

#[test]
fn cat048_values_from_lsbs() {
    let bytes = cat048_block();
    let d = decode(&bytes);
    assert!(d.skipped.is_empty(), "{:?}", d.skipped);
    let r = cat048s(&bytes);
    assert_eq!(r.len(), 2);
    let a = r[0];
    let s = a.source.unwrap();
    assert_eq!((s.sac, s.sic), (25, 201));
    // Exact: 5 529 664 / 128 is a dyadic rational.
    assert!((a.time.unwrap().seconds() - 43200.5).abs() < 1e-12);
    let desc = a.descriptor.unwrap();
    assert_eq!(
        (desc.typ, desc.sim, desc.spi, desc.extension),
        (5, false, true, None)
    );
    let p = a.polar.unwrap();
    // 50 NM = 92 600 m exactly; θ 90° clockwise from north = east = 0 rad in Argus's convention.
    assert!((p.range_m() - 92_600.0).abs() < 1e-9);
    assert!((p.theta.degrees() - 90.0).abs() < 1e-12);
    assert!(p.theta.argus().abs() < 1e-15);
    assert_eq!(a.mode3a.unwrap().code, 0o7000);
    assert!((a.flight_level.unwrap().flight_level() - 350.0).abs() < 1e-12);
    assert_eq!(a.aircraft_address, Some(0x4c_a123));
    assert_eq!(a.track_number, Some(0xabc));
    let (x, y) = a.cartesian.unwrap().metres();
    assert!((x + 18_520.0).abs() < 1e-9 && (y - 37_040.0).abs() < 1e-9);
    let v = a.velocity.unwrap();
    // 0.125 NM/s = 231.5 m/s.
    assert!((v.speed_mps() - 231.5).abs() < 1e-12);
    assert!((v.heading.degrees() - 180.0).abs() < 1e-12);
    let ts = a.track_status.unwrap();
    assert_eq!(
        (ts.tentative, ts.rad, ts.manoeuvre, ts.cdm),
        (false, 2, true, 1)
    );
    assert_eq!(ts.extension, Some(0x40));
    // Second record: negative FL, items 130, 250, SP skipped by their length rules.
    let b = r[1];
    let fl = b.flight_level.unwrap();
    assert!(fl.garbled && !fl.not_validated);
    assert!((fl.flight_level() + 10.0).abs() < 1e-12);
    assert_eq!(b.source.map(|s| (s.sac, s.sic)), Some((1, 2)));
}

#[test]
fn cat048_reencodes_to_the_same_bytes_for_decoded_items() {
    // Record 1 holds only decoded items (with /161's spare bits cleared): the
    // encoder must reproduce it byte for byte.
    let bytes = cat048_block();
    let r = cat048s(&bytes);
    let mut out = Vec::new();
    encode_block(&r[..1], &mut out).unwrap();
    let mut expect = bytes[..3 + 31].to_vec();
    expect[2] = 34;
    expect[3 + 2 + 17] = 0x0a; // /161 spare nibble cleared
    assert_eq!(out, expect);
}

#[test]
fn cat034_north_marker_and_sector() {
    let block: &[u8] = &[
        34, 0, 20, //
        // FSPEC FRN 1, 2, 3, 5 → 0b1110_1000.
        0xe8, 0x19, 0xc9, 0x01, 0x00, 0x00, 0x80, // north marker at 1 s (128 = 0x80)
        0x02, 0x00, // rotation period 4.0 s × 128 = 512 = 0x0200
        // FSPEC FRN 1, 2, 3, 4 → 0b1111_0000.
        0xf0, 0x19, 0xc9, 0x02, 0x00, 0x01, 0x40,
        0x40, // sector 64 × 360/256 = 90°, t 2.5 s = 320
    ];
    let d = decode(block);
    assert!(d.skipped.is_empty(), "{:?}", d.skipped);
    let r: Vec<Cat034> = d
        .records
        .into_iter()
        .filter_map(|r| {
            if let Record::Cat034(c) = r {
                Some(c)
            } else {
                None
            }
        })
        .collect();
    assert_eq!(r.len(), 2);
    assert_eq!(r[0].message_type, Some(MessageType::NorthMarker));
    assert_eq!(r[0].time, Some(TimeOfDay(128)));
    assert!((r[0].rotation_period.unwrap().seconds() - 4.0).abs() < 1e-12);
    assert_eq!(r[1].message_type, Some(MessageType::SectorCrossing));
    assert!((r[1].time.unwrap().seconds() - 2.5).abs() < 1e-12);
    assert!((r[1].sector.unwrap().degrees() - 90.0).abs() < 1e-12);
}

#[test]
fn bad_framing_is_typed_and_the_rest_kept() {
    let good = cat048_block();
    // Unknown category block, then a good block: one typed skip at offset 0, both records kept.
    let mut input = vec![99, 0, 5, 0xaa, 0xbb];
    input.extend_from_slice(&good);
    let d = decode(&input);
    assert_eq!(d.records.len(), 2);
    assert_eq!(d.skipped.len(), 1);
    assert_eq!(
        d.skipped[0].error,
        DecodeError::UnknownCategory { offset: 0, cat: 99 }
    );
    assert_eq!(d.skipped[0].dropped, 5);

    // FSPEC that never ends: all FX bits set up to the block's end.
    let mut input = vec![48, 0, 13];
    input.extend([0xff; 10]);
    input.extend_from_slice(&good);
    let d = decode(&input);
    assert!(matches!(
        d.skipped[0].error,
        DecodeError::FspecUnterminated {
            offset: 3,
            cat: 48,
            max: 4
        }
    ));
    assert_eq!(d.records.len(), 2, "the next block is kept");

    // LEN that overstates the input: records present still decoded, lie reported.
    let mut lie = good.clone();
    lie[1] = 0x01;
    let d = decode(&lie);
    assert_eq!(d.records.len(), 2);
    assert!(matches!(
        d.skipped[0].error,
        DecodeError::BlockLengthExceedsInput { offset: 0, .. }
    ));

    // LEN below the header.
    let d = decode(&[48, 0, 2, 0, 0]);
    assert!(matches!(
        d.skipped[0].error,
        DecodeError::BlockLengthTooShort {
            offset: 0,
            declared: 2
        }
    ));

    // Truncated in I048/040 of the first record: item named, offset of the item.
    let cut = &good[..12];
    let d = decode(cut);
    let e = d
        .skipped
        .iter()
        .find(|s| matches!(s.error, DecodeError::ItemOverrun { .. }))
        .unwrap();
    assert_eq!(e.error.offset(), 3 + 2 + 2 + 3 + 1);
    assert_eq!(
        e.error.item().map(|i| i.to_string()),
        Some("I048/040".to_string())
    );

    // Explicit length 0 in SP: item named, record framing lost for the block.
    // FSPEC: FRN 27 only (three empty octets with FX, then 0x04); SP LEN 0 at byte 7.
    let d = decode(&[48, 0, 8, 0x01, 0x01, 0x01, 0x04, 0x00]);
    assert_eq!(d.skipped.len(), 1);
    assert_eq!(d.skipped[0].error.offset(), 7);
    assert_eq!(
        d.skipped[0].error.item().map(|i| i.to_string()),
        Some("I048/SP".to_string())
    );

    // Empty FSPEC: skipped alone, the next record is kept.
    let d = decode(&[48, 0, 7, 0x00, 0x80, 1, 2]);
    assert_eq!(d.records.len(), 1);
    assert_eq!(
        d.skipped[0].error,
        DecodeError::EmptyRecord { offset: 3, cat: 48 }
    );
}

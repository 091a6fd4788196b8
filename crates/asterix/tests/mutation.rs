//! Seeded mutation test: random byte flips, truncations and length lies over
//! encoded CAT048 / CAT034 / CAT062 samples never panic, always terminate, and every
//! skip is typed with an offset inside the input. Reduced count here (10⁴
//! mutated inputs of ~20 records each); the full ≥ 10⁶-record run is the same
//! loop with a larger count.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use argus_asterix::{
    Azimuth16, Cartesian062, CartesianPosition, Cat034, Cat048, Cat062, DataSource, DecodeError,
    FlightLevel, MeasuredPolar, MessageType, Mode3A, PolarVelocity, ReportDescriptor,
    RotationPeriod, Sector, TimeOfDay, TrackStatus, Velocity062, Wgs84Position, decode,
    encode_block,
};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Two CAT048 blocks and one CAT034 block with every encodable item, some
/// extensions present, plus a block of an unknown category.
fn samples() -> Vec<u8> {
    let full = |i: u16| Cat048 {
        source: Some(DataSource { sac: 25, sic: 201 }),
        time: Some(TimeOfDay(5_529_664 + u32::from(i))),
        descriptor: Some(ReportDescriptor {
            typ: 5,
            spi: i.is_multiple_of(2),
            extension: i.is_multiple_of(3).then_some(0x40),
            ..ReportDescriptor::default()
        }),
        polar: Some(MeasuredPolar {
            rho: 1000 + i * 37,
            theta: Azimuth16(i.wrapping_mul(911)),
        }),
        mode3a: Some(Mode3A {
            code: 0o1234,
            ..Mode3A::default()
        }),
        flight_level: Some(FlightLevel {
            quarter_fl: 1400 - i16::try_from(i).unwrap_or(0),
            ..FlightLevel::default()
        }),
        aircraft_address: Some(0x4c_a123 + u32::from(i)),
        track_number: Some(i),
        cartesian: Some(CartesianPosition { x: -1280, y: 2560 }),
        velocity: Some(PolarVelocity {
            groundspeed: 2048,
            heading: Azimuth16(32768),
        }),
        track_status: Some(TrackStatus {
            rad: 2,
            cdm: 1,
            extension: (!i.is_multiple_of(2)).then_some(0x40),
            ..TrackStatus::default()
        }),
    };
    let plots: Vec<Cat048> = (0..12).map(full).collect();
    let sparse: Vec<Cat048> = (0..6)
        .map(|i| Cat048 {
            source: Some(DataSource { sac: 1, sic: 2 }),
            polar: full(i).polar,
            ..Cat048::default()
        })
        .collect();
    let service = [
        Cat034 {
            source: Some(DataSource { sac: 25, sic: 201 }),
            message_type: Some(MessageType::NorthMarker),
            time: Some(TimeOfDay(128)),
            rotation_period: Some(RotationPeriod(512)),
            ..Cat034::default()
        },
        Cat034 {
            source: Some(DataSource { sac: 25, sic: 201 }),
            message_type: Some(MessageType::SectorCrossing),
            time: Some(TimeOfDay(320)),
            sector: Some(Sector(64)),
            ..Cat034::default()
        },
    ];
    let mut b = Vec::new();
    encode_block(&plots, &mut b).unwrap();
    encode_block(&service, &mut b).unwrap();
    b.extend_from_slice(&[99, 0, 6, 1, 2, 3]);
    encode_block(&sparse, &mut b).unwrap();
    let tracks: Vec<Cat062> = (0..4)
        .map(|i| Cat062 {
            source: Some(DataSource { sac: 7, sic: 8 }),
            time: Some(TimeOfDay(1000 + i)),
            wgs84: Some(Wgs84Position {
                lat: 8_388_608,
                lon: -16_777_216,
            }),
            cartesian: Some(Cartesian062 { x: -2000, y: 1001 }),
            velocity: Some(Velocity062 { vx: 400, vy: -200 }),
            track_number: Some(u16::try_from(i).unwrap_or(0)),
        })
        .collect();
    encode_block(&tracks, &mut b).unwrap();
    b
}

#[test]
fn mutated_inputs_never_panic_and_every_skip_is_typed() {
    let base = samples();
    let clean = decode(&base);
    assert_eq!(clean.records.len(), 24);
    assert_eq!(clean.skipped.len(), 1, "only the unknown category");

    let mut rng = ChaCha8Rng::seed_from_u64(0x00a5_7e41);
    let mut skips = 0usize;
    let mut records = 0usize;
    for _ in 0..10_000 {
        let mut m = base.clone();
        match rng.random_range(0..4u8) {
            // 1–4 random byte flips.
            0 => {
                for _ in 0..rng.random_range(1..=4) {
                    let i = rng.random_range(0..m.len());
                    m[i] ^= rng.random_range(1..=255u8);
                }
            }
            // Truncation anywhere.
            1 => m.truncate(rng.random_range(0..m.len())),
            // A block length that lies (first block's LEN).
            2 => {
                let lie: u16 = rng.random();
                m[1..3].copy_from_slice(&lie.to_be_bytes());
            }
            // An FSPEC chain that never ends: FX bits forced on from a random point.
            _ => {
                let i = rng.random_range(3..m.len());
                for b in &mut m[i..(i + rng.random_range(1..8)).min(base.len())] {
                    *b |= 1;
                }
            }
        }
        let d = decode(&m);
        // Each record consumes ≥ 2 bytes (FSPEC + one item): termination bound.
        assert!(d.records.len() <= m.len() / 2 + 1);
        let dropped: usize = d.skipped.iter().map(|s| s.dropped).sum();
        assert!(dropped <= m.len());
        for s in &d.skipped {
            assert!(
                s.error.offset() <= m.len(),
                "{:?} beyond {}",
                s.error,
                m.len()
            );
            // Item errors name an item of a known category (a flipped CAT byte may land on 21).
            if let DecodeError::ItemOverrun { item, .. } | DecodeError::InvalidItem { item, .. } =
                s.error
            {
                assert!(matches!(item.cat, 21 | 34 | 48 | 62));
            }
            assert!(!s.error.to_string().is_empty());
        }
        skips += d.skipped.len();
        records += d.records.len();
    }
    eprintln!("mutation: {skips} skips, {records} records kept over 10^4 inputs");
    // The mutations must actually be exercised: most inputs produce a skip
    // beyond the clean one, and most records survive (the rest of a block or
    // the next block is kept).
    assert!(skips > 15_000, "skips {skips}");
    assert!(records > 50_000, "records {records}");
}

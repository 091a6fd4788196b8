//! Encode → decode is the identity for every field written (proptest), and the
//! SI conversions round to within half an LSB.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use argus_asterix::{
    Azimuth16, CartesianPosition, Cat034, Cat048, DataSource, FlightLevel, MeasuredPolar,
    MessageType, Mode3A, PolarVelocity, Record, ReportDescriptor, RotationPeriod, Sector,
    TimeOfDay, TrackStatus, decode, encode_block,
};
use proptest::option::of;
use proptest::prelude::*;

fn source() -> impl Strategy<Value = DataSource> {
    (any::<u8>(), any::<u8>()).prop_map(|(sac, sic)| DataSource { sac, sic })
}

fn time() -> impl Strategy<Value = TimeOfDay> {
    (0u32..1 << 24).prop_map(TimeOfDay)
}

/// Extension octets as the decoder returns them: FX cleared.
fn ext() -> impl Strategy<Value = Option<u8>> {
    of(any::<u8>().prop_map(|e| e & 0xfe))
}

fn cat048() -> impl Strategy<Value = Cat048> {
    let descriptor =
        (0u8..8, any::<[bool; 4]>(), ext()).prop_map(|(typ, f, extension)| ReportDescriptor {
            typ,
            sim: f[0],
            rdp: f[1],
            spi: f[2],
            rab: f[3],
            extension,
        });
    let polar = (any::<u16>(), any::<u16>()).prop_map(|(rho, t)| MeasuredPolar {
        rho,
        theta: Azimuth16(t),
    });
    let mode3a = (any::<[bool; 3]>(), 0u16..0o10000).prop_map(|(f, code)| Mode3A {
        not_validated: f[0],
        garbled: f[1],
        not_extracted: f[2],
        code,
    });
    let fl = (any::<[bool; 2]>(), -8192i16..8192).prop_map(|(f, quarter_fl)| FlightLevel {
        not_validated: f[0],
        garbled: f[1],
        quarter_fl,
    });
    let cart = (any::<i16>(), any::<i16>()).prop_map(|(x, y)| CartesianPosition { x, y });
    let vel = (any::<u16>(), any::<u16>()).prop_map(|(g, h)| PolarVelocity {
        groundspeed: g,
        heading: Azimuth16(h),
    });
    let status =
        (any::<[bool; 3]>(), 0u8..4, 0u8..4, ext()).prop_map(|(f, rad, cdm, extension)| {
            TrackStatus {
                tentative: f[0],
                rad,
                doubtful: f[1],
                manoeuvre: f[2],
                cdm,
                extension,
            }
        });
    (
        (
            of(source()),
            of(time()),
            of(descriptor),
            of(polar),
            of(mode3a),
            of(fl),
        ),
        (
            of(0u32..1 << 24),
            of(0u16..4096),
            of(cart),
            of(vel),
            of(status),
        ),
    )
        .prop_map(|((s, t, d, p, m, f), (a, n, c, v, st))| Cat048 {
            source: s,
            time: t,
            descriptor: d,
            polar: p,
            mode3a: m,
            flight_level: f,
            aircraft_address: a,
            track_number: n,
            cartesian: c,
            velocity: v,
            track_status: st,
        })
        // A record with no item is not a record (EmptyRecord on decode).
        .prop_filter("at least one item", |r| *r != Cat048::default())
}

fn cat034() -> impl Strategy<Value = Cat034> {
    (
        of(source()),
        of(any::<u8>().prop_map(MessageType::from_code)),
        of(time()),
        of(any::<u8>().prop_map(Sector)),
        of(any::<u16>().prop_map(RotationPeriod)),
    )
        .prop_map(
            |(source, message_type, time, sector, rotation_period)| Cat034 {
                source,
                message_type,
                time,
                sector,
                rotation_period,
            },
        )
        .prop_filter("at least one item", |r| *r != Cat034::default())
}

proptest! {
    #[test]
    fn cat048_round_trip(records in proptest::collection::vec(cat048(), 1..20)) {
        let mut bytes = Vec::new();
        encode_block(&records, &mut bytes).unwrap();
        let d = decode(&bytes);
        prop_assert!(d.skipped.is_empty(), "{:?}", d.skipped);
        let back: Vec<Cat048> = d.records.into_iter()
            .filter_map(|r| if let Record::Cat048(c) = r { Some(c) } else { None })
            .collect();
        prop_assert_eq!(back, records);
    }

    #[test]
    fn cat034_round_trip(records in proptest::collection::vec(cat034(), 1..20)) {
        let mut bytes = Vec::new();
        encode_block(&records, &mut bytes).unwrap();
        let d = decode(&bytes);
        prop_assert!(d.skipped.is_empty(), "{:?}", d.skipped);
        let back: Vec<Cat034> = d.records.into_iter()
            .filter_map(|r| if let Record::Cat034(c) = r { Some(c) } else { None })
            .collect();
        prop_assert_eq!(back, records);
    }

    /// Range and Argus azimuth survive quantisation within half an LSB.
    #[test]
    fn polar_si_round_trip(range in 0.0f64..235_000.0, az in -std::f64::consts::PI..std::f64::consts::PI) {
        let p = MeasuredPolar::from_range_azimuth(range, az).unwrap();
        // Half an LSB of each field: 1852/512 m, π/2^16 rad; plus float slack.
        prop_assert!((p.range_m() - range).abs() <= MeasuredPolar::RHO_LSB_M / 2.0 + 1e-9);
        let d = argus_sensors::wrap_angle(p.theta.argus() - az);
        prop_assert!(d.abs() <= std::f64::consts::PI / 65536.0 + 1e-12);
    }

    #[test]
    fn time_si_round_trip(t in 0.0f64..131_071.99) {
        let q = TimeOfDay::from_seconds(argus_asterix::ItemId { cat: 48, name: "140" }, t).unwrap();
        // Half of 1/128 s.
        prop_assert!((q.seconds() - t).abs() <= 1.0 / 256.0 + 1e-9);
    }
}

#[test]
fn out_of_range_encodes_are_typed() {
    assert!(MeasuredPolar::from_range_azimuth(-1.0, 0.0).is_err());
    assert!(MeasuredPolar::from_range_azimuth(1e6, 0.0).is_err());
    assert!(MeasuredPolar::from_range_azimuth(f64::NAN, 0.0).is_err());
    assert!(MeasuredPolar::from_range_azimuth(1.0, f64::INFINITY).is_err());
    assert!(RotationPeriod::from_seconds(-0.1).is_err());
    // 2^24/128 s = 131 072 s does not fit 24 bits.
    assert!(
        TimeOfDay::from_seconds(
            argus_asterix::ItemId {
                cat: 34,
                name: "030"
            },
            131_072.0
        )
        .is_err()
    );
    let bad = Cat048 {
        flight_level: Some(FlightLevel {
            quarter_fl: 9000,
            ..FlightLevel::default()
        }),
        ..Cat048::default()
    };
    assert!(encode_block(&[bad], &mut Vec::new()).is_err());
}

#[test]
fn compass_points_in_argus_convention() {
    // θ = 0 (north) → π/2; θ = 2^15 (180°, south) → −π/2; θ = 3·2^14 (270°, west) → π.
    use std::f64::consts::{FRAC_PI_2, PI};
    assert!((Azimuth16(0).argus() - FRAC_PI_2).abs() < 1e-15);
    assert!((Azimuth16(32768).argus() + FRAC_PI_2).abs() < 1e-15);
    assert!((Azimuth16(49152).argus() - PI).abs() < 1e-15);
    let id = argus_asterix::ItemId {
        cat: 48,
        name: "040",
    };
    assert_eq!(Azimuth16::from_argus(id, 0.0).unwrap(), Azimuth16(16384));
    // Just below north wraps to 0, not 65536.
    assert_eq!(
        Azimuth16::from_argus(id, FRAC_PI_2 + 1e-9).unwrap(),
        Azimuth16(0)
    );
}

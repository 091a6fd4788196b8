//! Argus-written sample blocks of every category this crate encodes (CAT048,
//! CAT034, CAT021, CAT062) plus one block of an unknown category: the input
//! of the mutation runs and of the cross-check with an independent decoder.
//! Every item Argus writes appears, with and without its optional extensions.

use crate::adsb_quality::{Quality, QualityExt};
use crate::block::encode_block;
use crate::cat021::{Cat021, LatLon};
use crate::cat034::{Cat034, MessageType, RotationPeriod, Sector};
use crate::cat048::{
    CartesianPosition, Cat048, FlightLevel, MeasuredPolar, Mode3A, PolarVelocity, ReportDescriptor,
    TrackStatus,
};
use crate::cat062::{Cartesian062, Cat062, Velocity062, Wgs84Position};
use crate::error::EncodeError;
use crate::fields::{Azimuth16, DataSource, TimeOfDay};

/// Records in [`all_categories`], by category: (48, 34, 21, 62).
pub const RECORDS: (usize, usize, usize, usize) = (18, 2, 6, 4);

fn plot(i: u16) -> Cat048 {
    Cat048 {
        source: Some(DataSource { sac: 25, sic: 201 }),
        time: Some(TimeOfDay(5_529_664 + u32::from(i))),
        descriptor: Some(ReportDescriptor {
            typ: 5,
            spi: i.is_multiple_of(2),
            extension: i.is_multiple_of(3).then_some(0x94),
            ..ReportDescriptor::default()
        }),
        polar: Some(MeasuredPolar {
            rho: 1000 + i * 37,
            theta: Azimuth16(i.wrapping_mul(911)),
        }),
        mode3a: Some(Mode3A {
            code: 0o1234 + i,
            garbled: i.is_multiple_of(5),
            ..Mode3A::default()
        }),
        flight_level: Some(FlightLevel {
            quarter_fl: 1400 - i16::try_from(i).unwrap_or(0) * 300,
            ..FlightLevel::default()
        }),
        aircraft_address: Some(0x4c_a123 + u32::from(i)),
        track_number: Some(i * 311),
        cartesian: Some(CartesianPosition {
            x: -1280 + i16::try_from(i).unwrap_or(0) * 97,
            y: 2560,
        }),
        velocity: Some(PolarVelocity {
            groundspeed: 2048 + i * 13,
            heading: Azimuth16(32768u16.wrapping_add(i * 1000)),
        }),
        track_status: Some(TrackStatus {
            rad: 2,
            cdm: u8::try_from(i % 4).unwrap_or(0),
            manoeuvre: i.is_multiple_of(4),
            extension: (!i.is_multiple_of(2)).then_some(0xa0),
            ..TrackStatus::default()
        }),
    }
}

fn adsb(i: u32) -> Cat021 {
    // Positions on the items' grids (counts of 180/2^23 ° and 180/2^30 °),
    // either side of the equator and the prime meridian.
    let k = i32::try_from(i).unwrap_or(0);
    Cat021 {
        source: Some(DataSource { sac: 7, sic: 21 }),
        t_position: Some(TimeOfDay(4_000_000 + i * 3)),
        position: Some(LatLon {
            lat_deg: f64::from(2_000_000 - 900_000 * k) * LatLon::LSB_130_DEG,
            lon_deg: f64::from(-7_000_000 + 2_800_000 * k) * LatLon::LSB_130_DEG,
        }),
        position_hr: (i != 2).then(|| LatLon {
            lat_deg: f64::from(400_000_000 - 150_000_000 * k) * LatLon::LSB_131_DEG,
            lon_deg: f64::from(-1_000_000_000 + 390_000_001 * k) * LatLon::LSB_131_DEG,
        }),
        t_velocity: Some(TimeOfDay(4_000_001 + i * 3)),
        target_address: Some(0x3c_0000 + i * 0x1111),
        t_rx_position: Some(TimeOfDay(4_000_002 + i * 3)),
        t_rx_velocity: (i != 1).then_some(TimeOfDay(4_000_003 + i * 3)),
        quality: Some(Quality {
            nac_v: u8::try_from(i % 5).unwrap_or(0),
            nic: u8::try_from(6 + i).unwrap_or(0),
            extension: (i != 3).then(|| QualityExt {
                nic_baro: i.is_multiple_of(2),
                sil: u8::try_from(i % 4).unwrap_or(0),
                nac_p: u8::try_from(7 + i).unwrap_or(0),
            }),
        }),
        t_report: Some(TimeOfDay(4_000_010 + i * 3)),
    }
}

/// The Argus-written samples as one raw block stream: two CAT048 blocks (12
/// full reports, 6 sparse ones), a CAT034 block (north marker, sector
/// crossing), an unknown-category block (99), a CAT021 block, a CAT062 block.
///
/// # Errors
/// Never in practice; an [`EncodeError`] would mean a sample value is out of range.
pub fn all_categories() -> Result<Vec<u8>, EncodeError> {
    let plots: Vec<Cat048> = (0..12).map(plot).collect();
    let sparse: Vec<Cat048> = (0..6)
        .map(|i| Cat048 {
            source: Some(DataSource { sac: 1, sic: 2 }),
            polar: plot(i).polar,
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
    let reports: Vec<Cat021> = (0..6).map(adsb).collect();
    let tracks: Vec<Cat062> = (0..4)
        .map(|i: i32| Cat062 {
            source: Some(DataSource { sac: 7, sic: 8 }),
            time: Some(TimeOfDay(1000 + i.unsigned_abs())),
            wgs84: Some(Wgs84Position {
                lat: 8_388_608 - i * 1_000_003,
                lon: -16_777_216 + i * 7_000_001,
            }),
            cartesian: Some(Cartesian062 {
                x: -2000 - i * 1_000_000,
                y: 1001 + i * 999,
            }),
            velocity: Some(Velocity062 {
                vx: 400 - 300 * i16::try_from(i).unwrap_or(0),
                vy: -200,
            }),
            track_number: Some(u16::try_from(i).unwrap_or(0) * 4000),
        })
        .collect();
    let mut b = Vec::new();
    encode_block(&plots, &mut b)?;
    encode_block(&service, &mut b)?;
    b.extend_from_slice(&[99, 0, 6, 1, 2, 3]);
    encode_block(&sparse, &mut b)?;
    encode_block(&reports, &mut b)?;
    encode_block(&tracks, &mut b)?;
    Ok(b)
}

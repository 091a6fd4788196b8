//! ASTERIX decode: 200 full CAT048 target reports (every decoded item, ~31
//! bytes each) in one data block, and 200 CAT021 ADS-B reports (every
//! decoded item, ~44 bytes each); throughput in records per second (goal
//! ≥ 10⁶ CAT048 records/s on one core).
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use std::hint::black_box;

use argus_asterix::{
    Azimuth16, CartesianPosition, Cat021, Cat048, DataSource, FlightLevel, LatLon, MeasuredPolar,
    Mode3A, PolarVelocity, Quality, QualityExt, ReportDescriptor, TimeOfDay, TrackStatus, decode,
    encode_block,
};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};

const N: u16 = 200;

fn block() -> Vec<u8> {
    let plots: Vec<Cat048> = (0..N)
        .map(|i| Cat048 {
            source: Some(DataSource { sac: 25, sic: 201 }),
            time: Some(TimeOfDay(5_529_664 + u32::from(i))),
            descriptor: Some(ReportDescriptor {
                typ: 5,
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
                quarter_fl: 1400,
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
                ..TrackStatus::default()
            }),
        })
        .collect();
    let mut b = Vec::new();
    encode_block(&plots, &mut b).unwrap();
    b
}

fn cat048_decode(c: &mut Criterion) {
    let bytes = block();
    assert_eq!(decode(&bytes).records.len(), usize::from(N));
    let mut group = c.benchmark_group("asterix");
    group.throughput(Throughput::Elements(u64::from(N)));
    group.bench_function("cat048_decode", |b| b.iter(|| decode(black_box(&bytes))));
    group.finish();
}

fn adsb_block() -> Vec<u8> {
    let reports: Vec<Cat021> = (0..u32::from(N))
        .map(|i| {
            let t = Some(TimeOfDay(4_000_000 + i));
            let lat = f64::from(i) * 1e-3 + 48.0;
            Cat021 {
                source: Some(DataSource { sac: 7, sic: 21 }),
                position: Some(LatLon {
                    lat_deg: lat,
                    lon_deg: 2.5,
                }),
                position_hr: Some(LatLon {
                    lat_deg: lat,
                    lon_deg: 2.5,
                }),
                t_position: t,
                t_velocity: t,
                t_rx_position: t,
                t_rx_velocity: t,
                t_report: t,
                target_address: Some(0x39_0000 + i),
                quality: Some(Quality {
                    nac_v: 2,
                    nic: 8,
                    extension: Some(QualityExt {
                        nic_baro: true,
                        sil: 3,
                        nac_p: 9,
                    }),
                }),
            }
        })
        .collect();
    let mut b = Vec::new();
    encode_block(&reports, &mut b).unwrap();
    b
}

fn cat021_decode(c: &mut Criterion) {
    let bytes = adsb_block();
    assert_eq!(decode(&bytes).records.len(), usize::from(N));
    let mut group = c.benchmark_group("asterix");
    group.throughput(Throughput::Elements(u64::from(N)));
    group.bench_function("cat021_decode", |b| b.iter(|| decode(black_box(&bytes))));
    group.finish();
}

criterion_group!(benches, cat048_decode, cat021_decode);
criterion_main!(benches);

//! CAT021 (ed. 2.1): a hand-built vector from the LSBs, encode → decode identity
//! for every field written, and the encoder's range checks.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use argus_asterix::{
    Cat021, DataSource, EncodeError, LatLon, Quality, QualityExt, Record, TimeOfDay, decode,
    encode_block,
};
use proptest::option::of;
use proptest::prelude::*;

#[test]
fn cat021_values_from_lsbs() {
    let block: &[u8] = &[
        21, 0, 37, //
        // FSPEC: FRN 1, 5, 6, 7 → 0x8e|FX; FRN 11, 12 → 0x18|FX; FRN 17 → 0x20|FX; FRN 28 → 0x02.
        0x8f, 0x19, 0x21, 0x02, //
        0x00, 0x01, // I021/010
        0x00, 0x01, 0x00, // I021/071 2 s × 128 = 256
        0x20, 0x00, 0x00, 0xc0, 0x00,
        0x00, // I021/130 45° × 2^23/180 = 2^21; −90° = −2^22
        0x10, 0x00, 0x00, 0x00, 0xe0, 0x00, 0x00,
        0x00, // I021/131 2^28; −2^29 (LSB 180/2^30)
        0xab, 0xcd, 0xef, // I021/080
        0x00, 0x01, 0x80, // I021/073 3 s = 384
        0x51, 0xf2, // I021/090 NACv 2, NIC 8 | FX; NIC BARO, SIL 3, NACp 9
        0x00, 0x02, 0x00, // I021/077 4 s = 512
    ];
    let d = decode(block);
    assert!(d.skipped.is_empty(), "{:?}", d.skipped);
    let Some(Record::Cat021(r)) = d.records.first().cloned() else {
        panic!("no CAT021 record")
    };
    assert_eq!(r.t_position, Some(TimeOfDay(256)));
    // Exact: dyadic LSBs.
    let p = r.position.unwrap();
    assert!((p.lat_deg - 45.0).abs() < 1e-12 && (p.lon_deg + 90.0).abs() < 1e-12);
    let h = r.position_hr.unwrap();
    assert!((h.lat_deg - 45.0).abs() < 1e-12 && (h.lon_deg + 90.0).abs() < 1e-12);
    assert_eq!(r.target_address, Some(0xab_cdef));
    assert_eq!(r.t_rx_position, Some(TimeOfDay(384)));
    assert_eq!(r.t_report, Some(TimeOfDay(512)));
    let q = r.quality.unwrap();
    assert_eq!((q.nac_v, q.nic), (2, 8));
    let e = q.extension.unwrap();
    assert_eq!((e.nic_baro, e.sil, e.nac_p), (true, 3, 9));
    // Encoding it back gives the same bytes (every item here is one Argus writes).
    let mut again = Vec::new();
    encode_block(&[r], &mut again).unwrap();
    assert_eq!(again, block);
}

fn time() -> impl Strategy<Value = TimeOfDay> {
    (0u32..1 << 24).prop_map(TimeOfDay)
}

/// A position on the item's grid (LSB 180/2^pow °: 23 for /130, 30 for /131):
/// counts × LSB, as the decoder returns it.
fn on_grid(pow: u32) -> impl Strategy<Value = LatLon> {
    let half = 1i64 << pow;
    let lsb = 180.0 / f64::from(1u32 << pow);
    (-half / 2..=half / 2, -half..half).prop_map(move |(la, lo)| {
        // |counts| ≤ 2^31: exact in f64.
        #[allow(clippy::cast_precision_loss)]
        LatLon {
            lat_deg: la as f64 * lsb,
            lon_deg: lo as f64 * lsb,
        }
    })
}

fn cat021() -> impl Strategy<Value = Cat021> {
    let source = (any::<u8>(), any::<u8>()).prop_map(|(sac, sic)| DataSource { sac, sic });
    let quality =
        (0u8..8, 0u8..16, of((any::<bool>(), 0u8..4, 0u8..16))).prop_map(|(nac_v, nic, ext)| {
            Quality {
                nac_v,
                nic,
                extension: ext.map(|(nic_baro, sil, nac_p)| QualityExt {
                    nic_baro,
                    sil,
                    nac_p,
                }),
            }
        });
    (
        (of(source), of(on_grid(23)), of(on_grid(30))),
        (of(time()), of(time()), of(time()), of(time()), of(time())),
        (of(0u32..1 << 24), of(quality)),
    )
        .prop_map(
            |((source, position, position_hr), (t0, t1, t2, t3, t4), (target_address, quality))| {
                Cat021 {
                    source,
                    position,
                    position_hr,
                    t_position: t0,
                    t_velocity: t1,
                    t_rx_position: t2,
                    t_rx_velocity: t3,
                    t_report: t4,
                    target_address,
                    quality,
                }
            },
        )
}

proptest! {
    #[test]
    fn cat021_round_trip_is_identity(records in prop::collection::vec(cat021(), 1..8)) {
        // An all-`None` record has an empty FSPEC, which the decoder skips by rule.
        let records: Vec<Cat021> = records
            .into_iter()
            .map(|r| if r == Cat021::default() { Cat021 { target_address: Some(1), ..r } } else { r })
            .collect();
        let mut bytes = Vec::new();
        encode_block(&records, &mut bytes).unwrap();
        let d = decode(&bytes);
        prop_assert!(d.skipped.is_empty(), "{:?}", d.skipped);
        let back: Vec<Cat021> = d
            .records
            .into_iter()
            .map(|r| match r {
                Record::Cat021(c) => c,
                other => panic!("not CAT021: {other:?}"),
            })
            .collect();
        // Exact: on-grid positions are dyadic rationals, the rest integers.
        prop_assert_eq!(back, records);
    }

    #[test]
    fn cat021_position_within_half_an_lsb(lat in -90.0f64..=90.0, lon in -180.0f64..180.0) {
        let r = Cat021 {
            position: Some(LatLon { lat_deg: lat, lon_deg: lon }),
            position_hr: Some(LatLon { lat_deg: lat, lon_deg: lon }),
            ..Cat021::default()
        };
        let mut bytes = Vec::new();
        encode_block(&[r], &mut bytes).unwrap();
        let Some(Record::Cat021(b)) = decode(&bytes).records.first().cloned() else {
            panic!("no record")
        };
        // Half an LSB (rounding to nearest), plus 1e-9 for the f64 arithmetic;
        // longitude compared modulo 360° (180° is written as −180°).
        for (p, lsb) in [(b.position.unwrap(), LatLon::LSB_130_DEG), (b.position_hr.unwrap(), LatLon::LSB_131_DEG)] {
            prop_assert!((p.lat_deg - lat).abs() <= lsb / 2.0 + 1e-9);
            let dlon = (p.lon_deg - lon + 540.0).rem_euclid(360.0) - 180.0;
            prop_assert!(dlon.abs() <= lsb / 2.0 + 1e-9);
        }
    }
}

#[test]
fn cat021_encoder_refuses_what_does_not_fit() {
    let bad = [
        Cat021 {
            position: Some(LatLon {
                lat_deg: 90.5,
                lon_deg: 0.0,
            }),
            ..Cat021::default()
        },
        Cat021 {
            position_hr: Some(LatLon {
                lat_deg: 0.0,
                lon_deg: f64::NAN,
            }),
            ..Cat021::default()
        },
        Cat021 {
            target_address: Some(1 << 24),
            ..Cat021::default()
        },
    ];
    for r in bad {
        let e = encode_block(&[r], &mut Vec::new()).unwrap_err();
        assert!(
            matches!(e, EncodeError::OutOfRange { item, .. } if item.cat == 21),
            "{e}"
        );
    }
    // 180° E is −180°: the same meridian, and the top count does not overflow.
    let r = Cat021 {
        position: Some(LatLon {
            lat_deg: 0.0,
            lon_deg: 180.0,
        }),
        ..Cat021::default()
    };
    let mut bytes = Vec::new();
    encode_block(&[r], &mut bytes).unwrap();
    let Some(Record::Cat021(b)) = decode(&bytes).records.first().cloned() else {
        panic!("no record")
    };
    // Exact: −180° is −2^23 counts of a dyadic LSB.
    assert!((b.position.unwrap().lon_deg + 180.0).abs() < 1e-12);
}

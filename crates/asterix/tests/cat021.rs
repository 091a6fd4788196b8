//! CAT021 (ed. 2.1) decode: a hand-built vector from the LSBs.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use argus_asterix::{Cat021, Record, TimeOfDay, decode, encode_block};

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
    // Decode only: encoding is a typed error, not an empty record.
    assert!(encode_block(&[Cat021::default()], &mut Vec::new()).is_err());
}

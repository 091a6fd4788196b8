//! CAT021 ADS-B target reports (EUROCONTROL ASTERIX Part 12 Category 021,
//! edition 2.1), decode only.
//!
//! Decoded: I021/010, /130, /131, /071, /072, /073, /075, /077, /080, /090
//! (NUCr/NACv, NUCp/NIC and, when present, the first extension's NIC BARO,
//! SIL, NACp). Every other item is skipped by its length rule.

use crate::error::EncodeError;
use crate::fields::{DataSource, TimeOfDay};
use crate::record::{Category, RecordWriter};
use crate::uap::{Format, Uap, UapSlot};

const F1: Option<Format> = Some(Format::Fixed(1));
const F2: Option<Format> = Some(Format::Fixed(2));
const X1: Format = Format::Extended { first: 1, ext: 1 };

/// I021/220 met information: WS, WD, TMP (2 octets), TRB (1).
const I220: &[Option<Format>] = &[F2, F2, F2, F1];
/// I021/110 trajectory intent: TIS (extended), TID (repetitive, 15 octets).
const I110: &[Option<Format>] = &[Some(X1), Some(Format::Repetitive(15))];
/// I021/295 data ages: 23 one-octet subfields.
const I295: &[Option<Format>] = &[F1; 23];

/// The CAT021 UAP, edition 2.1 (FRN 1–49; FRN 43–47 spare).
const SLOTS: &[UapSlot] = &[
    Some(("010", Format::Fixed(2))),
    Some(("040", X1)),
    Some(("161", Format::Fixed(2))),
    Some(("015", Format::Fixed(1))),
    Some(("071", Format::Fixed(3))),
    Some(("130", Format::Fixed(6))),
    Some(("131", Format::Fixed(8))),
    Some(("072", Format::Fixed(3))),
    Some(("150", Format::Fixed(2))),
    Some(("151", Format::Fixed(2))),
    Some(("080", Format::Fixed(3))),
    Some(("073", Format::Fixed(3))),
    Some(("074", Format::Fixed(4))),
    Some(("075", Format::Fixed(3))),
    Some(("076", Format::Fixed(4))),
    Some(("140", Format::Fixed(2))),
    Some(("090", X1)),
    Some(("210", Format::Fixed(1))),
    Some(("070", Format::Fixed(2))),
    Some(("230", Format::Fixed(2))),
    Some(("145", Format::Fixed(2))),
    Some(("152", Format::Fixed(2))),
    Some(("200", Format::Fixed(1))),
    Some(("155", Format::Fixed(2))),
    Some(("157", Format::Fixed(2))),
    Some(("160", Format::Fixed(4))),
    Some(("165", Format::Fixed(2))),
    Some(("077", Format::Fixed(3))),
    Some(("170", Format::Fixed(6))),
    Some(("020", Format::Fixed(1))),
    Some(("220", Format::Compound(I220))),
    Some(("146", Format::Fixed(2))),
    Some(("148", Format::Fixed(2))),
    Some(("110", Format::Compound(I110))),
    Some(("016", Format::Fixed(1))),
    Some(("008", Format::Fixed(1))),
    Some(("271", X1)),
    Some(("132", Format::Fixed(1))),
    Some(("250", Format::Repetitive(8))),
    Some(("260", Format::Fixed(7))),
    Some(("400", Format::Fixed(1))),
    Some(("295", Format::Compound(I295))),
    None,
    None,
    None,
    None,
    None,
    Some(("RE", Format::Explicit)),
    Some(("SP", Format::Explicit)),
];

/// I021/130 (LSB 180/2^23 °, 3 octets each) or I021/131 (LSB 180/2^30 °, 4
/// octets each) WGS-84 position, as degrees.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LatLon {
    /// Latitude, degrees.
    pub lat_deg: f64,
    /// Longitude, degrees.
    pub lon_deg: f64,
}

/// I021/090 quality indicators: the first octet and the first extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Quality {
    /// NUCr or NACv (3 bits).
    pub nac_v: u8,
    /// NUCp or NIC (4 bits).
    pub nic: u8,
    /// First extension: NIC BARO (1 bit), SIL (2 bits), NACp (4 bits).
    pub extension: Option<QualityExt>,
}

/// I021/090 first extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct QualityExt {
    /// NIC BARO.
    pub nic_baro: bool,
    /// SIL.
    pub sil: u8,
    /// NACp.
    pub nac_p: u8,
}

/// A CAT021 ADS-B report: the decoded items, each `None` when absent.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Cat021 {
    /// I021/010.
    pub source: Option<DataSource>,
    /// I021/130 position.
    pub position: Option<LatLon>,
    /// I021/131 high-resolution position.
    pub position_hr: Option<LatLon>,
    /// I021/071 time of applicability for position.
    pub t_position: Option<TimeOfDay>,
    /// I021/072 time of applicability for velocity.
    pub t_velocity: Option<TimeOfDay>,
    /// I021/073 time of message reception for position.
    pub t_rx_position: Option<TimeOfDay>,
    /// I021/075 time of message reception for velocity.
    pub t_rx_velocity: Option<TimeOfDay>,
    /// I021/077 time of report transmission.
    pub t_report: Option<TimeOfDay>,
    /// I021/080 24-bit target address.
    pub target_address: Option<u32>,
    /// I021/090.
    pub quality: Option<Quality>,
}

fn signed(b: &[u8]) -> f64 {
    // Big-endian two's complement of 3 or 4 octets, sign-extended via the top byte.
    let mut v = i64::from(b[0] as i8);
    for &x in &b[1..] {
        v = (v << 8) | i64::from(x);
    }
    // |v| < 2^31: exact in f64.
    #[allow(clippy::cast_precision_loss)]
    let f = v as f64;
    f
}

impl Category for Cat021 {
    const UAP: Uap = Uap {
        cat: 21,
        slots: SLOTS,
    };

    fn decode_item(&mut self, frn: usize, b: &[u8]) -> Result<(), &'static str> {
        let lsb23 = 180.0 / f64::from(1u32 << 23);
        let lsb30 = 180.0 / f64::from(1u32 << 30);
        match frn {
            1 => {
                self.source = Some(DataSource {
                    sac: b[0],
                    sic: b[1],
                })
            }
            5 => self.t_position = Some(TimeOfDay::read(b)),
            6 => {
                self.position = Some(LatLon {
                    lat_deg: signed(&b[0..3]) * lsb23,
                    lon_deg: signed(&b[3..6]) * lsb23,
                });
            }
            7 => {
                self.position_hr = Some(LatLon {
                    lat_deg: signed(&b[0..4]) * lsb30,
                    lon_deg: signed(&b[4..8]) * lsb30,
                });
            }
            8 => self.t_velocity = Some(TimeOfDay::read(b)),
            11 => self.target_address = Some(u32::from_be_bytes([0, b[0], b[1], b[2]])),
            12 => self.t_rx_position = Some(TimeOfDay::read(b)),
            14 => self.t_rx_velocity = Some(TimeOfDay::read(b)),
            17 => {
                self.quality = Some(Quality {
                    nac_v: b[0] >> 5,
                    nic: (b[0] >> 1) & 0x0f,
                    extension: b.get(1).map(|e| QualityExt {
                        nic_baro: e & 0x80 != 0,
                        sil: (e >> 5) & 3,
                        nac_p: (e >> 1) & 0x0f,
                    }),
                });
            }
            28 => self.t_report = Some(TimeOfDay::read(b)),
            _ => {}
        }
        Ok(())
    }

    /// CAT021 is decoded only.
    fn encode_items(&self, _w: &mut RecordWriter) -> Result<(), EncodeError> {
        Err(EncodeError::Unsupported { cat: 21 })
    }
}

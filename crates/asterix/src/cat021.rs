//! CAT021 ADS-B target reports (EUROCONTROL ASTERIX Part 12 Category 021,
//! edition 2.1; the UAP is the same in edition 2.6).
//!
//! Decoded and encoded: I021/010, /071, /130, /131, /072, /080, /073, /075,
//! /090 (NUCr/NACv, NUCp/NIC and, when present, the first extension's NIC
//! BARO, SIL, NACp), /077. Every other item is skipped by its length rule.
//!
//! Times (edition 2.1): /071 time of applicability for position, /072 for
//! velocity, /073 time of message reception for position, /075 for velocity,
//! /077 time of ASTERIX report transmission; all 24-bit, LSB 1/128 s since
//! midnight UTC. The high-precision receptions /074 and /076 are skipped.

use crate::adsb_quality::Quality;
use crate::error::{EncodeError, ItemId};
use crate::fields::{DataSource, TimeOfDay, quantise};
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

impl LatLon {
    /// I021/130 LSB, degrees: 180 / 2^23.
    pub const LSB_130_DEG: f64 = 180.0 / 8_388_608.0;
    /// I021/131 LSB, degrees: 180 / 2^30.
    pub const LSB_131_DEG: f64 = 180.0 / 1_073_741_824.0;

    /// The nearest counts of 180/2^`pow` degrees (I021/130: 24-bit, pow 23;
    /// I021/131: 32-bit, pow 30). Latitude must lie in [−90°, 90°];
    /// longitude is wrapped into [−180°, 180°) (so 180° is written as −180°).
    fn counts(self, item: ItemId, pow: u32) -> Result<(i32, i32), EncodeError> {
        // 180° in counts: 2^pow (23 or 30).
        let top_count = 1i64 << pow;
        let top = f64::from(1u32 << pow);
        let lsb = 180.0 / top;
        let lat = quantise(item, "latitude", self.lat_deg, lsb, -top / 2.0, top / 2.0)?;
        if !self.lon_deg.is_finite() {
            return Err(EncodeError::OutOfRange {
                item,
                what: "longitude",
                value: self.lon_deg,
            });
        }
        let wrapped = (self.lon_deg + 180.0).rem_euclid(360.0) - 180.0;
        let lon = quantise(item, "longitude", wrapped, lsb, -top, top)?;
        // Rounding just below 180° reaches +180°, which is written as −180°.
        let lon = if lon == top_count { -lon } else { lon };
        // Both in [−2^30, 2^30] ⊂ i32 by the checks above.
        Ok((
            i32::try_from(lat).unwrap_or(0),
            i32::try_from(lon).unwrap_or(0),
        ))
    }
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

fn id(name: &'static str) -> ItemId {
    ItemId { cat: 21, name }
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
                    lat_deg: signed(&b[0..3]) * LatLon::LSB_130_DEG,
                    lon_deg: signed(&b[3..6]) * LatLon::LSB_130_DEG,
                });
            }
            7 => {
                self.position_hr = Some(LatLon {
                    lat_deg: signed(&b[0..4]) * LatLon::LSB_131_DEG,
                    lon_deg: signed(&b[4..8]) * LatLon::LSB_131_DEG,
                });
            }
            8 => self.t_velocity = Some(TimeOfDay::read(b)),
            11 => self.target_address = Some(u32::from_be_bytes([0, b[0], b[1], b[2]])),
            12 => self.t_rx_position = Some(TimeOfDay::read(b)),
            14 => self.t_rx_velocity = Some(TimeOfDay::read(b)),
            17 => self.quality = Some(Quality::read(b)),
            28 => self.t_report = Some(TimeOfDay::read(b)),
            _ => {}
        }
        Ok(())
    }

    fn encode_items(&self, w: &mut RecordWriter) -> Result<(), EncodeError> {
        if let Some(s) = self.source {
            w.put(1, &[s.sac, s.sic])?;
        }
        if let Some(t) = self.t_position {
            w.put(5, &t.bytes())?;
        }
        if let Some(p) = self.position {
            let (lat, lon) = p.counts(id("130"), 23)?;
            let (a, b) = (lat.to_be_bytes(), lon.to_be_bytes());
            w.put(6, &[a[1], a[2], a[3], b[1], b[2], b[3]])?;
        }
        if let Some(p) = self.position_hr {
            let (lat, lon) = p.counts(id("131"), 30)?;
            let (a, b) = (lat.to_be_bytes(), lon.to_be_bytes());
            w.put(7, &[a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3]])?;
        }
        if let Some(t) = self.t_velocity {
            w.put(8, &t.bytes())?;
        }
        if let Some(a) = self.target_address {
            if a > 0x00ff_ffff {
                return Err(EncodeError::OutOfRange {
                    item: id("080"),
                    what: "24-bit target address",
                    value: f64::from(a),
                });
            }
            let [_, x, y, z] = a.to_be_bytes();
            w.put(11, &[x, y, z])?;
        }
        if let Some(t) = self.t_rx_position {
            w.put(12, &t.bytes())?;
        }
        if let Some(t) = self.t_rx_velocity {
            w.put(14, &t.bytes())?;
        }
        if let Some(q) = self.quality {
            let mut b = [0u8; 2];
            let n = q.bytes(&mut b);
            w.put(17, &b[..n])?;
        }
        if let Some(t) = self.t_report {
            w.put(28, &t.bytes())?;
        }
        Ok(())
    }
}

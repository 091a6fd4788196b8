//! CAT062 system track data (EUROCONTROL ASTERIX Part 9 Category 062,
//! edition 1.18): the core items a tracker scores against.
//!
//! Decoded: I062/010, /040, /070, /100, /105, /185. Every other item of the
//! UAP is skipped by its length rule (compound items by their subfields).

use crate::error::EncodeError;
use crate::fields::{DataSource, TimeOfDay, i16_at, u16_at};
use crate::record::{Category, RecordWriter};
use crate::uap::{Format, Uap, UapSlot};

const F1: Option<Format> = Some(Format::Fixed(1));
const F2: Option<Format> = Some(Format::Fixed(2));
const F4: Option<Format> = Some(Format::Fixed(4));
const F6: Option<Format> = Some(Format::Fixed(6));
const F7: Option<Format> = Some(Format::Fixed(7));
const X1: Format = Format::Extended { first: 1, ext: 1 };

/// I062/380 aircraft derived data, subfields 1–28.
const I380: &[Option<Format>] = &[
    Some(Format::Fixed(3)),
    F6,
    F2,
    F2,
    F2,
    F2,
    F2, // ADR ID MHG IAS TAS SAL FSS
    F1,
    Some(Format::Repetitive(15)),
    F2,
    F2,
    F7,
    F2,
    F2, // TIS TID COM SAB ACS BVR GVR
    F2,
    F2,
    F2,
    F2,
    F1,
    Some(Format::Fixed(8)),
    F1, // RAN TAR TAN GSP VUN MET EMC
    F6,
    F2,
    F1,
    Some(Format::Repetitive(8)),
    F2,
    F2,
    F2, // POS GAL PUN MB IAR MAC BPS
];
/// I062/290 system track update ages, subfields 1–10.
const I290: &[Option<Format>] = &[F1, F1, F1, F1, F2, F1, F1, F1, F1, F1];
/// I062/295 track data ages: 31 one-octet subfields.
const I295: &[Option<Format>] = &[F1; 31];
/// I062/390 flight plan related data, subfields 1–18.
const I390: &[Option<Format>] = &[
    F2,
    F7,
    F4,
    F1,
    F4,
    F1,
    F4, // TAG CSN IFI FCT TAC WTC DEP
    F4,
    Some(Format::Fixed(3)),
    F2,
    F2,
    Some(Format::Repetitive(4)),
    F6,
    F1, // DST RDS CFL CTL TOD AST STS
    F7,
    F7,
    F2,
    F7, // STD STA PEM PEC
];
/// I062/110 mode 5 data, subfields 1–7.
const I110: &[Option<Format>] = &[F1, F4, F6, F2, F2, F1, F1];
/// I062/500 estimated accuracies, subfields 1–8.
const I500: &[Option<Format>] = &[F4, F2, F4, F1, F1, F2, F2, F1];
/// I062/340 measured information, subfields 1–6.
const I340: &[Option<Format>] = &[F2, F4, F2, F2, F2, F1];

/// The CAT062 UAP, edition 1.18 (FRN 1–35; FRN 2 and 29–33 spare).
const SLOTS: &[UapSlot] = &[
    Some(("010", Format::Fixed(2))),
    None,
    Some(("015", Format::Fixed(1))),
    Some(("070", Format::Fixed(3))),
    Some(("105", Format::Fixed(8))),
    Some(("100", Format::Fixed(6))),
    Some(("185", Format::Fixed(4))),
    Some(("210", Format::Fixed(2))),
    Some(("060", Format::Fixed(2))),
    Some(("245", Format::Fixed(7))),
    Some(("380", Format::Compound(I380))),
    Some(("040", Format::Fixed(2))),
    Some(("080", X1)),
    Some(("290", Format::Compound(I290))),
    Some(("200", Format::Fixed(1))),
    Some(("295", Format::Compound(I295))),
    Some(("136", Format::Fixed(2))),
    Some(("130", Format::Fixed(2))),
    Some(("135", Format::Fixed(2))),
    Some(("220", Format::Fixed(2))),
    Some(("390", Format::Compound(I390))),
    Some(("270", X1)),
    Some(("300", Format::Fixed(1))),
    Some(("110", Format::Compound(I110))),
    Some(("120", Format::Fixed(2))),
    Some(("510", Format::Extended { first: 3, ext: 3 })),
    Some(("500", Format::Compound(I500))),
    Some(("340", Format::Compound(I340))),
    None,
    None,
    None,
    None,
    None,
    Some(("RE", Format::Explicit)),
    Some(("SP", Format::Explicit)),
];

/// I062/105 calculated position in WGS-84, LSB 180/2^25 degrees.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Wgs84Position {
    /// Latitude count.
    pub lat: i32,
    /// Longitude count.
    pub lon: i32,
}

impl Wgs84Position {
    /// LSB, degrees: 180 / 2^25.
    pub const LSB_DEG: f64 = 180.0 / 33_554_432.0;

    /// (latitude, longitude) in degrees.
    #[must_use]
    pub fn degrees(self) -> (f64, f64) {
        (
            f64::from(self.lat) * Self::LSB_DEG,
            f64::from(self.lon) * Self::LSB_DEG,
        )
    }
}

/// I062/100 calculated track position (Cartesian), 24-bit signed, LSB 0.5 m.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Cartesian062 {
    /// X count (24-bit two's complement).
    pub x: i32,
    /// Y count (24-bit two's complement).
    pub y: i32,
}

impl Cartesian062 {
    /// (x, y) in metres.
    #[must_use]
    pub fn metres(self) -> (f64, f64) {
        (f64::from(self.x) * 0.5, f64::from(self.y) * 0.5)
    }
}

/// I062/185 calculated track velocity (Cartesian), LSB 0.25 m/s.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Velocity062 {
    /// Vx count.
    pub vx: i16,
    /// Vy count.
    pub vy: i16,
}

impl Velocity062 {
    /// (vx, vy) in m/s.
    #[must_use]
    pub fn mps(self) -> (f64, f64) {
        (f64::from(self.vx) * 0.25, f64::from(self.vy) * 0.25)
    }
}

/// A CAT062 system track: the decoded items, each `None` when absent.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Cat062 {
    /// I062/010.
    pub source: Option<DataSource>,
    /// I062/070 time of track information.
    pub time: Option<TimeOfDay>,
    /// I062/105.
    pub wgs84: Option<Wgs84Position>,
    /// I062/100.
    pub cartesian: Option<Cartesian062>,
    /// I062/185.
    pub velocity: Option<Velocity062>,
    /// I062/040 track number.
    pub track_number: Option<u16>,
}

fn i24(b: &[u8]) -> i32 {
    // Place the 24 bits at the top, arithmetic shift back to sign-extend.
    i32::from_be_bytes([b[0], b[1], b[2], 0]) >> 8
}

fn i24_bytes(v: i32) -> [u8; 3] {
    let [a, b, c, _] = (v << 8).to_be_bytes();
    [a, b, c]
}

fn i32_at(b: &[u8], i: usize) -> i32 {
    i32::from_be_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]])
}

impl Category for Cat062 {
    const UAP: Uap = Uap {
        cat: 62,
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
            4 => self.time = Some(TimeOfDay::read(b)),
            5 => {
                self.wgs84 = Some(Wgs84Position {
                    lat: i32_at(b, 0),
                    lon: i32_at(b, 4),
                })
            }
            6 => {
                self.cartesian = Some(Cartesian062 {
                    x: i24(&b[0..3]),
                    y: i24(&b[3..6]),
                })
            }
            7 => {
                self.velocity = Some(Velocity062 {
                    vx: i16_at(b, 0),
                    vy: i16_at(b, 2),
                })
            }
            12 => self.track_number = Some(u16_at(b, 0)),
            _ => {}
        }
        Ok(())
    }

    fn encode_items(&self, w: &mut RecordWriter) -> Result<(), EncodeError> {
        if let Some(s) = self.source {
            w.put(1, &[s.sac, s.sic])?;
        }
        if let Some(t) = self.time {
            w.put(4, &t.bytes())?;
        }
        if let Some(p) = self.wgs84 {
            let mut b = [0u8; 8];
            b[..4].copy_from_slice(&p.lat.to_be_bytes());
            b[4..].copy_from_slice(&p.lon.to_be_bytes());
            w.put(5, &b)?;
        }
        if let Some(c) = self.cartesian {
            let (x, y) = (i24_bytes(c.x), i24_bytes(c.y));
            w.put(6, &[x[0], x[1], x[2], y[0], y[1], y[2]])?;
        }
        if let Some(v) = self.velocity {
            let [a, b] = v.vx.to_be_bytes();
            let [c, d] = v.vy.to_be_bytes();
            w.put(7, &[a, b, c, d])?;
        }
        if let Some(n) = self.track_number {
            w.put(12, &n.to_be_bytes())?;
        }
        Ok(())
    }
}

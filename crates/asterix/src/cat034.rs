//! CAT034 monoradar service messages (EUROCONTROL ASTERIX Part 2b Category
//! 034, edition 1.29): north markers and sector crossings.
//!
//! Decoded: I034/010, /000, /020, /030, /041. Every other item of the UAP is
//! skipped by its length rule.

use crate::error::{EncodeError, ItemId};
use crate::fields::{DataSource, TimeOfDay, quantise, u16_at};
use crate::record::{Category, RecordWriter};
use crate::uap::{Format, Uap, UapSlot};

const F1: Option<Format> = Some(Format::Fixed(1));
/// I034/050 system configuration and status: COM, –, –, PSR, SSR, MDS (2 octets).
const I050: &[Option<Format>] = &[F1, None, None, F1, F1, Some(Format::Fixed(2))];
/// I034/060 system processing mode: COM, –, –, PSR, SSR, MDS.
const I060: &[Option<Format>] = &[F1, None, None, F1, F1, F1];

/// The CAT034 UAP, edition 1.29 (FRN 1–14).
const SLOTS: &[UapSlot] = &[
    Some(("010", Format::Fixed(2))),
    Some(("000", Format::Fixed(1))),
    Some(("030", Format::Fixed(3))),
    Some(("020", Format::Fixed(1))),
    Some(("041", Format::Fixed(2))),
    Some(("050", Format::Compound(I050))),
    Some(("060", Format::Compound(I060))),
    Some(("070", Format::Repetitive(2))),
    Some(("100", Format::Fixed(8))),
    Some(("110", Format::Fixed(1))),
    Some(("120", Format::Fixed(8))),
    Some(("090", Format::Fixed(2))),
    Some(("RE", Format::Explicit)),
    Some(("SP", Format::Explicit)),
];

fn id(name: &'static str) -> ItemId {
    ItemId { cat: 34, name }
}

/// I034/000 message type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MessageType {
    /// 1: north marker.
    NorthMarker,
    /// 2: sector crossing.
    SectorCrossing,
    /// 3: geographical filtering.
    GeographicalFiltering,
    /// 4: jamming strobe.
    JammingStrobe,
    /// Any other value, kept as read.
    Other(u8),
}

impl MessageType {
    /// The wire value.
    #[must_use]
    pub fn code(self) -> u8 {
        match self {
            Self::NorthMarker => 1,
            Self::SectorCrossing => 2,
            Self::GeographicalFiltering => 3,
            Self::JammingStrobe => 4,
            Self::Other(v) => v,
        }
    }

    /// The message type of a wire value.
    #[must_use]
    pub fn from_code(v: u8) -> Self {
        match v {
            1 => Self::NorthMarker,
            2 => Self::SectorCrossing,
            3 => Self::GeographicalFiltering,
            4 => Self::JammingStrobe,
            v => Self::Other(v),
        }
    }
}

/// I034/020 sector number: azimuth of the sector's start, LSB 360°/2^8.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Sector(pub u8);

impl Sector {
    /// LSB, degrees: 360 / 256.
    pub const LSB_DEG: f64 = 360.0 / 256.0;

    /// Degrees clockwise from north.
    #[must_use]
    pub fn degrees(self) -> f64 {
        f64::from(self.0) * Self::LSB_DEG
    }
}

/// I034/041 antenna rotation period, LSB 1/128 s.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RotationPeriod(pub u16);

impl RotationPeriod {
    /// Seconds per revolution.
    #[must_use]
    pub fn seconds(self) -> f64 {
        f64::from(self.0) / 128.0
    }

    /// The nearest encoding of a period in seconds, in `[0, 65535/128]`.
    ///
    /// # Errors
    /// [`EncodeError::OutOfRange`] outside that range or if not finite.
    pub fn from_seconds(seconds: f64) -> Result<Self, EncodeError> {
        let q = quantise(
            id("041"),
            "rotation period",
            seconds,
            1.0 / 128.0,
            0.0,
            65535.0,
        )?;
        Ok(Self(u16::try_from(q).unwrap_or(0)))
    }
}

/// A CAT034 service message: the decoded items, each `None` when absent.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Cat034 {
    /// I034/010.
    pub source: Option<DataSource>,
    /// I034/000.
    pub message_type: Option<MessageType>,
    /// I034/030.
    pub time: Option<TimeOfDay>,
    /// I034/020.
    pub sector: Option<Sector>,
    /// I034/041.
    pub rotation_period: Option<RotationPeriod>,
}

impl Category for Cat034 {
    const UAP: Uap = Uap {
        cat: 34,
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
            2 => self.message_type = Some(MessageType::from_code(b[0])),
            3 => self.time = Some(TimeOfDay::read(b)),
            4 => self.sector = Some(Sector(b[0])),
            5 => self.rotation_period = Some(RotationPeriod(u16_at(b, 0))),
            _ => {}
        }
        Ok(())
    }

    fn encode_items(&self, w: &mut RecordWriter) -> Result<(), EncodeError> {
        if let Some(s) = self.source {
            w.put(1, &[s.sac, s.sic])?;
        }
        if let Some(m) = self.message_type {
            w.put(2, &[m.code()])?;
        }
        if let Some(t) = self.time {
            w.put(3, &t.bytes())?;
        }
        if let Some(s) = self.sector {
            w.put(4, &[s.0])?;
        }
        if let Some(p) = self.rotation_period {
            w.put(5, &p.0.to_be_bytes())?;
        }
        Ok(())
    }
}

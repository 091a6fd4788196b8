//! CAT048 monoradar target reports (EUROCONTROL ASTERIX Part 4 Category 048,
//! edition 1.31; the items decoded here have the same layout in editions
//! 1.21 to 1.32).
//!
//! Decoded: I048/010, /140, /020 (first octet and first extension), /040,
//! /042, /070, /090, /220, /161, /170 (first octet and first extension),
//! /200. Every other item of the UAP is skipped by its length rule.

use argus_sensors::RadarAzimuth;

use crate::error::{EncodeError, ItemId};
use crate::fields::{Azimuth16, DataSource, NM, TimeOfDay, i16_at, quantise, u16_at};
use crate::record::{Category, RecordWriter};
use crate::uap::{Format, Uap, UapSlot};

const X1: Format = Format::Extended { first: 1, ext: 1 };

/// I048/130 radar plot characteristics: 7 one-octet subfields (SRL, SRR, SAM,
/// PRL, PAM, RPD, APD).
const I130: &[Option<Format>] = &[Some(Format::Fixed(1)); 7];
/// I048/120 radial Doppler speed: CAL (2 octets), RDS (repetitive, 6 octets).
const I120: &[Option<Format>] = &[Some(Format::Fixed(2)), Some(Format::Repetitive(6))];

/// The CAT048 UAP, edition 1.31 (FRN 1–28).
const SLOTS: &[UapSlot] = &[
    Some(("010", Format::Fixed(2))),
    Some(("140", Format::Fixed(3))),
    Some(("020", X1)),
    Some(("040", Format::Fixed(4))),
    Some(("070", Format::Fixed(2))),
    Some(("090", Format::Fixed(2))),
    Some(("130", Format::Compound(I130))),
    Some(("220", Format::Fixed(3))),
    Some(("240", Format::Fixed(6))),
    Some(("250", Format::Repetitive(8))),
    Some(("161", Format::Fixed(2))),
    Some(("042", Format::Fixed(4))),
    Some(("200", Format::Fixed(4))),
    Some(("170", X1)),
    Some(("210", Format::Fixed(4))),
    Some(("030", X1)),
    Some(("080", Format::Fixed(2))),
    Some(("100", Format::Fixed(4))),
    Some(("110", Format::Fixed(2))),
    Some(("120", Format::Compound(I120))),
    Some(("230", Format::Fixed(2))),
    Some(("260", Format::Fixed(7))),
    Some(("055", Format::Fixed(1))),
    Some(("050", Format::Fixed(2))),
    Some(("065", Format::Fixed(1))),
    Some(("060", Format::Fixed(2))),
    Some(("SP", Format::Explicit)),
    Some(("RE", Format::Explicit)),
];

/// FRNs of the decoded items.
mod frn {
    pub(super) const I010: usize = 1;
    pub(super) const I140: usize = 2;
    pub(super) const I020: usize = 3;
    pub(super) const I040: usize = 4;
    pub(super) const I070: usize = 5;
    pub(super) const I090: usize = 6;
    pub(super) const I220: usize = 8;
    pub(super) const I161: usize = 11;
    pub(super) const I042: usize = 12;
    pub(super) const I200: usize = 13;
    pub(super) const I170: usize = 14;
}

fn id(name: &'static str) -> ItemId {
    ItemId { cat: 48, name }
}

/// I048/020 target report descriptor: the first octet and its first extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ReportDescriptor {
    /// TYP (3 bits): 0 no detection, 1 PSR, 2 SSR, 3 SSR + PSR, 4 Mode S all-call,
    /// 5 Mode S roll-call, 6 all-call + PSR, 7 roll-call + PSR.
    pub typ: u8,
    /// SIM: simulated target report.
    pub sim: bool,
    /// RDP: report from RDP chain 2.
    pub rdp: bool,
    /// SPI: special position identification.
    pub spi: bool,
    /// RAB: report from a field monitor (fixed transponder).
    pub rab: bool,
    /// The first extension's bits 8–2 (TST, ERR, XPP, ME, MI, FOE/FRI) as they
    /// stand in the octet, FX cleared; further extensions are skipped.
    pub extension: Option<u8>,
}

/// I048/040 measured position in polar coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct MeasuredPolar {
    /// RHO, LSB 1/256 NM.
    pub rho: u16,
    /// THETA, LSB 360°/2^16, clockwise from north.
    pub theta: Azimuth16,
}

impl MeasuredPolar {
    /// RHO's LSB in metres: 1852 / 256.
    pub const RHO_LSB_M: f64 = NM / 256.0;

    /// Slant range, metres.
    #[must_use]
    pub fn range_m(self) -> f64 {
        f64::from(self.rho) * Self::RHO_LSB_M
    }

    /// The nearest encoding of a range (m) and an azimuth in Argus's
    /// convention (rad ccw from east).
    ///
    /// # Errors
    /// [`EncodeError::OutOfRange`] if the range is outside `[0, 65535/256 NM]`
    /// or either value is not finite.
    pub fn from_range_azimuth(range_m: f64, argus_azimuth: f64) -> Result<Self, EncodeError> {
        let rho = quantise(id("040"), "RHO", range_m, Self::RHO_LSB_M, 0.0, 65535.0)?;
        Ok(Self {
            rho: u16::try_from(rho).unwrap_or(0),
            theta: Azimuth16::from_argus(id("040"), argus_azimuth)?,
        })
    }

    /// The same azimuth as a [`RadarAzimuth`] (clockwise from north, rad).
    #[must_use]
    pub fn radar_azimuth(self) -> RadarAzimuth {
        self.theta.radar()
    }
}

/// I048/042 calculated position in Cartesian coordinates (LSB 1/128 NM).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct CartesianPosition {
    /// X (east), LSB 1/128 NM.
    pub x: i16,
    /// Y (north), LSB 1/128 NM.
    pub y: i16,
}

impl CartesianPosition {
    /// LSB in metres: 1852 / 128.
    pub const LSB_M: f64 = NM / 128.0;

    /// (x, y) in metres.
    #[must_use]
    pub fn metres(self) -> (f64, f64) {
        (
            f64::from(self.x) * Self::LSB_M,
            f64::from(self.y) * Self::LSB_M,
        )
    }
}

/// I048/070 Mode-3/A code.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Mode3A {
    /// V: code not validated.
    pub not_validated: bool,
    /// G: garbled.
    pub garbled: bool,
    /// L: code not extracted during the last scan (smoothed).
    pub not_extracted: bool,
    /// The 12-bit code (four octal digits A B C D, `0o7777` at most).
    pub code: u16,
}

/// I048/090 flight level.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FlightLevel {
    /// V: code not validated.
    pub not_validated: bool,
    /// G: garbled.
    pub garbled: bool,
    /// Flight level in quarter flight levels (14-bit two's complement).
    pub quarter_fl: i16,
}

impl FlightLevel {
    /// Flight level (hundreds of feet).
    #[must_use]
    pub fn flight_level(self) -> f64 {
        f64::from(self.quarter_fl) * 0.25
    }
}

/// I048/170 track status: the first octet and its first extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct TrackStatus {
    /// CNF: tentative track.
    pub tentative: bool,
    /// RAD (2 bits): 0 combined, 1 PSR, 2 SSR/Mode S, 3 invalid.
    pub rad: u8,
    /// DOU: low confidence in plot-to-track association.
    pub doubtful: bool,
    /// MAH: horizontal manoeuvre sensed.
    pub manoeuvre: bool,
    /// CDM (2 bits): 0 level, 1 climbing, 2 descending, 3 unknown.
    pub cdm: u8,
    /// The first extension's bits 8–2 (TRE, GHO, SUP, TCC), FX cleared.
    pub extension: Option<u8>,
}

/// I048/200 calculated track velocity in polar coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PolarVelocity {
    /// Ground speed, LSB 2^-14 NM/s.
    pub groundspeed: u16,
    /// Heading, LSB 360°/2^16, clockwise from north.
    pub heading: Azimuth16,
}

impl PolarVelocity {
    /// Ground speed LSB in m/s: 1852 × 2^-14.
    pub const GSP_LSB_MPS: f64 = NM / 16384.0;

    /// Ground speed, m/s.
    #[must_use]
    pub fn speed_mps(self) -> f64 {
        f64::from(self.groundspeed) * Self::GSP_LSB_MPS
    }
}

/// A CAT048 target report: the decoded items, each `None` when absent.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Cat048 {
    /// I048/010.
    pub source: Option<DataSource>,
    /// I048/140.
    pub time: Option<TimeOfDay>,
    /// I048/020.
    pub descriptor: Option<ReportDescriptor>,
    /// I048/040.
    pub polar: Option<MeasuredPolar>,
    /// I048/070.
    pub mode3a: Option<Mode3A>,
    /// I048/090.
    pub flight_level: Option<FlightLevel>,
    /// I048/220: 24-bit ICAO aircraft address.
    pub aircraft_address: Option<u32>,
    /// I048/161: 12-bit track number.
    pub track_number: Option<u16>,
    /// I048/042.
    pub cartesian: Option<CartesianPosition>,
    /// I048/200.
    pub velocity: Option<PolarVelocity>,
    /// I048/170.
    pub track_status: Option<TrackStatus>,
}

fn bit(b: u8, n: u8) -> bool {
    b & (1 << n) != 0
}

fn flag(v: bool, n: u8) -> u8 {
    u8::from(v) << n
}

impl Category for Cat048 {
    const UAP: Uap = Uap {
        cat: 48,
        slots: SLOTS,
    };

    fn decode_item(&mut self, frn: usize, b: &[u8]) -> Result<(), &'static str> {
        match frn {
            frn::I010 => {
                self.source = Some(DataSource {
                    sac: b[0],
                    sic: b[1],
                })
            }
            frn::I140 => self.time = Some(TimeOfDay::read(b)),
            frn::I020 => {
                self.descriptor = Some(ReportDescriptor {
                    typ: b[0] >> 5,
                    sim: bit(b[0], 4),
                    rdp: bit(b[0], 3),
                    spi: bit(b[0], 2),
                    rab: bit(b[0], 1),
                    extension: b.get(1).map(|e| e & 0xfe),
                });
            }
            frn::I040 => {
                self.polar = Some(MeasuredPolar {
                    rho: u16_at(b, 0),
                    theta: Azimuth16(u16_at(b, 2)),
                });
            }
            frn::I070 => {
                let v = u16_at(b, 0);
                self.mode3a = Some(Mode3A {
                    not_validated: v & 0x8000 != 0,
                    garbled: v & 0x4000 != 0,
                    not_extracted: v & 0x2000 != 0,
                    code: v & 0x0fff,
                });
            }
            frn::I090 => {
                let v = u16_at(b, 0);
                // Sign-extend the 14-bit field: shift it to the top, arithmetic shift back.
                #[allow(clippy::cast_possible_wrap)]
                let quarter_fl = ((v << 2) as i16) >> 2;
                self.flight_level = Some(FlightLevel {
                    not_validated: v & 0x8000 != 0,
                    garbled: v & 0x4000 != 0,
                    quarter_fl,
                });
            }
            frn::I220 => self.aircraft_address = Some(u32::from_be_bytes([0, b[0], b[1], b[2]])),
            frn::I161 => self.track_number = Some(u16_at(b, 0) & 0x0fff),
            frn::I042 => {
                self.cartesian = Some(CartesianPosition {
                    x: i16_at(b, 0),
                    y: i16_at(b, 2),
                })
            }
            frn::I200 => {
                self.velocity = Some(PolarVelocity {
                    groundspeed: u16_at(b, 0),
                    heading: Azimuth16(u16_at(b, 2)),
                });
            }
            frn::I170 => {
                self.track_status = Some(TrackStatus {
                    tentative: bit(b[0], 7),
                    rad: (b[0] >> 5) & 3,
                    doubtful: bit(b[0], 4),
                    manoeuvre: bit(b[0], 3),
                    cdm: (b[0] >> 1) & 3,
                    extension: b.get(1).map(|e| e & 0xfe),
                });
            }
            _ => {}
        }
        Ok(())
    }

    fn encode_items(&self, w: &mut RecordWriter) -> Result<(), EncodeError> {
        if let Some(s) = self.source {
            w.put(frn::I010, &[s.sac, s.sic])?;
        }
        if let Some(t) = self.time {
            w.put(frn::I140, &t.bytes())?;
        }
        if let Some(d) = self.descriptor {
            let first = ((d.typ & 7) << 5)
                | flag(d.sim, 4)
                | flag(d.rdp, 3)
                | flag(d.spi, 2)
                | flag(d.rab, 1);
            match d.extension {
                None => w.put(frn::I020, &[first])?,
                Some(e) => w.put(frn::I020, &[first | 1, e & 0xfe])?,
            }
        }
        if let Some(p) = self.polar {
            let [r0, r1] = p.rho.to_be_bytes();
            let [t0, t1] = p.theta.0.to_be_bytes();
            w.put(frn::I040, &[r0, r1, t0, t1])?;
        }
        if let Some(m) = self.mode3a {
            let v = (u16::from(m.not_validated) << 15)
                | (u16::from(m.garbled) << 14)
                | (u16::from(m.not_extracted) << 13)
                | (m.code & 0x0fff);
            w.put(frn::I070, &v.to_be_bytes())?;
        }
        if let Some(f) = self.flight_level {
            if !(-8192..=8191).contains(&f.quarter_fl) {
                return Err(EncodeError::OutOfRange {
                    item: id("090"),
                    what: "quarter flight level",
                    value: f64::from(f.quarter_fl),
                });
            }
            #[allow(clippy::cast_sign_loss)]
            let v = (u16::from(f.not_validated) << 15)
                | (u16::from(f.garbled) << 14)
                | (f.quarter_fl as u16 & 0x3fff);
            w.put(frn::I090, &v.to_be_bytes())?;
        }
        if let Some(a) = self.aircraft_address {
            let [_, a0, a1, a2] = (a & 0x00ff_ffff).to_be_bytes();
            w.put(frn::I220, &[a0, a1, a2])?;
        }
        if let Some(t) = self.track_number {
            w.put(frn::I161, &(t & 0x0fff).to_be_bytes())?;
        }
        if let Some(c) = self.cartesian {
            let [x0, x1] = c.x.to_be_bytes();
            let [y0, y1] = c.y.to_be_bytes();
            w.put(frn::I042, &[x0, x1, y0, y1])?;
        }
        if let Some(v) = self.velocity {
            let [g0, g1] = v.groundspeed.to_be_bytes();
            let [h0, h1] = v.heading.0.to_be_bytes();
            w.put(frn::I200, &[g0, g1, h0, h1])?;
        }
        if let Some(s) = self.track_status {
            let first = flag(s.tentative, 7)
                | ((s.rad & 3) << 5)
                | flag(s.doubtful, 4)
                | flag(s.manoeuvre, 3)
                | ((s.cdm & 3) << 1);
            match s.extension {
                None => w.put(frn::I170, &[first])?,
                Some(e) => w.put(frn::I170, &[first | 1, e & 0xfe])?,
            }
        }
        Ok(())
    }
}

//! ASTERIX (EUROCONTROL's All-purpose Structured Surveillance Information
//! Exchange) codec for Argus: data-block and record framing, and the items a
//! tracker needs of CAT048 (monoradar target reports), CAT034 (north-marker
//! and sector-crossing messages) and CAT062 (system tracks), decoded and
//! encoded, and of CAT021 (ADS-B reports), decoded and encoded, with NACp
//! turned into a position covariance.
//!
//! # Editions
//! - Framing: EUROCONTROL ASTERIX Part 1 (data block: CAT, 16-bit LEN, records;
//!   record: FSPEC with FX chains; item formats fixed, extended, repetitive,
//!   explicit, compound).
//! - CAT048: ASTERIX Part 4 Category 048, edition 1.31 (UAP FRN 1–28). The
//!   items decoded have the same layout from edition 1.21 on.
//! - CAT034: ASTERIX Part 2b Category 034, edition 1.29 (UAP FRN 1–14).
//! - CAT021: ASTERIX Part 12 Category 021, edition 2.1 (UAP FRN 1–49, the
//!   same in edition 2.6): I021/010, /071–/073, /075, /077, /080, /090,
//!   /130, /131 decoded and encoded; NACp → covariance and NIC → Rc per
//!   RTCA DO-242A / DO-260B ([`Quality`]).
//! - CAT062: ASTERIX Part 9 Category 062, edition 1.18 (UAP FRN 1–35):
//!   I062/010, /040, /070, /100, /105, /185 decoded and encoded.
//!
//! # Why not an existing crate
//! Surveyed December 2026:
//! - `asterix` 0.4.0 (deku-based): CAT048 and CAT034 only (no CAT021 or
//!   CAT062), one heap-allocated FSPEC vector per record, and errors from
//!   deku that do not name the item and byte offset; no skipping policy for a
//!   bad record inside a block.
//! - `libasterix` 0.1.0: CAT048 and CAT062 only (no CAT034, which drives the
//!   sector processing), `anyhow` errors (untyped), FSPEC chains cut at four
//!   octets, a whole block rejected on the first bad record.
//!
//! Neither covers the needed categories (CAT021, CAT034, CAT048, CAT062) with
//! typed, offset-carrying errors, so the layouts are written here from the
//! category specifications.
//!
//! # Robustness
//! [`decode`] never panics and always terminates; every skipped block or
//! record is reported as a [`Skip`] with a typed [`DecodeError`] that names
//! the byte offset and, where one is involved, the item.
//!
//! # Azimuth convention
//! ASTERIX azimuths are clockwise from north; Argus's are counter-clockwise
//! from east. [`Azimuth16::argus`] and [`Azimuth16::from_argus`] convert
//! explicitly through [`argus_sensors::RadarAzimuth`].
//!
//! # Example
//! ```
//! use argus_asterix::{Cat048, DataSource, MeasuredPolar, Record, decode, encode_block};
//! let plot = Cat048 {
//!     source: Some(DataSource { sac: 1, sic: 2 }),
//!     polar: Some(MeasuredPolar::from_range_azimuth(50_000.0, 0.0)?),
//!     ..Cat048::default()
//! };
//! let mut bytes = Vec::new();
//! encode_block(&[plot], &mut bytes)?;
//! let decoded = decode(&bytes);
//! assert!(decoded.skipped.is_empty());
//! let Record::Cat048(back) = &decoded.records[0] else { unreachable!() };
//! let p = back.polar.unwrap();
//! // Range within half an LSB (1852/256/2 m); due east is 90° clockwise from north.
//! assert!((p.range_m() - 50_000.0).abs() <= MeasuredPolar::RHO_LSB_M / 2.0);
//! assert!((p.theta.degrees() - 90.0).abs() < 1e-9);
//! # Ok::<(), argus_asterix::EncodeError>(())
//! ```

mod adsb_quality;
mod block;
mod cat021;
mod cat034;
mod cat048;
mod cat062;
mod error;
mod fields;
pub mod mutation;
mod record;
pub mod samples;
mod uap;

pub use adsb_quality::{Quality, QualityExt, R95_PER_SIGMA, containment_radius_m, epu_m};
pub use block::{Decoded, Record, Skip, decode, encode_block};
pub use cat021::{Cat021, LatLon};
pub use cat034::{Cat034, MessageType, RotationPeriod, Sector};
pub use cat048::{
    CartesianPosition, Cat048, FlightLevel, MeasuredPolar, Mode3A, PolarVelocity, ReportDescriptor,
    TrackStatus,
};
pub use cat062::{Cartesian062, Cat062, Velocity062, Wgs84Position};
pub use error::{DecodeError, EncodeError, ItemId};
pub use fields::{Azimuth16, DataSource, NM, TimeOfDay};
pub use record::{Category, RecordWriter};
pub use uap::{Format, Uap, UapSlot};

//! ADS-B state vectors in the OpenSky / `traffic` layout as truth for Argus.
//!
//! - Read: [`read_csv`], [`read_json`] (an array of records or JSON Lines), or
//!   [`read_path`] by extension, gzipped or not. Columns: `timestamp`, `icao24`,
//!   `latitude`, `longitude` (required), `altitude`, `groundspeed`, `track`,
//!   `vertical_rate`, `callsign`, `onground` (optional; others ignored).
//! - Units, as the `traffic` package holds them (its `core/types.py`): altitude in
//!   feet, ground speed in knots, vertical rate in feet per minute, track in degrees
//!   clockwise from north, latitude/longitude in degrees WGS-84; timestamps as
//!   epoch numbers ([`EpochUnit`]) or ISO-8601 strings (UTC when no offset).
//!   [`StateVector`] keeps those; [`TruthSample`] is SI, converted with the exact
//!   factors [`FT`], [`KT`], [`FT_PER_MIN`].
//! - Clean: [`clean`] with the documented rules of [`CleaningConfig`] (stale
//!   positions, spikes, gaps, ground, missing and impossible altitudes), counting
//!   each rule's drops in a [`CleaningReport`].
//! - Use: per-aircraft [`Flight`]s of time-ordered samples, in ENU around a
//!   reference point through [`Flight::to_enu`].
//!
//! # Example
//! ```
//! use argus_adsb::{CleaningConfig, EpochUnit, clean, read_csv};
//! use argus_geo::{Geodetic, LocalFrame};
//!
//! let csv = "timestamp,icao24,latitude,longitude,altitude,groundspeed,track,vertical_rate,callsign,onground
//! 0,3c6444,49.0,2.5,10000,300,90,0,AFR123,false
//! 1,3c6444,49.0,2.5,10000,300,90,0,AFR123,false
//! 2,3c6444,49.0,2.50423,10000,300,90,0,AFR123,false
//! 3,3c6444,49.0,2.50634,10000,300,90,0,AFR123,false
//! ";
//! let records = read_csv(csv.as_bytes(), EpochUnit::Seconds)?;
//! let config = CleaningConfig { min_samples: 2, ..CleaningConfig::default() };
//! let (flights, report) = clean(&records, &config)?;
//! assert_eq!(report.stale_position, 1); // t = 1 repeats t = 0's position
//! assert_eq!(flights[0].samples.len(), 3);
//! // 300 kt due east (track 90°) is 154.3 m/s along +x.
//! let frame = LocalFrame::wgs84(Geodetic::from_degrees(49.0, 2.5, 0.0)?);
//! let enu = flights[0].to_enu(&frame)?;
//! let v = enu[0].velocity.unwrap();
//! assert!((v.east - 300.0 * 1852.0 / 3600.0).abs() < 1e-9 && v.north.abs() < 1e-9);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod clean;
mod error;
mod flight;
mod read;
mod record;
mod time;

pub use clean::{CleaningConfig, CleaningReport, clean};
pub use error::{AdsbError, Location};
pub use flight::{EnuSample, Flight, TruthSample};
pub use read::{Format, read_csv, read_json, read_path};
pub use record::{FT, FT_PER_MIN, KT, StateVector};
pub use time::EpochUnit;

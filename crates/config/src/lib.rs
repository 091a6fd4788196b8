//! The `argus track` configuration file (TOML, `docs/FORMATS.md`) turned into a checked
//! specification: [`load`] reads the file once (its `schema` keeps every value's line),
//! checks its `[[sensor]]` and `[estimator]` tables once with every default filled in
//! ([`Sensor`], [`argus_tracker::single::EstimatorSpec`]), its optional `[reference]` point ([`Reference`], sensors
//! given by latitude and longitude around it) and, with a `[tracker]` table, maps it
//! onto the tracker's configuration ([`MultiTarget`], whose validation errors are mapped
//! back to the file's keys). The result is a [`Job`]: one estimator over a plot file, or
//! the multi-target tracker.
//!
//! Every bad value is a [`ConfigError::Input`] naming the file, the line and the key
//! ([`Location`]); nothing a user writes panics.

mod error;
mod geo;
mod job;
mod schema;
mod spec;
#[cfg(test)]
mod tests;
mod tracker_config;
mod tracker_errors;

pub use crate::error::{ConfigError, Location};
pub use crate::geo::{Reference, to_reference};
pub use crate::job::{Job, Loaded, load, load_text};
pub use crate::spec::{Sensor, turned};
pub use crate::tracker_config::{DEFAULT_MAX_EXACT_EVENTS, MultiTarget};

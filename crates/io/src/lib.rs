//! Argus's file readers and writers, for the `argus` command and the Python bindings:
//!
//! - [`plotfile`]: the plot CSV (`docs/FORMATS.md`), read whole or streamed
//!   ([`plotfile::PlotReader`]) into [`plotfile::FilePlot`]s that keep their line, and
//!   written for simulated plots;
//! - [`asterix`]: ASTERIX files known by content (pcap, pcapng, raw blocks): CAT048 and
//!   CAT034 into plots and sector messages, CAT062 system tracks and CAT021 ADS-B reports
//!   into their CSVs, and the encoders of plots (CAT048, CAT034) and tracks (CAT062);
//! - [`source`]: an ASTERIX plot file for the sensors of an `argus track` configuration
//!   (`argus_config`), as one time-ordered [`event`] stream: the plots, the north-marker
//!   and sector times, the rotations;
//! - [`rows`]: the tracks CSV `argus track` writes;
//! - [`output`]: output files written atomically.
//!
//! Errors are [`IoError`]s naming the file (and, for a bad value, its line and field).

pub mod asterix;
mod error;
pub mod event;
pub mod output;
pub mod plotfile;
pub mod rows;
pub mod source;
pub mod track;

pub use crate::error::IoError;

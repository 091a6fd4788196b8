//! The plot file of `argus track`, known by content: the plot CSV, or ASTERIX (a pcap
//! or pcapng capture of UDP, or raw blocks) whose CAT048 reports become polar plots of
//! the `[[sensor]]` with their SAC/SIC and whose CAT034 messages drive the rotating
//! radar's sectors (`docs/FORMATS.md`, "ASTERIX").
//!
//! - A `[[sensor]]` is matched by its `sac`, `sic` keys, or else by `id = 256 · SAC +
//!   SIC`. A CAT048 report of a SAC/SIC no sensor has is an error naming it
//!   ([`IoError::UnknownSource`]): a capture of several radars needs each of them
//!   configured (CAT034 messages of other radars are ignored).
//! - A radar's CAT034 messages give its rotation when they hold an I034/041 period and a
//!   north marker: the period, and `north_time` the phase of the first north marker; the
//!   configured `rotation` direction is kept (clockwise by default). They replace a
//!   configured `revolution_period` / `north_time` (the radar's own word), and make a
//!   sensor without one a rotating radar.
//! - Every north-marker or sector-crossing time is a point the tracker advances to
//!   (`argus_tracker::Tracker::advance_to`): sectors that ended by then are processed
//!   even when no plot follows.
//! - Errors about a plot name the ASTERIX record's 1-based number where a CSV error names
//!   the line.

use std::path::Path;

use argus_asterix::DataSource;
use argus_sensors::{Plot, SensorId};

use crate::asterix::plots::{radar_data, rotation_of};
use crate::asterix::{self, source_of};
use crate::error::IoError;
use crate::event::{self, Event, MessageRotation};
use crate::plotfile::FilePlot;
use argus_config::Sensor;

/// What an ASTERIX plot file gives the tracker: its events ([`event::merged`]: the
/// rotations from CAT034, then the plots and the CAT034 message times of the configured
/// radars, in time order).
#[derive(Debug, Clone, Default)]
pub struct PlotSource {
    /// The events, in order.
    pub events: Vec<Event>,
}

impl PlotSource {
    /// Its plots alone, in time order.
    #[must_use]
    pub fn plots(&self) -> Vec<FilePlot> {
        self.events
            .iter()
            .filter_map(|e| match e {
                Event::Plot(p) => Some(*p),
                Event::Marker(_) | Event::Rotation(_) => None,
            })
            .collect()
    }
}

/// The data source a sensor answers to: its keys, or `id = 256 · SAC + SIC`.
fn answers_to(s: &Sensor) -> Option<DataSource> {
    s.asterix.or_else(|| source_of(s.id))
}

fn show(d: DataSource) -> String {
    format!("{}/{}", d.sac, d.sic)
}

/// Reads the plot file at `path` for the `sensors` of `config` when it is ASTERIX
/// (`None`: CSV, which the caller reads, only its first bytes read here).
///
/// # Errors
/// The CSV reader's errors; for ASTERIX, [`IoError::Capture`] for an unreadable
/// capture, [`IoError::UnknownSource`] for a report of a radar not configured,
/// [`IoError::Input`] for two sensors with one SAC/SIC or a plot whose values Argus
/// refuses.
pub fn read(path: &Path, config: &Path, sensors: &[Sensor]) -> Result<Option<PlotSource>, IoError> {
    let Some(surveillance) = asterix::read(path)? else {
        return Ok(None);
    };
    for (k, a) in sensors.iter().enumerate() {
        if let Some(b) = sensors[k + 1..]
            .iter()
            .find(|b| answers_to(a).is_some() && answers_to(a) == answers_to(b))
        {
            return Err(IoError::input(
                config,
                None,
                Some("sac"),
                format!(
                    "sensors {} and {} answer to one ASTERIX SAC/SIC {}",
                    a.id,
                    b.id,
                    answers_to(a).map_or_else(String::new, show)
                ),
            ));
        }
    }
    if let Some(note) = surveillance.skipped_note(path) {
        eprintln!("warning: {note}");
    }
    let data = radar_data(&surveillance);
    let sensor_of = |d: DataSource| sensors.iter().find(|s| answers_to(s) == Some(d));
    let mut plots = Vec::with_capacity(data.plots.len());
    for p in &data.plots {
        let Some(s) = sensor_of(p.source) else {
            return Err(IoError::UnknownSource {
                file: path.to_path_buf(),
                record: p.number,
                sac: p.source.sac,
                sic: p.source.sic,
                config: config.to_path_buf(),
                known: sensors
                    .iter()
                    .filter_map(answers_to)
                    .map(show)
                    .collect::<Vec<_>>()
                    .join(", "),
            });
        };
        let plot = Plot::polar(p.time, SensorId(s.id), p.range, p.azimuth)
            .map_err(|e| IoError::input(path, Some(p.number), Some("I048/040"), e.to_string()))?;
        plots.push(FilePlot {
            line: p.number,
            plot,
        });
    }
    let markers: Vec<f64> = data
        .services
        .iter()
        .filter(|m| sensor_of(m.source).is_some())
        .map(|m| m.time)
        .collect();
    let rotations: Vec<MessageRotation> = sensors
        .iter()
        .filter_map(|s| {
            let (period, north_time) = rotation_of(&data.services, answers_to(s)?)?;
            Some(MessageRotation {
                sensor: s.id,
                period,
                north_time,
            })
        })
        .collect();
    Ok(Some(PlotSource {
        events: event::merged(plots, &markers, &rotations),
    }))
}

//! `argus convert INPUT OUTPUT`: ASTERIX (pcap, pcapng or raw blocks, known by content)
//! to the CSV layouts and back, by the output's extension (`docs/FORMATS.md`).
//!
//! - CAT048 → the polar plot CSV `t,sensor,range,azimuth`: `t` from I048/140 (seconds
//!   of the day, made one time line across midnight), `sensor = 256 · SAC + SIC`,
//!   `range` from RHO in m, `azimuth` from θ converted explicitly to Argus's convention
//!   (counter-clockwise from east, rad).
//! - A polar plot CSV → CAT048 (+ CAT034 north markers and sector crossings with
//!   `--revolution-period`), as a pcap capture (`.pcap`) or raw blocks (`.ast`).
//! - CAT062 (a file without CAT048 plots) → the tracks CSV `t,track,x,vx,y,vy,status`
//!   that `argus score` reads; a tracks CSV (a header with `track`) → CAT062 of its
//!   confirmed rows.
//! - CAT021 (a file with neither) → the ADS-B CSV `timestamp,icao24,latitude,longitude,
//!   sigma_position` that `argus-adsb` reads ([`adsb_csv`]).

use std::path::Path;

use argus_io::asterix::adsb::adsb_csv;
use argus_io::asterix::encode::{self, Container, Sweep};
use argus_io::asterix::plots::radar_data;
use argus_io::asterix::tracks::{encode_tracks, tracks_csv};
use argus_io::asterix::{self, sensor_of};
use argus_io::output::write_atomic;
use argus_io::plotfile;

use crate::error::CliError;

/// Runs the conversion; returns the lines to print.
///
/// # Errors
/// [`CliError::Usage`] for a conversion that is not supported (CSV to CSV, ASTERIX to
/// ASTERIX, a file without CAT048 reports); the input's and the encoder's errors.
pub(crate) fn run(
    input: &Path,
    output: &Path,
    sweep: Option<Sweep>,
) -> Result<Vec<String>, CliError> {
    let container = Container::of(output);
    let mut lines = Vec::new();
    match (asterix::read(input)?, container) {
        (Some(s), None) => {
            if let Some(note) = s.skipped_note(input) {
                lines.push(note);
            }
            let data = radar_data(&s);
            if data.plots.is_empty() {
                let (text, rows, incomplete) = tracks_csv(&s);
                if rows == 0 {
                    let (text, rows, incomplete) = adsb_csv(&s);
                    if rows == 0 {
                        return Err(CliError::Usage(format!(
                            "{}: no CAT048 report with I048/010, /140 and /040, no CAT062 track with /070, /040, /100 and /185 and no CAT021 report with /071, /080 and /130 or /131 ({} records)",
                            input.display(),
                            s.records.len()
                        )));
                    }
                    write_atomic(output, text.as_bytes())?;
                    lines.push(format!(
                        "wrote {} ({rows} ADS-B rows from {} records; {incomplete} incomplete CAT021 reports)",
                        output.display(),
                        s.records.len()
                    ));
                    return Ok(lines);
                }
                write_atomic(output, text.as_bytes())?;
                lines.push(format!(
                    "wrote {} ({rows} track rows from {} records; {incomplete} incomplete CAT062 records)",
                    output.display(),
                    s.records.len()
                ));
                return Ok(lines);
            }
            let mut text = String::from("t,sensor,range,azimuth\n");
            for p in &data.plots {
                text.push_str(&format!(
                    "{},{},{},{}\n",
                    p.time,
                    sensor_of(p.source),
                    p.range,
                    p.azimuth
                ));
            }
            write_atomic(output, text.as_bytes())?;
            lines.push(format!(
                "wrote {} ({} plots from {} records; {} CAT034 messages, {} incomplete CAT048 reports, {} other records not converted)",
                output.display(),
                data.plots.len(),
                s.records.len(),
                data.services.len(),
                data.incomplete,
                data.other
            ));
        }
        (None, Some(c)) if is_tracks_csv(input)? => {
            // The system's own data source: SAC 0, SIC 0.
            let enc = encode_tracks(input, argus_asterix::DataSource::default())?;
            encode::write(output, &enc, c)?;
            lines.push(format!(
                "wrote {} ({} CAT062 records in {} datagrams)",
                output.display(),
                enc.reports,
                enc.datagrams.len()
            ));
        }
        (None, Some(c)) => {
            let plots: Vec<_> = plotfile::read(input)?.into_iter().map(|p| p.plot).collect();
            let enc = encode::encode_plots(&plots, sweep.as_ref())?;
            encode::write(output, &enc, c)?;
            lines.push(format!(
                "wrote {} ({} CAT048 reports, {} CAT034 messages in {} datagrams)",
                output.display(),
                enc.reports,
                enc.messages,
                enc.datagrams.len()
            ));
        }
        (Some(_), Some(_)) => {
            return Err(CliError::Usage(format!(
                "{} is ASTERIX already: give a .csv output",
                input.display()
            )));
        }
        (None, None) => {
            return Err(CliError::Usage(format!(
                "{} is CSV: give an ASTERIX output (.pcap or .ast)",
                input.display()
            )));
        }
    }
    Ok(lines)
}

/// Whether the CSV at `path` is a tracks file: its header has a `track` column.
fn is_tracks_csv(path: &Path) -> Result<bool, CliError> {
    let text = std::fs::read_to_string(path).map_err(|e| CliError::io(path, e))?;
    let header = text.lines().next().unwrap_or("");
    Ok(header
        .split(',')
        .any(|c| c.trim().trim_matches('"') == "track"))
}

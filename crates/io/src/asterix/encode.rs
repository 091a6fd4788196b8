//! Plots written as a radar sends them: CAT048 target reports (I048/010 SAC/SIC, /140
//! time of day, /020 descriptor, /040 measured polar position) in UDP datagrams, and for
//! a rotating radar CAT034 north markers (with I034/041, the rotation period) and sector
//! crossings at each sector boundary; as a pcap capture or as raw blocks.

use std::path::Path;
use std::time::Duration;

use argus_asterix::{
    Cat034, Cat048, DataSource, ItemId, MeasuredPolar, MessageType, ReportDescriptor,
    RotationPeriod, Sector, TimeOfDay, encode_block,
};
use argus_capture::{Datagram, Endpoints};
use argus_sensors::{Measurement, Plot};

use super::plots::DAY;
use super::source_of;
use crate::error::IoError;
use crate::output::write_atomic;

/// Records per CAT048 block (one block per datagram): 64 reports of 15 bytes keep a
/// datagram under 1 000 bytes, inside one Ethernet frame.
const RECORDS_PER_BLOCK: usize = 64;

/// A rotating radar's sweep: the CAT034 messages to write.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sweep {
    /// Revolution period (s).
    pub period: f64,
    /// A time the beam points north (s).
    pub north_time: f64,
    /// North → east (I034/020 sector numbers increase).
    pub clockwise: bool,
    /// Sector crossings per revolution (the north marker is the first).
    pub sectors: u32,
}

/// How a file of blocks is held.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Container {
    /// A pcap capture of UDP datagrams (`.pcap`).
    Pcap,
    /// Concatenated data blocks (`.ast`, `.asterix`).
    Blocks,
}

impl Container {
    /// The container an output path's extension asks for.
    pub fn of(path: &Path) -> Option<Self> {
        match path.extension()?.to_str()?.to_ascii_lowercase().as_str() {
            "pcap" => Some(Self::Pcap),
            "ast" | "asterix" => Some(Self::Blocks),
            _ => None,
        }
    }
}

/// The datagrams of an encoding, each at its time (s), and what they hold.
#[derive(Debug, Clone, Default)]
pub struct Encoded {
    /// `(time, payload)` in time order.
    pub datagrams: Vec<(f64, Vec<u8>)>,
    /// CAT048 records written.
    pub reports: usize,
    /// CAT034 records written.
    pub messages: usize,
}

fn bad(k: usize, p: &Plot, what: impl std::fmt::Display) -> IoError {
    IoError::Encode(format!(
        "plot {} (t = {} s, sensor {}): {what}",
        k + 1,
        p.time(),
        p.sensor().0
    ))
}

/// The time of day of `t` (s on the time line, ≥ 0): `t mod 86 400`.
fn tod(item: ItemId, t: f64) -> Result<TimeOfDay, String> {
    if !(t.is_finite() && t >= 0.0) {
        return Err(format!("time {t} s: ASTERIX times of day need t ≥ 0"));
    }
    TimeOfDay::from_seconds(item, t.rem_euclid(DAY)).map_err(|e| e.to_string())
}

fn source(k: usize, p: &Plot) -> Result<DataSource, IoError> {
    source_of(p.sensor().0).ok_or_else(|| {
        bad(
            k,
            p,
            "a sensor above 65 535 has no SAC/SIC (sensor = 256 · SAC + SIC)",
        )
    })
}

/// The CAT048 report of polar plot `p`.
fn report(k: usize, p: &Plot) -> Result<Cat048, IoError> {
    let Measurement::Polar(m) = p.measurement() else {
        return Err(bad(
            k,
            p,
            "CAT048 I048/040 carries 2-D polar plots (range, azimuth); this plot is not one",
        ));
    };
    let item = ItemId {
        cat: 48,
        name: "140",
    };
    Ok(Cat048 {
        source: Some(source(k, p)?),
        time: Some(tod(item, p.time()).map_err(|e| bad(k, p, e))?),
        // TYP 1 (single PSR detection), SIM: simulated plots.
        descriptor: Some(ReportDescriptor {
            typ: 1,
            sim: true,
            ..ReportDescriptor::default()
        }),
        polar: Some(
            MeasuredPolar::from_range_azimuth(m.range(), m.azimuth()).map_err(|e| bad(k, p, e))?,
        ),
        ..Cat048::default()
    })
}

/// One CAT034 message of boundary `k` of `sweep` at `t` for `source`.
fn message(sweep: &Sweep, k: i64, t: f64, source: DataSource) -> Result<Cat034, IoError> {
    let n = i64::from(sweep.sectors.max(1));
    let i = k.rem_euclid(n);
    let usage = |e: String| IoError::Encode(format!("CAT034 message at t = {t} s: {e}"));
    let time = tod(
        ItemId {
            cat: 34,
            name: "030",
        },
        t,
    )
    .map_err(usage)?;
    let mut m = Cat034 {
        source: Some(source),
        time: Some(time),
        ..Cat034::default()
    };
    if i == 0 {
        m.message_type = Some(MessageType::NorthMarker);
        m.rotation_period =
            Some(RotationPeriod::from_seconds(sweep.period).map_err(|e| usage(e.to_string()))?);
    } else {
        // I034/020: the azimuth of the sector's start, clockwise from north, 360°/2^8.
        let turn = i as f64 / n as f64;
        let cw = if sweep.clockwise { turn } else { 1.0 - turn };
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let sector = ((cw * 256.0).round() as i64).rem_euclid(256) as u8;
        m.message_type = Some(MessageType::SectorCrossing);
        m.sector = Some(Sector(sector));
    }
    Ok(m)
}

/// Collects CAT048 reports into datagrams.
struct Packer {
    out: Encoded,
    pending: Vec<Cat048>,
    last_time: f64,
}

impl Packer {
    fn flush(&mut self) -> Result<(), IoError> {
        if self.pending.is_empty() {
            return Ok(());
        }
        let mut bytes = Vec::new();
        encode_block(&self.pending, &mut bytes)
            .map_err(|e| IoError::Encode(format!("CAT048 block: {e}")))?;
        self.out.reports += self.pending.len();
        self.out.datagrams.push((self.last_time, bytes));
        self.pending.clear();
        Ok(())
    }

    fn messages(&mut self, t: f64, records: &[Cat034]) -> Result<(), IoError> {
        self.flush()?;
        let mut bytes = Vec::new();
        encode_block(records, &mut bytes)
            .map_err(|e| IoError::Encode(format!("CAT034 block: {e}")))?;
        self.out.messages += records.len();
        self.out.datagrams.push((t, bytes));
        Ok(())
    }
}

/// Encodes `plots` (in time order) as CAT048 datagrams, one block of up to 64 reports
/// each (a synchronous sensor: one datagram per scan time); with a `sweep`, a CAT034
/// datagram per sensor at each sector boundary from the first plot to the last one
/// (a north marker every `sectors`-th).
///
/// # Errors
/// [`IoError::Encode`] for a plot that is not 2-D polar, a negative time, a sensor
/// above 65 535, or a value outside its item's range.
pub fn encode_plots(plots: &[Plot], sweep: Option<&Sweep>) -> Result<Encoded, IoError> {
    let mut sensors: Vec<u32> = plots.iter().map(|p| p.sensor().0).collect();
    sensors.sort_unstable();
    sensors.dedup();
    let mut pack = Packer {
        out: Encoded::default(),
        pending: Vec::new(),
        last_time: 0.0,
    };
    let step = sweep.map(|s| s.period / f64::from(s.sectors.max(1)));
    #[allow(clippy::cast_possible_truncation)]
    let mut next_k = match (sweep, step, plots.first()) {
        (Some(s), Some(l), Some(p)) => Some(((p.time() - s.north_time) / l).ceil() as i64),
        _ => None,
    };
    for (k, p) in plots.iter().enumerate() {
        if let (Some(s), Some(l)) = (sweep, step) {
            while let Some(b) = next_k {
                let t = s.north_time + b as f64 * l;
                if t > p.time() {
                    break;
                }
                let records = sensors
                    .iter()
                    .filter_map(|id| source_of(*id))
                    .map(|src| message(s, b, t, src))
                    .collect::<Result<Vec<_>, _>>()?;
                pack.messages(t, &records)?;
                next_k = Some(b + 1);
            }
        } else if !pack.pending.is_empty() && p.time().total_cmp(&pack.last_time).is_ne() {
            pack.flush()?;
        }
        pack.pending.push(report(k, p)?);
        pack.last_time = p.time();
        if pack.pending.len() == RECORDS_PER_BLOCK {
            pack.flush()?;
        }
    }
    pack.flush()?;
    Ok(pack.out)
}

/// Writes `enc` to `out` atomically: a pcap capture (each datagram at its time after
/// 1970-01-01T00:00:00 UTC, so that the capture time of day is the ASTERIX one) or the
/// blocks concatenated.
///
/// # Errors
/// [`IoError::Capture`] for a datagram pcap cannot hold; [`IoError::Io`].
pub fn write(out: &Path, enc: &Encoded, container: Container) -> Result<(), IoError> {
    let bytes = match container {
        Container::Blocks => enc.datagrams.iter().flat_map(|(_, d)| d.clone()).collect(),
        Container::Pcap => {
            let datagrams: Vec<Datagram<'_>> = enc
                .datagrams
                .iter()
                .enumerate()
                .map(|(packet, (t, payload))| Datagram {
                    time: Duration::try_from_secs_f64(*t).ok(),
                    payload,
                    packet,
                })
                .collect();
            argus_capture::write_pcap(&datagrams, &Endpoints::default()).map_err(|source| {
                IoError::Capture {
                    file: out.to_path_buf(),
                    source,
                }
            })?
        }
    };
    write_atomic(out, &bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sweep(clockwise: bool) -> Sweep {
        Sweep {
            period: 4.0,
            north_time: 0.0,
            clockwise,
            sectors: 8,
        }
    }

    #[test]
    fn sector_messages_name_the_sector_start_clockwise_from_north() {
        let src = DataSource { sac: 0, sic: 1 };
        // Boundary 0 of each revolution: a north marker with the period (4 s = 512/128).
        let north = message(&sweep(true), 8, 4.0, src).unwrap();
        assert_eq!(north.message_type, Some(MessageType::NorthMarker));
        assert_eq!(north.rotation_period, Some(RotationPeriod(512)));
        assert_eq!(north.time, Some(TimeOfDay(512)));
        // Boundary 2 of 8: a quarter turn, 90° = 64 × 360°/256 clockwise; a
        // counter-clockwise beam is then at 270° (192).
        let cw = message(&sweep(true), 2, 1.0, src).unwrap();
        assert_eq!(cw.message_type, Some(MessageType::SectorCrossing));
        assert_eq!(cw.sector, Some(Sector(64)));
        assert_eq!(
            message(&sweep(false), 2, 1.0, src).unwrap().sector,
            Some(Sector(192))
        );
        // A negative boundary index is the same sector of the revolution before.
        assert_eq!(
            message(&sweep(true), -6, -3.0 + 86_400.0, src)
                .unwrap()
                .sector,
            Some(Sector(64))
        );
    }

    #[test]
    fn only_polar_plots_with_a_time_of_day_are_written() {
        let polar = Plot::polar(1.0, argus_sensors::SensorId(1), 1000.0, 0.0).unwrap();
        let enc = encode_plots(&[polar, polar], None).unwrap();
        // One scan time: one datagram, two reports, no sweep so no CAT034.
        assert_eq!((enc.datagrams.len(), enc.reports, enc.messages), (1, 2, 0));
        let neg = Plot::polar(-1.0, argus_sensors::SensorId(1), 1000.0, 0.0).unwrap();
        assert!(
            matches!(encode_plots(&[neg], None), Err(IoError::Encode(m)) if m.contains("t ≥ 0"))
        );
        let far = Plot::polar(0.0, argus_sensors::SensorId(1), 500e3, 0.0).unwrap();
        assert!(
            matches!(encode_plots(&[far], None), Err(IoError::Encode(m)) if m.contains("I048/040"))
        );
        let big = Plot::polar(0.0, argus_sensors::SensorId(70_000), 1000.0, 0.0).unwrap();
        assert!(
            matches!(encode_plots(&[big], None), Err(IoError::Encode(m)) if m.contains("65 535"))
        );
    }
}

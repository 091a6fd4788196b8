//! CAT048 target reports as polar plots and CAT034 service messages as sector events:
//! times of day made one time line across midnight, azimuths converted explicitly from
//! ASTERIX's clockwise-from-north θ to Argus's counter-clockwise-from-east.

use argus_asterix::{DataSource, MessageType, Record};

use super::Surveillance;

/// Seconds in a day: I048/140 and I034/030 count from midnight UTC.
pub(crate) const DAY: f64 = 86_400.0;

/// A CAT048 report with a data source, a time and a measured polar position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RadarPlot {
    /// 1-based record number in the file.
    pub number: u64,
    /// I048/010.
    pub source: DataSource,
    /// I048/140 on the file's time line (s, one day after another across midnight).
    pub time: f64,
    /// I048/040 RHO (m).
    pub range: f64,
    /// I048/040 θ in Argus's convention (rad, counter-clockwise from east, (−π, π]).
    pub azimuth: f64,
}

/// A CAT034 message with a data source and a time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Service {
    /// I034/010.
    pub source: DataSource,
    /// I034/030 on the file's time line (s).
    pub time: f64,
    /// I034/000.
    pub kind: MessageType,
    /// I034/041 antenna rotation period (s).
    pub period: Option<f64>,
}

/// The radar content of a file: plots and service messages, each in time order.
#[derive(Debug, Clone, Default)]
pub struct RadarData {
    /// The plots (stable-sorted by time).
    pub plots: Vec<RadarPlot>,
    /// The CAT034 messages with a source and a time (stable-sorted by time).
    pub services: Vec<Service>,
    /// CAT048 reports without I048/010, /140 or /040, or with RHO = 0: not plots.
    pub incomplete: usize,
    /// Records of other categories (CAT021, CAT062) and CAT034 without source or time.
    pub other: usize,
}

/// Times of day made one time line: a time more than half a day before the last one
/// seen is the next day's (the record crossed midnight); `t = day · 86 400 + tod`.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Clock {
    day: u32,
    last: Option<f64>,
}

impl Clock {
    /// The time-line time of a time of day (s).
    pub(crate) fn at(&mut self, tod: f64) -> f64 {
        if let Some(last) = self.last
            && tod + DAY / 2.0 < last
        {
            self.day += 1;
        }
        self.last = Some(tod);
        f64::from(self.day) * DAY + tod
    }
}

/// The plots and service messages of `s`, in time order.
pub fn radar_data(s: &Surveillance) -> RadarData {
    let mut out = RadarData::default();
    let mut clock = Clock::default();
    for r in &s.records {
        match &r.record {
            Record::Cat048(c) => {
                let (Some(source), Some(tod), Some(polar)) = (c.source, c.time, c.polar) else {
                    out.incomplete += 1;
                    continue;
                };
                let time = clock.at(tod.seconds());
                if polar.rho == 0 {
                    out.incomplete += 1;
                    continue;
                }
                out.plots.push(RadarPlot {
                    number: r.number,
                    source,
                    time,
                    range: polar.range_m(),
                    // Explicit: θ clockwise from north → Argus's ccw from east.
                    azimuth: polar.theta.argus(),
                });
            }
            Record::Cat034(c) => {
                let (Some(source), Some(tod)) = (c.source, c.time) else {
                    out.other += 1;
                    continue;
                };
                out.services.push(Service {
                    source,
                    time: clock.at(tod.seconds()),
                    kind: c.message_type.unwrap_or(MessageType::Other(0)),
                    period: c.rotation_period.map(|p| p.seconds()),
                });
            }
            _ => out.other += 1,
        }
    }
    out.plots.sort_by(|a, b| a.time.total_cmp(&b.time));
    out.services.sort_by(|a, b| a.time.total_cmp(&b.time));
    out
}

/// A radar's rotation as its CAT034 messages give it: the first I034/041 period, and
/// the phase of its first north marker (`north_time` in `[0, period)`). `None` without
/// both.
pub(crate) fn rotation_of(services: &[Service], source: DataSource) -> Option<(f64, f64)> {
    let mine = || services.iter().filter(move |s| s.source == source);
    let period = mine().find_map(|s| s.period).filter(|p| *p > 0.0)?;
    let north = mine().find(|s| s.kind == MessageType::NorthMarker)?.time;
    Some((period, north.rem_euclid(period)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_clock_crosses_midnight_once() {
        let mut c = Clock::default();
        // 23:59:59, then 00:00:01 (two seconds later), then a small step back (kept in
        // the day: not more than half a day).
        assert_eq!(c.at(86_399.0).to_bits(), 86_399.0f64.to_bits());
        assert_eq!(c.at(1.0).to_bits(), 86_401.0f64.to_bits());
        assert_eq!(c.at(0.5).to_bits(), 86_400.5f64.to_bits());
        assert_eq!(c.at(3600.0).to_bits(), 90_000.0f64.to_bits());
    }
}

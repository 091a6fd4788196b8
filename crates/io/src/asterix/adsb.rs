//! ADS-B reports: CAT021 (I021/071 time of applicability for position, /080 target
//! address, /131 high-resolution or /130 WGS-84 position, /090 NACp) to the ADS-B CSV
//! layout `argus-adsb` reads (`timestamp,icao24,latitude,longitude`; `altitude`,
//! `groundspeed`, `track`, … are items Argus does not decode yet, so not written), with
//! the position's per-axis σ from NACp (`sigma_position`, m; empty without NACp, an
//! extra column the ADS-B reader ignores).

use argus_asterix::Record;

use super::Surveillance;
use super::plots::Clock;

/// The ADS-B CSV text of the CAT021 reports of `s` that have a time of applicability
/// for position, a target address and a position, in file order: `timestamp` in seconds
/// of the time line (the first day's midnight is 0, a time more than 12 h before the
/// previous one is the next day's); and how many CAT021 reports lacked one of the three.
pub fn adsb_csv(s: &Surveillance) -> (String, usize, usize) {
    let mut clock = Clock::default();
    let mut text = String::from("timestamp,icao24,latitude,longitude,sigma_position\n");
    let (mut rows, mut incomplete) = (0, 0);
    for r in &s.records {
        let Record::Cat021(c) = &r.record else {
            continue;
        };
        let (Some(tod), Some(address), Some(p)) =
            (c.t_position, c.target_address, c.position_hr.or(c.position))
        else {
            incomplete += 1;
            continue;
        };
        let t = clock.at(tod.seconds());
        let sigma = c
            .quality
            .and_then(argus_asterix::Quality::position_sigma_m)
            .map_or(String::new(), |v| v.to_string());
        text.push_str(&format!(
            "{t},{address:06x},{},{},{sigma}\n",
            p.lat_deg, p.lon_deg
        ));
        rows += 1;
    }
    (text, rows, incomplete)
}

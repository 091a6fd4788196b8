//! The truth of `real-traffic`: the committed ADS-B hour, cleaned, in the radar's local
//! East-North plane.

use std::io::Read;

use argus_adsb::{CleaningConfig, CleaningReport, EpochUnit, clean, read_csv};
use argus_geo::{Geodetic, LocalFrame};

use crate::error::ScenarioError;

/// The busiest hour of the `traffic` 2.13 package's `collections/quickstart` sample
/// (OpenSky ADS-B around Paris; source, licence and extraction in
/// `data/real-traffic/README.md`), gzipped CSV in the OpenSky / `traffic` layout.
const EXTRACT: &[u8] =
    include_bytes!("../../../../data/real-traffic/quickstart-busiest-hour.csv.gz");

/// Epoch second of the hour's start, 2021-10-07 13:33:00 UTC: the scenario's `t = 0`.
pub(crate) const EPOCH_START: f64 = 1_633_613_580.0;

/// One truth sample in the local plane: time since [`EPOCH_START`] (s), position east /
/// north of the radar (m), velocity (m/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Sample {
    pub(crate) t: f64,
    pub(crate) x: f64,
    pub(crate) vx: f64,
    pub(crate) y: f64,
    pub(crate) vy: f64,
}

/// One continuous flight segment (the cleaning splits an aircraft at gaps).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Path {
    /// `icao24`, with `-k` for the k-th segment (k ≥ 1) of a split aircraft.
    pub(crate) name: String,
    /// Samples at strictly increasing times.
    pub(crate) samples: Vec<Sample>,
}

impl Path {
    /// The position at `t` by linear interpolation, `None` outside the path.
    pub(crate) fn position_at(&self, t: f64) -> Option<[f64; 2]> {
        let s = &self.samples;
        let first = s.first()?;
        let last = s.last()?;
        if t < first.t || t > last.t {
            return None;
        }
        let k = s.partition_point(|p| p.t <= t).clamp(1, s.len() - 1);
        let (a, b) = (&s[k - 1], &s[k]);
        let w = (t - a.t) / (b.t - a.t);
        Some([a.x + w * (b.x - a.x), a.y + w * (b.y - a.y)])
    }
}

/// The cleaned hour in the frame of a radar at `site`.
///
/// Velocity from the ADS-B ground speed and track where both are reported, else from the
/// neighbouring positions (central difference; one-sided at the ends).
///
/// # Errors
/// [`ScenarioError::Adsb`] if the extract does not read or clean (it is committed, so
/// only a corrupted build could), [`ScenarioError::Geo`] for a conversion failure.
pub(crate) fn load(site: Geodetic) -> Result<(Vec<Path>, CleaningReport), ScenarioError> {
    let mut text = Vec::new();
    flate2::read::GzDecoder::new(EXTRACT)
        .read_to_end(&mut text)
        .map_err(|e| ScenarioError::Degenerate {
            scenario: "real-traffic",
            message: format!("the committed extract does not decompress: {e}"),
        })?;
    let records = read_csv(text.as_slice(), EpochUnit::Seconds)?;
    let (flights, report) = clean(&records, &CleaningConfig::default())?;
    let frame = LocalFrame::wgs84(site);
    let mut paths = Vec::with_capacity(flights.len());
    let mut last_icao = String::new();
    let mut segment = 0;
    for f in &flights {
        if f.icao24 == last_icao {
            segment += 1;
        } else {
            segment = 0;
            last_icao.clone_from(&f.icao24);
        }
        let enu = f.to_enu(&frame)?;
        let mut samples: Vec<Sample> = enu
            .iter()
            .map(|e| Sample {
                t: e.time - EPOCH_START,
                x: e.position.east,
                vx: e.velocity.map_or(f64::NAN, |v| v.east),
                y: e.position.north,
                vy: e.velocity.map_or(f64::NAN, |v| v.north),
            })
            .collect();
        fill_velocity(&mut samples);
        let name = if segment == 0 {
            f.icao24.clone()
        } else {
            format!("{}-{segment}", f.icao24)
        };
        paths.push(Path { name, samples });
    }
    Ok((paths, report))
}

/// Replaces missing (NaN) velocities by position differences.
fn fill_velocity(s: &mut [Sample]) {
    let n = s.len();
    for k in 0..n {
        if s[k].vx.is_finite() && s[k].vy.is_finite() {
            continue;
        }
        let (a, b) = (k.saturating_sub(1), (k + 1).min(n - 1));
        let dt = s[b].t - s[a].t;
        if dt > 0.0 {
            s[k].vx = (s[b].x - s[a].x) / dt;
            s[k].vy = (s[b].y - s[a].y) / dt;
        } else {
            s[k].vx = 0.0;
            s[k].vy = 0.0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Paris CDG's aerodrome reference point (AIP France AD 2 LFPG: 49°00′35″ N,
    /// 002°32′52″ E, 392 ft).
    fn cdg() -> Geodetic {
        Geodetic::from_degrees(49.009_722, 2.547_778, 119.0).unwrap()
    }

    #[test]
    fn the_extract_loads_as_the_readme_says() {
        let (paths, report) = load(cdg()).unwrap();
        // data/real-traffic/README.md: 109 262 records of 123 aircraft.
        assert_eq!(report.records, 109_262);
        assert_eq!(report.aircraft, 123);
        assert!(!paths.is_empty());
        for p in &paths {
            assert!(p.samples.windows(2).all(|w| w[1].t > w[0].t), "{}", p.name);
            assert!(
                p.samples
                    .iter()
                    .all(|s| s.vx.is_finite() && s.vy.is_finite()),
                "{}",
                p.name
            );
            // Inside the hour.
            assert!(p.samples[0].t >= 0.0 && p.samples.last().unwrap().t < 3600.0);
        }
    }

    #[test]
    fn interpolation_is_linear_between_samples_and_none_outside() {
        let p = Path {
            name: "a".into(),
            samples: vec![
                Sample {
                    t: 0.0,
                    x: 0.0,
                    vx: 1.0,
                    y: 10.0,
                    vy: 0.0,
                },
                Sample {
                    t: 4.0,
                    x: 8.0,
                    vx: 1.0,
                    y: 10.0,
                    vy: 0.0,
                },
            ],
        };
        assert_eq!(p.position_at(1.0), Some([2.0, 10.0]));
        assert_eq!(p.position_at(4.0), Some([8.0, 10.0]));
        assert_eq!(p.position_at(-0.1), None);
        assert_eq!(p.position_at(4.1), None);
    }
}

//! The cleaning rules real ADS-B needs, and the report of what each dropped.
//!
//! Records are grouped by `icao24` (the aircraft), sorted by time (stably), and
//! passed through these rules in this order; each record is dropped by the first
//! rule it fails and counted under that rule in [`CleaningReport`]:
//!
//! 1. **missing position** — no latitude or longitude.
//! 2. **on ground** — the `onground` flag is set (surface movement at an airport is
//!    not part of an airborne surveillance picture). Off with
//!    [`CleaningConfig::drop_on_ground`].
//! 3. **missing altitude** — airborne but no altitude (a truth sample needs 3-D).
//! 4. **altitude out of bounds** — outside [`CleaningConfig::altitude_bounds_ft`]
//!    (default −2 000 ft to 60 000 ft: below the lowest airfields, above any civil
//!    ceiling; the quickstart hour has a 123 100 ft value).
//! 5. **duplicate time** — the same time as the previous kept record (first kept).
//! 6. **stale position** — latitude and longitude identical to the previous kept
//!    record's: the position was carried forward (a state vector repeats the last
//!    decoded position until a new one arrives), not measured again.
//! 7. **gap** — the flight is split where consecutive kept records are more than
//!    [`CleaningConfig::max_gap_s`] apart (nothing is dropped; splits are counted).
//! 8. **spikes** — within a segment, a record inconsistent with its neighbours:
//!    moving faster than [`CleaningConfig::max_speed_mps`] horizontally
//!    (**position spike**) or [`CleaningConfig::max_vertical_speed_mps`] vertically
//!    (**altitude spike**) both from the previous kept record and to the next
//!    record. A record with one neighbour (a segment's end) is a spike when it is
//!    inconsistent with it and that neighbour is consistent with its own other
//!    neighbour. A single outlier is removed; a genuine jump (both sides agree with
//!    their own side) is kept.
//! 9. **short segment** — segments left with fewer than
//!    [`CleaningConfig::min_samples`] records are dropped.

use argus_geo::{Ellipsoid, GeoError, Geodetic};

use crate::error::AdsbError;
use crate::flight::{Flight, TruthSample};
use crate::record::{FT, StateVector};

/// The cleaning thresholds (see the module docs for the rules).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CleaningConfig {
    /// Drop records flagged on ground (default `true`).
    pub drop_on_ground: bool,
    /// Plausible altitudes, feet (default −2 000 to 60 000).
    pub altitude_bounds_ft: (f64, f64),
    /// The fastest plausible ground speed, m/s (default 350 ≈ 680 kt; the fastest in
    /// the quickstart hour is 539 kt = 277 m/s).
    pub max_speed_mps: f64,
    /// The fastest plausible vertical speed, m/s (default 100 ≈ 19 700 ft/min; the
    /// quickstart hour's reported rates stay within ±6 400 ft/min).
    pub max_vertical_speed_mps: f64,
    /// A flight is split where records are more than this apart, seconds (default 60).
    pub max_gap_s: f64,
    /// Segments with fewer records are dropped (default 10).
    pub min_samples: usize,
}

impl Default for CleaningConfig {
    fn default() -> Self {
        Self {
            drop_on_ground: true,
            altitude_bounds_ft: (-2000.0, 60_000.0),
            max_speed_mps: 350.0,
            max_vertical_speed_mps: 100.0,
            max_gap_s: 60.0,
            min_samples: 10,
        }
    }
}

impl CleaningConfig {
    fn validate(&self) -> Result<(), AdsbError> {
        let positive = |what, value: f64| {
            if value > 0.0 && value.is_finite() {
                Ok(())
            } else {
                Err(AdsbError::Parameter {
                    what,
                    value,
                    domain: "must be finite and > 0",
                })
            }
        };
        positive("max_speed_mps", self.max_speed_mps)?;
        positive("max_vertical_speed_mps", self.max_vertical_speed_mps)?;
        positive("max_gap_s", self.max_gap_s)?;
        let (lo, hi) = self.altitude_bounds_ft;
        if !(lo.is_finite() && hi.is_finite() && lo < hi) {
            return Err(AdsbError::Parameter {
                what: "altitude_bounds_ft",
                value: lo,
                domain: "needs finite lo < hi",
            });
        }
        Ok(())
    }
}

/// What the cleaning kept and dropped, record counts per rule.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct CleaningReport {
    /// Records read.
    pub records: usize,
    /// Distinct `icao24` addresses read.
    pub aircraft: usize,
    /// Rule 1.
    pub missing_position: usize,
    /// Rule 2.
    pub on_ground: usize,
    /// Rule 3.
    pub missing_altitude: usize,
    /// Rule 4.
    pub altitude_out_of_bounds: usize,
    /// Rule 5.
    pub duplicate_time: usize,
    /// Rule 6.
    pub stale_position: usize,
    /// Rule 7: the number of splits made (no record dropped).
    pub gap_splits: usize,
    /// Rule 8, horizontal.
    pub position_spike: usize,
    /// Rule 8, vertical.
    pub altitude_spike: usize,
    /// Rule 9: records dropped with their short segments.
    pub short_segment: usize,
    /// Records kept.
    pub kept: usize,
    /// Flights (segments) kept.
    pub flights: usize,
    /// Distinct aircraft with at least one flight kept.
    pub aircraft_kept: usize,
}

/// One aircraft's records that passed rules 1–6, in SI.
struct Candidate {
    time: f64,
    lat: f64,
    lon: f64,
    alt_m: f64,
    /// ECEF of the point on the surface below, for horizontal distances.
    surface: [f64; 3],
    source: usize,
}

/// Applies the cleaning rules to `records` and returns the flights (sorted by
/// `icao24`, then time) and the report.
///
/// # Errors
/// [`AdsbError::Parameter`] for an invalid `config`, [`AdsbError::Record`] for a
/// record whose latitude or longitude is not a valid coordinate (records built by
/// hand; the readers check them).
pub fn clean(
    records: &[StateVector],
    config: &CleaningConfig,
) -> Result<(Vec<Flight>, CleaningReport), AdsbError> {
    config.validate()?;
    let mut report = CleaningReport {
        records: records.len(),
        ..CleaningReport::default()
    };
    let mut order: Vec<usize> = (0..records.len()).collect();
    order.sort_by(|&a, &b| {
        records[a]
            .icao24
            .cmp(&records[b].icao24)
            .then(records[a].time.total_cmp(&records[b].time))
    });
    let mut flights = Vec::new();
    let mut start = 0;
    while start < order.len() {
        let icao = &records[order[start]].icao24;
        let end = start
            + order[start..]
                .iter()
                .take_while(|&&i| &records[i].icao24 == icao)
                .count();
        report.aircraft += 1;
        let before = flights.len();
        clean_aircraft(
            records,
            &order[start..end],
            config,
            &mut report,
            &mut flights,
        )?;
        if flights.len() > before {
            report.aircraft_kept += 1;
        }
        start = end;
    }
    report.flights = flights.len();
    report.kept = flights.iter().map(|f: &Flight| f.samples.len()).sum();
    Ok((flights, report))
}

fn clean_aircraft(
    records: &[StateVector],
    idx: &[usize],
    config: &CleaningConfig,
    report: &mut CleaningReport,
    flights: &mut Vec<Flight>,
) -> Result<(), AdsbError> {
    // Rules 1–6.
    let mut kept: Vec<Candidate> = Vec::with_capacity(idx.len());
    for &i in idx {
        let r = &records[i];
        let (Some(lat), Some(lon)) = (r.latitude, r.longitude) else {
            report.missing_position += 1;
            continue;
        };
        if config.drop_on_ground && r.onground == Some(true) {
            report.on_ground += 1;
            continue;
        }
        let Some(alt_ft) = r.altitude_ft else {
            report.missing_altitude += 1;
            continue;
        };
        let (lo, hi) = config.altitude_bounds_ft;
        if !(lo..=hi).contains(&alt_ft) {
            report.altitude_out_of_bounds += 1;
            continue;
        }
        if let Some(prev) = kept.last() {
            if r.time.total_cmp(&prev.time).is_eq() {
                report.duplicate_time += 1;
                continue;
            }
            // Bit-identical: a carried-forward position repeats the very same value.
            if lat.to_bits() == prev.lat.to_bits() && lon.to_bits() == prev.lon.to_bits() {
                report.stale_position += 1;
                continue;
            }
        }
        let surface =
            surface_ecef(lat, lon).map_err(|source| AdsbError::Record { index: i, source })?;
        kept.push(Candidate {
            time: r.time,
            lat,
            lon,
            alt_m: alt_ft * FT,
            surface,
            source: i,
        });
    }
    // Rule 7: segments.
    let mut segments: Vec<&[Candidate]> = Vec::new();
    let mut s = 0;
    for k in 1..=kept.len() {
        if k == kept.len() || kept[k].time - kept[k - 1].time > config.max_gap_s {
            if k > s {
                segments.push(&kept[s..k]);
            }
            if k < kept.len() {
                report.gap_splits += 1;
            }
            s = k;
        }
    }
    // Rules 8–9.
    for seg in segments {
        let samples = despike(seg, config, report);
        if samples.len() < config.min_samples {
            report.short_segment += samples.len();
            continue;
        }
        let truth: Vec<TruthSample> = samples
            .iter()
            .map(|&k| TruthSample::from_record(&records[seg[k].source], seg[k].alt_m))
            .collect();
        flights.push(Flight::new(records, seg.iter().map(|c| c.source), truth));
    }
    Ok(())
}

/// Rule 8 on one segment: the indices of the records kept.
fn despike(seg: &[Candidate], config: &CleaningConfig, report: &mut CleaningReport) -> Vec<usize> {
    let n = seg.len();
    let mut kept: Vec<usize> = Vec::with_capacity(n);
    for k in 0..n {
        let prev = kept.last().copied();
        let next = (k + 1 < n).then_some(k + 1);
        let spike = match (prev, next) {
            (Some(p), Some(nx)) => {
                jump(seg, p, k, config).filter(|_| jump(seg, k, nx, config).is_some())
            }
            // The last record: its previous kept record must agree with the one before.
            (Some(p), None) => jump(seg, p, k, config).filter(|_| {
                kept.len() >= 2 && jump(seg, kept[kept.len() - 2], p, config).is_none()
            }),
            // The first record: the next must agree with the one after.
            (None, Some(nx)) => jump(seg, k, nx, config)
                .filter(|_| nx + 1 < n && jump(seg, nx, nx + 1, config).is_none()),
            (None, None) => None,
        };
        match spike {
            Some(Jump::Horizontal) => report.position_spike += 1,
            Some(Jump::Vertical) => report.altitude_spike += 1,
            None => kept.push(k),
        }
    }
    kept
}

/// Which speed limit a pair of records breaks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Jump {
    Horizontal,
    Vertical,
}

/// The limit broken going from `seg[a]` to `seg[b]`, horizontal first.
fn jump(seg: &[Candidate], a: usize, b: usize, config: &CleaningConfig) -> Option<Jump> {
    let dt = (seg[b].time - seg[a].time).abs();
    let (p, q) = (seg[a].surface, seg[b].surface);
    let d = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt();
    if d > config.max_speed_mps * dt {
        Some(Jump::Horizontal)
    } else if (seg[b].alt_m - seg[a].alt_m).abs() > config.max_vertical_speed_mps * dt {
        Some(Jump::Vertical)
    } else {
        None
    }
}

/// The ECEF point on the WGS-84 surface below `lat`, `lon` (degrees): horizontal
/// distances are chords (shorter than the arc by < 1 mm at 30 km).
fn surface_ecef(lat: f64, lon: f64) -> Result<[f64; 3], GeoError> {
    let e = Geodetic::from_degrees(lat, lon, 0.0)?.to_ecef(&Ellipsoid::WGS84);
    Ok([e.x, e.y, e.z])
}

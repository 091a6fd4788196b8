//! Cleaned flights: per-aircraft, time-ordered truth samples in SI units, and
//! their positions and velocities in a local ENU frame.

use argus_geo::{Enu, GeoError, Geodetic, LocalFrame};

use crate::record::StateVector;

/// One cleaned ADS-B sample, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TruthSample {
    /// Seconds since 1970-01-01 UTC.
    pub time: f64,
    /// Latitude, degrees.
    pub latitude_deg: f64,
    /// Longitude, degrees east.
    pub longitude_deg: f64,
    /// Barometric altitude, metres (see [`TruthSample::to_enu`] for how it is used).
    pub altitude_m: f64,
    /// Ground speed, m/s.
    pub groundspeed_mps: Option<f64>,
    /// Track over ground, radians clockwise from north.
    pub track_rad: Option<f64>,
    /// Vertical rate, m/s (positive up).
    pub vertical_rate_mps: Option<f64>,
}

/// A truth sample in a local frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnuSample {
    /// Seconds since 1970-01-01 UTC.
    pub time: f64,
    /// Position, metres.
    pub position: Enu,
    /// Velocity, m/s, when ground speed and track were given (vertical rate 0 when
    /// missing).
    pub velocity: Option<Enu>,
}

impl TruthSample {
    pub(crate) fn from_record(r: &StateVector, altitude_m: f64) -> Self {
        Self {
            time: r.time,
            latitude_deg: r.latitude.unwrap_or_default(),
            longitude_deg: r.longitude.unwrap_or_default(),
            altitude_m,
            groundspeed_mps: r.groundspeed_mps(),
            track_rad: r.track_rad(),
            vertical_rate_mps: r.vertical_rate_mps(),
        }
    }

    /// The sample in `frame`. The barometric altitude is used as the height above
    /// the ellipsoid: it differs from it by the geoid (≈ 45 m around Paris) and the
    /// pressure-altitude error (up to a few hundred metres), which moves `up` by as
    /// much but the horizontal position by only `δh · d / R⊕` (< 3 m for 100 m at
    /// 150 km). The velocity `(v sin χ, v cos χ, ḣ)` in the aircraft's own ENU axes
    /// (`χ` the track clockwise from north) is rotated into `frame`'s axes.
    ///
    /// # Errors
    /// [`GeoError`] for a coordinate out of range (samples built by hand).
    pub fn to_enu(&self, frame: &LocalFrame) -> Result<EnuSample, GeoError> {
        let here = Geodetic::from_degrees(self.latitude_deg, self.longitude_deg, self.altitude_m)?;
        let velocity = match (self.groundspeed_mps, self.track_rad) {
            (Some(v), Some(chi)) => {
                let local = LocalFrame::new(here, *frame.ellipsoid());
                let (s, c) = chi.sin_cos();
                let own = Enu {
                    east: v * s,
                    north: v * c,
                    up: self.vertical_rate_mps.unwrap_or(0.0),
                };
                Some(frame.vector_from_frame(&local, &own))
            }
            _ => None,
        };
        Ok(EnuSample {
            time: self.time,
            position: frame.geodetic_to_enu(&here),
            velocity,
        })
    }
}

/// One aircraft's cleaned, time-ordered samples between two gaps.
#[derive(Debug, Clone, PartialEq)]
pub struct Flight {
    /// The aircraft's ICAO 24-bit address.
    pub icao24: String,
    /// The first non-empty callsign of the segment's records.
    pub callsign: Option<String>,
    /// The samples, strictly increasing in time.
    pub samples: Vec<TruthSample>,
}

impl Flight {
    pub(crate) fn new(
        records: &[StateVector],
        sources: impl Iterator<Item = usize> + Clone,
        samples: Vec<TruthSample>,
    ) -> Self {
        let mut s = sources.clone();
        let icao24 = s
            .next()
            .map(|i| records[i].icao24.clone())
            .unwrap_or_default();
        let callsign = sources.filter_map(|i| records[i].callsign.clone()).next();
        Self {
            icao24,
            callsign,
            samples,
        }
    }

    /// The samples in `frame` (see [`TruthSample::to_enu`]).
    ///
    /// # Errors
    /// As [`TruthSample::to_enu`].
    pub fn to_enu(&self, frame: &LocalFrame) -> Result<Vec<EnuSample>, GeoError> {
        self.samples.iter().map(|s| s.to_enu(frame)).collect()
    }
}

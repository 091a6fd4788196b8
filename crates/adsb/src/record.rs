//! One ADS-B state vector in the OpenSky / `traffic` layout, and its units.

/// Feet to metres (exact, international foot).
pub const FT: f64 = 0.3048;
/// Knots to metres per second (exact: 1852 m per hour).
pub const KT: f64 = 1852.0 / 3600.0;
/// Feet per minute to metres per second.
pub const FT_PER_MIN: f64 = FT / 60.0;

/// One state vector as the `traffic` library holds it (its `core/types.py`
/// annotates `altitude` in `"ft"`, `groundspeed` in `"kts"`, `vertical_rate` in
/// `"ft/min"`; `track` is in degrees clockwise from true north, latitude and
/// longitude in degrees WGS-84). The raw values are kept in those units; the `*_si`
/// accessors convert explicitly.
#[derive(Debug, Clone, PartialEq)]
pub struct StateVector {
    /// Seconds since 1970-01-01T00:00:00 UTC.
    pub time: f64,
    /// The 24-bit ICAO transponder address, lower-case hex as given.
    pub icao24: String,
    /// Latitude, degrees (`None` when the record has no position).
    pub latitude: Option<f64>,
    /// Longitude, degrees east.
    pub longitude: Option<f64>,
    /// Barometric altitude, feet (`None` when not given, as on the ground).
    pub altitude_ft: Option<f64>,
    /// Ground speed, knots.
    pub groundspeed_kt: Option<f64>,
    /// Track over ground, degrees clockwise from north.
    pub track_deg: Option<f64>,
    /// Vertical rate, feet per minute (positive up).
    pub vertical_rate_fpm: Option<f64>,
    /// The flight's callsign, trimmed (`None` when empty).
    pub callsign: Option<String>,
    /// The on-ground flag when the input has one.
    pub onground: Option<bool>,
}

impl StateVector {
    /// Altitude in metres.
    #[must_use]
    pub fn altitude_m(&self) -> Option<f64> {
        self.altitude_ft.map(|a| a * FT)
    }

    /// Ground speed in m/s.
    #[must_use]
    pub fn groundspeed_mps(&self) -> Option<f64> {
        self.groundspeed_kt.map(|v| v * KT)
    }

    /// Vertical rate in m/s.
    #[must_use]
    pub fn vertical_rate_mps(&self) -> Option<f64> {
        self.vertical_rate_fpm.map(|v| v * FT_PER_MIN)
    }

    /// Track in radians clockwise from north.
    #[must_use]
    pub fn track_rad(&self) -> Option<f64> {
        self.track_deg.map(f64::to_radians)
    }
}

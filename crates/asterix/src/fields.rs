//! Field types shared by several categories, held as the raw integers the
//! wire carries (so encode → decode is exact), with conversions to SI units.

use argus_sensors::RadarAzimuth;

use crate::error::{EncodeError, ItemId};

/// Metres per nautical mile (exact, by definition).
pub const NM: f64 = 1852.0;

/// Rounds `value / lsb` to the nearest integer in `[min, max]`.
pub(crate) fn quantise(
    item: ItemId,
    what: &'static str,
    value: f64,
    lsb: f64,
    min: f64,
    max: f64,
) -> Result<i64, EncodeError> {
    let q = (value / lsb).round();
    // A negative value for an unsigned field is an error even when it would round to 0.
    if !q.is_finite() || q < min || q > max || (min >= 0.0 && value < 0.0) {
        return Err(EncodeError::OutOfRange { item, what, value });
    }
    // In range [min, max] ⊂ i64 by the check above.
    #[allow(clippy::cast_possible_truncation)]
    Ok(q as i64)
}

/// Data source identifier (I048/010, I034/010, I062/010): SAC and SIC.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct DataSource {
    /// System area code.
    pub sac: u8,
    /// System identification code.
    pub sic: u8,
}

/// Time of day, 24-bit count of 1/128 s since midnight UTC (I048/140, I034/030).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct TimeOfDay(pub u32);

impl TimeOfDay {
    /// LSB: 1/128 s.
    pub const LSB: f64 = 1.0 / 128.0;

    /// Seconds since midnight.
    #[must_use]
    pub fn seconds(self) -> f64 {
        f64::from(self.0) * Self::LSB
    }

    /// The nearest count to `seconds`, which must lie in `[0, 2^24 / 128)`.
    ///
    /// # Errors
    /// [`EncodeError::OutOfRange`] if it does not, or is not finite.
    pub fn from_seconds(item: ItemId, seconds: f64) -> Result<Self, EncodeError> {
        let q = quantise(
            item,
            "time of day",
            seconds,
            Self::LSB,
            0.0,
            f64::from((1u32 << 24) - 1),
        )?;
        Ok(Self(u32::try_from(q).unwrap_or(0)))
    }

    pub(crate) fn read(b: &[u8]) -> Self {
        Self(u32::from_be_bytes([0, b[0], b[1], b[2]]))
    }

    pub(crate) fn bytes(self) -> [u8; 3] {
        let [_, a, b, c] = (self.0 & 0x00ff_ffff).to_be_bytes();
        [a, b, c]
    }
}

/// An azimuth as the 16-bit count of 360°/2^16 clockwise from north
/// (I048/040 θ, I048/200 heading).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Azimuth16(pub u16);

impl Azimuth16 {
    /// LSB in degrees: 360 / 2^16.
    pub const LSB_DEG: f64 = 360.0 / 65536.0;

    /// Degrees clockwise from north, in `[0, 360)`.
    #[must_use]
    pub fn degrees(self) -> f64 {
        f64::from(self.0) * Self::LSB_DEG
    }

    /// Radians clockwise from north (the radar convention).
    #[must_use]
    pub fn radar(self) -> RadarAzimuth {
        RadarAzimuth(self.degrees().to_radians())
    }

    /// Argus's convention: radians counter-clockwise from east (+x), in
    /// `(−π, π]`, converted explicitly with [`RadarAzimuth::to_math`].
    #[must_use]
    pub fn argus(self) -> f64 {
        self.radar().to_math()
    }

    /// The nearest count to a radar-convention azimuth (any finite angle; wraps).
    ///
    /// # Errors
    /// [`EncodeError::OutOfRange`] if the angle is not finite.
    pub fn from_radar(item: ItemId, az: RadarAzimuth) -> Result<Self, EncodeError> {
        let deg = az.0.to_degrees().rem_euclid(360.0);
        let q = quantise(item, "azimuth", deg, Self::LSB_DEG, 0.0, 65536.0)?;
        // 360° rounds to 65536 ≡ 0.
        Ok(Self(u16::try_from(q % 65536).unwrap_or(0)))
    }

    /// The nearest count to an azimuth in Argus's convention (ccw from east, rad).
    ///
    /// # Errors
    /// [`EncodeError::OutOfRange`] if the angle is not finite.
    pub fn from_argus(item: ItemId, theta: f64) -> Result<Self, EncodeError> {
        if !theta.is_finite() {
            return Err(EncodeError::OutOfRange {
                item,
                what: "azimuth",
                value: theta,
            });
        }
        Self::from_radar(item, RadarAzimuth::from_math(theta))
    }
}

pub(crate) fn u16_at(b: &[u8], i: usize) -> u16 {
    u16::from_be_bytes([b[i], b[i + 1]])
}

pub(crate) fn i16_at(b: &[u8], i: usize) -> i16 {
    i16::from_be_bytes([b[i], b[i + 1]])
}

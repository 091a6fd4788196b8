//! Angle wrapping and the explicit conversion between the radar azimuth
//! convention (clockwise from north) and the one used inside Argus
//! (counter-clockwise from +x).

use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Wraps an angle to `(−π, π]`: the one angle wrap of the workspace.
///
/// The result is `angle − k·τ` for the integer `k` that puts it in `(−π, π]`, where
/// `τ` is `std::f64::consts::TAU`, computed without rounding: `%` is exact, and the one
/// correction by `±τ` is exact too (Sterbenz: both operands lie within a factor of two).
/// So an angle already in `(−π, π]` comes back bit for bit (a tiny `−1e-300` stays
/// `−1e-300`, `−0.0` stays `−0.0`), `wrap_angle(π) = π`, `wrap_angle(−π) = π`, every
/// odd multiple of `π` gives `π` and every even one `±0`. A huge angle is reduced
/// exactly modulo the `f64` `τ` (which is not exactly 2π, so the wrap of `1e300`
/// has no physical meaning, but it lies in range). A NaN or infinite input gives NaN
/// (there is no meaningful wrapped value); the filters reject non-finite residuals.
#[must_use]
#[inline]
pub fn wrap_angle(angle: f64) -> f64 {
    let r = angle % TAU;
    if r > PI {
        r - TAU
    } else if r <= -PI {
        r + TAU
    } else {
        r
    }
}

/// Converts an azimuth in the radar convention (clockwise from north, i.e. from
/// +y towards +x) to Argus' convention (counter-clockwise from +x), wrapped to
/// `(−π, π]`: `θ = π/2 − α`.
///
/// ```
/// use argus_sensors::{radar_to_math_azimuth, math_to_radar_azimuth};
/// use std::f64::consts::FRAC_PI_2;
/// // Due east is 90° clockwise from north and 0 rad from +x.
/// assert!(radar_to_math_azimuth(FRAC_PI_2).abs() < 1e-15);
/// // Due north is 0 in the radar convention and π/2 from +x.
/// assert!((radar_to_math_azimuth(0.0) - FRAC_PI_2).abs() < 1e-15);
/// assert!((math_to_radar_azimuth(FRAC_PI_2)).abs() < 1e-15);
/// ```
#[must_use]
pub fn radar_to_math_azimuth(radar_azimuth: f64) -> f64 {
    wrap_angle(FRAC_PI_2 - radar_azimuth)
}

/// Converts an azimuth in Argus' convention (counter-clockwise from +x) to the
/// radar convention (clockwise from north), in `[0, 2π)`: `α = π/2 − θ`.
/// A non-finite input gives NaN.
#[must_use]
pub fn math_to_radar_azimuth(math_azimuth: f64) -> f64 {
    let a = (FRAC_PI_2 - math_azimuth).rem_euclid(TAU);
    // rem_euclid can round up to exactly 2π.
    if a >= TAU { 0.0 } else { a }
}

/// An azimuth in the radar convention: clockwise from north, radians.
///
/// A newtype so that a radar-convention angle cannot be passed where Argus
/// expects the counter-clockwise-from-+x one; convert with [`RadarAzimuth::to_math`].
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd)]
pub struct RadarAzimuth(pub f64);

impl RadarAzimuth {
    /// The azimuth counter-clockwise from +x, in `(−π, π]` (see [`radar_to_math_azimuth`]).
    #[must_use]
    pub fn to_math(self) -> f64 {
        radar_to_math_azimuth(self.0)
    }

    /// The radar-convention azimuth of a counter-clockwise-from-+x one, in `[0, 2π)`
    /// (see [`math_to_radar_azimuth`]).
    #[must_use]
    pub fn from_math(math_azimuth: f64) -> Self {
        Self(math_to_radar_azimuth(math_azimuth))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_boundaries() {
        // Exact values from the definition of (−π, π].
        assert!((wrap_angle(PI) - PI).abs() < 1e-15);
        assert!((wrap_angle(-PI) - PI).abs() < 1e-15);
        assert!((wrap_angle(1.5 * PI) + 0.5 * PI).abs() < 1e-15);
        assert!((wrap_angle(-1.5 * PI) - 0.5 * PI).abs() < 1e-15);
        assert!((wrap_angle(7.0 * TAU + 0.25) - 0.25).abs() < 1e-12);
        // In range: returned unchanged, bit for bit.
        for a in [-1e-300, 1e-300, 0.1, -0.1, 3.0, -3.0, -0.0] {
            assert_eq!(wrap_angle(a).to_bits(), f64::to_bits(a));
        }
        // Multiples of π: odd ones give π, even ones ±0.
        for k in [-7.0, -3.0, -1.0, 1.0, 3.0, 7.0] {
            assert!((wrap_angle(k * PI) - PI).abs() < 1e-12);
        }
        assert!(wrap_angle(TAU).abs() < 1e-15 && wrap_angle(-4.0 * TAU).abs() < 1e-15);
        // Huge values stay in range (reduced modulo the f64 TAU).
        for a in [1e300, -1e300, f64::MAX, 5e15] {
            let w = wrap_angle(a);
            assert!(w > -PI && w <= PI, "{a} -> {w}");
        }
        assert!(wrap_angle(f64::INFINITY).is_nan());
        assert!(wrap_angle(f64::NAN).is_nan());
        for k in -2000..2000 {
            let w = wrap_angle(f64::from(k) * 0.01);
            assert!(w > -PI && w <= PI);
        }
    }

    #[test]
    fn radar_convention_compass_points() {
        // North, east, south, west: radar 0, 90°, 180°, 270° ↔ math 90°, 0°, −90°, 180°.
        let pairs = [
            (0.0, FRAC_PI_2),
            (FRAC_PI_2, 0.0),
            (PI, -FRAC_PI_2),
            (1.5 * PI, PI),
        ];
        for (radar, math) in pairs {
            assert!((radar_to_math_azimuth(radar) - math).abs() < 1e-15);
            assert!((RadarAzimuth(radar).to_math() - math).abs() < 1e-15);
            assert!((math_to_radar_azimuth(math) - radar).abs() < 1e-15);
        }
    }
}

//! A rotating radar's beam: its period, direction and phase, and when it crosses an
//! azimuth.

use std::f64::consts::{FRAC_PI_2, TAU};

use crate::TrackerError;
use crate::field::{ConfigField, SensorField};

/// Which way a rotating radar's beam turns, seen from above.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum RotationDirection {
    /// North → east → south (the usual surveillance radar); Argus's azimuth decreases.
    #[default]
    Clockwise,
    /// North → west → south; Argus's azimuth increases.
    Counterclockwise,
}

/// A rotating radar: its beam turns at a constant rate and each plot is taken when the
/// beam crosses the target, at its own time.
///
/// The beam's azimuth in Argus's convention (counter-clockwise from +x, east) is
/// `β(t) = π/2 ∓ 2π (t − north_time) / period` (− clockwise, + counter-clockwise).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rotation {
    /// Revolution period (s), finite and positive.
    pub period: f64,
    /// Direction of rotation.
    pub direction: RotationDirection,
    /// A time at which the beam points north (Argus azimuth π/2) (s), finite.
    pub north_time: f64,
}

impl Rotation {
    /// A clockwise radar of `period` s whose beam points north at t = 0.
    #[must_use]
    pub fn clockwise(period: f64) -> Self {
        Self {
            period,
            direction: RotationDirection::Clockwise,
            north_time: 0.0,
        }
    }

    /// This rotation with `north_time` (s).
    #[must_use]
    pub fn with_north_time(self, north_time: f64) -> Self {
        Self { north_time, ..self }
    }

    /// This rotation turning `direction`.
    #[must_use]
    pub fn with_direction(self, direction: RotationDirection) -> Self {
        Self { direction, ..self }
    }

    /// `+1` counter-clockwise, `−1` clockwise.
    fn sign(&self) -> f64 {
        match self.direction {
            RotationDirection::Clockwise => -1.0,
            RotationDirection::Counterclockwise => 1.0,
        }
    }

    /// The beam's azimuth at `t` (rad, Argus convention, wrapped to (−π, π]).
    #[must_use]
    pub fn beam_azimuth(&self, t: f64) -> f64 {
        let a = FRAC_PI_2 + self.sign() * TAU * (t - self.north_time) / self.period;
        wrap(a)
    }

    /// The first time `≥ after` at which the beam points at `azimuth` (rad).
    #[must_use]
    pub fn crossing_after(&self, azimuth: f64, after: f64) -> f64 {
        // β(t) = azimuth ⇔ t = north_time + sign (azimuth − π/2) P / 2π + k P.
        let phase = (self.sign() * (azimuth - FRAC_PI_2)).rem_euclid(TAU) / TAU * self.period;
        let base = self.north_time + phase;
        let k = ((after - base) / self.period).ceil();
        let mut t = base + k * self.period;
        // Round-off of the ceil: step to the first crossing at or after `after`.
        if t < after {
            t += self.period;
        } else if t - self.period >= after {
            t -= self.period;
        }
        t
    }

    pub(crate) fn validate(&self) -> Result<(), TrackerError> {
        if !(self.period.is_finite() && self.period > 0.0) {
            return Err(TrackerError::InvalidConfig {
                field: ConfigField::Sensor(SensorField::RevolutionPeriod),
                value: self.period,
                reason: "must be finite and positive",
            });
        }
        if !self.north_time.is_finite() {
            return Err(TrackerError::InvalidConfig {
                field: ConfigField::Sensor(SensorField::NorthTime),
                value: self.north_time,
                reason: "must be finite",
            });
        }
        Ok(())
    }
}

/// An angle wrapped to (−π, π].
fn wrap(a: f64) -> f64 {
    let w = (a + std::f64::consts::PI).rem_euclid(TAU) - std::f64::consts::PI;
    if w <= -std::f64::consts::PI {
        w + TAU
    } else {
        w
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_beam_crosses_an_azimuth_where_its_azimuth_equals_it() {
        // β(crossing_after(a, t)) = a, and the crossing is the first at or after t;
        // tolerance: round-off of angles of order 10 rad (1e-9 rad).
        for dir in [
            RotationDirection::Clockwise,
            RotationDirection::Counterclockwise,
        ] {
            let rot = Rotation::clockwise(5.0)
                .with_direction(dir)
                .with_north_time(1.3);
            for k in 0..50 {
                let a = -3.1 + 0.125 * f64::from(k);
                let after = -7.0 + 0.77 * f64::from(k);
                let t = rot.crossing_after(a, after);
                assert!(t >= after && t < after + 5.0, "{t} after {after}");
                let d = wrap(rot.beam_azimuth(t) - a);
                assert!(
                    d.abs() < 1e-9,
                    "{dir:?} a {a}: beam {}",
                    rot.beam_azimuth(t)
                );
            }
        }
        // Clockwise from north at t = 0: east (0) a quarter turn later.
        let rot = Rotation::clockwise(4.0);
        assert!((rot.crossing_after(0.0, 0.0) - 1.0).abs() < 1e-12);
        // … south (−π/2) half a turn later, west (π) three quarters.
        assert!((rot.crossing_after(-std::f64::consts::FRAC_PI_2, 0.0) - 2.0).abs() < 1e-12);
        assert!((rot.crossing_after(std::f64::consts::PI, 0.0) - 3.0).abs() < 1e-12);
    }
}

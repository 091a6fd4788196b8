//! Random civil flights: straight legs, each followed by a coordinated turn or a speed
//! change, kept inside a radar's coverage annulus.

use core::ops::Range;

use argus_core_math::Vector;
use rand::{Rng, RngExt};

use crate::{KinematicState, Segment, SimError, Trajectory};

/// How [`random_flight`] draws a flight (all ranges uniform; distances m, speeds m/s,
/// times s). The default is the simulated civil traffic of the aircraft-IMM tests:
/// 900 s at 120–250 m/s starting 40–120 km from the radar, legs of 40–150 s, then a
/// ±1–3 °/s turn of 30–120 s (65 %) or a ±0.5–1.5 m/s² speed change of 20–60 s, the whole
/// flight 20–150 km from the radar at every 5 s.
#[derive(Debug, Clone, PartialEq)]
pub struct FlightEnvelope {
    /// Flight length.
    pub duration: f64,
    /// Start distance from the radar (at the origin).
    pub start_range: Range<f64>,
    /// Distances the flight must keep, checked every `check_period` seconds.
    pub coverage: Range<f64>,
    /// Sampling of the coverage check.
    pub check_period: f64,
    /// Start speed, and the bounds a speed change keeps.
    pub speed: Range<f64>,
    /// Straight-leg duration.
    pub leg: Range<f64>,
    /// Probability that a leg is followed by a turn (otherwise a speed change).
    pub turn_fraction: f64,
    /// Turn duration.
    pub turn_duration: Range<f64>,
    /// Turn rate magnitude, deg/s (the sign is drawn).
    pub turn_rate_deg: Range<f64>,
    /// Speed-change duration.
    pub accel_duration: Range<f64>,
    /// Acceleration magnitude, m/s².
    pub accel: Range<f64>,
    /// Above this speed a speed change is a deceleration with probability ½ (so fast
    /// flights do not stay near the top speed); `None`: only the speed bounds decide.
    pub slow_down_above: Option<f64>,
}

impl Default for FlightEnvelope {
    fn default() -> Self {
        Self {
            duration: 900.0,
            start_range: 40e3..120e3,
            coverage: 20e3..150e3,
            check_period: 5.0,
            speed: 120.0..250.0,
            leg: 40.0..150.0,
            turn_fraction: 0.65,
            turn_duration: 30.0..120.0,
            turn_rate_deg: 1.0..3.0,
            accel_duration: 20.0..60.0,
            accel: 0.5..1.5,
            slow_down_above: Some(185.0),
        }
    }
}

/// Flights drawn before [`random_flight`] gives up on an envelope it cannot fill.
const ATTEMPTS: usize = 10_000;

/// One random planar flight in `envelope`, drawn again until it stays inside the
/// coverage (the same `rng` numbers give the same flight).
///
/// # Errors
/// [`SimError::InvalidParameter`] when the envelope's duration or check period is not
/// positive and finite, one of its ranges is empty or not finite, a duration range
/// reaches down to zero, or no flight of 10 000 draws stays inside the coverage.
pub fn random_flight<G: Rng>(
    rng: &mut G,
    envelope: &FlightEnvelope,
) -> Result<Trajectory, SimError> {
    check(envelope)?;
    let checks = (envelope.duration / envelope.check_period) as usize;
    for _ in 0..ATTEMPTS {
        let traj = draw(rng, envelope)?;
        if stays_inside(&traj, envelope, checks)? {
            return Ok(traj);
        }
    }
    Err(SimError::InvalidParameter {
        what: "flight coverage",
        value: envelope.coverage.end,
        reason: "no drawn flight stayed inside it",
    })
}

/// The envelope's domain: what [`draw`] needs to draw at all (a uniform draw from an empty
/// range would panic) and to end (every segment lasts a positive time).
fn check(e: &FlightEnvelope) -> Result<(), SimError> {
    let invalid = |what, value, reason| {
        Err(SimError::InvalidParameter {
            what,
            value,
            reason,
        })
    };
    for (what, value) in [
        ("flight duration", e.duration),
        ("coverage check period", e.check_period),
    ] {
        if !(value.is_finite() && value > 0.0) {
            return invalid(what, value, "must be positive and finite");
        }
    }
    for (what, r) in [
        ("start range", &e.start_range),
        ("coverage", &e.coverage),
        ("speed", &e.speed),
        ("leg duration", &e.leg),
        ("turn duration", &e.turn_duration),
        ("turn rate", &e.turn_rate_deg),
        ("acceleration duration", &e.accel_duration),
        ("acceleration", &e.accel),
    ] {
        if !(r.start.is_finite() && r.end.is_finite() && r.start < r.end) {
            return invalid(what, r.start, "must be a finite range with start < end");
        }
    }
    for (what, r) in [
        ("leg duration", &e.leg),
        ("turn duration", &e.turn_duration),
        ("acceleration duration", &e.accel_duration),
    ] {
        if r.start <= 0.0 {
            return invalid(what, r.start, "must start above zero");
        }
    }
    Ok(())
}

/// Whether `traj` keeps inside the coverage at every check time `k · check_period`,
/// `k = 0 ..= checks`.
fn stays_inside(traj: &Trajectory, e: &FlightEnvelope, checks: usize) -> Result<bool, SimError> {
    for k in 0..=checks {
        let s = traj.state_at(k as f64 * e.check_period)?;
        if !e.coverage.contains(&s.position.x.hypot(s.position.y)) {
            return Ok(false);
        }
    }
    Ok(true)
}

/// One flight of `envelope`, before the coverage check.
fn draw<G: Rng>(rng: &mut G, e: &FlightEnvelope) -> Result<Trajectory, SimError> {
    let r0 = rng.random_range(e.start_range.clone());
    let az0 = rng.random_range(0.0..core::f64::consts::TAU);
    let mut speed: f64 = rng.random_range(e.speed.clone());
    let mut heading: f64 = rng.random_range(0.0..core::f64::consts::TAU);
    let start = KinematicState::planar(
        r0 * az0.cos(),
        r0 * az0.sin(),
        speed * heading.cos(),
        speed * heading.sin(),
    );
    let (mut segments, mut t) = (Vec::new(), 0.0);
    while t < e.duration {
        let leg = rng.random_range(e.leg.clone());
        segments.push(Segment::ConstantVelocity { duration: leg });
        t += leg;
        if rng.random_range(0.0..1.0) < e.turn_fraction {
            let duration = rng.random_range(e.turn_duration.clone());
            let sign = if rng.random_range(0.0..1.0) < 0.5 {
                -1.0
            } else {
                1.0
            };
            let rate = sign * rng.random_range(e.turn_rate_deg.clone()).to_radians();
            segments.push(Segment::Turn { duration, rate });
            heading += rate * duration;
            t += duration;
        } else {
            let duration = rng.random_range(e.accel_duration.clone());
            let mut a = rng.random_range(e.accel.clone());
            // The draw for slowing down is made only when the top speed is not in the way
            // and the flight is above the threshold.
            if speed + a * duration > e.speed.end
                || e.slow_down_above
                    .is_some_and(|v| speed > v && rng.random_range(0.0..1.0) < 0.5)
            {
                a = -a;
            }
            if speed + a * duration < e.speed.start {
                a = a.abs();
            }
            let accel = Vector::<3>::new(a * heading.cos(), a * heading.sin(), 0.0);
            segments.push(Segment::Accelerate { duration, accel });
            speed += a * duration;
            t += duration;
        }
    }
    Trajectory::new(0.0, start, segments)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::run_rng;

    #[test]
    fn flights_keep_the_envelope_and_repeat_with_the_seed() {
        let e = FlightEnvelope::default();
        for run in 0..20 {
            let traj = random_flight(&mut run_rng(5, run), &e).unwrap();
            assert_eq!(traj, random_flight(&mut run_rng(5, run), &e).unwrap());
            for k in 0..=900 {
                let s = traj.state_at(f64::from(k)).unwrap();
                let r = s.position.x.hypot(s.position.y);
                let v = s.velocity.x.hypot(s.velocity.y);
                // Between the 5 s checks a flight moves ≤ 1.25 km; speed changes stop at
                // the bounds (the drawn acceleration is flipped when it would cross one).
                assert!((18.7e3..151.3e3).contains(&r), "run {run}: r {r} at {k} s");
                assert!((119.999..250.001).contains(&v), "run {run}: v {v} at {k} s");
            }
        }
    }

    #[test]
    fn an_envelope_that_cannot_be_filled_is_an_error() {
        let tiny = FlightEnvelope {
            coverage: 0.0..1.0,
            ..FlightEnvelope::default()
        };
        assert!(matches!(
            random_flight(&mut run_rng(1, 0), &tiny),
            Err(SimError::InvalidParameter {
                what: "flight coverage",
                ..
            })
        ));
        let bad = FlightEnvelope {
            duration: f64::NAN,
            ..FlightEnvelope::default()
        };
        assert!(random_flight(&mut run_rng(1, 0), &bad).is_err());
        // An empty range (a uniform draw from it would panic) and a zero-length leg (the
        // flight would never end) are errors naming them.
        for (envelope, name) in [
            (
                FlightEnvelope {
                    speed: 250.0..120.0,
                    ..FlightEnvelope::default()
                },
                "speed",
            ),
            (
                FlightEnvelope {
                    leg: 0.0..10.0,
                    ..FlightEnvelope::default()
                },
                "leg duration",
            ),
        ] {
            assert!(matches!(
                random_flight(&mut run_rng(1, 0), &envelope),
                Err(SimError::InvalidParameter { what, .. }) if what == name
            ));
        }
    }
}

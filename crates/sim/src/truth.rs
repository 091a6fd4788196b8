//! Ground truth: a target's trajectory as a list of flight segments, sampled at any time.

use argus_core_math::Vector;

use crate::error::{SimError, finite, non_negative};

/// A target's true position and velocity (m, m/s) in 3-D Cartesian coordinates.
/// A planar target simply keeps `z = vz = 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KinematicState {
    /// Position `[x, y, z]` in m.
    pub position: Vector<3>,
    /// Velocity `[vx, vy, vz]` in m/s.
    pub velocity: Vector<3>,
}

impl KinematicState {
    /// A planar state from `(x, y)` and `(vx, vy)`.
    #[must_use]
    pub fn planar(x: f64, y: f64, vx: f64, vy: f64) -> Self {
        Self {
            position: Vector::<3>::new(x, y, 0.0),
            velocity: Vector::<3>::new(vx, vy, 0.0),
        }
    }

    /// The 2-D state in the papers' order `[x, vx, y, vy]`.
    #[must_use]
    pub fn state_2d(&self) -> Vector<4> {
        Vector::<4>::new(
            self.position.x,
            self.velocity.x,
            self.position.y,
            self.velocity.y,
        )
    }

    /// The 3-D state in the papers' order `[x, vx, y, vy, z, vz]`.
    #[must_use]
    pub fn state_3d(&self) -> Vector<6> {
        Vector::<6>::from_column_slice(&[
            self.position.x,
            self.velocity.x,
            self.position.y,
            self.velocity.y,
            self.position.z,
            self.velocity.z,
        ])
    }
}

/// One flight segment. Durations are in s; a segment starts where the previous one ends.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Segment {
    /// Constant velocity.
    ConstantVelocity {
        /// Duration (s).
        duration: f64,
    },
    /// A coordinated turn in the horizontal plane at a fixed rate (rad/s, positive =
    /// counter-clockwise seen from +z); speed and vertical velocity are kept.
    Turn {
        /// Duration (s).
        duration: f64,
        /// Turn rate (rad/s).
        rate: f64,
    },
    /// A constant acceleration (m/s², 3-D).
    Accelerate {
        /// Duration (s).
        duration: f64,
        /// Acceleration `[ax, ay, az]` (m/s²).
        accel: Vector<3>,
    },
    /// A climb (or descent, negative) at a constant vertical speed (m/s), horizontal
    /// velocity kept. The vertical speed is set at the segment's start and kept after
    /// it; a later `Climb` with `vertical_speed = 0` levels off.
    Climb {
        /// Duration (s).
        duration: f64,
        /// Vertical speed (m/s).
        vertical_speed: f64,
    },
}

impl Segment {
    /// The segment's duration (s).
    #[must_use]
    pub fn duration(&self) -> f64 {
        match *self {
            Self::ConstantVelocity { duration }
            | Self::Turn { duration, .. }
            | Self::Accelerate { duration, .. }
            | Self::Climb { duration, .. } => duration,
        }
    }

    fn validate(&self) -> Result<(), SimError> {
        non_negative("segment duration", self.duration())?;
        match *self {
            Self::ConstantVelocity { .. } => {}
            Self::Turn { rate, .. } => {
                finite("turn rate", rate)?;
            }
            Self::Accelerate { accel, .. } => {
                for a in accel.iter() {
                    finite("acceleration", *a)?;
                }
            }
            Self::Climb { vertical_speed, .. } => {
                finite("vertical speed", vertical_speed)?;
            }
        }
        Ok(())
    }

    /// The state `tau` seconds into this segment, from the state at its start.
    ///
    /// Turn: `v(τ) = Rot(ωτ) v₀`, `p(τ) = p₀ + [sin ωτ, −(1−cos ωτ); 1−cos ωτ, sin ωτ] v₀ / ω`
    /// (Bar-Shalom, Li & Kirubarajan 2001, §11.7.1, the coordinated-turn transition).
    fn advance(&self, s: &KinematicState, tau: f64) -> KinematicState {
        let p = s.position;
        let v = s.velocity;
        match *self {
            Self::ConstantVelocity { .. } => KinematicState {
                position: p + v * tau,
                velocity: v,
            },
            Self::Turn { rate, .. } => {
                let wt = rate * tau;
                let (sn, cs) = wt.sin_cos();
                // sin(ωτ)/ω and (1 − cos ωτ)/ω, with their limits τ and 0 as ω → 0.
                let (a, b) = if rate.abs() < 1e-12 {
                    (tau, 0.0)
                } else {
                    (sn / rate, (1.0 - cs) / rate)
                };
                KinematicState {
                    position: Vector::<3>::new(
                        p.x + a * v.x - b * v.y,
                        p.y + b * v.x + a * v.y,
                        p.z + v.z * tau,
                    ),
                    velocity: Vector::<3>::new(cs * v.x - sn * v.y, sn * v.x + cs * v.y, v.z),
                }
            }
            Self::Accelerate { accel, .. } => KinematicState {
                position: p + v * tau + accel * (0.5 * tau * tau),
                velocity: v + accel * tau,
            },
            Self::Climb { vertical_speed, .. } => {
                let v = Vector::<3>::new(v.x, v.y, vertical_speed);
                KinematicState {
                    position: p + v * tau,
                    velocity: v,
                }
            }
        }
    }
}

/// A target's trajectory: a start time, a start state and flight segments, sampled
/// exactly (closed form within each segment) at any time of its span.
///
/// # Example
/// ```
/// use argus_sim::{KinematicState, Segment, Trajectory};
///
/// // 90 m/s along +x, then a quarter turn at +1.5 deg/s (60 s).
/// let traj = Trajectory::new(
///     0.0,
///     KinematicState::planar(0.0, 0.0, 90.0, 0.0),
///     vec![
///         Segment::ConstantVelocity { duration: 10.0 },
///         Segment::Turn { duration: 60.0, rate: 1.5_f64.to_radians() },
///     ],
/// )?;
/// let end = traj.state_at(70.0)?;
/// assert!((end.velocity.y - 90.0).abs() < 1e-9); // heading +y after 90°
/// # Ok::<(), argus_sim::SimError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    segments: Vec<Segment>,
    /// Start time of each segment (same length as `segments`).
    starts: Vec<f64>,
    /// State at the start of each segment.
    states: Vec<KinematicState>,
    end: f64,
}

impl Trajectory {
    /// Builds a trajectory starting at `t0` in `initial`.
    ///
    /// # Errors
    /// [`SimError::InvalidParameter`] for a non-finite start, a negative or non-finite
    /// duration or a non-finite segment parameter.
    pub fn new(t0: f64, initial: KinematicState, segments: Vec<Segment>) -> Result<Self, SimError> {
        finite("start time", t0)?;
        for c in initial.position.iter().chain(initial.velocity.iter()) {
            finite("initial state", *c)?;
        }
        let mut starts = Vec::with_capacity(segments.len());
        let mut states = Vec::with_capacity(segments.len());
        let mut t = t0;
        let mut s = initial;
        for seg in &segments {
            seg.validate()?;
            starts.push(t);
            states.push(s);
            s = seg.advance(&s, seg.duration());
            t += seg.duration();
        }
        if segments.is_empty() {
            // A trajectory with no segment is a single instant.
            starts.push(t0);
            states.push(initial);
        }
        Ok(Self {
            segments,
            starts,
            states,
            end: t,
        })
    }

    /// Start of the span (s).
    #[must_use]
    pub fn start(&self) -> f64 {
        self.starts.first().copied().unwrap_or(self.end)
    }

    /// End of the span (s).
    #[must_use]
    pub fn end(&self) -> f64 {
        self.end
    }

    /// The segments.
    #[must_use]
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }

    /// The true state at time `t` (s).
    ///
    /// # Errors
    /// [`SimError::TimeOutOfSpan`] when `t` is outside `[start, end]` (or NaN).
    pub fn state_at(&self, t: f64) -> Result<KinematicState, SimError> {
        let (start, end) = (self.start(), self.end);
        if !(t >= start - 1e-9 && t <= end + 1e-9) {
            return Err(SimError::TimeOutOfSpan { t, start, end });
        }
        // The last segment starting at or before t.
        let i = self.starts.partition_point(|&s| s <= t).saturating_sub(1);
        match (self.segments.get(i), self.states.get(i), self.starts.get(i)) {
            (Some(seg), Some(s0), Some(t0)) => Ok(seg.advance(s0, t - t0)),
            // No segment: the single instant.
            (None, Some(s0), _) => Ok(*s0),
            _ => Err(SimError::TimeOutOfSpan { t, start, end }),
        }
    }
}

/// Identifies a target in a scene.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
pub struct TargetId(pub u32);

/// Several targets flying at once.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Truth {
    targets: Vec<(TargetId, Trajectory)>,
}

impl Truth {
    /// An empty scene.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a target; ids are given in order of addition, from 0.
    pub fn add(&mut self, trajectory: Trajectory) -> TargetId {
        let id = TargetId(u32::try_from(self.targets.len()).unwrap_or(u32::MAX));
        self.targets.push((id, trajectory));
        id
    }

    /// The targets with their ids.
    #[must_use]
    pub fn targets(&self) -> &[(TargetId, Trajectory)] {
        &self.targets
    }

    /// The trajectory of `id`, if it exists.
    #[must_use]
    pub fn get(&self, id: TargetId) -> Option<&Trajectory> {
        self.targets
            .iter()
            .find_map(|(i, t)| (*i == id).then_some(t))
    }

    /// The earliest start and latest end over all targets; `None` for an empty scene.
    #[must_use]
    pub fn span(&self) -> Option<(f64, f64)> {
        let start = self
            .targets
            .iter()
            .map(|(_, t)| t.start())
            .reduce(f64::min)?;
        let end = self.targets.iter().map(|(_, t)| t.end()).reduce(f64::max)?;
        Some((start, end))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quarter_turn_lands_on_circle() {
        // A 90° CCW turn of speed v and rate ω from heading +x ends at (v/ω, v/ω)
        // relative to its start, heading +y: circle geometry, exact to round-off.
        let w = 1.5_f64.to_radians();
        let v = 90.0;
        let traj = Trajectory::new(
            0.0,
            KinematicState::planar(0.0, 0.0, v, 0.0),
            vec![Segment::Turn {
                duration: std::f64::consts::FRAC_PI_2 / w,
                rate: w,
            }],
        )
        .unwrap();
        let s = traj.state_at(traj.end()).unwrap();
        assert!((s.position.x - v / w).abs() < 1e-9, "{s:?}");
        assert!((s.position.y - v / w).abs() < 1e-9, "{s:?}");
        assert!(s.velocity.x.abs() < 1e-12 && (s.velocity.y - v).abs() < 1e-12);
    }

    #[test]
    fn segments_chain_and_sampling_is_continuous() {
        // CV 10 s at 10 m/s, then accelerate 2 m/s² for 5 s, then climb at 3 m/s for 4 s.
        // Hand values: x(10) = 100; x(15) = 100 + 50 + 25 = 175, vx = 20; z(19) = 12, x(19) = 255.
        let traj = Trajectory::new(
            0.0,
            KinematicState::planar(0.0, 0.0, 10.0, 0.0),
            vec![
                Segment::ConstantVelocity { duration: 10.0 },
                Segment::Accelerate {
                    duration: 5.0,
                    accel: Vector::<3>::new(2.0, 0.0, 0.0),
                },
                Segment::Climb {
                    duration: 4.0,
                    vertical_speed: 3.0,
                },
            ],
        )
        .unwrap();
        assert!((traj.state_at(10.0).unwrap().position.x - 100.0).abs() < 1e-12);
        let s15 = traj.state_at(15.0).unwrap();
        assert!((s15.position.x - 175.0).abs() < 1e-12 && (s15.velocity.x - 20.0).abs() < 1e-12);
        let s19 = traj.state_at(19.0).unwrap();
        assert!((s19.position.z - 12.0).abs() < 1e-12 && (s19.position.x - 255.0).abs() < 1e-12);
        assert!(matches!(
            traj.state_at(19.5),
            Err(SimError::TimeOutOfSpan { .. })
        ));
        assert!(traj.state_at(f64::NAN).is_err());
    }

    #[test]
    fn rejects_bad_segments() {
        let s0 = KinematicState::planar(0.0, 0.0, 1.0, 0.0);
        assert!(
            Trajectory::new(0.0, s0, vec![Segment::ConstantVelocity { duration: -1.0 }]).is_err()
        );
        assert!(
            Trajectory::new(
                0.0,
                s0,
                vec![Segment::Turn {
                    duration: 1.0,
                    rate: f64::NAN
                }]
            )
            .is_err()
        );
    }
}

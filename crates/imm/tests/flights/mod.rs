//! The simulated civil flights of docs/aircraft-imm.md and their plots, shared by
//! `aircraft_flights.rs` (the filter) and `aircraft_smoothing.rs` (the smoother): the
//! same seeds, the seed-000 radar.

use argus_core_math::Vector;
use argus_sensors::Measurement;
use argus_sim::{
    KinematicState, Schedule, Segment, SensorId, SensorKind, SensorSpec, Trajectory, Truth,
    generate_plots, run_rng,
};
use rand::RngExt;

pub(crate) const SIGMA_R: f64 = 70.0;
pub(crate) const SIGMA_AZ_DEG: f64 = 0.08;
const PERIOD: f64 = 5.0;
/// Flight length, s.
const DURATION: f64 = 900.0;
/// Steps after the start left out of the averages (the two-point start's transient).
pub(crate) const WARMUP_STEPS: usize = 6;

/// One random flight inside the 20–150 km annulus (drawn again until it stays inside).
pub(crate) fn flight(run: u64) -> Trajectory {
    let mut rng = run_rng(18_002, run);
    loop {
        let r0 = rng.random_range(40e3..120e3);
        let az0 = rng.random_range(0.0..std::f64::consts::TAU);
        let mut speed: f64 = rng.random_range(120.0..250.0);
        let mut heading: f64 = rng.random_range(0.0..std::f64::consts::TAU);
        let start = KinematicState::planar(
            r0 * az0.cos(),
            r0 * az0.sin(),
            speed * heading.cos(),
            speed * heading.sin(),
        );
        let mut segments = Vec::new();
        let mut t = 0.0;
        while t < DURATION {
            let leg = rng.random_range(40.0..150.0);
            segments.push(Segment::ConstantVelocity { duration: leg });
            t += leg;
            if rng.random_range(0.0..1.0) < 0.65 {
                let duration = rng.random_range(30.0..120.0);
                let sign = if rng.random_range(0.0..1.0) < 0.5 {
                    -1.0
                } else {
                    1.0
                };
                let rate = sign * rng.random_range(1.0_f64..3.0).to_radians();
                segments.push(Segment::Turn { duration, rate });
                heading += rate * duration;
                t += duration;
            } else {
                let duration = rng.random_range(20.0..60.0);
                let mut a = rng.random_range(0.5..1.5);
                if speed + a * duration > 250.0
                    || (speed > 185.0 && rng.random_range(0.0..1.0) < 0.5)
                {
                    a = -a;
                }
                if speed + a * duration < 120.0 {
                    a = a.abs();
                }
                let accel = Vector::<3>::new(a * heading.cos(), a * heading.sin(), 0.0);
                segments.push(Segment::Accelerate { duration, accel });
                speed += a * duration;
                t += duration;
            }
        }
        let traj = Trajectory::new(0.0, start, segments).unwrap();
        let inside = (0..=(DURATION / PERIOD) as usize).all(|k| {
            let s = traj.state_at(k as f64 * PERIOD).unwrap();
            (20e3..150e3).contains(&s.position.x.hypot(s.position.y))
        });
        if inside {
            return traj;
        }
    }
}

/// The plots of one flight: `(t, [r, θ])` and the true `[x, vx, y, vy]` at each.
pub(crate) fn plots(traj: &Trajectory, run: u64) -> Vec<(f64, Vector<2>, Vector<4>)> {
    let mut truth = Truth::new();
    truth.add(traj.clone());
    let radar = SensorSpec::new(
        SensorId(1),
        Vector::<3>::zeros(),
        SensorKind::Polar {
            sigma_range: SIGMA_R,
            sigma_azimuth: SIGMA_AZ_DEG.to_radians(),
        },
        Schedule::RotatingBeam {
            period: PERIOD,
            azimuth_at_zero: 0.0,
        },
    )
    .unwrap();
    let mut rng = run_rng(18_003, run);
    generate_plots(&truth, &[radar], &mut rng)
        .unwrap()
        .iter()
        .filter_map(|p| match p.plot.measurement() {
            Measurement::Polar(m) => {
                let (range, azimuth) = (m.range(), m.azimuth());
                Some((
                    p.plot.time(),
                    Vector::<2>::new(range, azimuth),
                    traj.state_at(p.plot.time()).unwrap().state_2d(),
                ))
            }
            _ => None,
        })
        .collect()
}

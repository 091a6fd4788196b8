//! The simulated civil flights of docs/aircraft-imm.md and their plots, shared by
//! `aircraft_flights.rs` (the filter) and `aircraft_smoothing.rs` (the smoother): the
//! same seeds, the seed-000 radar.

use argus_core_math::Vector;
use argus_sensors::Measurement;
use argus_sim::{
    FlightEnvelope, Schedule, SensorId, SensorKind, SensorSpec, Trajectory, Truth, generate_plots,
    random_flight, run_rng,
};

pub(crate) const SIGMA_R: f64 = 70.0;
pub(crate) const SIGMA_AZ_DEG: f64 = 0.08;
const PERIOD: f64 = 5.0;
/// Steps after the start left out of the averages (the two-point start's transient).
pub(crate) const WARMUP_STEPS: usize = 6;

/// One random flight of the default envelope (20–150 km from the radar, 900 s at
/// 120–250 m/s, legs, turns and speed changes; [`FlightEnvelope`]).
pub(crate) fn flight(run: u64) -> Trajectory {
    random_flight(&mut run_rng(18_002, run), &FlightEnvelope::default()).unwrap()
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

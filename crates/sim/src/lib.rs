//! Simulation for Argus: ground truth, plot generation and the Monte Carlo runner.
//!
//! - [`Trajectory`]: a target's truth from flight segments (constant velocity, fixed-rate
//!   turn, acceleration, climb/descent), sampled exactly at any time; [`Truth`] holds
//!   several targets.
//! - [`SensorSpec`] and [`generate_plots`]: each sensor's plots at its own times
//!   ([`Schedule::Periodic`] or a [`Schedule::RotatingBeam`] crossing the targets), with
//!   noise, bias, detection probability or Swerling I amplitudes, and Poisson clutter.
//!   The noise-free value is the sensor's `argus-sensors` measurement model (`h` of
//!   [`argus_sensors::Polar2D`], [`argus_sensors::Spherical3D`] or
//!   [`argus_sensors::CartesianPosition`]); each plot is an [`argus_sensors::Plot`],
//!   labelled with its true [`Origin`] for scoring ([`LabelledPlot`]).
//! - [`monte_carlo`]: runs in parallel with rayon, each seeded by [`run_rng`] from
//!   (base seed, run index), results in run order whatever the thread count.
//! - [`Metrics`]: RMSE per step, ANEES/ANIS with 95 % intervals, warm-up-excluded
//!   averages, track losses.
//! - [`Ospa`] and [`Gospa`] (with its localisation / missed / false split) between truth
//!   and estimated positions; [`TrackStatistics`] (track breaks, id swaps, time to
//!   confirm, false-track rate) from per-scan [`TrackScan`] associations.
//!
//! This crate makes truth and plots; it runs no filter.
//!
//! # Example
//! ```
//! use argus_sim::{
//!     KinematicState, Schedule, Segment, SensorKind, SensorSpec, Trajectory, Truth,
//!     generate_plots, run_rng,
//! };
//! use argus_core_math::Vector;
//! use argus_sensors::SensorId;
//!
//! let mut truth = Truth::new();
//! truth.add(Trajectory::new(
//!     0.0,
//!     KinematicState::planar(10_000.0, 0.0, 0.0, 100.0),
//!     vec![Segment::ConstantVelocity { duration: 20.0 }],
//! )?);
//! let radar = SensorSpec::new(
//!     SensorId(0),
//!     Vector::<3>::zeros(),
//!     SensorKind::Polar { sigma_range: 50.0, sigma_azimuth: 1e-3 },
//!     Schedule::Periodic { period: 2.0, offset: 0.0 },
//! )?;
//! let plots = generate_plots(&truth, &[radar], &mut run_rng(1, 0))?;
//! assert_eq!(plots.len(), 11); // t = 0, 2, …, 20 with P_D = 1
//! # Ok::<(), argus_sim::SimError>(())
//! ```

mod error;
mod metrics;
mod montecarlo;
mod ospa;
mod plots;
mod random_flight;
mod sensor;
mod track_metrics;
mod truth;

/// The workspace's sensor id (defined in `argus-sensors`), re-exported for scenarios.
pub use argus_sensors::SensorId;
pub use error::SimError;
pub use metrics::{Interval, Metrics, MetricsSums, RunRecord, StepMetrics, StepRecord};
pub use montecarlo::{monte_carlo, run_rng};
pub use ospa::{Gospa, GospaValue, Ospa, OspaValue};
pub use plots::{
    LabelledPlot, Origin, Rotation, beam_crossings, beam_crossings_along, generate_plots,
};
pub use random_flight::{FlightEnvelope, random_flight};
pub use sensor::{Bias, Clutter, ClutterRegion, Detection, Schedule, SensorKind, SensorSpec};
pub use track_metrics::{TrackScan, TrackStatistics};
pub use truth::{KinematicState, Segment, TargetId, Trajectory, Truth};

/// Re-export of the generator type every run uses.
pub use rand_chacha::ChaCha8Rng;

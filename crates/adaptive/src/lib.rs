//! Adaptive filters.
//!
//! - The decoupled tracking filter of Fitzgerald (1985) on converted radar-beacon
//!   plots ([`DecoupledFilter`], the CDKF of seed 003), its adaptive-`R` version
//!   ([`AdaptiveDecoupledFilter`], the ADKF, with [`REstimate`] and the corrected
//!   post-fit sample [`post_fit_sample`]), and the full coupled 6-state Kalman
//!   filter [`CoupledCvFilter`] as the accuracy reference.
//! - The radar-beacon plots (seed 003 eqs 9–12, corrected):
//!   [`argus_sensors::SphericalMeasurement`]s checked by [`beacon_plot`], converted to
//!   [`ConvertedPlot`]; their SNR-driven accuracy (eqs 6–8) is `argus_sensors`'
//!   [`SnrNoise`](argus_sensors::SnrNoise).
//! - GLRT maneuver detection, MRAS input estimation and the adaptive filter of
//!   seed 001 ([`glrt`], [`mras`], [`maneuver`]).
//! - One error type, [`AdaptiveError`].
//!
//! The Monte Carlo experiments that run these filters ("rbs-landing" of seed 003,
//! "maneuver-1d" and "drag-bearing" of seed 001) are in `argus-scenarios`.
//!
//! State layout: `[x, vx, y, vy, z, vz]`, SI units, azimuth from +x counter-clockwise.
//!
//! # Example
//! ```
//! use argus_adaptive::{
//!     AdaptiveDecoupledFilter, AdaptiveRConfig, AdaptiveState, ConvertedPlot, DecoupledEstimate,
//!     DecoupledFilter, FrameHandling, REstimate, Warmup, beacon_plot_of,
//! };
//! use argus_core_math::{Matrix, Vector};
//! use argus_sensors::SnrNoise;
//!
//! // Seed 003 eqs 6–8: Δr = 149.9 m, 2° beams, k_m = 1.6, σr = 2.97 m at 3006 m.
//! let link = SnrNoise::link_for_range_sigma(149.9, 2.97, 3006.0)?;
//! let radar = SnrNoise::new(149.9, 2f64.to_radians(), 2f64.to_radians(), 1.6, link)?;
//! let truth = Vector::<3>::new(-3000.0, -100.0, 157.2);
//! let sph = beacon_plot_of(&truth)?;
//! let plot = ConvertedPlot::from_spherical(&sph, &radar.sigmas_at_range(sph.range()))?;
//!
//! let cdkf = DecoupledFilter::new(0.05, FrameHandling::Rotate)?;
//! let adkf = AdaptiveDecoupledFilter::new(cdkf, AdaptiveRConfig::new(20, 1e-6, Warmup::Constant)?);
//! let block = Matrix::<2, 2>::new(100.0, 0.0, 0.0, 25.0);
//! let mean = Vector::<6>::new(-3003.5, 35.0, -100.0, 0.0, 157.0, -1.8);
//! let state = AdaptiveState {
//!     estimate: DecoupledEstimate::new(mean, [block; 3], *plot.frame())?,
//!     r: REstimate::new(plot.cartesian_noise())?,
//! };
//! let predicted = adkf.predict(&state, 0.1)?;
//! let (posterior, info) = adkf.update(&predicted, &plot)?;
//! assert!(info.innovation.nis.is_finite());
//! assert!((posterior.estimate.position() - truth).norm() < 10.0);
//! # Ok::<(), argus_adaptive::AdaptiveError>(())
//! ```

mod adaptive_r;
mod coupled;
mod decoupled;
mod decoupled_plot;
mod error;

pub use adaptive_r::{
    AdaptiveDecoupledFilter, AdaptiveRConfig, AdaptiveState, AdaptiveUpdate, REstimate, Warmup,
    post_fit_sample,
};
pub use coupled::CoupledCvFilter;
pub use decoupled::{DecoupledEstimate, DecoupledFilter, DecoupledUpdate, FrameHandling};
pub use decoupled_plot::{ConvertedPlot, aligned_frame, beacon_plot, beacon_plot_of};
pub use error::{AdaptiveError, finite as check_finite, positive as check_positive};

// Seed 001: GLRT maneuver detection, MRAS input estimation, the adaptive filter.
pub mod glrt;
pub mod maneuver;
pub mod mras;
pub use glrt::{Detection, FailureKind, Glrt, GlrtConfig, GlrtOutcome, StepLinearization};
pub use maneuver::{
    Compensation, InputLinearization, ManeuverFilter, ManeuverReport, ManeuverState, ModelInput,
};
pub use mras::Mras;

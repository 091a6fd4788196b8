//! Interacting multiple model (IMM) estimation and the multi-IMM measurement-noise
//! estimator of seed 000 (Jeon et al., 2010).
//!
//! - [`Imm`]: an IMM over `R` mode-matched filters (any [`argus_filters::GaussianFilter`])
//!   sharing an `N`-state: mixing with the spread-of-means term, mode probabilities in log
//!   space, combination; the interval is an argument of every cycle. [`MarkovMatrix`]
//!   validates the transition matrix; [`Embedded`] lifts a smaller model into the common state.
//!   [`PlanarImm`] is the IMM of Kalman filters on CV / fixed-rate CT models built from a
//!   run-time list ([`planar_filters`], [`markov_rows`]), its mode count picked by
//!   [`by_mode_count!`] (1 … [`MAX_PLANAR_MODES`]).
//! - [`MultiImm`]: the estimator of seed 000 eqs (8)–(14): `K` IMMs differing only in the
//!   assumed range/azimuth variances, per-step noise-mode probabilities with a uniform prior,
//!   reference update, `±p` grid and per-step clip, all parameters ([`NoiseGrid`]), with an
//!   independent range/azimuth grid as an option.
//! - [`VariationalNoiseImm`]: beyond the paper, one IMM plus a variational-Bayes recursion
//!   for range and azimuth variances whose fixed point is the true noise.
//! - [`DifferenceNoiseImm`]: beyond the paper, one IMM whose range and azimuth variances
//!   come from third differences of the raw plots (their expectation is the truth whatever
//!   the IMM's motion models); [`EvidenceNoiseImm`]: five IMMs and a fitted likelihood curve.
//! - [`AircraftImm`]: an IMM of unequal state sizes for aircraft — CV modes on
//!   `[x, vx, y, vy]` beside a coordinated turn with the turn rate as a state, mixed by
//!   Granström, Willett & Bar-Shalom's (2015) unbiased rule ([`Augmentation`]), updated
//!   in (range, azimuth) ([`AircraftRadar`]), with a documented default tuning
//!   ([`AircraftTuning`]) and a two-point start ([`two_point_start`]); see the
//!   [`aircraft`] module docs and docs/aircraft-imm.md.
//! - [`ImmTrack`], [`imm_smooth`]: fixed-interval IMM smoothing (forward–backward, after
//!   Kim's 1994 pairwise form weighed by each mode's backward likelihood) with smoothed mode
//!   probabilities; the equations and references are in [`smooth`].
//! - [`AircraftTrack`], [`aircraft_smooth`]: the same smoother for the aircraft IMM's
//!   modes of unequal state sizes (each pair brought into the later mode's state by the
//!   forward mixing map; [`aircraft`] module, docs/smoothing.md).
//! - Polar plots are converted with the unbiased conversion ([`unbiased_conversion`],
//!   [`UnbiasedConversion`]) using each hypothesis' own variances.
//!
//! Nothing allocates per step: estimates are arrays of stack Gaussians
//! (`[ImmEstimate<N, R>; K]` for the multi-IMM, i.e. 15 stack filters for the paper's 5 × 3).
//!
//! # Example
//! ```
//! use argus_imm::{MarkovMatrix, NoiseGrid, NoiseVariances};
//!
//! // Seed 000 eq (20) and the paper's grid (eq 14, p = 0.1).
//! let pi = MarkovMatrix::new([[0.95, 0.025, 0.025], [0.05, 0.95, 0.0], [0.05, 0.0, 0.95]])?;
//! let grid = NoiseGrid::<5>::common(0.1)?;
//! assert!((grid.factors()[0][0] - 0.8).abs() < 1e-12);
//! let truth = NoiseVariances::from_sigmas(70.0, 0.08_f64.to_radians())?;
//! assert!((truth.range() - 4900.0).abs() < 1e-9);
//! # let _ = pi;
//! # Ok::<(), argus_imm::ImmError>(())
//! ```

pub mod aircraft;
mod difference;
mod embed;
mod error;
mod evidence;
mod imm;
mod markov;
mod multi;
mod multi_merged;
mod planar;
mod polar;
pub mod smooth;
mod variational;

#[cfg(test)]
mod test_support;
#[cfg(test)]
mod tests;

pub use aircraft::{
    AircraftEkf, AircraftEstimate, AircraftImm, AircraftPrediction, AircraftRadar,
    AircraftSmoothed, AircraftStep, AircraftTrack, AircraftTransition, AircraftTuning,
    AircraftUpdate, Augmentation, PairTransition, aircraft_smooth, start_from_cv, two_point_start,
};
pub use difference::{DifferenceEstimate, DifferenceNoiseImm};
pub use embed::Embedded;
pub use error::ImmError;
pub use evidence::{EvidenceEstimate, EvidenceNoiseImm};
pub use imm::{Imm, ImmEstimate, ImmPrediction, ImmUpdate, moment_match};
pub use markov::{MarkovMatrix, PROBABILITY_SUM_TOL, log_probabilities, log_sum_exp};
pub use multi::{MultiImm, MultiImmEstimate, MultiImmUpdate, NoiseGrid};
pub use planar::{MAX_PLANAR_MODES, PlanarImm, markov_rows, per_mode, planar_filters};
pub use polar::{
    NoiseVariances, PlotConversion, PositionMeasurement, UnbiasedConversion, unbiased_conversion,
};
pub use smooth::{
    ForwardRecord, ImmSmoothError, ImmSmoothed, ImmStep, ImmTrack, ImmTransition, ModeTrack,
    PairWeights, imm_smooth,
};
pub use variational::{VariationalEstimate, VariationalNoiseImm};

//! Multisensor registration (seed 004: Kim, Kim, Park & Song, 2011): bias estimation
//! with pseudo-measurements for asynchronous sensors, the EXX baseline (Lin,
//! Bar-Shalom & Kirubarajan 2005) and compensation of the local tracks.
//!
//! - [`PolarSensor`], [`ConvertedPlot`]: the biased polar radar (an
//!   [`argus_sensors::Polar2D`] with an [`argus_sensors::PolarBias`]) and its linearisation
//!   `z = H X + B C β + w` (eqs (1)–(6)) at a chosen [`Linearization`].
//! - [`BiasedLocalFilter`], [`BiasedTrack`]: the CV filter on biased plots carrying the
//!   bias sensitivity `G`, so that `X̂ᵇ = X̂ + G β` (eqs (7)–(21)).
//! - [`pseudo_measurement`]: the stacked pseudo bias measurement of one plot against the
//!   other sensors' tracks (eqs (22)–(32)); [`BiasEstimator`]: sequential least squares
//!   over targets (eqs (33)–(36)), stack matrices for few sensors and faer for many.
//! - [`exx_pseudo_measurement`], [`ExxCollector`]: the EXX baseline on plot triples.
//! - [`Registrar`]: the asynchronous loop of Fig. 1; [`BiasedTrack::compensated`]:
//!   eqs (37)–(41).
//!
//! The bias-32 scenario of SPEC §004 that runs these pieces is in `argus-scenarios`.
//!
//! State order `[x, vx, y, vy]`; azimuth from +x counter-clockwise; SI units.
//!
//! # Example
//! ```
//! use argus_core_math::{Gaussian, Matrix, Vector};
//! use argus_registration::{BiasedLocalFilter, BiasedTrack, ConvertedPlot};
//!
//! // One linearised plot z = H X + B C β + w with β = [1, 0, 0, 0] and B C = [I₂ 0].
//! let bc = Matrix::<2, 4>::new(1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0);
//! let beta = Vector::<4>::new(1.0, 0.0, 0.0, 0.0);
//! let plot = ConvertedPlot::new(1.0, bc * beta, Matrix::<2, 2>::identity(), bc)?;
//! let filter = BiasedLocalFilter::new(0.0)?;
//! let start = Gaussian::new(Vector::<4>::zeros(), Matrix::<4, 4>::identity())?;
//! let track = filter.update(&BiasedTrack::bias_free(start, 0.0)?, &plot)?;
//! // The track moved by G β and the compensation removes it exactly.
//! let comp = track.compensated(&beta, &Matrix::<4, 4>::zeros())?;
//! assert!(comp.mean().norm() < 1e-12);
//! # Ok::<(), argus_registration::RegistrationError>(())
//! ```
//!
//! # References
//! H. W. Kim, D. H. Kim, H. D. Park, T. L. Song, "Multisensor Bias Estimation with Pseudo
//! Measurement for Asynchronous Sensors", 2011 (seed 004); X. Lin, Y. Bar-Shalom,
//! T. Kirubarajan, IEEE T-AES 40(2) 2004 and 41(3) 2005.

mod error;
mod estimator;
mod exx;
mod local;
mod polar;
mod pseudo;
mod registrar;

pub use error::{RegistrationError, finite as check_finite, positive as check_positive};
pub use estimator::{Backend, BiasEstimator, PseudoMeasurement, STACK_MAX_SENSORS};
pub use exx::{ExxCollector, exx_pseudo_measurement};
pub use local::{BiasedLocalFilter, BiasedTrack, position_matrix};
pub use polar::{ConvertedPlot, Linearization, PolarSensor};
pub use pseudo::pseudo_measurement;
pub use registrar::{Initiation, PlotOutcome, Registrar, RegistrarConfig};

//! Data association in clutter (seed 002): the validation gate, the nearest-neighbour
//! (NN), strongest-neighbour (SN), probabilistic strongest-neighbour (PSN) and
//! probabilistic data association (PDA) filters, the Rayleigh/Swerling I amplitude
//! model, and off-line performance prediction (HYCA for NN, with the recursion's own
//! gain or the plain NN's Kalman gain; the information reduction factor for PDA).
//!
//! Every association filter implements [`Associator`]: it takes the predicted
//! estimate and the [`MeasurementPrediction`](argus_filters::MeasurementPrediction)
//! that any [`GaussianFilter`](argus_filters::GaussianFilter) (KF, EKF, UKF) computed
//! once for the step, plus the scan's [`Candidate`] plots, and returns an [`Outcome`]
//! whose `log_likelihood` feeds an IMM's mode probabilities (IMM-PDA: call it per mode).
//!
//! # Example
//! ```
//! use argus_association::{Associator, Candidate, ClutterModel, Gate, Pda, track_step};
//! use argus_core_math::{Gaussian, Matrix, Vector};
//! use argus_filters::Kf;
//! use argus_motion_models::Cv2D;
//! use argus_sensors::CartesianPosition;
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let kf = Kf::new(Cv2D::discrete(1.0)?);
//! let radar = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 100.0)?;
//! let pda = Pda::new(Gate::from_probability(0.99, 2)?, 0.9, ClutterModel::Poisson { density: 1e-4 })?;
//! let prior = Gaussian::new(Vector::<4>::new(0.0, 10.0, 0.0, 0.0), Matrix::<4, 4>::identity() * 100.0)?;
//! let plots = [Candidate::new(Vector::<2>::new(11.0, 1.0)), Candidate::new(Vector::<2>::new(300.0, 0.0))];
//! let out = track_step(&kf, &pda, &radar, &prior, 1.0, &plots)?;
//! assert_eq!(out.gated, 1); // the far plot is outside the 99 % gate
//! # Ok(()) }
//! ```

mod amplitude;
mod associator;
mod error;
mod gate;
mod imm;
mod neighbour;
mod pda;
mod prediction;
mod psn;
mod quadrature;

pub use amplitude::AmplitudeModel;
pub use associator::{Associator, Candidate, Outcome, track_step};
pub use error::AssociationError;
pub use gate::Gate;
pub use imm::imm_associate;
pub use neighbour::{NearestNeighbour, StrongestNeighbour};
pub use pda::{ClutterModel, Pda};
pub use prediction::{
    LinearSystem, NnMoments, PerformancePredictor, PredictedFilter, PredictionStep, SteadyState,
    hyca_factors, nn_moments, pda_irf,
};
pub use psn::Psn;

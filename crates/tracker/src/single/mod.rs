//! The single-target engine: one estimator over every plot of a run, in order, one
//! estimate per row (`argus track` without a `[tracker]` table).
//!
//! A [`SingleTarget`] is built from an [`EstimatorSpec`] (the KF or EKF on the CV model,
//! an IMM of 1 … [`MAX_MODELS`] CV / fixed-rate CT Kalman filters, seed 000's multi-IMM
//! around it, or the aircraft IMM), the sensors the plots come from ([`SingleSensor`]:
//! id, position, polar and elevation σ) and an optional [`Smoothing`]. [`SingleTarget::run`]
//! takes the plots ([`TaggedPlot`]: a plot with the caller's tag, e.g. its line in a plot
//! file) and yields a [`SingleRun`]: one [`Estimate`] per row (2-D `[x, vx, y, vy]` or
//! 3-D `[x, vx, y, vy, z, vz]`, [`Estimates`]) and which values the rows have
//! ([`Columns`]).
//!
//! - **KF / EKF** ([`EstimatorSpec::KfConverted`], [`EstimatorSpec::Ekf`]): 2-D plots get
//!   the 2-D CV model, 3-D ones (spherical or Cartesian 3-D, as the first plot) the 3-D
//!   one. The track starts from the first two plots by two-point differencing
//!   ([`argus_filters::two_point_cv2`], [`argus_filters::two_point_cv3`]) on the plots
//!   converted to global positions (polar and spherical plots by the unbiased conversion
//!   with the sensor's σ, Cartesian reports as given); then one predict + update per
//!   plot (no prediction between plots of one instant). The KF is updated with converted
//!   plots, the EKF with polar / spherical plots themselves.
//! - **IMM** ([`EstimatorSpec::Imm`]): every mode from the same two-point start with
//!   `μ₀`; plots of one instant are applied in turn without mixing or prediction. Rows
//!   have the combined estimate and the mode probabilities.
//! - **Multi-IMM** ([`EstimatorSpec::MultiImm`]) over one polar radar's plots, its
//!   initial noise reference the sensor's σ; rows also have the noise estimate.
//! - **Aircraft IMM** ([`EstimatorSpec::Aircraft`]) over one 2-D radar's polar plots,
//!   started by its own two-point start ([`argus_imm::AircraftTuning::start`]); rows also
//!   have the CT mode's turn rate and its σ.
//!
//! With smoothing, every row also gets its step's smoothed estimate (and smoothed mode
//! probabilities): RTS for the KF / EKF (the estimator's own prediction), the IMM
//! smoothers of `argus_imm` over the recorded forward pass for the IMMs (the multi-IMM's
//! over its posteriors merged over the noise hypotheses); see [`crate::smooth`].
//!
//! Errors ([`SingleError`]) name the tag of the plot they are about or the sensor whose
//! σ is missing.

mod aircraft;
mod dim;
mod error;
mod estimator;
mod imm;
mod kf;
mod output;
mod smoothed;
mod spec;
mod start;
#[cfg(test)]
mod tests;

pub use error::{OneRadar, SingleError};
pub use estimator::{cv_kf, position, step, unbiased};
pub use output::{Columns, Estimate, Estimates, SingleRun, TaggedPlot};
pub use spec::{EstimatorSpec, ImmSpec, MAX_MODELS, MultiSpec, SingleSensor};

use crate::smooth::Smoothing;

/// The single-target engine (module docs): an estimator, its sensors and its smoothing.
#[derive(Debug, Clone, PartialEq)]
pub struct SingleTarget {
    estimator: EstimatorSpec,
    sensors: Vec<SingleSensor>,
    smoothing: Option<Smoothing>,
}

impl SingleTarget {
    /// The engine of `estimator` over plots of `sensors`, smoothed by `smoothing` when
    /// given. The estimator is built (and its parameters checked) by [`Self::run`].
    #[must_use]
    pub fn new(
        estimator: EstimatorSpec,
        sensors: Vec<SingleSensor>,
        smoothing: Option<Smoothing>,
    ) -> Self {
        Self {
            estimator,
            sensors,
            smoothing,
        }
    }

    /// Runs the estimator over `plots` (in time order): one estimate per plot from the
    /// second (plots of one instant each give a row).
    ///
    /// # Errors
    /// [`SingleError`]: a plot the estimator cannot use (its tag), a sensor without the
    /// σ its plots need, fewer than two plots, a failed start or step (the plot's tag), a
    /// failed smoothing step, parameters the estimator's models refuse.
    pub fn run(&self, plots: &[TaggedPlot]) -> Result<SingleRun, SingleError> {
        let ctx = start::Ctx {
            sensors: &self.sensors,
            smoothing: self.smoothing,
        };
        kf::run(&ctx, &self.estimator, plots)
    }
}

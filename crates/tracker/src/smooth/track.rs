//! One smoother of the tracker's tracks, used by `argus track --smooth` with a `[tracker]`
//! table (`argus_io`), by the `real-traffic` scenario and by Python: a track's rows —
//! each its time, filtered estimate and [`EstimatorState`] as the tracker gave them —
//! smoothed over the track's life by the smoother of the tracker's estimator.
//!
//! # KF and EKF ([`EstimatorConfig::Kf`], [`EstimatorConfig::Ekf`])
//! The tracker keeps per track only its filtered estimate `x̂ₖ, Pₖ`. That is enough and
//! exact: it predicts a track from its last posterior by the linear CV model `F(dt)`,
//! `Q(dt)` of `sigma_a` (`Cv2D::discrete`), so the same prediction from the row before
//! (over the two rows' time difference) is the tracker's own `x̂ₖ⁻, Pₖ⁻` to round-off,
//! and `Cₖ = Pₖ₋₁ Fᵀ` ([`super::rts_rows`]).
//!
//! # The two-mode IMM ([`EstimatorConfig::ImmCv2`])
//! Each row keeps the track's mode-conditioned estimates and probabilities
//! ([`EstimatorState::Imm`]: after the plot or, after a miss, the mode predictions with
//! `μ̄`), and the track is smoothed by `argus_imm`'s fixed-interval IMM smoother through
//! [`super::ImmRecorder`]: the forward record (every mode's estimate predicted through
//! every model with its cross covariance, `ln μ̄`) recomputed from the row before's mode
//! estimates by an IMM built as the tracker builds its own ([`crate::two_mode_imm`]).
//! With GNN this is the IMM's own forward pass (the mixing and mode predictions are
//! linear maps of the same recorded posterior); with JPDA each mode's posterior is the
//! PDA mixture's moment match, and the smoother runs over those recorded moments (the
//! usual smoother of a PDA filter's output), as for the KF with JPDA.
//!
//! # The multi-IMM ([`EstimatorConfig::MultiImm`])
//! The hypotheses differ only in `R` and share the dynamics, so the posterior merged over
//! them ([`argus_imm::MultiImmEstimate::merged`]) is an IMM posterior of those dynamics,
//! and the two-mode IMM's smoother runs over the merged posteriors: the recorded merged
//! moments smoothed with the `R` the forward pass estimated (the adaptive noise model has
//! no smoother: its grid moves with the data).
//!
//! # The aircraft IMM ([`EstimatorConfig::Aircraft`])
//! Each row keeps the aircraft IMM's modes ([`EstimatorState::Aircraft`]), and the track
//! is smoothed by `argus_imm`'s aircraft-IMM smoother through [`super::AircraftRecorder`],
//! its record recomputed from the row before's modes by the IMM of the configuration's
//! tuning ([`argus_imm::AircraftTuning::build`], as the tracker builds it); exact in the
//! same sense as the two-mode IMM.
//!
//! Rows of one time are one step whose estimate is the last row's ([`super::steps`]);
//! every row of that time gets the step's smoothed value.

use argus_core_math::Gaussian;
use argus_filters::Kf;
use argus_imm::{AircraftEkf, ForwardRecord};
use argus_motion_models::Cv2D;

use super::{AircraftRecorder, Failure, ImmRecorder, ModeRecorder, Smoothing, rts_rows, steps};
use crate::{EstimatorConfig, EstimatorState, TrackerConfig, TrackerError, TwoModeImm};

/// One row of a track to smooth: its time, its filtered estimate and its estimator state,
/// as the tracker gave them ([`crate::TrackSnapshot`]).
#[derive(Debug, Clone, Copy)]
pub struct FilteredRow<'a> {
    /// The row's time (s).
    pub time: f64,
    /// The track's (combined) filtered estimate `[x, vx, y, vy]`.
    pub estimate: &'a Gaussian<4>,
    /// The track's estimator state.
    pub state: &'a EstimatorState,
}

/// One row smoothed: the combined estimate and, for the IMMs, the smoothed mode
/// probabilities (two for the IMM and the multi-IMM, three for the aircraft IMM).
#[derive(Debug, Clone, PartialEq)]
pub struct SmoothedRow {
    /// The smoothed `[x, vx, y, vy]` and its covariance.
    pub estimate: Gaussian<4>,
    /// The smoothed mode probabilities (`None` for the KF and the EKF).
    pub modes: Option<Vec<f64>>,
}

/// The smoother of the tracks of one tracker configuration (module docs).
#[derive(Debug, Clone)]
pub struct TrackSmoother {
    kind: Kind,
}

#[derive(Debug, Clone)]
enum Kind {
    /// RTS, with the tracks' CV Kalman filter.
    Rts(Kf<Cv2D>),
    /// The IMM smoother, with the tracks' IMM (for the multi-IMM: its IMMs' common
    /// dynamics, over the posteriors merged over the noise hypotheses).
    Imm(TwoModeImm),
    /// The aircraft-IMM smoother, with the tracks' aircraft IMM.
    Aircraft(Box<AircraftEkf<2, 3>>),
}

impl TrackSmoother {
    /// The smoother of the tracks of a tracker configured by `config`, its filters built
    /// as the tracker builds them.
    ///
    /// # Errors
    /// [`TrackerError::Motion`] / [`TrackerError::Imm`] / [`TrackerError::InvalidConfig`]
    /// for a bad `sigma_a`, IMM or aircraft tuning (a validated configuration has none).
    pub fn new(config: &TrackerConfig) -> Result<Self, TrackerError> {
        let kind = match config.estimator {
            EstimatorConfig::Kf | EstimatorConfig::Ekf => {
                Kind::Rts(Kf::new(Cv2D::discrete(config.sigma_a)?))
            }
            EstimatorConfig::ImmCv2 {
                sigma_a_low,
                sigma_a_high,
                p_stay,
            }
            | EstimatorConfig::MultiImm {
                sigma_a_low,
                sigma_a_high,
                p_stay,
                ..
            } => Kind::Imm(crate::two_mode_imm(sigma_a_low, sigma_a_high, p_stay)?),
            EstimatorConfig::Aircraft { tuning } => Kind::Aircraft(Box::new(tuning.build()?)),
        };
        Ok(Self { kind })
    }

    /// The number of smoothed mode probabilities per row: 0 (KF, EKF), 2 (IMM,
    /// multi-IMM) or 3 (aircraft IMM).
    #[must_use]
    pub fn mode_count(&self) -> usize {
        match self.kind {
            Kind::Rts(_) => 0,
            Kind::Imm(_) => 2,
            Kind::Aircraft(_) => 3,
        }
    }

    /// One track's rows, in time order, smoothed: one [`SmoothedRow`] per row (rows of
    /// one time share their step's).
    ///
    /// # Errors
    /// [`Failure`] at the step whose row has no state of the smoother's estimator, whose
    /// time goes backwards, or whose prediction or backward step fails.
    pub fn smooth(
        &self,
        rows: &[FilteredRow<'_>],
        how: Smoothing,
    ) -> Result<Vec<SmoothedRow>, Failure> {
        match &self.kind {
            Kind::Rts(kf) => {
                let seq: Vec<(f64, Gaussian<4>)> =
                    rows.iter().map(|r| (r.time, *r.estimate)).collect();
                Ok(rts_rows(kf, &seq, how)?
                    .into_iter()
                    .map(|estimate| SmoothedRow {
                        estimate,
                        modes: None,
                    })
                    .collect())
            }
            Kind::Imm(imm) => mode_rows(ImmRecorder::new(), imm, rows, how, |s| match s {
                EstimatorState::Imm(est) => Ok(*est),
                EstimatorState::MultiImm(m) => m
                    .merged()
                    .map_err(|e| format!("the multi-IMM's hypotheses cannot be merged: {e}")),
                _ => Err("the row has no IMM state".to_owned()),
            }),
            Kind::Aircraft(imm) => mode_rows(
                AircraftRecorder::new(),
                imm.as_ref(),
                rows,
                how,
                |s| match s {
                    EstimatorState::Aircraft(a) => Ok(**a),
                    _ => Err("the row has no aircraft-IMM state".to_owned()),
                },
            ),
        }
    }
}

/// The smoothing of one track's rows by a mode-switching estimator `imm` recorded in
/// `rec`, each row's posterior taken from its state by `state` (an error text when the
/// row has none): one smoothed row per row (rows of one time share their step's).
///
/// # Errors
/// [`Failure`] at the step whose row has no state, whose time goes backwards, or whose
/// prediction or backward step fails.
fn mode_rows<T: ForwardRecord<M, 4, Estimate = E>, M, E>(
    mut rec: ModeRecorder<T, E>,
    imm: &M,
    rows: &[FilteredRow<'_>],
    how: Smoothing,
    state: impl Fn(&EstimatorState) -> Result<E, String>,
) -> Result<Vec<SmoothedRow>, Failure> {
    let times: Vec<f64> = rows.iter().map(|r| r.time).collect();
    let row_step = steps(&times).row_step;
    for (r, &k) in rows.iter().zip(&row_step) {
        let est = state(r.state).map_err(|m| Failure::new(k, r.time, m))?;
        rec.record(imm, r.time, est)?;
    }
    let s = rec.smooth(imm, how)?;
    row_step
        .iter()
        .zip(&times)
        .map(|(&k, &t)| {
            s.get(k)
                .map(|s| SmoothedRow {
                    estimate: *T::combined(s),
                    modes: Some(T::mode_probabilities(s).to_vec()),
                })
                .ok_or_else(|| Failure::new(k, t, "no smoothed step".to_owned()))
        })
        .collect()
}

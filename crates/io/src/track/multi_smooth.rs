//! Smoothing the multi-target tracker's tracks (`argus track --smooth` with a `[tracker]`
//! table): every track that was confirmed at some scan is smoothed over its own life,
//! from its rows.
//!
//! # KF and EKF (`kf-converted`, `ekf`)
//! The tracker keeps per track only its filtered estimate `x̂ₖ, Pₖ` (no prediction, no
//! transition). That is enough and exact: the tracker predicts a track from its last
//! posterior by the linear CV model `F(dt)`, `Q(dt)` of `sigma_a` (`Cv2D::discrete`), so
//! the same prediction from the row before (over the two rows' time difference) is the
//! tracker's own `x̂ₖ⁻, Pₖ⁻` to round-off, and `Cₖ = Pₖ₋₁ Fᵀ` ([`super::smooth`]).
//!
//! # The two-mode IMM (`imm`, [`EstimatorConfig::ImmCv2`])
//! Each row keeps the track's IMM state ([`EstimatorState::Imm`]: the mode-conditioned
//! estimates `x̂ⁱₖ, Pⁱₖ` and probabilities `μⁱₖ`, after the plot or, after a miss, the
//! mode predictions with `μ̄`), and the track is smoothed by `argus_imm`'s fixed-interval
//! IMM smoother ([`argus_imm::imm_smooth`], the single-target `imm`'s, through the same
//! [`ImmRecorder`]). Its forward record — every mode's estimate predicted through every
//! model with the cross covariance, `x̂ⁱʲₖ₊₁|ₖ, Pⁱʲₖ₊₁|ₖ, Cⁱʲₖ₊₁`, and `ln μ̄ⱼ = ln Σᵢ πᵢⱼ
//! μⁱₖ` — is recomputed from the row before's mode estimates over the two rows' time
//! difference, with an IMM built from the same `sigma_a_low`, `sigma_a_high`, `p_stay`
//! by the same constructors as the tracker's (`Cv2D::discrete`, the Markov matrix
//! `[[p, 1 − p], [1 − p, p]]`). In which sense it is exact:
//! - with GNN it is the IMM's own forward pass: the tracker's mixing and mode predictions
//!   are linear maps of the same recorded posterior, so the record is the one
//!   `argus_imm::ImmTrack::step` would have kept over the same plots (tested against it
//!   to 1e-9, `tests/smooth_imm_tracks.rs`); a miss is recorded as the IMM's prediction,
//!   which it is;
//! - with JPDA (IMM-JPDA) each mode's posterior is the PDA mixture's moment match; the
//!   smoother runs over those recorded moments (exact with respect to the recorded
//!   forward pass, the usual smoother of a PDA filter's output), not the smoother of the
//!   mixture — as for the KF with JPDA.
//!
//! Rows of one time (scans of two sensors at one instant) are one step whose estimate is
//! the last row's, as for the single-target IMM ([`super::smooth`]). The smoothed mode
//! probabilities go to `mu_1s, mu_2s`.
//!
//! # The aircraft IMM (`aircraft-imm`, [`EstimatorConfig::Aircraft`])
//! Each row keeps the track's aircraft-IMM state ([`EstimatorState::Aircraft`]: the CV
//! modes' `[x, vx, y, vy]`, the CT mode's `[x, vx, y, vy, ω]` and the three mode
//! probabilities, after the plot or, after a miss, the mode predictions with `μ̄`), and
//! the track is smoothed by `argus_imm`'s aircraft-IMM smoother
//! ([`argus_imm::aircraft_smooth`], the single-target `aircraft-imm`'s, through the same
//! [`AircraftRecorder`]), its record recomputed from the row before's modes with an IMM
//! built from the configuration's tuning by [`argus_imm::AircraftTuning::build`] (as the
//! tracker builds it). Exact in the same sense as the two-mode IMM: with GNN the record
//! is the one the single-target run keeps over the same plots (tested to 1e-9,
//! `tests/smooth_aircraft_tracks.rs`); with JPDA it smooths the recorded PDA moments.
//! The smoothed mode probabilities go to `mu_1s, mu_2s, mu_3s`.
//!
//! # The multi-IMM (`multi-imm`, [`EstimatorConfig::MultiImm`])
//! Each row keeps the track's multi-IMM state ([`EstimatorState::MultiImm`]: the
//! [`MULTI_IMM_HYPOTHESES`] IMMs' mode estimates and probabilities and the noise-mode
//! probabilities `νᵐ`, after the plot or, after a miss, the IMMs' mode predictions), and
//! the track is smoothed over its recorded moments, as IMM-JPDA tracks are: the
//! hypotheses differ only in `R` and share the dynamics (`sigma_a_low`, `sigma_a_high`,
//! `p_stay`), so the posterior merged over the hypotheses
//! ([`MultiImmEstimate::merged`]: per mode `i` the moment match of `Σₘ νₘ μₘⁱ N(x̂ₘⁱ,
//! Pₘⁱ) / μⁱ`, `μⁱ = Σₘ νₘ μₘⁱ`) is an IMM posterior of those dynamics, and the two-mode
//! IMM's smoother above runs over the merged posteriors (its record recomputed from the
//! row before's merged modes). This smooths the recorded merged moments with the `R` the
//! forward pass estimated; it is not a smoother of the adaptive noise model, which has
//! none (its grid moves with the data). With GNN it is the single-target `multi-imm
//! --smooth` over the same plots (tested to 1e-9, `tests/smooth_multi_imm_tracks.rs`).
//! The smoothed mode probabilities go to `mu_1s, mu_2s`.
//!
//! Which rows: a smoothed track's rows from its first (the tentative ones included) to
//! its last before deletion; a track's `deleted` row and every row of a track never
//! confirmed have empty smoothed cells.

use std::collections::BTreeMap;

use crate::rows::{Column, Point, TrackRows};
use argus_core_math::Gaussian;
use argus_filters::Kf;
use argus_imm::{
    AircraftEkf, AircraftEstimate, ForwardRecord, ImmEstimate, MultiImmEstimate, NoiseVariances,
};
use argus_motion_models::Cv2D;
use argus_tracker::{
    DeletionReason, EstimatorConfig, EstimatorState, MULTI_IMM_HYPOTHESES, ModeProbabilities,
    SensorId, TrackSnapshot, TrackStatus, TrackerConfig, TwoModeImm, two_mode_imm,
};

use argus_tracker::smooth::{
    self, AircraftRecorder, Failure, ImmRecorder, ModeRecorder, Smoothing, rts_rows,
};

use super::names::{reason_name, status_name};
use super::smooth::SmoothFailure as _;
use crate::IoError;

/// One row as the tracker gave it.
#[derive(Debug, Clone)]
struct Row {
    sensor: u32,
    track: u64,
    status: TrackStatus,
    reason: Option<DeletionReason>,
    time: f64,
    estimate: Gaussian<4>,
    modes: Option<ModeProbabilities>,
    noise: Option<NoiseVariances>,
    score: f64,
    /// The IMM state (IMM tracks only).
    imm: Option<ImmEstimate<4, 2>>,
    /// The multi-IMM state (multi-IMM tracks only; boxed: its K IMMs).
    multi: Option<Box<MultiImmEstimate<4, 2, MULTI_IMM_HYPOTHESES>>>,
    /// The aircraft-IMM state (aircraft tracks only; boxed: 584 bytes).
    aircraft: Option<Box<AircraftEstimate<2, 3>>>,
    /// The aircraft IMM's turn rate and its σ (rad/s).
    turn_rate: Option<(f64, f64)>,
}

/// The smoother of the tracks' estimator.
#[derive(Debug)]
enum Smoother {
    /// RTS, with the tracks' CV Kalman filter.
    Rts(Kf<Cv2D>),
    /// The IMM smoother, with the tracks' IMM (for the multi-IMM: its IMMs' common
    /// dynamics, over the posteriors merged over the noise hypotheses).
    Imm(TwoModeImm),
    /// The aircraft-IMM smoother, with the tracks' aircraft IMM.
    Aircraft(Box<AircraftEkf<2, 3>>),
}

/// One track's smoothed rows: the combined estimate, and the IMM's mode probabilities
/// (two for `imm`, three for `aircraft-imm`).
type SmoothedRow = (Gaussian<4>, Option<Vec<f64>>);

/// The rows of a run kept for smoothing, and the tracks' filter.
#[derive(Debug)]
pub(super) struct Recorded {
    rows: Vec<Row>,
    smoother: Smoother,
}

impl Recorded {
    /// An empty record for the tracker configured by `c`.
    ///
    /// # Errors
    /// [`IoError::Motion`] / [`IoError::Tracker`] for a bad `sigma_a` or `p_stay`
    /// (already refused by the configuration).
    pub(super) fn new(c: &TrackerConfig) -> Result<Self, IoError> {
        let smoother = match c.estimator {
            EstimatorConfig::Kf | EstimatorConfig::Ekf => {
                Smoother::Rts(Kf::new(Cv2D::discrete(c.sigma_a)?))
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
            } => Smoother::Imm(two_mode_imm(sigma_a_low, sigma_a_high, p_stay)?),
            EstimatorConfig::Aircraft { tuning } => Smoother::Aircraft(Box::new(tuning.build()?)),
        };
        Ok(Self {
            rows: Vec::new(),
            smoother,
        })
    }

    /// The smoothed columns: `xs, vxs, ys, vys, sigma_xs, sigma_ys`, and `mu_1s, mu_2s`
    /// for the IMM (`mu_1s … mu_3s` for the aircraft IMM).
    pub(super) fn columns(&self) -> Vec<Column> {
        Column::smoothed_tracker(match self.smoother {
            Smoother::Rts(_) => 0,
            Smoother::Imm(_) => 2,
            Smoother::Aircraft(_) => 3,
        })
    }

    /// Keeps the row of `track` from the scan of `sensor`.
    pub(super) fn push(&mut self, sensor: SensorId, track: TrackSnapshot) {
        let modes = track.mode_probabilities();
        let noise = track.noise_estimate();
        let turn_rate = track.turn_rate();
        let (imm, multi, aircraft) = match track.state {
            EstimatorState::Plain => (None, None, None),
            EstimatorState::Imm(imm) => (Some(imm), None, None),
            EstimatorState::MultiImm(m) => (None, Some(m), None),
            EstimatorState::Aircraft(a) => (None, None, Some(a)),
        };
        self.rows.push(Row {
            sensor: sensor.0,
            track: track.id.0,
            status: track.status,
            reason: track.deletion,
            time: track.time,
            estimate: track.estimate,
            modes,
            noise,
            score: track.score,
            imm,
            multi,
            aircraft,
            turn_rate,
        });
    }

    /// Smooths every track confirmed at some scan and writes every row, in order, to
    /// `out`; returns the number of tracks smoothed.
    ///
    /// # Errors
    /// [`IoError::Smooth`] naming the track and step of the first failure (nothing is
    /// written).
    pub(super) fn smooth_into(self, how: Smoothing, out: &mut TrackRows) -> Result<usize, IoError> {
        let rows = self.rows;
        let mut by_track: BTreeMap<u64, Vec<usize>> = BTreeMap::new();
        for (i, r) in rows.iter().enumerate() {
            by_track.entry(r.track).or_default().push(i);
        }
        let mut smoothed: Vec<Option<SmoothedRow>> = vec![None; rows.len()];
        let mut count = 0;
        for (id, idx) in by_track {
            if !idx
                .iter()
                .any(|&i| rows[i].status == TrackStatus::Confirmed)
            {
                continue;
            }
            let live: Vec<usize> = idx
                .into_iter()
                .filter(|&i| rows[i].status != TrackStatus::Deleted)
                .collect();
            let s = match &self.smoother {
                Smoother::Rts(kf) => {
                    let seq: Vec<(f64, Gaussian<4>)> = live
                        .iter()
                        .map(|&i| (rows[i].time, rows[i].estimate))
                        .collect();
                    rts_rows(kf, &seq, how)
                        .map(|s| s.into_iter().map(|g| (g, None)).collect::<Vec<_>>())
                }
                Smoother::Imm(imm) => imm_rows(imm, &rows, &live, how),
                Smoother::Aircraft(imm) => aircraft_rows(imm, &rows, &live, how),
            }
            .map_err(|f| f.into_cli(id))?;
            for (&i, g) in live.iter().zip(s) {
                smoothed[i] = Some(g);
            }
            count += 1;
        }
        for (r, s) in rows.iter().zip(&smoothed) {
            let reason = r.reason.map_or("", reason_name);
            let p = Point::new(r.time, &r.estimate)
                .of_track(r.sensor, r.track, status_name(r.status), reason)
                .modes(r.modes.as_ref().map(|m| m.as_slice()))
                .noise(r.noise)
                .turn_rate(r.turn_rate)
                .score(r.score)
                .smoothed(s.as_ref().map(|s| &s.0))
                .smoothed_modes(s.as_ref().and_then(|s| s.1.as_deref()));
            out.push(&p);
        }
        Ok(count)
    }
}

/// The IMM smoothing of one track's rows `live` (indices into `rows`, in time order):
/// one smoothed row per row (rows of one time share their step's).
///
/// # Errors
/// [`Failure`] at the step whose row has no IMM state, whose time goes backwards, or
/// whose prediction or backward step fails.
fn imm_rows(
    imm: &TwoModeImm,
    rows: &[Row],
    live: &[usize],
    how: Smoothing,
) -> Result<Vec<SmoothedRow>, Failure> {
    mode_rows(ImmRecorder::new(), imm, rows, live, how, |r| {
        match (r.imm, r.multi.as_deref()) {
            (Some(est), _) => Ok(est),
            (None, Some(m)) => m
                .merged()
                .map_err(|e| format!("the multi-IMM's hypotheses cannot be merged: {e}")),
            (None, None) => Err("the row has no IMM state".to_owned()),
        }
    })
}

/// The aircraft-IMM smoothing of one track's rows `live` (indices into `rows`, in time
/// order): one smoothed row per row (rows of one time share their step's).
///
/// # Errors
/// [`Failure`] at the step whose row has no aircraft-IMM state, whose time goes
/// backwards, or whose prediction or backward step fails.
fn aircraft_rows(
    imm: &AircraftEkf<2, 3>,
    rows: &[Row],
    live: &[usize],
    how: Smoothing,
) -> Result<Vec<SmoothedRow>, Failure> {
    mode_rows(AircraftRecorder::new(), imm, rows, live, how, |r| {
        r.aircraft
            .as_deref()
            .copied()
            .ok_or_else(|| "the row has no aircraft-IMM state".to_owned())
    })
}

/// The smoothing of one track's rows `live` (indices into `rows`, in time order) by a
/// mode-switching estimator `imm` recorded in `rec`, each row's posterior taken by
/// `state` (an error text when the row has none): one smoothed row per row (rows of one
/// time share their step's).
///
/// # Errors
/// [`Failure`] at the step whose row has no state, whose time goes backwards, or whose
/// prediction or backward step fails.
fn mode_rows<T: ForwardRecord<M, 4, Estimate = E>, M, E>(
    mut rec: ModeRecorder<T, E>,
    imm: &M,
    rows: &[Row],
    live: &[usize],
    how: Smoothing,
    state: impl Fn(&Row) -> Result<E, String>,
) -> Result<Vec<SmoothedRow>, Failure> {
    let times: Vec<f64> = live.iter().map(|&i| rows[i].time).collect();
    let row_step = smooth::steps(&times).row_step;
    for (k, &i) in live.iter().enumerate() {
        let r = &rows[i];
        let est = state(r).map_err(|m| Failure::new(row_step[k], r.time, m))?;
        rec.record(imm, r.time, est)?;
    }
    let s = rec.smooth(imm, how)?;
    row_step
        .iter()
        .zip(&times)
        .map(|(&k, &t)| {
            s.get(k)
                .map(|s| (*T::combined(s), Some(T::mode_probabilities(s).to_vec())))
                .ok_or_else(|| Failure::new(k, t, "no smoothed step".to_owned()))
        })
        .collect()
}

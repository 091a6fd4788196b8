//! Smoothing the multi-target tracker's tracks (`argus track --smooth` with a `[tracker]`
//! table): every track that was confirmed at some scan is smoothed over its own life,
//! from its rows.
//!
//! The tracker keeps per track only its filtered estimate `x̂ₖ, Pₖ` (no prediction, no
//! transition). For its CV Kalman filter and EKF (`kf-converted`, `ekf`) that is enough
//! and exact: the tracker predicts a track from its last posterior by the linear CV model
//! `F(dt)`, `Q(dt)` of `sigma_a` (`Cv2D::discrete`), so the same prediction from the row
//! before (over the two rows' time difference) is the tracker's own `x̂ₖ⁻, Pₖ⁻` to
//! round-off, and `Cₖ = Pₖ₋₁ Fᵀ` ([`super::smooth`]). With JPDA the posterior is the PDA
//! mixture's moment match; the RTS pass over those moments is exact with respect to the
//! recorded forward pass (the usual smoother of a PDA filter's output), not the smoother
//! of the mixture. The tracker's IMM and multi-IMM tracks expose only their combined
//! estimate and mode probabilities, not the mode-conditioned estimates the IMM smoother
//! needs: smoothing them is refused (a typed error naming `estimator.kind`).
//!
//! Which rows: a smoothed track's rows from its first (the tentative ones included) to
//! its last before deletion; a track's `deleted` row and every row of a track never
//! confirmed have empty smoothed cells.

use std::collections::BTreeMap;

use argus_core_math::Gaussian;
use argus_filters::Kf;
use argus_imm::NoiseVariances;
use argus_motion_models::Cv2D;
use argus_tracker::{
    DeletionReason, EstimatorConfig, ModeProbabilities, SensorId, Track, TrackStatus, TrackerConfig,
};

use super::multi::{Files, reason_name, status_name};
use super::rows::{Point, TrackRows};
use super::smooth::{Smoothing, rts_rows};
use crate::error::CliError;

/// One row as the tracker gave it.
#[derive(Debug, Clone, Copy)]
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
}

/// The rows of a run kept for smoothing, and the tracks' Kalman filter.
#[derive(Debug)]
pub(super) struct Recorded {
    rows: Vec<Row>,
    filter: Kf<Cv2D>,
}

impl Recorded {
    /// An empty record for the tracker configured by `c`.
    ///
    /// # Errors
    /// [`CliError::Input`] at `estimator.kind` for the IMM and multi-IMM (module docs);
    /// [`CliError::Motion`] for a bad `sigma_a` (already refused by the configuration).
    pub(super) fn new(files: &Files<'_>, c: &TrackerConfig) -> Result<Self, CliError> {
        match c.estimator {
            EstimatorConfig::Kf | EstimatorConfig::Ekf => Ok(Self {
                rows: Vec::new(),
                filter: Kf::new(Cv2D::discrete(c.sigma_a)?),
            }),
            _ => Err(CliError::input(
                files.config,
                None,
                Some("estimator.kind"),
                "--smooth / --smooth-lag with [tracker]: the tracker's IMM and multi-IMM tracks \
                 keep only their combined estimate, not the per-mode estimates the IMM smoother \
                 needs; the tracker's kinds that smooth are kf-converted and ekf",
            )),
        }
    }

    /// Keeps the row of `track` from the scan of `sensor`.
    pub(super) fn push(&mut self, sensor: SensorId, track: &Track) {
        self.rows.push(Row {
            sensor: sensor.0,
            track: track.id().0,
            status: track.status(),
            reason: track.deletion(),
            time: track.time(),
            estimate: *track.estimate(),
            modes: track.mode_probabilities(),
            noise: track.noise_estimate(),
            score: track.score(),
        });
    }

    /// Smooths every track confirmed at some scan and writes every row, in order, to
    /// `out`; returns the number of tracks smoothed.
    ///
    /// # Errors
    /// [`CliError::Smooth`] naming the track and step of the first failure (nothing is
    /// written).
    pub(super) fn smooth_into(
        self,
        how: Smoothing,
        out: &mut TrackRows,
    ) -> Result<usize, CliError> {
        let rows = self.rows;
        let mut by_track: BTreeMap<u64, Vec<usize>> = BTreeMap::new();
        for (i, r) in rows.iter().enumerate() {
            by_track.entry(r.track).or_default().push(i);
        }
        let mut smoothed: Vec<Option<Gaussian<4>>> = vec![None; rows.len()];
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
            let seq: Vec<(f64, Gaussian<4>)> = live
                .iter()
                .map(|&i| (rows[i].time, rows[i].estimate))
                .collect();
            let s = rts_rows(&self.filter, &seq, how).map_err(|f| f.into_cli(id))?;
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
                .score(r.score)
                .smoothed(s.as_ref());
            out.push(&p);
        }
        Ok(count)
    }
}

//! The prediction step of a scan and of a sector: each track's prediction and, for the
//! EKF on polar plots, its measurement prediction in `(r, θ)`.

use super::Tracker;
use crate::plot::PolarModel;

impl Tracker {
    /// Whether the predictions carry the EKF's polar measurement prediction: an estimator
    /// gating in `(r, θ)`, a polar sensor and a polar plot among `self.points` (else
    /// `polar_mp` stays empty, so the KF path does not touch it).
    pub(super) fn ekf_polar(&self, polar_sensor: Option<&PolarModel>) -> bool {
        self.est.gates_polar()
            && polar_sensor.is_some()
            && self.points.iter().any(|p| p.polar.is_some())
    }

    /// Empties the prediction buffers (`predicted`, `imm_predicted`, `polar_mp`) before
    /// one prediction per track is pushed.
    pub(super) fn clear_predictions(&mut self) {
        self.predicted.clear();
        self.imm_predicted.clear();
        self.polar_mp.clear();
    }

    /// Predicts track `k` over `dt` ([`crate::estimator::Estimator::predict`]: an IMM
    /// track's mode-conditioned prediction pushed on `imm_predicted`; the state of a
    /// multi-IMM or aircraft-IMM track becomes its prediction), and pushes the combined
    /// prediction on `predicted` (`None` when the filter fails) and, with `ekf_polar`, its
    /// measurement prediction at `polar_sensor` on `polar_mp`.
    pub(super) fn predict_track(
        &mut self,
        k: usize,
        dt: f64,
        ekf_polar: bool,
        polar_sensor: Option<&PolarModel>,
    ) {
        let track = &mut self.tracks[k];
        let pred = self.est.predict(
            &mut track.state,
            &track.estimate,
            dt,
            &mut self.imm_predicted,
        );
        if ekf_polar {
            let mp = pred
                .as_ref()
                .and_then(|p| self.est.polar_prediction(p, polar_sensor));
            self.polar_mp.push(mp);
        }
        self.predicted.push(pred);
    }
}

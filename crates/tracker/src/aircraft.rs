//! The aircraft IMM per track ([`crate::EstimatorConfig::Aircraft`]): gating per mode in
//! `(r, θ)` with the mode-mixture likelihood, the update with one polar plot, the start.
//!
//! Gating as IMM-JPDA gates (Blom & Bloem 2000; Bar-Shalom, Willett & Tian 2011): each
//! mode `j` predicts the plot, `ẑⱼ = h(x̂ⱼ⁻)`, `Sⱼ = Hⱼ Pⱼ⁻ Hⱼᵀ + R` (EKF, `H` at the
//! mode's prediction; the CT mode on its five states); a plot is in the track's gate when
//! it is in some mode's (`minⱼ νⱼᵀ Sⱼ⁻¹ νⱼ ≤ γ`, the GNN cost), and its likelihood is
//! `Σⱼ μ̄ⱼ N(νⱼ; 0, Sⱼ) / r`: the mixture over the predicted mode probabilities, divided
//! by the Jacobian `r` of the polar map (`dx dy = r dr dθ`) to be per m² like the
//! clutter density, as the EKF's.

use argus_core_math::{Gaussian, Vector};
use argus_filters::{GaussianFilter, MeasurementPrediction};
use argus_imm::{AircraftEkf, log_sum_exp};

use crate::innovation::polar_half;
use crate::plot::{PolarModel, ScanPoint};
use crate::state::AircraftState;

/// The tracker's aircraft IMM: two CV modes and the CT mode, EKFs.
pub(crate) type Aircraft3 = AircraftEkf<2, 3>;

/// One aircraft track's gate in a scan: each mode's measurement prediction in `(r, θ)`
/// and `ln μ̄ⱼ`, made once per track and scan (on the stack).
pub(crate) struct AircraftGate<'a> {
    cv: [MeasurementPrediction<4, 2>; 2],
    ct: MeasurementPrediction<5, 2>,
    log_mu: [f64; 3],
    /// Each mode's predicted position `(x, y)` (the centre of its query box).
    centres: [Vector<2>; 3],
    sensor: &'a PolarModel,
}

impl<'a> AircraftGate<'a> {
    /// The gate of a track whose state holds its prediction; `None` when a mode's
    /// measurement prediction fails.
    pub(crate) fn new(
        imm: &Aircraft3,
        state: &AircraftState,
        sensor: &'a PolarModel,
    ) -> Option<Self> {
        let radar = &sensor.aircraft;
        let [f0, f1] = imm.cv_filters();
        let [g0, g1] = state.cv_modes();
        let cv = [
            f0.predict_measurement(g0, radar.cv()).ok()?,
            f1.predict_measurement(g1, radar.cv()).ok()?,
        ];
        let g2 = state.ct_mode();
        let ct = imm.ct_filter().predict_measurement(g2, radar.ct()).ok()?;
        let at = |m: &Vector<4>| Vector::<2>::new(m[0], m[2]);
        let centres = [
            at(g0.mean()),
            at(g1.mean()),
            Vector::<2>::new(g2.mean()[0], g2.mean()[2]),
        ];
        Some(Self {
            cv,
            ct,
            log_mu: *state.log_mode_probabilities(),
            centres,
            sensor,
        })
    }

    /// The grid query box holding every mode's polar gate `νᵀ S⁻¹ ν ≤ gamma` as converted
    /// plots: the bounding box of the modes' boxes ([`polar_half`] around each mode's
    /// predicted position).
    pub(crate) fn query_box(&self, gamma: f64) -> (Vector<2>, [f64; 2]) {
        let stretch = self.sensor.conversion_stretch;
        let halves = [
            polar_half(&self.cv[0], gamma, stretch),
            polar_half(&self.cv[1], gamma, stretch),
            polar_half(&self.ct, gamma, stretch),
        ];
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for (c, h) in self.centres.iter().zip(halves) {
            for i in 0..2 {
                lo[i] = lo[i].min(c[i] - h);
                hi[i] = hi[i].max(c[i] + h);
            }
        }
        (
            Vector::<2>::new(0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])),
            [0.5 * (hi[0] - lo[0]), 0.5 * (hi[1] - lo[1])],
        )
    }

    /// The plot's smallest normalised distance over the modes and its mixture
    /// log-likelihood per m² (module docs); `None` for a Cartesian plot (refused before
    /// any scan) or when an innovation fails.
    #[inline]
    pub(crate) fn innovation(&self, p: &ScanPoint) -> Option<(f64, f64)> {
        let z = p.polar?;
        let radar = &self.sensor.aircraft;
        let i0 = self.cv[0].innovation(radar.cv(), &z).ok()?;
        let i1 = self.cv[1].innovation(radar.cv(), &z).ok()?;
        let i2 = self.ct.innovation(radar.ct(), &z).ok()?;
        let nis = i0.nis.min(i1.nis).min(i2.nis);
        let terms = [
            self.log_mu[0] + i0.log_likelihood(),
            self.log_mu[1] + i1.log_likelihood(),
            self.log_mu[2] + i2.log_likelihood(),
        ];
        Some((nis, log_sum_exp(&terms) - z[0].ln()))
    }
}

/// Predicts an aircraft track over `dt` in place (`dt = 0`: unchanged): the state becomes
/// its prediction (mixed and predicted modes, `μ̄` as probabilities); returns the combined
/// prediction on `[x, vx, y, vy]`.
pub(crate) fn predict(imm: &Aircraft3, state: &mut AircraftState, dt: f64) -> Option<Gaussian<4>> {
    if dt > 0.0 {
        *state = imm.predict(state, dt).ok()?.into_estimate();
    }
    state.combined().ok()
}

/// Updates an aircraft track whose state holds its prediction with the polar plot `z` of
/// `sensor`: the combined posterior and the plot's log-likelihood per m²
/// (`ln Σⱼ μ̄ⱼ Λⱼ − ln r`). The state becomes the posterior; `None` when a step fails.
pub(crate) fn update(
    imm: &Aircraft3,
    state: &mut AircraftState,
    sensor: &PolarModel,
    z: &Vector<2>,
) -> Option<(Gaussian<4>, f64)> {
    let u = imm
        .update(&state.into_prediction(), &sensor.aircraft, z)
        .ok()?;
    let combined = u.estimate.combined().ok()?;
    *state = u.estimate;
    Some((combined, u.log_likelihood - z[0].ln()))
}

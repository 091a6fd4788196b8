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

/// The moment-matched Gaussian of a weighted mixture, summed part by part without
/// storing the parts: with `dᵢ = x̂ᵢ − x_ref` (centred on `reference`, the mode's
/// prediction, so that no large position cancels), `W = Σ wᵢ`, `x̂ = x_ref + Σ wᵢ dᵢ / W`,
/// `P = Σ wᵢ (Pᵢ + dᵢ dᵢᵀ) / W − (x̂ − x_ref)(x̂ − x_ref)ᵀ` — the same moments as
/// [`Gaussian::mixture_of`].
struct MomentSum<const N: usize> {
    reference: Vector<N>,
    w: f64,
    s1: Vector<N>,
    s2: argus_core_math::Matrix<N, N>,
}

impl<const N: usize> MomentSum<N> {
    fn new(reference: Vector<N>) -> Self {
        Self {
            reference,
            w: 0.0,
            s1: Vector::<N>::zeros(),
            s2: argus_core_math::Matrix::<N, N>::zeros(),
        }
    }

    fn add(&mut self, w: f64, g: &Gaussian<N>) {
        let d = g.mean() - self.reference;
        self.w += w;
        self.s1 += d * w;
        self.s2 += (g.cov() + d * d.transpose()) * w;
    }

    /// The mixture; `None` when the weights vanish or the result is not a Gaussian.
    fn gaussian(&self) -> Option<Gaussian<N>> {
        if !(self.w.is_finite() && self.w > 0.0) {
            return None;
        }
        let m = self.s1 / self.w;
        let p = self.s2 / self.w - m * m.transpose();
        Gaussian::from_symmetrized(self.reference + m, &p).ok()
    }
}

/// The IMM-JPDA update of an aircraft track whose state holds its prediction, from its
/// JPDA marginals `β_j` over the plots `points` of `sensor` (computed from the mixture
/// likelihoods of [`AircraftGate::innovation`]), as `crate::pda::imm_jpda_update` does for
/// the two-CV IMM: with `N_r,j = N(ν_r,j; 0, S_r,j)` of mode `r`'s EKF update with plot
/// `j` and `N_j = Σ_s μ̄_s N_s,j`, `P(r, j) = β_j μ̄_r N_r,j / N_j`, `P(r, 0) = β₀ μ̄_r`;
/// `μ_r = Σ_j P(r, j)` and mode `r`'s estimate the mixture of its prediction and its
/// updates with the weights `P(r, j) / μ_r` (Blom & Bloem 2000; Bar-Shalom, Willett &
/// Tian 2011). The polar Jacobian `r` is common to every mode of a plot and cancels in
/// `N_r,j / N_j`. The state becomes the posterior; returns the combined estimate, `None`
/// when a step fails. No allocation: the mixtures are summed part by part.
pub(crate) fn jpda_update(
    imm: &Aircraft3,
    state: &mut AircraftState,
    weights: &[(usize, f64)],
    points: &[ScanPoint],
    sensor: &PolarModel,
) -> Option<Gaussian<4>> {
    let radar = &sensor.aircraft;
    let mu_bar = state.mode_probabilities();
    let [c0, c1] = *state.cv_modes();
    let ct = *state.ct_mode();
    let b0 = (1.0 - weights.iter().map(|w| w.1).sum::<f64>()).max(0.0);
    let mut cv_sums = [MomentSum::new(*c0.mean()), MomentSum::new(*c1.mean())];
    let mut ct_sum = MomentSum::new(*ct.mean());
    cv_sums[0].add(b0 * mu_bar[0], &c0);
    cv_sums[1].add(b0 * mu_bar[1], &c1);
    ct_sum.add(b0 * mu_bar[2], &ct);
    let [f0, f1] = imm.cv_filters();
    for &(j, b) in weights {
        let z = points[j].polar?;
        let (p0, i0) = f0.update(&c0, radar.cv(), &z).ok()?;
        let (p1, i1) = f1.update(&c1, radar.cv(), &z).ok()?;
        let (p2, i2) = imm.ct_filter().update(&ct, radar.ct(), &z).ok()?;
        let lc = state.log_mode_probabilities();
        let joint = [
            lc[0] + i0.log_likelihood(),
            lc[1] + i1.log_likelihood(),
            lc[2] + i2.log_likelihood(),
        ];
        let total = log_sum_exp(&joint);
        if !total.is_finite() {
            return None;
        }
        cv_sums[0].add(b * (joint[0] - total).exp(), &p0);
        cv_sums[1].add(b * (joint[1] - total).exp(), &p1);
        ct_sum.add(b * (joint[2] - total).exp(), &p2);
    }
    let mu = [cv_sums[0].w, cv_sums[1].w, ct_sum.w];
    let sum: f64 = mu.iter().sum();
    if !(sum.is_finite() && sum > 0.0) {
        return None;
    }
    // A mode whose weight vanished keeps its prediction.
    let cv = [
        cv_sums[0].gaussian().unwrap_or(c0),
        cv_sums[1].gaussian().unwrap_or(c1),
    ];
    let ct = ct_sum.gaussian().unwrap_or(ct);
    let posterior = AircraftState::new(cv, ct, mu.map(|m| m / sum)).ok()?;
    let combined = posterior.combined().ok()?;
    *state = posterior;
    Some(combined)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::{CartesianPlots, SensorModel};
    use crate::{SensorConfig, SensorId};
    use argus_imm::AircraftTuning;
    use argus_sensors::Plot;

    /// A track 5 s after a two-point start on an aircraft turning at 2 °/s, predicted, with
    /// the radar and two plots near it.
    fn setup() -> (Aircraft3, AircraftState, SensorModel, [ScanPoint; 2]) {
        let tuning = AircraftTuning::<2, 3>::default();
        let imm = tuning.build().unwrap();
        let cfg = SensorConfig::polar(SensorId(1), [0.0, 0.0], 70.0, 0.08_f64.to_radians());
        let sensor = SensorModel::new(&cfg).unwrap();
        let radar = &sensor.polar.as_ref().unwrap().aircraft;
        let plot = |x: f64, y: f64| Vector::<2>::new(x.hypot(y), y.atan2(x));
        let mut est = tuning
            .start(radar, &plot(50e3, 20e3), &plot(51e3, 20e3), 5.0)
            .unwrap();
        est = imm
            .step(&est, 5.0, radar, &plot(52e3, 20.1e3))
            .unwrap()
            .estimate;
        let state = imm.predict(&est, 5.0).unwrap().into_estimate();
        let point = |z: Vector<2>| {
            let p = Plot::polar(10.0, SensorId(1), z[0], z[1]).unwrap();
            sensor
                .point(0, &p, CartesianPlots::Refused("aircraft IMM"))
                .unwrap()
        };
        let points = [point(plot(53e3, 20.3e3)), point(plot(52.9e3, 20.1e3))];
        (imm, state, sensor, points)
    }

    #[test]
    fn jpda_with_one_certain_plot_is_the_imm_update() {
        // β = 1 for one plot (β₀ = 0): P(r, j) = μ̄_r N_r / N is the IMM's posterior mode
        // probability and each mode's mixture has one part, its EKF update. Tolerance:
        // round-off of the part-by-part sums (1e-9 relative).
        let (imm, mut state, sensor, points) = setup();
        let pm = sensor.polar.as_ref().unwrap();
        let mut gnn = state;
        let (g_gnn, _) = update(&imm, &mut gnn, pm, &points[0].polar.unwrap()).unwrap();
        let g_jpda = jpda_update(&imm, &mut state, &[(0, 1.0)], &points, pm).unwrap();
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * (1.0 + b.abs());
        for k in 0..4 {
            assert!(close(g_jpda.mean()[k], g_gnn.mean()[k]), "{k}");
            assert!(close(g_jpda.cov()[(k, k)], g_gnn.cov()[(k, k)]), "{k}");
        }
        for (a, b) in state
            .mode_probabilities()
            .iter()
            .zip(gnn.mode_probabilities())
        {
            assert!(close(*a, b), "{a} vs {b}");
        }
        assert!(close(state.turn_rate().0, gnn.turn_rate().0));
    }

    #[test]
    fn jpda_weights_move_the_estimate_between_prediction_and_plots() {
        // With β₀ = 1 (no plot weighted) the posterior is the prediction; with two plots
        // at β = 0.5 each the combined position lies between the two single-plot updates
        // (within 1 m: the posterior is a convex combination of every mode's update with
        // either plot, and its mode weights are not quite those of either single update).
        let (imm, state, sensor, points) = setup();
        let pm = sensor.polar.as_ref().unwrap();
        let mut coast = state;
        let g0 = jpda_update(&imm, &mut coast, &[(0, 0.0)], &points, pm).unwrap();
        let pred = state.combined().unwrap();
        assert!((g0.mean() - pred.mean()).norm() < 1e-6 * pred.mean().norm());
        let mut both = state;
        let g = jpda_update(&imm, &mut both, &[(0, 0.5), (1, 0.5)], &points, pm).unwrap();
        let one = |j: usize| {
            let mut s = state;
            update(&imm, &mut s, pm, &points[j].polar.unwrap())
                .unwrap()
                .0
        };
        let (a, b) = (one(0), one(1));
        let (lo, hi) = (a.mean()[0].min(b.mean()[0]), a.mean()[0].max(b.mean()[0]));
        assert!(
            (lo - 1.0..=hi + 1.0).contains(&g.mean()[0]),
            "{lo} {} {hi}",
            g.mean()[0]
        );
        // The spread between the two plots inflates the position variance.
        assert!(g.cov()[(0, 0)] > a.cov()[(0, 0)].min(b.cov()[(0, 0)]));
    }
}

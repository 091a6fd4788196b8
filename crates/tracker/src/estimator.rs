//! The per-track estimators: what gating, likelihoods and updates look like for each.

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{Ekf, GaussianFilter, Kf, MeasurementPrediction};
use argus_imm::{Imm, ImmEstimate, ImmPrediction, MarkovMatrix, MultiImm, NoiseGrid, log_sum_exp};
use argus_motion_models::Cv2D;
use argus_sensors::Polar2D;
use argus_sensors::PolarMeasurement;

use crate::config::MULTI_IMM_HYPOTHESES;
use crate::plot::{PolarModel, ScanPoint};
use crate::track::MultiState;
use crate::{EstimatorConfig, TrackerConfig, TrackerError};

/// The filters of the configured estimator, built once.
#[derive(Debug, Clone)]
pub(crate) struct Estimators {
    /// The CV Kalman filter: the KF estimator, the EKF's linear (Cartesian) update, and
    /// the gating of IMM and multi-IMM tracks on their combined prediction.
    pub(crate) kf: Kf<Cv2D>,
    pub(crate) ekf: Option<Ekf<Cv2D>>,
    pub(crate) imm: Option<Imm<Kf<Cv2D>, 4, 2>>,
    pub(crate) multi: Option<MultiImm<Kf<Cv2D>, 4, 2, MULTI_IMM_HYPOTHESES>>,
}

impl Estimators {
    pub(crate) fn new(config: &TrackerConfig) -> Result<Self, TrackerError> {
        let kf = Kf::new(Cv2D::discrete(config.sigma_a)?);
        let imm2 = |sigma_a_low, sigma_a_high, p_stay: f64| {
            let markov = MarkovMatrix::new([[p_stay, 1.0 - p_stay], [1.0 - p_stay, p_stay]])
                .map_err(|_| TrackerError::InvalidConfig {
                    field: "estimator.p_stay",
                    value: p_stay,
                    reason: "does not make a Markov matrix",
                })?;
            let filters = [
                Kf::new(Cv2D::discrete(sigma_a_low)?),
                Kf::new(Cv2D::discrete(sigma_a_high)?),
            ];
            Imm::new(filters, markov).map_err(|_| TrackerError::InvalidConfig {
                field: "estimator",
                value: p_stay,
                reason: "the IMM rejected it",
            })
        };
        let mut out = Self {
            kf,
            ekf: None,
            imm: None,
            multi: None,
        };
        match config.estimator {
            EstimatorConfig::Kf => {}
            EstimatorConfig::Ekf => out.ekf = Some(Ekf::new(Cv2D::discrete(config.sigma_a)?)),
            EstimatorConfig::ImmCv2 {
                sigma_a_low,
                sigma_a_high,
                p_stay,
            } => out.imm = Some(imm2(sigma_a_low, sigma_a_high, p_stay)?),
            EstimatorConfig::MultiImm {
                sigma_a_low,
                sigma_a_high,
                p_stay,
                grid_spacing,
                clip,
            } => {
                let bad = |field, value| TrackerError::InvalidConfig {
                    field,
                    value,
                    reason: "the multi-IMM rejected it",
                };
                let grid = NoiseGrid::common(grid_spacing)
                    .map_err(|_| bad("estimator.grid_spacing", grid_spacing))?;
                let imm = imm2(sigma_a_low, sigma_a_high, p_stay)?;
                out.multi = Some(
                    MultiImm::new(imm, grid, clip)
                        .map_err(|_| bad("estimator.clip", clip.unwrap_or(f64::NAN)))?,
                );
            }
        }
        Ok(out)
    }

    /// Predicts a single-filter (KF or EKF) estimate over `dt` (`dt = 0`: unchanged).
    pub(crate) fn predict_single(&self, est: &Gaussian<4>, dt: f64) -> Option<Gaussian<4>> {
        if dt <= 0.0 {
            return Some(*est);
        }
        match &self.ekf {
            Some(ekf) => ekf.predict(est, dt).ok(),
            None => self.kf.predict(est, dt).ok(),
        }
    }

    /// The EKF's measurement prediction for polar plots of `sensor`, when the estimator is
    /// the EKF.
    pub(crate) fn polar_prediction(
        &self,
        pred: &Gaussian<4>,
        sensor: Option<&PolarModel>,
    ) -> Option<MeasurementPrediction<4, 2>> {
        let (ekf, pm) = (self.ekf.as_ref()?, sensor?);
        ekf.predict_measurement(pred, &pm.model).ok()
    }

    /// A single-filter update with one plot: the posterior and the plot's log-likelihood
    /// per m² (for a polar plot in the EKF, the `(r, θ)` density divided by the Jacobian
    /// `r` of the polar map, `dx dy = r dr dθ`).
    pub(crate) fn update_single(
        &self,
        pred: &Gaussian<4>,
        polar: Option<&Polar2D<4>>,
        p: &ScanPoint,
    ) -> Option<(Gaussian<4>, f64)> {
        match (&self.ekf, polar, p.polar) {
            (Some(ekf), Some(model), Some(z)) => {
                let (post, innov) = ekf.update(pred, model, &z).ok()?;
                Some((post, innov.log_likelihood() - z[0].ln()))
            }
            _ => {
                let (post, innov) = self.kf.update(pred, &p.model, &p.position).ok()?;
                Some((post, innov.log_likelihood()))
            }
        }
    }
}

/// The normalised distance `νᵀ S⁻¹ ν` and the log-likelihood per m² of plot `p` for a
/// track predicted at `pred`: through the EKF's polar prediction `polar` for a polar plot
/// when given, through the linear Cartesian model otherwise.
#[inline]
pub(crate) fn innovation(
    pred: &Gaussian<4>,
    polar: Option<(&MeasurementPrediction<4, 2>, &Polar2D<4>)>,
    p: &ScanPoint,
) -> Option<(f64, f64)> {
    if let (Some((mp, model)), Some(z)) = (polar, p.polar) {
        let innov = mp.innovation(model, &z).ok()?;
        return Some((innov.nis, innov.log_likelihood() - z[0].ln()));
    }
    position_innovation(pred, p)
}

/// The linear position innovation of the CV state in closed form: with `H` selecting
/// the plot's position components, `S = P_pp + R` is 2 × 2, `νᵀ S⁻¹ ν` and
/// `ln N(ν; 0, S)` follow from `det S` without a factorisation or a gain (gating needs
/// neither). Equal to the Kalman filter's innovation to round-off (tested).
#[inline]
pub(crate) fn position_innovation(pred: &Gaussian<4>, p: &ScanPoint) -> Option<(f64, f64)> {
    let [i, j] = p.model.indices();
    let (x, cov, r) = (pred.mean(), pred.cov(), &p.covariance);
    let (s00, s01, s11) = (
        cov[(i, i)] + r[(0, 0)],
        cov[(i, j)] + 0.5 * (r[(0, 1)] + r[(1, 0)]),
        cov[(j, j)] + r[(1, 1)],
    );
    let det = s00 * s11 - s01 * s01;
    if !(s00 > 0.0 && det > 0.0 && det.is_finite()) {
        return None;
    }
    let (a, b) = (p.position[0] - x[i], p.position[1] - x[j]);
    let nis = (s11 * a * a - 2.0 * s01 * a * b + s00 * b * b) / det;
    if !nis.is_finite() {
        return None;
    }
    let log_likelihood = -0.5 * (nis + det.ln()) - (2.0 * std::f64::consts::PI).ln();
    Some((nis, log_likelihood))
}

/// IMM-JPDA gating and likelihood of plot `p`: per mode `r` the normalised distance and
/// `ln N(ν_r; 0, S_r)`; the plot is in the gate if it is in some mode's gate, and its
/// likelihood is the mixture `ln Σ_r μ̄_r N(ν_r; 0, S_r)`.
pub(crate) fn imm_innovation(
    imm: &Imm<Kf<Cv2D>, 4, 2>,
    pred: &ImmPrediction<4, 2>,
    p: &ScanPoint,
) -> Option<(f64, f64)> {
    let mut nis = f64::INFINITY;
    let mut terms = [f64::NEG_INFINITY; 2];
    for (r, (f, g)) in imm.filters().iter().zip(pred.modes()).enumerate() {
        let mp = f.predict_measurement(g, &p.model).ok()?;
        let innov = mp.innovation(&p.model, &p.position).ok()?;
        nis = nis.min(innov.nis);
        terms[r] = pred.log_predicted_probabilities()[r] + innov.log_likelihood();
    }
    Some((nis, log_sum_exp(&terms)))
}

/// The moment-matched Gaussian of the weighted parts (weights need not sum to one);
/// `None` when the weights vanish or the result is not a valid Gaussian.
pub(crate) fn mixture(parts: &[(f64, Gaussian<4>)]) -> Option<Gaussian<4>> {
    let total: f64 = parts.iter().map(|p| p.0).sum();
    if !(total.is_finite() && total > 0.0) {
        return None;
    }
    let mut mean = Vector::<4>::zeros();
    for (w, g) in parts {
        mean += g.mean() * (*w / total);
    }
    let mut cov = Matrix::<4, 4>::zeros();
    for (w, g) in parts {
        let d = g.mean() - mean;
        cov += (g.cov() + d * d.transpose()) * (*w / total);
    }
    Gaussian::from_symmetrized(mean, &cov).ok()
}

/// The JPDA (PDA) update of a single-filter track: the moment-matched mixture of the
/// prediction (weight `β₀ = 1 − Σ β_j`) and the update with each plot (weight `β_j`),
/// which is the standard PDA update when all plots share one `R` (Bar-Shalom & Tse 1975).
pub(crate) fn jpda_update(
    est: &Estimators,
    pred: &Gaussian<4>,
    polar: Option<&Polar2D<4>>,
    weights: &[(usize, f64)],
    points: &[ScanPoint],
) -> Option<Gaussian<4>> {
    let b0 = (1.0 - weights.iter().map(|w| w.1).sum::<f64>()).max(0.0);
    let mut parts: Vec<(f64, Gaussian<4>)> = Vec::with_capacity(weights.len() + 1);
    parts.push((b0, *pred));
    for &(j, b) in weights {
        let (post, _) = est.update_single(pred, polar, &points[j])?;
        parts.push((b, post));
    }
    mixture(&parts)
}

/// One IMM update (or coast through a miss): the moment-matched posterior with the
/// plot's total log-likelihood, and the IMM estimate; `None` on failure.
pub(crate) fn imm_step(
    imm: &Imm<Kf<Cv2D>, 4, 2>,
    pred: ImmPrediction<4, 2>,
    hit: Option<&ScanPoint>,
) -> Option<(Gaussian<4>, Option<f64>, ImmEstimate<4, 2>)> {
    let (est, ll) = match hit {
        Some(p) => {
            let u = imm.update(&pred, &p.model, &p.position).ok()?;
            (u.estimate, Some(u.log_likelihood))
        }
        None => (pred.into_estimate(), None),
    };
    Some((est.combined().ok()?, ll, est))
}

/// The IMM-JPDA update of one track from its mode-matched predictions and its JPDA
/// marginals `β_j` (computed from the mixed likelihoods `Σ_r μ̄_r N_r,j`).
///
/// With `N_r,j = N(ν_r,j; 0, S_r,j)` and `N_j = Σ_s μ̄_s N_s,j`, the joint posterior of
/// mode `r` and "plot `j` is the target's" is `P(r, j) = β_j μ̄_r N_r,j / N_j` and of
/// "no plot is" `P(r, 0) = β₀ μ̄_r` (the miss factor does not depend on the mode). So:
/// - mode probability `μ_r = Σ_j P(r, j) = μ̄_r (β₀ + Σ_j β_j N_r,j / N_j)`: the mode
///   likelihood summed over the plot events;
/// - mode `r`'s estimate: the PDA mixture of its prediction and its Kalman updates with
///   the weights `P(r, j) / μ_r`.
///
/// With identical modes `N_r,j = N_j`, `μ_r = μ̄_r` and every mode gets the JPDA+KF update.
///
/// # References
/// H. A. P. Blom, E. A. Bloem, "Probabilistic data association avoiding track
/// coalescence", IEEE Trans. Automatic Control 45(2), 2000 (IMM-JPDA); Y. Bar-Shalom,
/// P. Willett, X. Tian, *Tracking and Data Fusion*, YBS 2011 (IMM-JPDA, and IMM-PDA as its
/// one-track case).
pub(crate) fn imm_jpda_update(
    imm: &Imm<Kf<Cv2D>, 4, 2>,
    pred: &ImmPrediction<4, 2>,
    weights: &[(usize, f64)],
    points: &[ScanPoint],
) -> Option<(Gaussian<4>, ImmEstimate<4, 2>)> {
    let lc = pred.log_predicted_probabilities();
    let modes = pred.modes();
    let b0 = (1.0 - weights.iter().map(|w| w.1).sum::<f64>()).max(0.0);
    let mut parts: [Vec<(f64, Gaussian<4>)>; 2] = [
        Vec::with_capacity(weights.len() + 1),
        Vec::with_capacity(weights.len() + 1),
    ];
    for (r, part) in parts.iter_mut().enumerate() {
        part.push((b0 * lc[r].exp(), modes[r]));
    }
    for &(j, b) in weights {
        let p = &points[j];
        let mut post = [modes[0]; 2];
        let mut joint = [f64::NEG_INFINITY; 2];
        for (r, (f, g)) in imm.filters().iter().zip(modes).enumerate() {
            let (g_post, innov) = f.update(g, &p.model, &p.position).ok()?;
            post[r] = g_post;
            joint[r] = lc[r] + innov.log_likelihood();
        }
        let total = log_sum_exp(&joint);
        if !total.is_finite() {
            return None;
        }
        for (r, part) in parts.iter_mut().enumerate() {
            part.push((b * (joint[r] - total).exp(), post[r]));
        }
    }
    let mut mu = [0.0; 2];
    let mut new_modes = *modes;
    for (r, part) in parts.iter().enumerate() {
        mu[r] = part.iter().map(|p| p.0).sum();
        if mu[r] > 0.0 {
            new_modes[r] = mixture(part)?;
        }
    }
    let sum: f64 = mu.iter().sum();
    if !(sum.is_finite() && sum > 0.0) {
        return None;
    }
    let est = ImmEstimate::new(new_modes, mu.map(|m| m / sum)).ok()?;
    Some((est.combined().ok()?, est))
}

/// One multi-IMM update of a track whose state holds its prediction (from
/// [`MultiImm::predict`]): the new state, its combined estimate and the plot's
/// log-likelihood `ln (1/K) Σₘ Λᵐ` (per m², the hypotheses' measurements being converted
/// positions). `None` on failure.
pub(crate) fn multi_update(
    multi: &MultiImm<Kf<Cv2D>, 4, 2, MULTI_IMM_HYPOTHESES>,
    predicted: &MultiState,
    pm: &PolarModel,
    z: &Vector<2>,
) -> Option<(MultiState, Gaussian<4>, f64)> {
    let plot = PolarMeasurement::new(z[0], z[1]).ok()?;
    let u = multi.update(predicted, &plot, &pm.conversion).ok()?;
    let ll = log_sum_exp(&u.log_likelihoods) - (MULTI_IMM_HYPOTHESES as f64).ln();
    let combined = u.estimate.combined().ok()?;
    Some((u.estimate, combined, ll))
}

/// The axis-aligned box around a predicted track that holds its chi-square gate for any
/// Cartesian plot whose position variances are at most `r_max`: centre `(x, y)` and
/// half-widths `√(γ (P_xx + R_max,xx))`, `√(γ (P_yy + R_max,yy))`.
pub(crate) fn gate_box(pred: &Gaussian<4>, gamma: f64, r_max: [f64; 2]) -> (Vector<2>, [f64; 2]) {
    let p = pred.cov();
    let centre = Vector::<2>::new(pred.mean()[0], pred.mean()[2]);
    let half = [
        (gamma * (p[(0, 0)] + r_max[0])).sqrt(),
        (gamma * (p[(2, 2)] + r_max[1])).sqrt(),
    ];
    (centre, half)
}

/// The half-width of a square box around the predicted position that holds the EKF's
/// polar gate `νᵀ S⁻¹ ν ≤ γ` as converted plots: the gate implies `|Δr| ≤ a = √(γ S_rr)`
/// and `|Δθ| ≤ b = √(γ S_θθ)`, so a raw plot is within `a + r̂ min(b, 2)` of the
/// prediction (`r̂ |2 sin(Δθ/2)| ≤ r̂ min(|Δθ|, 2)`), and the unbiased conversion moves it
/// outwards by `r (1/λ − 1)` more, `r ≤ r̂ + a`.
pub(crate) fn polar_half(mp: &MeasurementPrediction<4, 2>, gamma: f64, stretch: f64) -> f64 {
    let s = mp.s();
    let a = (gamma * s[(0, 0)]).sqrt();
    let b = (gamma * s[(1, 1)]).sqrt();
    let r = mp.z_pred()[0];
    a + r * b.min(2.0) + (r + a) * stretch
}

/// The bounding box of the per-mode gate boxes of an IMM prediction.
pub(crate) fn imm_gate_box(
    pred: &ImmPrediction<4, 2>,
    gamma: f64,
    r_max: [f64; 2],
) -> (Vector<2>, [f64; 2]) {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for g in pred.modes() {
        let (c, h) = gate_box(g, gamma, r_max);
        for i in 0..2 {
            lo[i] = lo[i].min(c[i] - h[i]);
            hi[i] = hi[i].max(c[i] + h[i]);
        }
    }
    (
        Vector::<2>::new(0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])),
        [0.5 * (hi[0] - lo[0]), 0.5 * (hi[1] - lo[1])],
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use argus_sensors::CartesianPosition;

    #[test]
    fn closed_form_position_innovation_equals_the_kalman_filter() {
        // The KF's innovation (Cholesky of S, solve, log-determinant) against the 2×2
        // closed form; tolerance: round-off relative to the values.
        #[rustfmt::skip]
        let p = Matrix::<4, 4>::new(
            900.0, 60.0, 100.0, 0.0,
            60.0, 100.0, 0.0, 5.0,
            100.0, 0.0, 700.0, 40.0,
            0.0, 5.0, 40.0, 80.0,
        );
        let pred = Gaussian::new(Vector::<4>::new(1000.0, 10.0, -500.0, 3.0), p).unwrap();
        let kf = Kf::new(Cv2D::discrete(2.0).unwrap());
        for (z, r) in [
            (
                Vector::<2>::new(1030.0, -470.0),
                Matrix::<2, 2>::new(400.0, 50.0, 50.0, 300.0),
            ),
            (
                Vector::<2>::new(900.0, -600.0),
                Matrix::<2, 2>::new(2500.0, -900.0, -900.0, 900.0),
            ),
        ] {
            let model = CartesianPosition::<4, 2>::cv(r).unwrap();
            let point = ScanPoint {
                position: z,
                covariance: r,
                model,
                polar: None,
            };
            let (nis, ll) = position_innovation(&pred, &point).unwrap();
            let mp = kf.predict_measurement(&pred, &model).unwrap();
            let innov = mp.innovation(&model, &z).unwrap();
            assert!((nis - innov.nis).abs() < 1e-12 * (1.0 + innov.nis));
            assert!(
                (ll - innov.log_likelihood()).abs() < 1e-12 * (1.0 + innov.log_likelihood().abs())
            );
        }
    }
}

//! Gating: each plot's normalised distance and likelihood for a predicted track, and the
//! grid query boxes that hold the gates.

use argus_core_math::{Gaussian, Vector};
use argus_filters::{GaussianFilter, Kf, MeasurementPrediction};
use argus_imm::{Imm, ImmPrediction, log_sum_exp};
use argus_motion_models::Cv2D;
use argus_sensors::Polar2D;

use crate::plot::ScanPoint;

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
pub(crate) fn polar_half<const N: usize>(
    mp: &MeasurementPrediction<N, 2>,
    gamma: f64,
    stretch: f64,
) -> f64 {
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
    use argus_core_math::Matrix;
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

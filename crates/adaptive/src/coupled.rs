//! The full (coupled) 6-state Kalman filter on converted plots: the accuracy
//! reference for the decoupled filter of seed 003.

use argus_core_math::{Gaussian, Matrix, check_finite_matrix};
use argus_filters::{CovarianceForm, FilterError, GaussianFilter, MeasurementPrediction, check_dt};
use argus_sensors::MeasurementModel;

use crate::error::{AdaptiveError, positive};

/// A linear Kalman filter for the 3-D constant-velocity state
/// `[x, vx, y, vy, z, vz]` with discrete white-noise acceleration `q` per axis:
/// `F = blockdiag([[1, T], [0, 1]])`, `Q = q² blockdiag(G Gᵀ)`, `G = [T²/2, T]ᵀ`.
/// It keeps the full 6×6 covariance, including the cross-axis terms that the
/// decoupled filter drops.
///
/// # References
/// Kim & Hwang (2013), seed 003, eqs (14)–(25) (the conventional KF the
/// decoupled filter approximates); Bar-Shalom, Li & Kirubarajan (2001) §5.2, §6.3.2.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoupledCvFilter {
    accel_sd: f64,
    form: CovarianceForm,
}

impl CoupledCvFilter {
    /// A filter with acceleration noise `q` (m/s²) and the Joseph covariance update.
    ///
    /// # Errors
    /// [`AdaptiveError::InvalidParameter`] or [`AdaptiveError::NonFinite`] for a `q`
    /// that is not finite and positive.
    pub fn new(accel_sd: f64) -> Result<Self, AdaptiveError> {
        Ok(Self {
            accel_sd: positive(accel_sd, "acceleration noise q")?,
            form: CovarianceForm::Joseph,
        })
    }

    /// The same filter with another covariance form.
    #[must_use]
    pub fn with_form(self, form: CovarianceForm) -> Self {
        Self { form, ..self }
    }

    /// The transition `F(T)`.
    #[must_use]
    pub fn transition(dt: f64) -> Matrix<6, 6> {
        let mut f = Matrix::<6, 6>::identity();
        for i in 0..3 {
            f[(2 * i, 2 * i + 1)] = dt;
        }
        f
    }

    /// The process noise `Q(T)`.
    #[must_use]
    pub fn process_noise(&self, dt: f64) -> Matrix<6, 6> {
        let q2 = self.accel_sd * self.accel_sd;
        let mut q = Matrix::<6, 6>::zeros();
        for i in 0..3 {
            q[(2 * i, 2 * i)] = q2 * dt.powi(4) / 4.0;
            q[(2 * i, 2 * i + 1)] = q2 * dt.powi(3) / 2.0;
            q[(2 * i + 1, 2 * i)] = q2 * dt.powi(3) / 2.0;
            q[(2 * i + 1, 2 * i + 1)] = q2 * dt * dt;
        }
        q
    }
}

impl GaussianFilter<6> for CoupledCvFilter {
    #[allow(non_snake_case)]
    fn predict(&self, prior: &Gaussian<6>, dt: f64) -> Result<Gaussian<6>, FilterError> {
        check_dt(dt)?;
        let F = Self::transition(dt);
        let P = F * prior.cov() * F.transpose() + self.process_noise(dt);
        Ok(Gaussian::from_symmetrized(F * prior.mean(), &P)?)
    }

    #[allow(non_snake_case)]
    fn predict_measurement<const M: usize, Me: MeasurementModel<6, M>>(
        &self,
        predicted: &Gaussian<6>,
        meas: &Me,
    ) -> Result<MeasurementPrediction<6, M>, FilterError> {
        let x = predicted.mean();
        let H = meas.jacobian(x);
        let R = meas.noise(x);
        check_finite_matrix(&H, "measurement Jacobian")?;
        check_finite_matrix(&R, "measurement noise R")?;
        let PHt = predicted.cov() * H.transpose();
        let S = H * PHt + R;
        MeasurementPrediction::new(meas.predict(x), S, PHt, Some(H), R, self.form)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::decoupled_plot::{ConvertedPlot, aligned_frame};
    use argus_core_math::Vector;

    #[test]
    fn steady_state_matches_the_alpha_beta_filter() {
        // Kalata's tracking index λ = q T² / σ fixes the steady-state α of the
        // α–β filter: α = −(λ² + 8λ − (λ + 4)√(λ² + 8λ))/8 (Bar-Shalom et al. 2001, §6.5.3).
        // The position gain of the KF must converge to it (1e-6).
        let (q, t, sigma) = (1.0, 1.0, 1.0);
        let f = CoupledCvFilter::new(q).unwrap();
        let plot = ConvertedPlot::new(
            Vector::<3>::zeros(),
            aligned_frame(0.0, 0.0),
            Vector::<3>::repeat(sigma * sigma),
        )
        .unwrap();
        let mut g = Gaussian::new(Vector::<6>::zeros(), Matrix::<6, 6>::identity() * 10.0).unwrap();
        let mut gain = 0.0;
        for _ in 0..200 {
            let pred = f.predict(&g, t).unwrap();
            let mp = f.predict_measurement(&pred, &plot).unwrap();
            gain = mp.gain()[(0, 0)];
            g = mp.update(&pred, &Vector::<3>::zeros()).unwrap();
        }
        let l: f64 = q * t * t / sigma;
        let alpha = -(l * l + 8.0 * l - (l + 4.0) * (l * l + 8.0 * l).sqrt()) / 8.0;
        assert!((gain - alpha).abs() < 1e-6, "{gain} vs {alpha}");
    }

    #[test]
    fn bad_dt_is_rejected() {
        let f = CoupledCvFilter::new(0.05).unwrap();
        let g = Gaussian::new(Vector::<6>::zeros(), Matrix::<6, 6>::identity()).unwrap();
        assert!(matches!(
            f.predict(&g, 0.0),
            Err(FilterError::InvalidInterval { .. })
        ));
        assert!(CoupledCvFilter::new(0.0).is_err());
    }
}

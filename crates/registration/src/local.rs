//! The biased local filter of seed 004 §3: a CV Kalman filter per (sensor, target) run
//! on biased plots, carrying the bias sensitivity `G` so that its estimate splits as
//! `X̂ᵇ = X̂ + G β`.
//!
//! State order `[x, vx, y, vy]` (the workspace convention; the paper orders
//! `[x, y, vx, vy]`), so `H = [[1,0,0,0],[0,0,1,0]]`.

use argus_core_math::{Gaussian, Matrix, Vector, check_finite_matrix, check_finite_vector};
use argus_filters::{GaussianFilter, Kf};
use argus_motion_models::{Cv2D, LinearMotionModel, MotionModel};
use argus_sensors::CartesianPosition;

use crate::error::{RegistrationError, finite};
use crate::polar::ConvertedPlot;

/// The position-selection matrix `H` for the `[x, vx, y, vy]` layout (eq (5) reordered).
#[must_use]
pub fn position_matrix() -> Matrix<2, 4> {
    Matrix::<2, 4>::new(1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0)
}

/// A local track on biased plots: the biased estimate `X̂ᵇ` with the covariance `P` of the
/// bias-free part (eqs (14), (21)), the bias sensitivity `G` and the track time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BiasedTrack {
    estimate: Gaussian<4>,
    g: Matrix<4, 4>,
    time: f64,
}

impl BiasedTrack {
    /// A track from its parts.
    ///
    /// # Errors
    /// [`RegistrationError::NonFinite`] / [`RegistrationError::Math`] for a non-finite time or `G`.
    pub fn new(
        estimate: Gaussian<4>,
        g: Matrix<4, 4>,
        time: f64,
    ) -> Result<Self, RegistrationError> {
        finite("track time", time)?;
        check_finite_matrix(&g, "bias sensitivity G")?;
        Ok(Self { estimate, g, time })
    }

    /// A track started bias-free (known unbiased initial estimate): `G = 0` (text after eq (11)).
    ///
    /// # Errors
    /// [`RegistrationError::NonFinite`] for a non-finite time.
    pub fn bias_free(estimate: Gaussian<4>, time: f64) -> Result<Self, RegistrationError> {
        Self::new(estimate, Matrix::<4, 4>::zeros(), time)
    }

    /// Two-point differencing from two plots of the same sensor, eqs (8)–(11):
    /// `X̂ᵇ = [z₁, (z₁ − z₀)/T]`, `G = [B₁C₁; (B₁C₁ − B₀C₀)/T]`,
    /// `P = [[R₁, R₁/T], [R₁/T, (R₁ + R₀)/T²]]` (per axis pair, reordered to `[x, vx, y, vy]`).
    ///
    /// # Errors
    /// [`RegistrationError::TimeNotIncreasing`] unless `second` is later than `first`;
    /// [`RegistrationError::Math`] if `P` is not positive definite.
    #[allow(non_snake_case)]
    pub fn two_point(
        first: &ConvertedPlot,
        second: &ConvertedPlot,
    ) -> Result<Self, RegistrationError> {
        let T = second.time() - first.time();
        if T.is_nan() || T <= 0.0 {
            return Err(RegistrationError::TimeNotIncreasing {
                what: "two-point initiation",
                prev: first.time(),
                now: second.time(),
            });
        }
        let (z0, z1) = (first.z(), second.z());
        let (R0, R1) = (first.noise(), second.noise());
        let (BC0, BC1) = (first.bias_jacobian(), second.bias_jacobian());
        let mut x = Vector::<4>::zeros();
        let mut P = Matrix::<4, 4>::zeros();
        let mut G = Matrix::<4, 4>::zeros();
        for a in 0..2 {
            x[2 * a] = z1[a];
            x[2 * a + 1] = (z1[a] - z0[a]) / T;
            for b in 0..2 {
                P[(2 * a, 2 * b)] = R1[(a, b)];
                P[(2 * a, 2 * b + 1)] = R1[(a, b)] / T;
                P[(2 * a + 1, 2 * b)] = R1[(a, b)] / T;
                P[(2 * a + 1, 2 * b + 1)] = (R1[(a, b)] + R0[(a, b)]) / (T * T);
            }
            for k in 0..4 {
                G[(2 * a, k)] = BC1[(a, k)];
                G[(2 * a + 1, k)] = (BC1[(a, k)] - BC0[(a, k)]) / T;
            }
        }
        Self::new(Gaussian::new(x, P)?, G, second.time())
    }

    /// The biased estimate `X̂ᵇ` with covariance `P` (the covariance of `X̂ᵇ − G β` about the truth).
    #[must_use]
    pub fn estimate(&self) -> &Gaussian<4> {
        &self.estimate
    }

    /// The bias sensitivity `G`.
    #[must_use]
    pub fn g(&self) -> &Matrix<4, 4> {
        &self.g
    }

    /// The track time (s).
    #[must_use]
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The bias-compensated estimate, eqs (38) and (41): `X̂ = X̂ᵇ − G β̂`,
    /// `P = P + G Σ Gᵀ`, with `β̂`, `Σ` this sensor's bias estimate and its covariance.
    ///
    /// # Errors
    /// [`RegistrationError::Math`] for non-finite input or a `Σ` that makes the result
    /// lose positive definiteness.
    pub fn compensated(
        &self,
        beta: &Vector<4>,
        sigma: &Matrix<4, 4>,
    ) -> Result<Gaussian<4>, RegistrationError> {
        check_finite_vector(beta, "bias estimate")?;
        check_finite_matrix(sigma, "bias covariance")?;
        let mean = self.estimate.mean() - self.g * beta;
        let cov = self.estimate.cov() + self.g * sigma * self.g.transpose();
        Ok(Gaussian::from_symmetrized(mean, &cov)?)
    }
}

/// The CV local filter of seed 004 (eqs (7), (42), (43)): `Φ(T)` and DCWNA process noise
/// with power spectral density `q̃` (m²/s³), on biased plots, propagating `G`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BiasedLocalFilter {
    kf: Kf<Cv2D>,
}

impl BiasedLocalFilter {
    /// A filter with process-noise power spectral density `q̃ ≥ 0` (m²/s³): the workspace's
    /// Kalman filter on the continuous-white-noise CV model ([`Cv2D::continuous`]).
    ///
    /// # Errors
    /// [`RegistrationError::InvalidParameter`] for a negative or non-finite `q̃`.
    pub fn new(q_tilde: f64) -> Result<Self, RegistrationError> {
        finite("process noise PSD", q_tilde)?;
        let model = Cv2D::continuous(q_tilde).map_err(|_| RegistrationError::InvalidParameter {
            what: "process noise PSD",
            value: q_tilde,
            reason: "must be non-negative",
        })?;
        Ok(Self { kf: Kf::new(model) })
    }

    /// `Φ(T)`, eq (42), for `[x, vx, y, vy]`.
    #[must_use]
    pub fn transition(&self, dt: f64) -> Matrix<4, 4> {
        self.kf.model().transition(dt)
    }

    /// `Q(T)`, eq (43) (DCWNA), for `[x, vx, y, vy]`.
    #[must_use]
    pub fn process_noise(&self, dt: f64) -> Matrix<4, 4> {
        self.kf.model().process_noise(&Vector::<4>::zeros(), dt)
    }

    /// Predicts the track to `time ≥ track.time()`, eqs (13)–(14): `X̂ᵇ⁻ = Φ X̂ᵇ`,
    /// `P⁻ = Φ P Φᵀ + Q` (the Kalman filter's prediction), `G⁻ = Φ G`. A zero interval
    /// returns the track unchanged.
    ///
    /// # Errors
    /// [`RegistrationError::TimeNotIncreasing`] when `time` is earlier than the track,
    /// [`RegistrationError::NonFinite`] for a non-finite time.
    pub fn predict(
        &self,
        track: &BiasedTrack,
        time: f64,
    ) -> Result<BiasedTrack, RegistrationError> {
        finite("prediction time", time)?;
        let dt = time - track.time;
        if dt < 0.0 {
            return Err(RegistrationError::TimeNotIncreasing {
                what: "local track prediction",
                prev: track.time,
                now: time,
            });
        }
        if dt == 0.0 {
            return Ok(*track);
        }
        let estimate = self.kf.predict(&track.estimate, dt)?;
        Ok(BiasedTrack {
            estimate,
            g: self.transition(dt) * track.g,
            time,
        })
    }

    /// Predicts to the plot's time and updates with it through the Kalman filter (Joseph
    /// form), eqs (16)–(21), and carries `G` with eq (20) corrected to
    /// `G⁺ = (I − K H) Φ G + K B C` (the paper prints `(I − K) H Φ G`, which does not even
    /// have the right dimensions), `K` the filter's gain.
    ///
    /// # Errors
    /// As [`Self::predict`], and [`RegistrationError::Math`] when `S` or the posterior is
    /// not positive definite. The input track is never modified.
    #[allow(non_snake_case)]
    pub fn update(
        &self,
        track: &BiasedTrack,
        plot: &ConvertedPlot,
    ) -> Result<BiasedTrack, RegistrationError> {
        let pred = self.predict(track, plot.time())?;
        let sensor = CartesianPosition::<4, 2>::new([0, 2], *plot.noise())?;
        let mp = self.kf.predict_measurement(&pred.estimate, &sensor)?;
        let estimate = mp.update(&pred.estimate, &(plot.z() - mp.z_pred()))?;
        let K = mp.gain();
        let G = (Matrix::<4, 4>::identity() - K * position_matrix()) * pred.g
            + K * plot.bias_jacobian();
        check_finite_matrix(&G, "bias sensitivity G")?;
        Ok(BiasedTrack {
            estimate,
            g: G,
            time: plot.time(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dcwna_noise_matches_closed_form() {
        // Eq (43) at T = 2, q̃ = 6: T³/3·q̃ = 16, T²/2·q̃ = 12, T·q̃ = 12.
        let f = BiasedLocalFilter::new(6.0).unwrap();
        let q = f.process_noise(2.0);
        assert!((q[(0, 0)] - 16.0).abs() < 1e-12);
        assert!((q[(0, 1)] - 12.0).abs() < 1e-12);
        assert!((q[(3, 3)] - 12.0).abs() < 1e-12);
        assert!(q[(0, 2)].abs() < 1e-15);
    }

    #[test]
    fn bad_input_is_rejected_and_track_kept() {
        assert!(BiasedLocalFilter::new(-1.0).is_err());
        assert!(BiasedLocalFilter::new(f64::NAN).is_err());
        let f = BiasedLocalFilter::new(6.0).unwrap();
        let est = Gaussian::new(Vector::<4>::zeros(), Matrix::<4, 4>::identity()).unwrap();
        let tr = BiasedTrack::bias_free(est, 5.0).unwrap();
        let copy = tr;
        assert!(matches!(
            f.predict(&tr, 4.0),
            Err(RegistrationError::TimeNotIncreasing { .. })
        ));
        let p = ConvertedPlot::new(
            3.0,
            Vector::<2>::zeros(),
            Matrix::<2, 2>::identity(),
            Matrix::<2, 4>::zeros(),
        )
        .unwrap();
        assert!(f.update(&tr, &p).is_err());
        assert_eq!(tr, copy);
        let p0 = ConvertedPlot::new(
            1.0,
            Vector::<2>::zeros(),
            Matrix::<2, 2>::identity(),
            Matrix::<2, 4>::zeros(),
        )
        .unwrap();
        assert!(matches!(
            BiasedTrack::two_point(&p0, &p0),
            Err(RegistrationError::TimeNotIncreasing { .. })
        ));
        let mut g = Matrix::<4, 4>::zeros();
        g[(1, 1)] = f64::NAN;
        assert!(BiasedTrack::new(est, g, 0.0).is_err());
        assert!(
            tr.compensated(
                &Vector::<4>::new(f64::NAN, 0.0, 0.0, 0.0),
                &Matrix::<4, 4>::identity()
            )
            .is_err()
        );
    }
}

//! Rayleigh clutter and Swerling I target amplitudes with a detection threshold.

use crate::error::{AssociationError, check_non_negative};

/// Amplitude model of Li & Bar-Shalom (1998): envelope normalised to the noise,
/// clutter Rayleigh `p₀(a) = a e^{−a²/2}`, target Swerling I (Rayleigh envelope)
/// `p₁(a) = a/(1+d) e^{−a²/(2(1+d))}` with mean SNR `d`; a plot is declared when
/// `a ≥ τ`. Hence
///
/// - `P_FA = e^{−τ²/2}`, `P_D = e^{−τ²/(2(1+d))}`;
/// - above the threshold, `p₀τ(a) = p₀(a)/P_FA`, `p₁τ(a) = p₁(a)/P_D`;
/// - the likelihood ratio `ρ(a) = p₁τ(a)/p₀τ(a) = P_FA/(P_D (1+d)) · e^{a² d/(2(1+d))}`;
/// - the tails above `a ≥ τ`: `F̄₀(a) = e^{−(a²−τ²)/2}`, `F̄₁(a) = e^{−(a²−τ²)/(2(1+d))}`.
///
/// This is the convention of `argus_sim::Detection::Swerling1`.
///
/// # References
/// Li, X. R. & Bar-Shalom, Y. (1998), "Tracking in clutter with strongest neighbor
/// measurements — Part I", IEEE TAC 43(11), §II (amplitude model); seed 002 §2.4.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AmplitudeModel {
    snr: f64,
    threshold: f64,
    p_d: f64,
    p_fa: f64,
}

impl AmplitudeModel {
    /// The model for mean SNR `snr_db` (dB) and threshold `τ` (normalised amplitude).
    ///
    /// # Errors
    /// [`AssociationError::InvalidParameter`] when `snr_db` is not finite or `τ` is
    /// negative or not finite.
    pub fn new(snr_db: f64, threshold: f64) -> Result<Self, AssociationError> {
        if !snr_db.is_finite() {
            return Err(AssociationError::InvalidParameter {
                what: "mean SNR (dB)",
                value: snr_db,
                reason: "must be finite",
            });
        }
        check_non_negative(threshold, "detection threshold")?;
        let snr = 10f64.powf(snr_db / 10.0);
        let t2 = threshold * threshold;
        Ok(Self {
            snr,
            threshold,
            p_d: (-t2 / (2.0 * (1.0 + snr))).exp(),
            p_fa: (-t2 / 2.0).exp(),
        })
    }

    /// The model with the threshold that gives detection probability `p_d` at mean SNR
    /// `snr_db`: `τ = √(−2(1+d) ln P_D)`.
    ///
    /// # Errors
    /// [`AssociationError::InvalidParameter`] when `p_d ∉ (0, 1]` or `snr_db` is not finite.
    pub fn from_detection_probability(snr_db: f64, p_d: f64) -> Result<Self, AssociationError> {
        crate::error::check_prob_open_closed(p_d, "detection probability")?;
        if !snr_db.is_finite() {
            return Err(AssociationError::InvalidParameter {
                what: "mean SNR (dB)",
                value: snr_db,
                reason: "must be finite",
            });
        }
        let d = 10f64.powf(snr_db / 10.0);
        Self::new(snr_db, (-2.0 * (1.0 + d) * p_d.ln()).max(0.0).sqrt())
    }

    /// Mean SNR `d` (linear).
    #[must_use]
    pub fn snr(&self) -> f64 {
        self.snr
    }

    /// Detection threshold `τ`.
    #[must_use]
    pub fn threshold(&self) -> f64 {
        self.threshold
    }

    /// Detection probability `P_D = e^{−τ²/(2(1+d))}`.
    #[must_use]
    pub fn p_d(&self) -> f64 {
        self.p_d
    }

    /// False-alarm probability per cell `P_FA = e^{−τ²/2}`.
    #[must_use]
    pub fn p_fa(&self) -> f64 {
        self.p_fa
    }

    /// Checks that `a` is a finite amplitude at or above the threshold.
    ///
    /// # Errors
    /// [`AssociationError::InvalidAmplitude`] naming plot `index`.
    pub fn check(&self, a: f64, index: usize) -> Result<(), AssociationError> {
        // A relative slack of 1e-12 tolerates a threshold round-trip through text.
        if a.is_finite() && a >= self.threshold * (1.0 - 1e-12) {
            Ok(())
        } else {
            Err(AssociationError::InvalidAmplitude {
                index,
                value: a,
                threshold: self.threshold,
            })
        }
    }

    /// Clutter amplitude density above the threshold, `p₀τ(a) = a e^{−a²/2}/P_FA`
    /// (zero below `τ`).
    #[must_use]
    pub fn clutter_pdf(&self, a: f64) -> f64 {
        if a < self.threshold {
            0.0
        } else {
            a * (-(a * a - self.threshold * self.threshold) / 2.0).exp()
        }
    }

    /// Target amplitude density above the threshold,
    /// `p₁τ(a) = a/(1+d) e^{−a²/(2(1+d))}/P_D` (zero below `τ`).
    #[must_use]
    pub fn target_pdf(&self, a: f64) -> f64 {
        if a < self.threshold {
            0.0
        } else {
            let s = 1.0 + self.snr;
            a / s * (-(a * a - self.threshold * self.threshold) / (2.0 * s)).exp()
        }
    }

    /// The likelihood ratio `ρ(a) = p₁τ(a)/p₀τ(a) = e^{(a²−τ²) d/(2(1+d))}/(1+d)`.
    #[must_use]
    pub fn likelihood_ratio(&self, a: f64) -> f64 {
        let s = 1.0 + self.snr;
        let excess = a * a - self.threshold * self.threshold;
        (excess * self.snr / (2.0 * s)).exp() / s
    }

    /// `ln ρ(a) = (a²−τ²) d/(2(1+d)) − ln(1+d)`, which does not overflow for strong plots.
    #[must_use]
    pub fn ln_likelihood_ratio(&self, a: f64) -> f64 {
        let s = 1.0 + self.snr;
        (a * a - self.threshold * self.threshold) * self.snr / (2.0 * s) - s.ln()
    }

    /// Probability that a clutter plot's amplitude exceeds `a ≥ τ`: `e^{−(a²−τ²)/2}`.
    #[must_use]
    pub fn clutter_tail(&self, a: f64) -> f64 {
        (-(a * a - self.threshold * self.threshold).max(0.0) / 2.0).exp()
    }

    /// Probability that a detected target's amplitude exceeds `a ≥ τ`:
    /// `e^{−(a²−τ²)/(2(1+d))}`.
    #[must_use]
    pub fn target_tail(&self, a: f64) -> f64 {
        (-(a * a - self.threshold * self.threshold).max(0.0) / (2.0 * (1.0 + self.snr))).exp()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn detection_and_false_alarm_probabilities() {
        // P_FA = e^{−τ²/2}, P_D = P_FA^{1/(1+d)} (Swerling I, Li & Bar-Shalom 1998).
        let m = AmplitudeModel::new(10.0, 2.0).unwrap();
        assert!((m.p_fa() - (-2.0f64).exp()).abs() < 1e-15);
        assert!((m.p_d() - (-2.0f64 / 11.0).exp()).abs() < 1e-15);
        let m2 = AmplitudeModel::from_detection_probability(20.0, 0.9).unwrap();
        assert!((m2.p_d() - 0.9).abs() < 1e-12);
    }

    #[test]
    fn densities_integrate_to_one_and_ratio_matches() {
        // Trapezoid on [τ, τ+40]: both truncated densities integrate to 1 (1e-6).
        let m = AmplitudeModel::new(13.0, 1.5).unwrap();
        let (mut s0, mut s1) = (0.0, 0.0);
        let h = 1e-3;
        for i in 0..40_000 {
            let a = m.threshold() + (f64::from(i) + 0.5) * h;
            s0 += m.clutter_pdf(a) * h;
            s1 += m.target_pdf(a) * h;
            let r = m.target_pdf(a) / m.clutter_pdf(a);
            if a < m.threshold() + 10.0 {
                assert!((m.likelihood_ratio(a) / r - 1.0).abs() < 1e-9);
                assert!((m.ln_likelihood_ratio(a) - r.ln()).abs() < 1e-9);
            }
        }
        assert!((s0 - 1.0).abs() < 1e-6, "{s0}");
        assert!((s1 - 1.0).abs() < 1e-6, "{s1}");
        // Tails: F̄(τ) = 1.
        assert!((m.clutter_tail(m.threshold()) - 1.0).abs() < 1e-15);
        assert!((m.target_tail(m.threshold()) - 1.0).abs() < 1e-15);
    }

    #[test]
    fn rejects_bad_input() {
        assert!(AmplitudeModel::new(f64::NAN, 1.0).is_err());
        assert!(AmplitudeModel::new(10.0, -1.0).is_err());
        assert!(AmplitudeModel::from_detection_probability(10.0, 0.0).is_err());
        assert!(AmplitudeModel::from_detection_probability(10.0, 1.5).is_err());
        let m = AmplitudeModel::new(10.0, 2.0).unwrap();
        assert!(matches!(
            m.check(1.0, 3),
            Err(AssociationError::InvalidAmplitude { index: 3, .. })
        ));
        assert!(m.check(f64::INFINITY, 0).is_err());
        assert!(m.check(2.5, 0).is_ok());
    }
}

//! The probabilistic strongest-neighbour (PSN) filter.

use argus_core_math::{Gaussian, Vector};
use argus_filters::MeasurementPrediction;
use argus_sensors::MeasurementModel;

use crate::amplitude::AmplitudeModel;
use crate::associator::{Associator, Candidate, Outcome, for_each_gated, gaussian_checked};
use crate::error::{AssociationError, check_non_negative};
use crate::gate::Gate;

/// The probabilistic strongest-neighbour (PSN) filter: like SN it uses only the
/// strongest gated plot, but weighs the three events of its origin — `M₀` no plot in
/// the gate, `M_T` the SN plot is the target's, `M_F` it is clutter.
///
/// The derivation (ours; seed 002 gives no formulas). Target detected with `P_D`,
/// inside the gate with `P_G`, innovation `ν_t ~ N(0, S)`, amplitude density `p₁τ`;
/// clutter Poisson with density `λ`, uniform, amplitude density `p₀τ`. For the SN plot
/// at `(ν, a)` the factor "no other plot stronger than `a`" common to both origins
/// cancels, leaving
///
/// ```text
/// w_T = P_D N(ν; 0, S) ρ(a),    w_F = λ [1 − P_D P_G F̄₁(a)],    β_T = w_T/(w_T + w_F)
/// ```
///
/// (`ρ = p₁τ/p₀τ`, `F̄₁(a)` the target's amplitude tail). Given `M_T` the update is the
/// Kalman one, `Pᶜ`. Given `M_F` (and `M₀`) the target's plot is known *not* to be in
/// the gate with amplitude above `a` (above `τ` for `M₀`): with
/// `q = P_D P_G F̄₁(a)` and `q' = P_D G_{n+2}(γ) F̄₁(a)`, the innovation of the target
/// is zero-mean with covariance `S (1 − q')/(1 − q)`, so
///
/// ```text
/// P_F = P⁻ + (q − q')/(1 − q) · K S Kᵀ          (negative information: P_F ≥ P⁻)
/// x = x⁻ + β_T K ν
/// P = β_T Pᶜ + (1 − β_T) P_F + β_T (1 − β_T) K ν νᵀ Kᵀ
/// ```
///
/// With `λ = 0` and a gated plot, `β_T = 1` and it is the Kalman filter exactly.
///
/// # References
/// Li, X. R. & Bar-Shalom, Y. (1998), "Tracking in clutter with strongest neighbor
/// measurements — Part I: theoretical analysis", IEEE TAC 43(11) (events `M₀`, `M_T`,
/// `M_F` and the amplitude model); seed 002 §2.4.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Psn {
    gate: Gate,
    amplitude: AmplitudeModel,
    density: f64,
}

impl Psn {
    /// The PSN filter with gate `gate`, amplitude model `amplitude` (which fixes `P_D`)
    /// and clutter density `density` (detections per unit measurement volume).
    ///
    /// # Errors
    /// [`AssociationError::InvalidParameter`] for a negative or non-finite density.
    pub fn new(
        gate: Gate,
        amplitude: AmplitudeModel,
        density: f64,
    ) -> Result<Self, AssociationError> {
        check_non_negative(density, "clutter density")?;
        Ok(Self {
            gate,
            amplitude,
            density,
        })
    }

    /// The amplitude model.
    #[must_use]
    pub fn amplitude(&self) -> &AmplitudeModel {
        &self.amplitude
    }

    /// `(q − q')/(1 − q)` for a target tail probability `tail` (1 for `M₀`).
    fn negative_information(&self, tail: f64) -> f64 {
        let p_d = self.amplitude.p_d();
        let q = p_d * self.gate.p_gate() * tail;
        let q2 = p_d * self.gate.second_moment_factor() * tail;
        // q ≤ P_G < 1 (the gate probability is below one by construction).
        (q - q2) / (1.0 - q)
    }
}

impl Associator for Psn {
    fn gate(&self) -> &Gate {
        &self.gate
    }

    /// `log_likelihood` is `ln(w_T + w_F)` for the SN plot (the factors common to
    /// every model cancel), `ln(1 − P_D P_G)` when no plot is gated.
    ///
    /// # Errors
    /// Also [`AssociationError::MissingAmplitude`] / [`AssociationError::InvalidAmplitude`]
    /// for a gated plot without an amplitude at or above the threshold.
    #[allow(non_snake_case)]
    fn associate<const N: usize, const M: usize, Me: MeasurementModel<N, M>>(
        &self,
        predicted: &Gaussian<N>,
        mp: &MeasurementPrediction<N, M>,
        meas: &Me,
        plots: &[Candidate<M>],
    ) -> Result<Outcome<N>, AssociationError> {
        let mut best: Option<(usize, Vector<M>, f64, f64)> = None;
        let gated = for_each_gated(&self.gate, mp, meas, plots, |i, innov, c| {
            let a = c.amplitude.ok_or(AssociationError::MissingAmplitude {
                index: i,
                filter: "the PSN filter",
            })?;
            self.amplitude.check(a, i)?;
            if best.is_none_or(|(_, _, _, b)| a > b) {
                best = Some((i, innov.residual, innov.nis, a));
            }
            Ok(())
        })?;
        let K = mp.gain();
        let P_minus = predicted.cov();
        let KSKt = K * mp.s() * K.transpose();
        let p_d = self.amplitude.p_d();
        let Some((index, nu, nis, a)) = best else {
            let cov = P_minus + KSKt * self.negative_information(1.0);
            return Ok(Outcome {
                posterior: gaussian_checked(*predicted.mean(), &cov)?,
                gated,
                used: None,
                miss_probability: 1.0,
                log_likelihood: (1.0 - p_d * self.gate.p_gate()).ln(),
            });
        };
        let tail = self.amplitude.target_tail(a);
        // In logs: ρ(a) overflows for strong plots at high SNR.
        let ln_w_t =
            p_d.ln() + mp.log_likelihood_from_nis(nis) + self.amplitude.ln_likelihood_ratio(a);
        let ln_w_f = (self.density * (1.0 - p_d * self.gate.p_gate() * tail)).ln();
        let (hi, lo) = if ln_w_t >= ln_w_f {
            (ln_w_t, ln_w_f)
        } else {
            (ln_w_f, ln_w_t)
        };
        let log_likelihood = hi + (lo - hi).exp().ln_1p();
        let beta_t = (ln_w_t - log_likelihood).exp();
        if !(beta_t.is_finite() && log_likelihood.is_finite()) {
            return Err(AssociationError::Math(
                argus_core_math::MathError::NonFinite {
                    what: "PSN event weights",
                },
            ));
        }
        let P_c = mp.posterior_cov(P_minus);
        let P_f = P_minus + KSKt * self.negative_information(tail);
        let Knu = K * nu;
        let cov =
            P_c * beta_t + P_f * (1.0 - beta_t) + Knu * Knu.transpose() * (beta_t * (1.0 - beta_t));
        let mean = predicted.mean() + Knu * beta_t;
        Ok(Outcome {
            posterior: gaussian_checked(mean, &cov)?,
            gated,
            used: Some(index),
            miss_probability: 1.0 - beta_t,
            log_likelihood,
        })
    }
}

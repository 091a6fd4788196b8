//! Adaptive measurement-noise estimation from the post-fit residual (seed 003
//! eqs 28–32, corrected) and the adaptive decoupled filter (ADKF).

use argus_core_math::{Matrix, SpdFactor, Vector, symmetrize};

use crate::decoupled::{DecoupledEstimate, DecoupledFilter, DecoupledUpdate};
use crate::decoupled_plot::ConvertedPlot;
use crate::error::{AdaptiveError, positive};

/// How the estimate `R̂` starts.
///
/// The printed method ([`Warmup::Constant`]) starts from the assumed `R̂₀` and lets
/// each post-fit sample in with weight `1/L`. When the plots are much noisier than
/// assumed, the first plots are then fused with a far too small `R̂`: the state is
/// pulled off while `P` shrinks as if the plots were good, and with a small process
/// noise that error stays for hundreds of plots (seed 003 SCN.3: ANEES 13.6 over the
/// approach). The post-fit residual cannot fix this quickly: with `R̂ ≪ R` and
/// `P⁻ ≳ R̂` it is shrunk by `R̂ S⁻¹` and its sample is biased low.
/// [`Warmup::InnovationScale`] (the default) estimates the scale of `R` from the
/// innovations before each of the first `L` updates instead.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Warmup {
    /// Ours (the default): for the first `L` plots, `R̂ = max(λ̄, 1) R₀`, with `R₀`
    /// the plot's own assumed covariance (its aligned variances `r̄₀`) and `λ̄` the
    /// running mean, over the plots so far *including this one* and over the three
    /// aligned axes, of the innovation-based scale sample
    /// `(ν̄ᵢ² − p̄ᵢ⁻) / r̄₀ᵢ` (its expectation is `λ` whenever `P⁻` is right, whatever
    /// `R` the filter used before). So the plot is weighted with an `R` estimated
    /// before it is fused. `λ̄` is floored at 1 while it rests on fewer than `L`
    /// plots: under-estimating `R` at the start ruins the track, over-estimating it
    /// only slows the pull-in. After `L` plots, `R̂ = max(λ̄, 1) R₀` of the `L`-th
    /// plot, and the paper's post-fit moving average (window `L`) from there on.
    #[default]
    InnovationScale,
    /// The paper: `R̂ₖ = R̂ₖ₋₁ + (R_s − R̂ₖ₋₁)/L` from the first plot on, starting
    /// from the assumed (normal-case) `R̂₀`.
    Constant,
    /// A window that grows `1, 2, …, L`: the first plots replace the prior `R̂₀`
    /// instead of being averaged into it with weight `1/L`.
    Growing,
    /// The paper's window, but the first `steps` samples are innovation based,
    /// `ννᵀ − H P⁻ Hᵀ` (unbiased whatever `R` the filter used, as long as `P⁻` is
    /// right, which holds at the start), then post-fit samples as in the paper.
    /// (A growing window with single indefinite innovation samples collapses `R̂`
    /// onto the floor: measured, so the window stays at `L`.)
    Innovation {
        /// How many innovation-based samples.
        steps: usize,
    },
}

/// Parameters of the adaptive `R` estimator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdaptiveRConfig {
    window: usize,
    floor: f64,
    warmup: Warmup,
}

impl AdaptiveRConfig {
    /// Window `L ≥ 1` of the moving average (eq 31), variance floor (m², > 0)
    /// keeping `R̂` positive definite, and the warm-up rule.
    ///
    /// # Errors
    /// [`AdaptiveError::InvalidParameter`] for `L = 0` or a floor that is not
    /// finite and positive.
    pub fn new(window: usize, floor: f64, warmup: Warmup) -> Result<Self, AdaptiveError> {
        if window == 0 {
            return Err(AdaptiveError::InvalidParameter {
                what: "moving-average window L",
                value: 0.0,
                reason: "must be at least 1",
            });
        }
        Ok(Self {
            window,
            floor: positive(floor, "R floor")?,
            warmup,
        })
    }

    /// The window `L`.
    #[must_use]
    pub fn window(&self) -> usize {
        self.window
    }

    /// The variance floor (m²).
    #[must_use]
    pub fn floor(&self) -> f64 {
        self.floor
    }

    /// The warm-up rule.
    #[must_use]
    pub fn warmup(&self) -> Warmup {
        self.warmup
    }

    /// The averaging weight `1/Lₖ` for the `count`-th sample (0-based).
    fn weight(&self, count: usize) -> f64 {
        let l = match self.warmup {
            Warmup::Constant | Warmup::Innovation { .. } | Warmup::InnovationScale => self.window,
            Warmup::Growing => (count + 1).min(self.window),
        };
        1.0 / l as f64
    }
}

/// One post-fit sample of `R` (eq 28 with the sign corrected):
/// `R_s = ε εᵀ + H P⁺ Hᵀ`, `ε = z − H x⁺`.
///
/// For a filter that uses the true `R`, `ε = R S⁻¹ ν`, so
/// `E[εεᵀ] = R S⁻¹ R = R − H P⁺ Hᵀ` and `E[R_s] = R`; the printed minus sign
/// would give `R − 2 H P⁺ Hᵀ` (biased low, possibly indefinite).
///
/// # References
/// Kim & Hwang (2013), seed 003, eqs (28)–(30); SPEC section 003.
#[must_use]
pub fn post_fit_sample<const M: usize>(residual: &Vector<M>, hph: &Matrix<M, M>) -> Matrix<M, M> {
    residual * residual.transpose() + hph
}

/// The running estimate `R̂` of the measurement-noise covariance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct REstimate<const M: usize> {
    r_hat: Matrix<M, M>,
    count: usize,
    /// Sum of the start-up scale samples ([`Warmup::InnovationScale`]).
    scale_sum: f64,
}

impl<const M: usize> REstimate<M> {
    /// Starts from the assumed covariance `r0`.
    ///
    /// # Errors
    /// [`AdaptiveError::Math`] when `r0` is non-finite, asymmetric or not positive definite.
    pub fn new(r0: Matrix<M, M>) -> Result<Self, AdaptiveError> {
        SpdFactor::new(&r0, "initial R estimate")?;
        Ok(Self {
            r_hat: r0,
            count: 0,
            scale_sum: 0.0,
        })
    }

    /// The current `R̂`.
    #[must_use]
    pub fn r_hat(&self) -> &Matrix<M, M> {
        &self.r_hat
    }

    /// How many samples have been averaged in.
    #[must_use]
    pub fn count(&self) -> usize {
        self.count
    }

    /// Averages one sample in (eq 31), symmetrises (eq 32, corrected to
    /// `(R + Rᵀ)/2`) and floors: if `R̂ − floor·I` is not positive definite,
    /// the off-diagonal terms are dropped and each variance raised to at least the floor.
    ///
    /// # Errors
    /// [`AdaptiveError::NonFinite`] for a non-finite sample. `self` is untouched.
    pub fn update(
        &self,
        config: &AdaptiveRConfig,
        sample: &Matrix<M, M>,
    ) -> Result<Self, AdaptiveError> {
        if let Some(v) = sample.iter().copied().find(|v| !v.is_finite()) {
            return Err(AdaptiveError::NonFinite {
                what: "R sample",
                value: v,
            });
        }
        let w = config.weight(self.count);
        let rf = self.r_hat + (sample - self.r_hat) * w;
        let r = floor_matrix(&symmetrize(&rf), config.floor);
        Ok(Self {
            r_hat: r,
            count: self.count.saturating_add(1),
            scale_sum: self.scale_sum,
        })
    }
}

/// Keeps `r ≥ floor·I`: unchanged when `r − floor·I` is positive definite,
/// otherwise its diagonal with each entry at least `floor`.
fn floor_matrix<const M: usize>(r: &Matrix<M, M>, floor: f64) -> Matrix<M, M> {
    let shifted = r - Matrix::<M, M>::identity() * floor;
    if SpdFactor::new_symmetric(&shifted, "R estimate").is_ok() {
        return *r;
    }
    let mut out = Matrix::<M, M>::zeros();
    for i in 0..M {
        out[(i, i)] = r[(i, i)].max(floor);
    }
    out
}

/// The state of the adaptive decoupled filter: the track estimate and `R̂` (Cartesian).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdaptiveState {
    /// The decoupled track estimate.
    pub estimate: DecoupledEstimate,
    /// The running Cartesian measurement-noise estimate.
    pub r: REstimate<3>,
}

/// What one adaptive update produced besides the new state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdaptiveUpdate {
    /// The decoupled update's innovation data (computed with `R̂ₖ₋₁`).
    pub innovation: DecoupledUpdate,
    /// The `R̄` used for the gain: `diag(Dᵀ R̂ₖ₋₁ D)`, floored.
    pub aligned_r: Vector<3>,
    /// The post-fit residual `ε = z − H x⁺`.
    pub post_fit_residual: Vector<3>,
    /// The sample averaged in this step; during the start-up of
    /// [`Warmup::InnovationScale`], the innovation sample `D diag(ν̄ᵢ² − p̄ᵢ⁻) Dᵀ` whose
    /// scale entered `λ̄`.
    pub sample: Matrix<3, 3>,
}

/// The adaptive decoupled Kalman filter (ADKF): the decoupled filter whose `R`
/// is the running post-fit estimate `R̂` (eqs 28–32), rotated into each plot's
/// aligned frame (`R̄ = diag(Dᵀ R̂ D)`, the decoupled filter keeps the diagonal).
///
/// # References
/// Kim & Hwang (2013), seed 003, eqs (25), (28)–(32), with the sign of eq (28)
/// and eq (32) corrected (SPEC section 003).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdaptiveDecoupledFilter {
    inner: DecoupledFilter,
    config: AdaptiveRConfig,
}

impl AdaptiveDecoupledFilter {
    /// Wraps a decoupled filter with the adaptive `R` estimator.
    #[must_use]
    pub fn new(inner: DecoupledFilter, config: AdaptiveRConfig) -> Self {
        Self { inner, config }
    }

    /// The estimator configuration.
    #[must_use]
    pub fn config(&self) -> &AdaptiveRConfig {
        &self.config
    }

    /// Predicts the track over `dt` (`R̂` is carried unchanged).
    ///
    /// # Errors
    /// As [`DecoupledFilter::predict`].
    pub fn predict(&self, prior: &AdaptiveState, dt: f64) -> Result<AdaptiveState, AdaptiveError> {
        Ok(AdaptiveState {
            estimate: self.inner.predict(&prior.estimate, dt)?,
            r: prior.r,
        })
    }

    /// Updates with a converted plot (its own aligned variances are ignored: the
    /// filter uses `R̂`), then averages the post-fit sample into `R̂`.
    ///
    /// # Errors
    /// As [`DecoupledFilter::update`], and [`AdaptiveError::NonFinite`] for a
    /// non-finite sample. `predicted` is untouched.
    #[allow(non_snake_case)]
    pub fn update(
        &self,
        predicted: &AdaptiveState,
        plot: &ConvertedPlot,
    ) -> Result<(AdaptiveState, AdaptiveUpdate), AdaptiveError> {
        if self.config.warmup == Warmup::InnovationScale && predicted.r.count() < self.config.window
        {
            return self.startup_update(predicted, plot);
        }
        let D = plot.frame();
        let r_aligned = D.transpose() * predicted.r.r_hat() * D;
        let aligned_r = Vector::<3>::new(
            r_aligned[(0, 0)].max(self.config.floor),
            r_aligned[(1, 1)].max(self.config.floor),
            r_aligned[(2, 2)].max(self.config.floor),
        );
        let used = plot.with_aligned_variances(aligned_r)?;
        let (post, innovation) = self.inner.update(&predicted.estimate, &used)?;
        let post_fit_residual = plot.position() - post.position();
        let innovation_phase = match self.config.warmup {
            Warmup::Innovation { steps } => predicted.r.count() < steps,
            Warmup::Constant | Warmup::Growing | Warmup::InnovationScale => false,
        };
        let sample = if innovation_phase {
            // ννᵀ − H P⁻ Hᵀ with H P⁻ Hᵀ = D diag(s̄ − r̄) Dᵀ.
            let hpm = D
                * Matrix::<3, 3>::from_diagonal(&(innovation.aligned_s - aligned_r))
                * D.transpose();
            innovation.residual * innovation.residual.transpose() - hpm
        } else {
            post_fit_sample(&post_fit_residual, &post.position_cov())
        };
        let r = predicted.r.update(&self.config, &sample)?;
        Ok((
            AdaptiveState { estimate: post, r },
            AdaptiveUpdate {
                innovation,
                aligned_r,
                post_fit_residual,
                sample,
            },
        ))
    }

    /// One of the first `L` updates of [`Warmup::InnovationScale`]: scale the plot's
    /// assumed `R` by the running innovation-based `λ̄` (this plot included) before fusing it.
    #[allow(non_snake_case)]
    fn startup_update(
        &self,
        predicted: &AdaptiveState,
        plot: &ConvertedPlot,
    ) -> Result<(AdaptiveState, AdaptiveUpdate), AdaptiveError> {
        let D = plot.frame();
        let p_bar = self
            .inner
            .aligned_position_variances(&predicted.estimate, plot);
        let nu_bar = D.transpose() * (plot.position() - predicted.estimate.position());
        let r0 = plot.aligned_variances();
        // E[ν̄ᵢ²] = p̄ᵢ⁻ + λ r̄₀ᵢ when P⁻ is right: one unbiased sample of λ per axis.
        let sample_scale = (0..3)
            .map(|i| (nu_bar[i] * nu_bar[i] - p_bar[i]) / r0[i])
            .sum::<f64>()
            / 3.0;
        if !sample_scale.is_finite() {
            return Err(AdaptiveError::NonFinite {
                what: "start-up scale sample of R",
                value: sample_scale,
            });
        }
        let count = predicted.r.count().saturating_add(1);
        let scale_sum = predicted.r.scale_sum + sample_scale;
        let scale = (scale_sum / count as f64).max(1.0);
        let aligned_r = r0 * scale;
        let used = plot.with_aligned_variances(aligned_r)?;
        let (post, innovation) = self.inner.update(&predicted.estimate, &used)?;
        let post_fit_residual = plot.position() - post.position();
        let r_hat = used.cartesian_noise();
        SpdFactor::new_symmetric(&symmetrize(&r_hat), "start-up R estimate")?;
        let r = REstimate {
            r_hat: symmetrize(&r_hat),
            count,
            scale_sum,
        };
        let sample =
            D * Matrix::<3, 3>::from_diagonal(&Vector::<3>::from_fn(|i, _| {
                nu_bar[i] * nu_bar[i] - p_bar[i]
            })) * D.transpose();
        Ok((
            AdaptiveState { estimate: post, r },
            AdaptiveUpdate {
                innovation,
                aligned_r,
                post_fit_residual,
                sample,
            },
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moving_average_and_growing_window() {
        // Eq (31) with L = 4 from R̂ = 4I and a constant sample 8I: 4 + (8 − 4)/4 = 5.
        let c = AdaptiveRConfig::new(4, 1e-6, Warmup::Constant).unwrap();
        let r = REstimate::<2>::new(Matrix::<2, 2>::identity() * 4.0).unwrap();
        let r1 = r.update(&c, &(Matrix::<2, 2>::identity() * 8.0)).unwrap();
        assert!((r1.r_hat()[(0, 0)] - 5.0).abs() < 1e-12);
        // Growing: the first sample replaces the prior entirely (weight 1/1).
        let g = AdaptiveRConfig::new(4, 1e-6, Warmup::Growing).unwrap();
        let r2 = r.update(&g, &(Matrix::<2, 2>::identity() * 8.0)).unwrap();
        assert!((r2.r_hat()[(0, 0)] - 8.0).abs() < 1e-12);
        assert_eq!(r2.count(), 1);
    }

    #[test]
    fn floor_keeps_r_positive_definite() {
        let c = AdaptiveRConfig::new(1, 0.5, Warmup::Constant).unwrap();
        let r = REstimate::<2>::new(Matrix::<2, 2>::identity()).unwrap();
        // An indefinite sample (what the printed sign of eq 28 can produce).
        let bad = Matrix::<2, 2>::new(1.0, 2.0, 2.0, -3.0);
        let r1 = r.update(&c, &bad).unwrap();
        assert!((r1.r_hat() - Matrix::<2, 2>::new(1.0, 0.0, 0.0, 0.5)).amax() < 1e-15);
        assert!(SpdFactor::new(r1.r_hat(), "r").is_ok());
    }

    #[test]
    fn bad_input_is_rejected_and_state_kept() {
        assert!(AdaptiveRConfig::new(0, 1.0, Warmup::Constant).is_err());
        assert!(AdaptiveRConfig::new(5, -1.0, Warmup::Constant).is_err());
        assert!(AdaptiveRConfig::new(5, f64::NAN, Warmup::Constant).is_err());
        assert!(REstimate::<2>::new(Matrix::<2, 2>::new(1.0, 2.0, 2.0, 1.0)).is_err());
        let c = AdaptiveRConfig::new(5, 1e-3, Warmup::Constant).unwrap();
        let r = REstimate::<2>::new(Matrix::<2, 2>::identity()).unwrap();
        let before = r;
        assert!(matches!(
            r.update(&c, &Matrix::<2, 2>::new(f64::NAN, 0.0, 0.0, 1.0)),
            Err(AdaptiveError::NonFinite {
                what: "R sample",
                ..
            })
        ));
        assert_eq!(r, before);
    }
}

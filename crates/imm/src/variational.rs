//! A variational-Bayes measurement-noise estimator around one IMM (beyond seed 000).

use argus_core_math::Matrix;
use argus_filters::GaussianFilter;
use argus_sensors::PolarMeasurement;

use crate::error::{check_forgetting, check_positive};
use crate::{Imm, ImmError, ImmEstimate, ImmUpdate, NoiseVariances, PlotConversion};

/// The state of a [`VariationalNoiseImm`]: the IMM estimate and inverse-gamma statistics
/// `(α, β_r, β_θ)` of the range and azimuth variances, `σ̂² = β / α`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VariationalEstimate<const N: usize, const R: usize> {
    imm: ImmEstimate<N, R>,
    alpha: f64,
    beta: [f64; 2],
}

impl<const N: usize, const R: usize> VariationalEstimate<N, R> {
    /// A start from `imm`, the initial guess `initial` of the variances and a prior weight of
    /// `prior_count` pseudo-plots (`α₀ = prior_count / 2`, `β₀ = α₀ σ²`).
    ///
    /// # Errors
    /// [`ImmError::InvalidParameter`] unless `prior_count` is finite and positive.
    pub fn new(
        imm: ImmEstimate<N, R>,
        initial: NoiseVariances,
        prior_count: f64,
    ) -> Result<Self, ImmError> {
        check_positive("prior count", prior_count)?;
        let alpha = 0.5 * prior_count;
        Ok(Self {
            imm,
            alpha,
            beta: [alpha * initial.range(), alpha * initial.azimuth()],
        })
    }

    /// The IMM estimate.
    #[must_use]
    pub fn imm(&self) -> &ImmEstimate<N, R> {
        &self.imm
    }

    /// The current variance estimates `β / α`.
    ///
    /// # Errors
    /// [`ImmError::InvalidParameter`] if they are not finite and positive (not reachable from
    /// a validated start).
    pub fn variances(&self) -> Result<NoiseVariances, ImmError> {
        NoiseVariances::new(self.beta[0] / self.alpha, self.beta[1] / self.alpha)
    }
}

/// An IMM whose range and azimuth noise variances are estimated separately by a
/// variational-Bayes (inverse-gamma) recursion on the polar post-fit residuals.
///
/// Per plot, with the variances `σ̂² = β/α` of the previous step:
/// 1. one IMM cycle with the plot converted under `σ̂²` (the same conversion as the multi-IMM);
/// 2. from the combined posterior `x⁺, P⁺`: the polar residual `ε = (r − |p̂|, θ − ∠p̂)` and
///    `J P⁺ Jᵀ`, `J = ∂(r, θ)/∂(x, y)` at `p̂`;
/// 3. `α ← ρ α + ½`, `β_i ← ρ β_i + ½ (ε_i² + (J P⁺ Jᵀ)_ii)` for range and azimuth.
///
/// `E[ε εᵀ] = R − J P⁺ Jᵀ` for a consistent filter (seed 003 eq (28), corrected sign), so
/// the true `R` is a fixed point, independent of any grid; `ρ ∈ (0, 1]` forgets old plots
/// (window ≈ `1/(1−ρ)` plots). It is the one-pass variant of the VB adaptive Kalman filter:
/// one IMM of `R` filters per plot, against `K · R` for the multi-IMM.
///
/// # References
/// S. Särkkä & A. Nummenmaa, "Recursive noise adaptive Kalman filtering by variational
/// Bayesian approximations", IEEE TAC 54(3), 2009 (eqs for `α`, `β` with forgetting `ρ`);
/// Bar-Shalom, Li & Kirubarajan (2001) §10.4 for the polar Jacobian.
#[derive(Debug, Clone, PartialEq)]
pub struct VariationalNoiseImm<F, const N: usize, const R: usize> {
    imm: Imm<F, N, R>,
    forgetting: f64,
    iterations: usize,
}

impl<F: GaussianFilter<N>, const N: usize, const R: usize> VariationalNoiseImm<F, N, R> {
    /// Around `imm`, with forgetting factor `forgetting` (`ρ`, 1 = none).
    ///
    /// # Errors
    /// [`ImmError::InvalidParameter`] unless `forgetting ∈ (0, 1]`.
    pub fn new(imm: Imm<F, N, R>, forgetting: f64) -> Result<Self, ImmError> {
        check_forgetting(forgetting)?;
        Ok(Self {
            imm,
            forgetting,
            iterations: 1,
        })
    }

    /// The number of variational iterations per plot (default 1): each re-runs the IMM
    /// update (not the prediction) with the variances of the previous iteration, as in
    /// Särkkä & Nummenmaa's VB-AKF. Cost: one prediction and `iterations` updates per mode.
    ///
    /// # Errors
    /// [`ImmError::InvalidParameter`] for 0.
    pub fn with_iterations(mut self, iterations: usize) -> Result<Self, ImmError> {
        if iterations == 0 {
            return Err(ImmError::InvalidParameter {
                what: "variational iterations",
                value: 0.0,
                reason: "at least one",
            });
        }
        self.iterations = iterations;
        Ok(self)
    }

    /// The IMM.
    #[must_use]
    pub fn imm(&self) -> &Imm<F, N, R> {
        &self.imm
    }

    /// One step with `plot` after `dt` seconds; returns the new estimate and the IMM update.
    ///
    /// # Errors
    /// As [`Imm::step`] and the conversion; [`ImmError::InvalidParameter`] when the estimated
    /// position is at the radar (the polar residual is undefined). `est` is never modified.
    #[allow(non_snake_case)]
    pub fn step<const M: usize, C: PlotConversion<N, M>>(
        &self,
        est: &VariationalEstimate<N, R>,
        dt: f64,
        plot: &PolarMeasurement,
        conversion: &C,
    ) -> Result<(VariationalEstimate<N, R>, ImmUpdate<N, R>), ImmError> {
        let rho = self.forgetting;
        let alpha = rho * est.alpha + 0.5;
        let mut var = est.variances()?;
        let pred = self.imm.predict(&est.imm, dt)?;
        let mut beta = est.beta;
        let mut upd = None;
        for _ in 0..self.iterations {
            let (meas, z) = conversion.convert(plot, &var)?;
            let u = self.imm.update(&pred, &meas, &z)?;
            let post = u.estimate.combined()?;
            let p = conversion.position(post.mean());
            let rng = p.norm();
            if !(rng.is_finite() && rng > 0.0) {
                return Err(ImmError::InvalidParameter {
                    what: "estimated range",
                    value: rng,
                    reason: "the polar residual needs a target away from the radar",
                });
            }
            let (c, s) = (p[0] / rng, p[1] / rng);
            let J = Matrix::<2, 2>::new(c, s, -s / rng, c / rng);
            let JPJ = J * conversion.position_cov(post.cov()) * J.transpose();
            let e_r = plot.range() - rng;
            let e_t = argus_sensors::wrap_angle(plot.azimuth() - p[1].atan2(p[0]));
            beta = [
                rho * est.beta[0] + 0.5 * (e_r * e_r + JPJ[(0, 0)]),
                rho * est.beta[1] + 0.5 * (e_t * e_t + JPJ[(1, 1)]),
            ];
            var = NoiseVariances::new(beta[0] / alpha, beta[1] / alpha)?;
            upd = Some(u);
        }
        let upd = upd.ok_or(ImmError::Empty {
            what: "variational iterations",
        })?;
        let next = VariationalEstimate {
            imm: upd.estimate,
            alpha,
            beta,
        };
        next.variances()?;
        Ok((next, upd))
    }
}

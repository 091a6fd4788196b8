//! The off-line covariance recursion of the NN and PDA filters in clutter.

use argus_core_math::{Matrix, SpdFactor, check_finite_matrix, symmetrize, unit_ball_volume};

use super::{hyca_factors, nn_moments, pda_irf};
use crate::error::{AssociationError, check_non_negative, check_prob_open_closed};
use crate::gate::Gate;

/// Which filter's expected covariance to predict.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PredictedFilter {
    /// The NN filter's HYCA recursion (factor `c_T − c_F`); the NN filter is assumed to
    /// use the recursion's own gain `W̄` and gate with `S̄` (Li & Bar-Shalom 1996; seed
    /// 002 Fig. 2).
    NearestNeighbour,
    /// The plain NN filter: Kalman gain `K = P H ᵀS⁻¹` and gate `S` from its own
    /// covariance `P`, which ignores clutter. HYCA in its general-gain form
    /// (Li & Bar-Shalom 1996's conditional averaging over `M₀`, `M_T`, `M_F`, derived
    /// for a gain other than the MSE-optimal one; see [`nn_moments`]):
    ///
    /// ```text
    /// P̄(k|k) = P̄⁻ − W̄ M_T Kᵀ − K M_T W̄ᵀ + K (M_T + C_F) Kᵀ,   W̄ = P̄⁻Hᵀ S̄⁻¹
    /// M_T = E[ν νᵀ 1{M_T}] = L E[uuᵀ1{M_T}] Lᵀ,   C_F = E[ν νᵀ 1{M_F}] = c_F S
    /// P(k|k)  = P⁻ − [1 − P(M₀)] K S Kᵀ   (the filter's own covariance, averaged)
    /// ```
    ///
    /// Under `M_T` the state error's part orthogonal to the target's innovation is
    /// independent of the event, so `E[x̃ νᵀ 1{M_T}] = W̄ M_T`; under `M_F` the nearest
    /// clutter plot's direction is uniform and independent of the target, so
    /// `E[x̃ νᵀ 1{M_F}] = 0`. With `K = W̄` and `S = S̄` this is
    /// [`PredictedFilter::NearestNeighbour`]. The filter's random covariance (it is not
    /// updated after a miss) is replaced by its expectation, and its gain by the gain of
    /// that expectation.
    NearestNeighbourKalmanGain,
    /// The PDA filter's information-reduction-factor recursion (factor `q₂`).
    Pda,
}

/// A linear-Gaussian system `x(k) = F x(k−1) + v`, `Cov v = Q`; `z = H x + w`,
/// `Cov w = R`, for the off-line recursions.
#[allow(non_snake_case)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearSystem<const N: usize, const M: usize> {
    F: Matrix<N, N>,
    Q: Matrix<N, N>,
    H: Matrix<M, N>,
    R: Matrix<M, M>,
}

impl<const N: usize, const M: usize> LinearSystem<N, M> {
    /// The system `(F, Q, H, R)`.
    ///
    /// # Errors
    /// [`AssociationError::Math`] when a matrix is non-finite, `Q` is not symmetric
    /// positive semi-definite (checked as `Q + εI` PD) or `R` is not positive definite.
    #[allow(non_snake_case)]
    pub fn new(
        F: Matrix<N, N>,
        Q: Matrix<N, N>,
        H: Matrix<M, N>,
        R: Matrix<M, M>,
    ) -> Result<Self, AssociationError> {
        check_finite_matrix(&F, "transition matrix F")?;
        check_finite_matrix(&Q, "process noise Q")?;
        check_finite_matrix(&H, "measurement matrix H")?;
        check_finite_matrix(&R, "measurement noise R")?;
        let scale = Q.abs().max().max(1e-300);
        SpdFactor::new(
            &(Q + Matrix::<N, N>::identity() * (scale * 1e-9)),
            "process noise Q",
        )?;
        SpdFactor::new(&R, "measurement noise R")?;
        Ok(Self { F, Q, H, R })
    }
}

/// One step of an off-line recursion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PredictionStep<const N: usize, const M: usize> {
    /// `P̄(k|k−1)`.
    pub predicted: Matrix<N, N>,
    /// `S̄(k)`.
    pub s: Matrix<M, M>,
    /// `W̄(k) = P̄(k|k−1) Hᵀ S̄⁻¹`.
    pub gain: Matrix<N, M>,
    /// Expected clutter plots in the gate `μ = λ V̄`.
    pub mu: f64,
    /// The information reduction factor (`c_T − c_F` or `q₂`); for
    /// [`PredictedFilter::NearestNeighbourKalmanGain`], whose update is not of that
    /// form, the probability `1 − P(M₀)` that the filter updates.
    pub factor: f64,
    /// The expected MSE `P̄(k|k)` (`P̄(k|k−1) − factor · W̄ S̄ W̄ᵀ` except for
    /// [`PredictedFilter::NearestNeighbourKalmanGain`]).
    pub posterior: Matrix<N, N>,
    /// The gain the filter uses: `W̄` except for
    /// [`PredictedFilter::NearestNeighbourKalmanGain`] (its Kalman gain `K`).
    pub filter_gain: Matrix<N, M>,
    /// The filter's own covariance after the step: `posterior` except for
    /// [`PredictedFilter::NearestNeighbourKalmanGain`].
    pub filter_posterior: Matrix<N, N>,
}

/// The outcome of iterating a recursion to steady state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SteadyState<const N: usize, const M: usize> {
    /// The recursion converged.
    Converged {
        /// The last step (its `posterior` is the steady state).
        step: PredictionStep<N, M>,
        /// Iterations used.
        iterations: usize,
    },
    /// The covariance grew without bound: the prediction says the track is lost (no
    /// finite steady-state error to report).
    Diverged {
        /// Iteration at which the trace exceeded the bound.
        iterations: usize,
        /// `tr P̄(k|k)` then.
        trace: f64,
    },
}

/// Off-line predictor of a clutter filter's expected error covariance from `P_D`, the
/// clutter density and the gate, without simulation.
///
/// # References
/// Li & Bar-Shalom (1996) (HYCA, NN); Kershaw & Evans (1996) (PDA); seed 002 §2.2–2.3.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PerformancePredictor<const N: usize, const M: usize> {
    system: LinearSystem<N, M>,
    gate: Gate,
    p_d: f64,
    density: f64,
    filter: PredictedFilter,
}

impl<const N: usize, const M: usize> PerformancePredictor<N, M> {
    /// The predictor of `filter` on `system` with gate `gate`, detection probability
    /// `p_d` and clutter density `density`.
    ///
    /// # Errors
    /// [`AssociationError::InvalidParameter`] for `P_D ∉ (0, 1]` or a negative density;
    /// [`AssociationError::DimensionMismatch`] for a gate of another dimension.
    pub fn new(
        system: LinearSystem<N, M>,
        gate: Gate,
        p_d: f64,
        density: f64,
        filter: PredictedFilter,
    ) -> Result<Self, AssociationError> {
        check_prob_open_closed(p_d, "detection probability")?;
        check_non_negative(density, "clutter density")?;
        gate.check_dim::<M>()?;
        Ok(Self {
            system,
            gate,
            p_d,
            density,
            filter,
        })
    }

    /// One step from `P̄(k−1|k−1) = posterior`, the filter's own covariance being the
    /// same matrix.
    ///
    /// # Errors
    /// [`AssociationError::Math`] for a non-finite or non-PD `S̄`.
    pub fn step(&self, posterior: &Matrix<N, N>) -> Result<PredictionStep<N, M>, AssociationError> {
        self.step_with_filter(posterior, posterior)
    }

    /// One step from the expected MSE `P̄(k−1|k−1) = posterior` and the filter's own
    /// covariance `filter_posterior` (used only by
    /// [`PredictedFilter::NearestNeighbourKalmanGain`]).
    ///
    /// # Errors
    /// [`AssociationError::Math`] for a non-finite or non-PD `S̄` or `S`, or (for
    /// [`PredictedFilter::NearestNeighbourKalmanGain`]) a `filter_posterior` that is
    /// not finite, symmetric and positive definite.
    #[allow(non_snake_case)]
    pub fn step_with_filter(
        &self,
        posterior: &Matrix<N, N>,
        filter_posterior: &Matrix<N, N>,
    ) -> Result<PredictionStep<N, M>, AssociationError> {
        let sys = &self.system;
        let P_pred = symmetrize(&(sys.F * posterior * sys.F.transpose() + sys.Q));
        check_finite_matrix(&P_pred, "predicted MSE P̄(k|k−1)")?;
        let S = symmetrize(&(sys.H * P_pred * sys.H.transpose() + sys.R));
        let Sf = SpdFactor::new_symmetric(&S, "predicted innovation covariance S̄")?;
        let W = Sf.solve_matrix(&(sys.H * P_pred)).transpose();
        let sqrt_det = (0.5 * Sf.log_det()).exp();
        if self.filter == PredictedFilter::NearestNeighbourKalmanGain {
            return self.step_kalman_gain(P_pred, S, &Sf, W, filter_posterior);
        }
        let mu = self.density * self.gate.volume_from_sqrt_det(sqrt_det);
        let factor = match self.filter {
            PredictedFilter::Pda => pda_irf(&self.gate, mu, self.p_d)?,
            _ => {
                let beta = self.density * unit_ball_volume(M) * sqrt_det;
                let (c_t, c_f) = hyca_factors(&self.gate, beta, self.p_d)?;
                c_t - c_f
            }
        };
        let P_post = symmetrize(&(P_pred - W * S * W.transpose() * factor));
        check_finite_matrix(&P_post, "predicted MSE P̄(k|k)")?;
        Ok(PredictionStep {
            predicted: P_pred,
            s: S,
            gain: W,
            mu,
            factor,
            posterior: P_post,
            filter_gain: W,
            filter_posterior: P_post,
        })
    }

    /// The update of [`PredictedFilter::NearestNeighbourKalmanGain`].
    #[allow(non_snake_case)]
    fn step_kalman_gain(
        &self,
        P_pred: Matrix<N, N>,
        S_bar: Matrix<M, M>,
        S_bar_f: &SpdFactor<M>,
        W: Matrix<N, M>,
        filter_posterior: &Matrix<N, N>,
    ) -> Result<PredictionStep<N, M>, AssociationError> {
        let sys = &self.system;
        SpdFactor::new(filter_posterior, "filter covariance P(k−1|k−1)")?;
        let Pf_pred = symmetrize(&(sys.F * filter_posterior * sys.F.transpose() + sys.Q));
        let S = symmetrize(&(sys.H * Pf_pred * sys.H.transpose() + sys.R));
        let Sfac = SpdFactor::new_symmetric(&S, "filter's innovation covariance S")?;
        let K = Sfac.solve_matrix(&(sys.H * Pf_pred)).transpose();
        let L = Sfac.l();
        let sqrt_det = (0.5 * Sfac.log_det()).exp();
        let beta = self.density * unit_ball_volume(M) * sqrt_det;
        // Σ = L⁻¹ S̄ L⁻ᵀ: Σ⁻¹ = Lᵀ S̄⁻¹ L, |Σ| = |S̄| / |S|.
        let sigma_inv = symmetrize(&(L.transpose() * S_bar_f.solve_matrix(&L)));
        let sqrt_det_sigma = (0.5 * (S_bar_f.log_det() - Sfac.log_det())).exp();
        let m = nn_moments(&self.gate, beta, self.p_d, &sigma_inv, sqrt_det_sigma)?;
        let M_T = L * m.target * L.transpose();
        let C_F = S * m.clutter;
        let cross = W * M_T * K.transpose();
        let P_post =
            symmetrize(&(P_pred - cross - cross.transpose() + K * (M_T + C_F) * K.transpose()));
        check_finite_matrix(&P_post, "predicted MSE P̄(k|k)")?;
        let update = 1.0 - m.none;
        let Pf_post = symmetrize(&(Pf_pred - K * S * K.transpose() * update));
        Ok(PredictionStep {
            predicted: P_pred,
            s: S_bar,
            gain: W,
            mu: self.density * self.gate.volume_from_sqrt_det(sqrt_det),
            factor: update,
            posterior: P_post,
            filter_gain: K,
            filter_posterior: Pf_post,
        })
    }

    /// Iterates from `initial` (both the expected MSE and the filter's own covariance)
    /// until the relative change of both is below `tol` (at most `max_iter` steps). Reports [`SteadyState::Diverged`] when the trace
    /// exceeds `10⁶` times the larger of the initial trace and `tr Q`'s.
    ///
    /// # Errors
    /// As [`Self::step`]; [`AssociationError::InvalidParameter`] for a non-positive `tol`
    /// or a zero `max_iter`; a run that neither converges nor diverges in `max_iter`
    /// steps is reported as [`AssociationError::InvalidParameter`] on `max_iter`.
    pub fn steady_state(
        &self,
        initial: &Matrix<N, N>,
        tol: f64,
        max_iter: usize,
    ) -> Result<SteadyState<N, M>, AssociationError> {
        if !(tol.is_finite() && tol > 0.0) {
            return Err(AssociationError::InvalidParameter {
                what: "tolerance",
                value: tol,
                reason: "must be finite and positive",
            });
        }
        check_finite_matrix(initial, "initial MSE")?;
        let bound = 1e6
            * initial
                .trace()
                .max(self.system.Q.trace())
                .max(self.system.R.trace());
        let (mut p, mut pf) = (*initial, *initial);
        for it in 1..=max_iter {
            let step = self.step_with_filter(&p, &pf)?;
            let trace = step.posterior.trace();
            if trace.is_nan() || trace > bound {
                return Ok(SteadyState::Diverged {
                    iterations: it,
                    trace,
                });
            }
            let change = ((step.posterior - p).abs().max() / step.posterior.abs().max())
                .max((step.filter_posterior - pf).abs().max() / step.filter_posterior.abs().max());
            p = step.posterior;
            pf = step.filter_posterior;
            if change < tol {
                return Ok(SteadyState::Converged {
                    step,
                    iterations: it,
                });
            }
        }
        Err(AssociationError::InvalidParameter {
            what: "max_iter",
            value: max_iter as f64,
            reason: "the recursion neither converged nor diverged within this many steps",
        })
    }
}

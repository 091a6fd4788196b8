//! The adaptive filter of seed 001: any Kalman-type filter in normal running, a
//! windowed GLRT watching its innovations, a correction on detection, and for a
//! persistent input the estimate `B û` carried in the prediction (optionally refined
//! by the MRAS input estimator) until the GLRT detects its removal.
//!
//! # One step
//! 1. `Φ = ∂f/∂x` and the input gain `Γ` over `dt` at the prior mean ([`InputLinearization`]).
//! 2. Predict with the inner filter; add `Γ û` when an input is carried (eq 4-3).
//! 3. Update with the plot; the innovation `r`, `H`, `K`, `S` feed the GLRT (and MRAS).
//! 4. On a detection `(θ̂, û, C)`: correct `x += [D − F] û` (eq 3-11), `P += [D − F] C⁻¹ [D − F]ᵀ`
//!    (eq 3-12), reset the window. For a persistent input the carried input becomes
//!    `û_old + û`; when that total is no longer significant (`ûᵀ_tot C û_tot < η`) the
//!    input is declared removed, the correction uses `Δu = −û_old` instead, and the
//!    filter is back to the plain one.
//! 5. With [`Compensation::GlrtMras`], after a persistent detection the remaining input
//!    error is estimated recursively ([`crate::mras::Mras`]); the output is
//!    `x̄ + [D − F] δû`, `P̄ + [D − F] L [D − F]ᵀ`, and the GLRT sees the innovation minus
//!    the part `G δû` the estimator already explains. At the next detection `δû` is folded
//!    into the state and the carried input.
//!
//! A failed step returns an error and leaves the [`ManeuverState`] unchanged.
//!
//! # References
//! - Lee & Kim (1987), seed 001, sections 3.2 and 4, eqs 3-11, 3-12, 4-3 to 4-7.
//! - Willsky & Jones (1976), GLR detection of jumps in linear systems.

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{GaussianFilter, Innovation, check_dt};
use argus_motion_models::MotionModel;
use argus_sensors::MeasurementModel;

use crate::error::AdaptiveError;
use crate::glrt::{Detection, FailureKind, Glrt, GlrtConfig, StepLinearization};
use crate::mras::Mras;

/// The linearisation the detector needs from the motion model: the transition
/// `Φ(m, m−1)` and the gain `Γ` of a constant input held over the interval.
pub trait InputLinearization<const N: usize, const P: usize> {
    /// `Φ = ∂f/∂x` at `x` over `dt`.
    fn transition(&self, x: &Vector<N>, dt: f64) -> Matrix<N, N>;
    /// `Γ = ∫₀^dt Φ(dt − s) B ds` for the continuous input matrix `B`.
    fn input_gain(&self, x: &Vector<N>, dt: f64) -> Matrix<N, P>;
}

/// Any [`MotionModel`] with a continuous-time input matrix `B` (`ẋ = a(x) + B u`).
/// `Φ` is the model's Jacobian; `Γ = ∫₀^dt Φ(s) B ds` by Simpson's rule on
/// `Φ(0) = I`, `Φ(dt/2)`, `Φ(dt)` (exact for the constant-velocity model, whose `Φ(s)`
/// is affine in `s`; second-order accurate otherwise).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModelInput<Mo, const N: usize, const P: usize> {
    model: Mo,
    b: Matrix<N, P>,
}

impl<Mo, const N: usize, const P: usize> ModelInput<Mo, N, P> {
    /// Wraps `model` with the input matrix `b`.
    ///
    /// # Errors
    /// [`AdaptiveError::Math`] when `b` is not finite.
    pub fn new(model: Mo, b: Matrix<N, P>) -> Result<Self, AdaptiveError> {
        argus_core_math::check_finite_matrix(&b, "input matrix B")?;
        Ok(Self { model, b })
    }

    /// The wrapped model.
    #[must_use]
    pub fn model(&self) -> &Mo {
        &self.model
    }
}

impl<Mo: MotionModel<N>, const N: usize, const P: usize> InputLinearization<N, P>
    for ModelInput<Mo, N, P>
{
    fn transition(&self, x: &Vector<N>, dt: f64) -> Matrix<N, N> {
        self.model.jacobian(x, dt)
    }

    fn input_gain(&self, x: &Vector<N>, dt: f64) -> Matrix<N, P> {
        let half = self.model.jacobian(x, 0.5 * dt);
        let full = self.model.jacobian(x, dt);
        (self.b + half * self.b * 4.0 + full * self.b) * (dt / 6.0)
    }
}

/// How the adaptive filter compensates a detected maneuver.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Compensation {
    /// GLRT correction only (seed 001 section 3.2).
    #[default]
    Glrt,
    /// GLRT correction, then recursive (MRAS) estimation of the persistent input
    /// (section 4). Same as [`Compensation::Glrt`] for [`FailureKind::Jump`].
    GlrtMras,
}

/// The running state of one adaptive track: the filter's estimate, the GLRT window,
/// the carried input and the MRAS estimator.
#[derive(Debug, Clone)]
pub struct ManeuverState<const N: usize, const M: usize, const P: usize> {
    filter: Gaussian<N>,
    output: Gaussian<N>,
    glrt: Glrt<N, M, P>,
    input: Option<Vector<P>>,
    mras: Option<Mras<N, P>>,
    steps: u64,
}

impl<const N: usize, const M: usize, const P: usize> ManeuverState<N, M, P> {
    /// A track starting from `initial` with an empty GLRT window (allocated here).
    #[must_use]
    pub fn new(initial: Gaussian<N>, config: GlrtConfig) -> Self {
        Self {
            filter: initial,
            output: initial,
            glrt: Glrt::new(config),
            input: None,
            mras: None,
            steps: 0,
        }
    }

    /// The same track with a prior information `Λ₀` on the input for the detector's
    /// estimate (see [`Glrt::with_input_prior`]).
    ///
    /// # Errors
    /// As [`Glrt::with_input_prior`].
    pub fn with_input_prior(mut self, info: Matrix<P, P>) -> Result<Self, AdaptiveError> {
        self.glrt = self.glrt.with_input_prior(info)?;
        Ok(self)
    }

    /// The same track with the detector's threshold replaced by `eta` (window, input and
    /// filter kept): `f64::MAX` turns detection off, e.g. to follow the statistic of a
    /// copy of a running track on noise-free plots.
    ///
    /// # Errors
    /// As [`GlrtConfig::new`] for `eta`.
    pub fn with_threshold(mut self, eta: f64) -> Result<Self, AdaptiveError> {
        self.glrt = self.glrt.with_threshold(eta)?;
        Ok(self)
    }

    /// The compensated estimate (the filter's own plus the MRAS term, if running).
    #[must_use]
    pub fn estimate(&self) -> &Gaussian<N> {
        &self.output
    }

    /// The inner filter's estimate `x̄`, `P̄` (GLRT corrections included, MRAS term not).
    #[must_use]
    pub fn filter_estimate(&self) -> &Gaussian<N> {
        &self.filter
    }

    /// The input estimate in use: the carried input plus the MRAS refinement. `None`
    /// in normal running (no persistent input believed on).
    #[must_use]
    pub fn input_estimate(&self) -> Option<Vector<P>> {
        self.input.map(|u| {
            u + self
                .mras
                .and_then(|m| m.estimate())
                .map_or(Vector::zeros(), |(du, _)| du)
        })
    }

    /// Steps processed.
    #[must_use]
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// The GLRT window.
    #[must_use]
    pub fn glrt(&self) -> &Glrt<N, M, P> {
        &self.glrt
    }
}

/// What one adaptive step did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ManeuverReport<const N: usize, const M: usize, const P: usize> {
    /// The inner filter's innovation of the plot.
    pub innovation: Innovation<M>,
    /// The largest GLRT statistic and its onset age, if any hypothesis was testable.
    pub max_statistic: Option<(f64, usize)>,
    /// The detection applied at this step, if any.
    pub detection: Option<Detection<N, P>>,
    /// Whether this step's detection was judged to be the removal of the carried input.
    pub input_removed: bool,
}

/// The adaptive filter: inner filter `F`, linearisation `L`, GLRT configuration.
#[derive(Debug, Clone)]
pub struct ManeuverFilter<F, L> {
    filter: F,
    lin: L,
    compensation: Compensation,
}

impl<F, L> ManeuverFilter<F, L> {
    /// Builds the adaptive filter around `filter`.
    #[must_use]
    pub fn new(filter: F, lin: L, compensation: Compensation) -> Self {
        Self {
            filter,
            lin,
            compensation,
        }
    }

    /// The inner filter.
    #[must_use]
    pub fn inner(&self) -> &F {
        &self.filter
    }

    /// The compensation mode.
    #[must_use]
    pub fn compensation(&self) -> Compensation {
        self.compensation
    }

    /// One predict–update–detect–correct step of `state` over `dt` with plot `z`.
    ///
    /// # Errors
    /// [`AdaptiveError::Filter`] for a bad `dt` (time going backwards or standing
    /// still), a non-finite plot or a filter failure; [`AdaptiveError::Math`] for a
    /// non-finite or non-PD result. `state` is unchanged on error.
    #[allow(non_snake_case)]
    pub fn step<const N: usize, const M: usize, const P: usize, Me>(
        &self,
        state: &mut ManeuverState<N, M, P>,
        dt: f64,
        meas: &Me,
        z: &Vector<M>,
    ) -> Result<ManeuverReport<N, M, P>, AdaptiveError>
    where
        F: GaussianFilter<N>,
        L: InputLinearization<N, P>,
        Me: MeasurementModel<N, M>,
    {
        check_dt(dt)?;
        argus_core_math::check_finite_vector(z, "measurement")?;
        let prior = &state.filter;
        let phi = self.lin.transition(prior.mean(), dt);
        let gamma = self.lin.input_gain(prior.mean(), dt);
        let mut pred = self.filter.predict(prior, dt)?;
        if let Some(u) = state.input {
            pred = Gaussian::from_symmetrized(pred.mean() + gamma * u, pred.cov())?;
        }
        let mp = self.filter.predict_measurement(&pred, meas)?;
        let innovation = mp.innovation(meas, z)?;
        let post = mp.update(&pred, &innovation.residual)?;
        let H = mp
            .jacobian()
            .copied()
            .unwrap_or_else(|| meas.jacobian(pred.mean()));
        let lin = StepLinearization {
            phi: &phi,
            gamma: &gamma,
            h: &H,
            gain: mp.gain(),
            s_factor: mp.s_factor(),
            residual: &innovation.residual,
        };
        // MRAS: the GLRT sees what the running input estimate does not explain.
        let (mras_next, glrt_residual) = match &state.mras {
            Some(m) => (
                Some(m.step(&lin)?),
                innovation.residual - m.predicted_innovation(&lin),
            ),
            None => (None, innovation.residual),
        };
        let outcome = state.glrt.step(&StepLinearization {
            residual: &glrt_residual,
            ..lin
        })?;

        let mut mean = *post.mean();
        let mut cov = *post.cov();
        let mut input = state.input;
        let mut mras = mras_next;
        let mut input_removed = false;
        let kind = state.glrt.config().kind();
        let eta = state.glrt.config().threshold();
        if let Some(det) = outcome.detection {
            // Fold the MRAS refinement into the state and the carried input.
            if let Some((du, l)) = mras.and_then(|m| m.estimate()) {
                let sens = mras.map_or(Matrix::<N, P>::zeros(), |m| m.sensitivity());
                mean += sens * du;
                cov += sens * l * sens.transpose();
                input = input.map(|u| u + du);
            }
            mras = None;
            match kind {
                FailureKind::Jump => {
                    mean += det.state_correction();
                    cov += det.covariance_increase();
                }
                FailureKind::Persistent => {
                    let old = input.unwrap_or_else(Vector::zeros);
                    let total = old + det.input;
                    let significant = total.dot(&(det.information * total)) >= eta;
                    if input.is_some() && !significant {
                        input_removed = true;
                        mean += det.sensitivity * (-old);
                        cov += det.covariance_increase();
                        input = None;
                    } else {
                        mean += det.state_correction();
                        input = Some(total);
                        match self.compensation {
                            Compensation::Glrt => cov += det.covariance_increase(),
                            Compensation::GlrtMras => mras = Some(Mras::after_detection(&det)),
                        }
                    }
                }
            }
        }
        let filter = Gaussian::from_symmetrized(mean, &cov)?;
        let output = match mras.and_then(|m| m.estimate().map(|e| (m.sensitivity(), e))) {
            Some((sens, (du, l))) => {
                Gaussian::from_symmetrized(mean + sens * du, &(cov + sens * l * sens.transpose()))?
            }
            None => filter,
        };
        // Commit.
        if outcome.detection.is_some() {
            state.glrt.reset();
        } else {
            state.glrt.commit();
        }
        state.filter = filter;
        state.output = output;
        state.input = input;
        state.mras = mras;
        state.steps += 1;
        Ok(ManeuverReport {
            innovation,
            max_statistic: outcome.max_statistic,
            detection: outcome.detection,
            input_removed,
        })
    }
}

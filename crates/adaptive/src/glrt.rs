//! Generalised likelihood-ratio test (GLRT) for maneuver onset (Willsky & Jones),
//! over a finite window of onset times, computed incrementally.
//!
//! # Model
//! After an onset at step `θ` the true state deviates from the maneuver-free one by
//! `D(m;θ) u`, and the filter's innovation is `r(m) = G(m;θ) u + r₁(m)` with `r₁`
//! the maneuver-free (white, covariance `S`) innovation. With `Φ = Φ(m, m−1)`, `Γ`
//! the input gain over the interval, `H` the measurement Jacobian and `K` the gain:
//!
//! - deviation: `D(θ;θ) = Γ`; `D(m;θ) = Φ D(m−1;θ)` for a one-time jump
//!   ([`FailureKind::Jump`], seed 001 eq 3-1) or `Φ D(m−1;θ) + Γ` for a persistent input
//!   ([`FailureKind::Persistent`]);
//! - signature: `G(m;θ) = H [D(m;θ) − Φ F(m−1;θ)]`, `F(m;θ) = K G(m;θ) + Φ F(m−1;θ)`,
//!   `F(θ−1;θ) = 0` (eqs 3-3, 3-4; with `Γ = I` and a jump, `G(θ;θ) = H`, `F(θ;θ) = K H`
//!   as printed);
//! - `d = Σ_{j=θ..m} Gᵀ S⁻¹ r`, `C = Σ_{j=θ..m} Gᵀ S⁻¹ G` (eqs 3-5, 3-7, the transpose
//!   and limits corrected), `l = dᵀ C⁻¹ d` (eq 3-6), decide when `max_θ l ≥ η` (eq 3-8)
//!   over `m − M ≤ θ ≤ m − N` (eq 3-10); `û = C⁻¹ d` (eq 3-9);
//! - correction `x += [D − F] û`, `P += [D − F] C⁻¹ [D − F]ᵀ` (eqs 3-11, 3-12).
//!
//! Under no maneuver and a fixed `θ`, `l` is χ² with `P` degrees of freedom; the
//! maximum over the window is larger (the false-alarm rate per step is measured
//! in the tests, not derived).
//!
//! # Cost
//! One step updates at most `M + 1` hypotheses (`O(M)` small fixed-size products),
//! never the whole history. The hypotheses live in two buffers allocated once at
//! construction: a step writes the next window into the spare buffer and only
//! [`Glrt::commit`] makes it current, so a step that is not committed changes nothing.
//!
//! # References
//! - Lee & Kim (1987), seed 001, eqs 3-1 to 3-12 (corrected in `SPEC.md`, section 001).
//! - A. S. Willsky and H. L. Jones, "A generalized likelihood ratio approach to the
//!   detection and estimation of jumps in linear systems", IEEE TAC 21(1), 1976.

use argus_core_math::{Matrix, SpdFactor, Vector, check_finite_matrix, check_finite_vector};

use crate::error::AdaptiveError;

/// Longest onset window accepted (`M`), to bound memory and per-step cost.
pub const MAX_WINDOW: usize = 10_000;

/// The kind of change the detector looks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FailureKind {
    /// A one-time jump of the state by `Γ u` at the onset (seed 001 eq 3-1).
    Jump,
    /// An input `u` that stays on from the onset: the state gains `Γ u` every step.
    Persistent,
}

/// Parameters of the GLRT.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GlrtConfig {
    max_age: usize,
    min_age: usize,
    threshold: f64,
    kind: FailureKind,
}

impl GlrtConfig {
    /// Onset window `m − M ≤ θ ≤ m − N` (`max_age = M`, `min_age = N`), threshold `η`,
    /// and the kind of change.
    ///
    /// # Errors
    /// [`AdaptiveError::InvalidWindow`] when `N > M` or `M > MAX_WINDOW`;
    /// [`AdaptiveError::InvalidParameter`] when `η` is not finite and positive.
    pub fn new(
        max_age: usize,
        min_age: usize,
        threshold: f64,
        kind: FailureKind,
    ) -> Result<Self, AdaptiveError> {
        if min_age > max_age {
            return Err(AdaptiveError::InvalidWindow {
                max_age,
                min_age,
                reason: "the shortest onset age N exceeds the longest M",
            });
        }
        if max_age > MAX_WINDOW {
            return Err(AdaptiveError::InvalidWindow {
                max_age,
                min_age,
                reason: "M exceeds MAX_WINDOW",
            });
        }
        if !(threshold.is_finite() && threshold > 0.0) {
            return Err(AdaptiveError::InvalidParameter {
                what: "GLRT threshold eta",
                value: threshold,
                reason: "must be finite and positive",
            });
        }
        Ok(Self {
            max_age,
            min_age,
            threshold,
            kind,
        })
    }

    /// `M`, the longest onset age considered.
    #[must_use]
    pub fn max_age(&self) -> usize {
        self.max_age
    }

    /// `N`, the shortest onset age considered.
    #[must_use]
    pub fn min_age(&self) -> usize {
        self.min_age
    }

    /// The threshold `η`.
    #[must_use]
    pub fn threshold(&self) -> f64 {
        self.threshold
    }

    /// The kind of change looked for.
    #[must_use]
    pub fn kind(&self) -> FailureKind {
        self.kind
    }
}

/// What the detector needs from one filter step: the linearisation used and the
/// innovation. `Φ` is the transition from the previous step to this one, `Γ` the
/// input (or jump) gain over that interval, `H`, `K`, `S` those of this update and
/// `r` the innovation.
#[allow(non_snake_case)]
#[derive(Debug, Clone, Copy)]
pub struct StepLinearization<'a, const N: usize, const M: usize, const P: usize> {
    /// `Φ(m, m−1)`.
    pub phi: &'a Matrix<N, N>,
    /// `Γ(m)`: input gain over the interval (`B` in SPEC's notation).
    pub gamma: &'a Matrix<N, P>,
    /// `H(m)`.
    pub h: &'a Matrix<M, N>,
    /// `K(m)`.
    pub gain: &'a Matrix<N, M>,
    /// The Cholesky factor of `S(m)`.
    pub s_factor: &'a SpdFactor<M>,
    /// The innovation `r(m)`.
    pub residual: &'a Vector<M>,
}

impl<const N: usize, const M: usize, const P: usize> StepLinearization<'_, N, M, P> {
    /// Checks that every matrix and the residual are finite.
    ///
    /// # Errors
    /// [`AdaptiveError::Math`] naming the first non-finite quantity.
    pub fn validate(&self) -> Result<(), AdaptiveError> {
        check_finite_matrix(self.phi, "transition Phi")?;
        check_finite_matrix(self.gamma, "input gain Gamma")?;
        check_finite_matrix(self.h, "measurement Jacobian H")?;
        check_finite_matrix(self.gain, "Kalman gain K")?;
        check_finite_vector(self.residual, "innovation r")?;
        Ok(())
    }
}

/// The signature chain of one onset hypothesis.
#[derive(Debug, Clone, Copy)]
struct Hypothesis<const N: usize, const P: usize> {
    age: usize,
    deviation: Matrix<N, P>,
    response: Matrix<N, P>,
    d: Vector<P>,
    c: Matrix<P, P>,
}

impl<const N: usize, const P: usize> Hypothesis<N, P> {
    /// Advances the chain by one step (eqs 3-3, 3-4) and accumulates `d`, `C`.
    fn advance<const M: usize>(
        prev: Option<&Self>,
        kind: FailureKind,
        lin: &StepLinearization<'_, N, M, P>,
    ) -> Self {
        let (deviation, phi_f, age) = match prev {
            None => (*lin.gamma, Matrix::<N, P>::zeros(), 0),
            Some(h) => {
                let dev = match kind {
                    FailureKind::Jump => lin.phi * h.deviation,
                    FailureKind::Persistent => lin.phi * h.deviation + lin.gamma,
                };
                (dev, lin.phi * h.response, h.age + 1)
            }
        };
        let g = lin.h * (deviation - phi_f);
        let response = phi_f + lin.gain * g;
        let sinv_g = lin.s_factor.solve_matrix(&g);
        let (d0, c0) = prev.map_or((Vector::<P>::zeros(), Matrix::<P, P>::zeros()), |h| {
            (h.d, h.c)
        });
        Self {
            age,
            deviation,
            response,
            d: d0 + sinv_g.transpose() * lin.residual,
            c: c0 + g.transpose() * sinv_g,
        }
    }
}

/// A maneuver declared by the GLRT.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Detection<const N: usize, const P: usize> {
    /// `m − θ̂`: how many steps before the current one the onset is estimated.
    pub age: usize,
    /// The statistic `l = dᵀ C⁻¹ d` of the winning onset (eq 3-6).
    pub statistic: f64,
    /// `û = C⁻¹ d` (eq 3-9).
    pub input: Vector<P>,
    /// `C⁻¹`, the covariance of `û`.
    pub input_cov: Matrix<P, P>,
    /// `C`, the information of `û` (kept for later input-estimation stages).
    pub information: Matrix<P, P>,
    /// `D(m;θ̂) − F(m;θ̂)`: maps an input error to the remaining state error (eq 3-11).
    pub sensitivity: Matrix<N, P>,
}

impl<const N: usize, const P: usize> Detection<N, P> {
    /// The state correction `[D − F] û` (eq 3-11).
    #[must_use]
    pub fn state_correction(&self) -> Vector<N> {
        self.sensitivity * self.input
    }

    /// The covariance increase `[D − F] C⁻¹ [D − F]ᵀ` (eq 3-12).
    #[must_use]
    pub fn covariance_increase(&self) -> Matrix<N, N> {
        self.sensitivity * self.input_cov * self.sensitivity.transpose()
    }
}

/// The outcome of one detector step (not yet committed).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GlrtOutcome<const N: usize, const P: usize> {
    /// The largest statistic in the eligible window and its onset age, if any
    /// hypothesis was identifiable (`C` positive definite).
    pub max_statistic: Option<(f64, usize)>,
    /// The detection, when the largest statistic reaches `η`.
    pub detection: Option<Detection<N, P>>,
}

/// The windowed GLRT detector. `N` state, `M` measurement, `P` input dimensions.
#[derive(Debug, Clone)]
pub struct Glrt<const N: usize, const M: usize, const P: usize> {
    config: GlrtConfig,
    prior_info: Matrix<P, P>,
    has_prior: bool,
    current: Vec<Hypothesis<N, P>>,
    next: Vec<Hypothesis<N, P>>,
}

impl<const N: usize, const M: usize, const P: usize> Glrt<N, M, P> {
    /// A detector with an empty window. Allocates its two buffers of `M + 1`
    /// hypotheses here, never in [`Glrt::step`].
    #[must_use]
    pub fn new(config: GlrtConfig) -> Self {
        let cap = config.max_age + 1;
        Self {
            config,
            prior_info: Matrix::zeros(),
            has_prior: false,
            current: Vec::with_capacity(cap),
            next: Vec::with_capacity(cap),
        }
    }

    /// The same detector with a prior information `Λ₀ = L(0)⁻¹` (positive definite) on a
    /// zero-mean input: a detection's estimate becomes `û = (C + Λ₀)⁻¹ d` with covariance
    /// `(C + Λ₀)⁻¹` and information `C + Λ₀` — seed 001 eq 4-6 with a finite `L(0)` and
    /// `u(0) = 0`, applied at the detection. The detection statistic stays the paper's
    /// `dᵀ C⁻¹ d` (eq 3-6). Use it when part of the input is barely observable (a 2-D
    /// acceleration seen through bearings only), where `C⁻¹ d` is unbounded in that part.
    ///
    /// # Errors
    /// [`AdaptiveError::Math`] when `Λ₀` is non-finite, not symmetric or not positive definite.
    pub fn with_input_prior(mut self, info: Matrix<P, P>) -> Result<Self, AdaptiveError> {
        check_finite_matrix(&info, "GLRT input prior information")?;
        SpdFactor::new(&info, "GLRT input prior information")?;
        self.prior_info = info;
        self.has_prior = true;
        Ok(self)
    }

    /// The same detector, window kept, with threshold `eta`.
    ///
    /// # Errors
    /// As [`GlrtConfig::new`] for `eta`.
    pub fn with_threshold(mut self, eta: f64) -> Result<Self, AdaptiveError> {
        let c = self.config;
        self.config = GlrtConfig::new(c.max_age, c.min_age, eta, c.kind)?;
        Ok(self)
    }

    /// The prior information on the input (zero unless set by [`Glrt::with_input_prior`]).
    #[must_use]
    pub fn input_prior(&self) -> &Matrix<P, P> {
        &self.prior_info
    }

    /// The configuration.
    #[must_use]
    pub fn config(&self) -> &GlrtConfig {
        &self.config
    }

    /// How many onset hypotheses the window holds now.
    #[must_use]
    pub fn len(&self) -> usize {
        self.current.len()
    }

    /// Whether the window is empty (just built or reset).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.current.is_empty()
    }

    /// Empties the window: call it after the estimate was corrected for a detection,
    /// since every stored signature assumed the uncorrected filter.
    pub fn reset(&mut self) {
        self.current.clear();
        self.next.clear();
    }

    /// Computes the next window from one filter step and evaluates the statistic.
    /// The detector keeps its current window until [`Glrt::commit`].
    ///
    /// Hypotheses younger than `N` steps are carried but not tested; older than `M`
    /// are dropped. A hypothesis whose `C` is not yet positive definite (an input not
    /// yet identifiable, e.g. a 2-D input from one bearing) is carried, not tested.
    ///
    /// # Errors
    /// [`AdaptiveError::Math`] when a step quantity is non-finite.
    pub fn step(
        &mut self,
        lin: &StepLinearization<'_, N, M, P>,
    ) -> Result<GlrtOutcome<N, P>, AdaptiveError> {
        lin.validate()?;
        let kind = self.config.kind;
        self.next.clear();
        self.next.push(Hypothesis::advance(None, kind, lin));
        for h in &self.current {
            if h.age < self.config.max_age {
                self.next.push(Hypothesis::advance(Some(h), kind, lin));
            }
        }
        let mut best: Option<(f64, usize, usize, SpdFactor<P>)> = None;
        for (i, h) in self.next.iter().enumerate() {
            if h.age < self.config.min_age {
                continue;
            }
            let Ok(cf) = SpdFactor::new_symmetric(&argus_core_math::symmetrize(&h.c), "GLRT C")
            else {
                continue;
            };
            let l = cf.mahalanobis_sq(&h.d);
            if !l.is_finite() {
                continue;
            }
            if best.as_ref().is_none_or(|b| l > b.0) {
                best = Some((l, h.age, i, cf));
            }
        }
        let max_statistic = best.as_ref().map(|b| (b.0, b.1));
        let detection = match best {
            Some((l, age, i, cf)) if l >= self.config.threshold => self.next.get(i).and_then(|h| {
                let information = h.c + self.prior_info;
                let cf = if !self.has_prior {
                    cf
                } else {
                    SpdFactor::new_symmetric(
                        &argus_core_math::symmetrize(&information),
                        "GLRT C + prior",
                    )
                    .ok()?
                };
                let input = cf.solve_vector(&h.d);
                let det = Detection {
                    age,
                    statistic: l,
                    input,
                    input_cov: cf.inverse(),
                    information,
                    sensitivity: h.deviation - h.response,
                };
                let finite = det.input.iter().all(|x| x.is_finite())
                    && det.input_cov.iter().all(|x| x.is_finite())
                    && det.sensitivity.iter().all(|x| x.is_finite());
                finite.then_some(det)
            }),
            _ => None,
        };
        Ok(GlrtOutcome {
            max_statistic,
            detection,
        })
    }

    /// Makes the window computed by the last [`Glrt::step`] current.
    pub fn commit(&mut self) {
        std::mem::swap(&mut self.current, &mut self.next);
    }
}

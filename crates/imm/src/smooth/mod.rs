//! Fixed-interval IMM smoothing with smoothed mode probabilities.
//!
//! # The form chosen
//! A forward–backward smoother in RTS form: the forward pass is the IMM itself; the
//! backward pass is Kim's (1994) pairwise smoother — one RTS step per mode pair
//! `(mₖ = i, mₖ₊₁ = j)`, collapsed per mode — in which each pair is weighed, and its RTS
//! step aimed, with mode `j`'s *backward likelihood* `βⱼ(x) = p(Zₖ₊₁:ₙ | xₖ₊₁ = x,
//! mₖ₊₁ = j)`, recovered as the ratio of mode `j`'s smoothed estimate to the IMM's
//! mode-`j` prediction ([`PairWeights::BackwardLikelihood`], the default; eqs (1b), (5b)).
//! Given `mₖ₊₁ = j` the future plots depend on the past only through `xₖ₊₁`, so `βⱼ` is
//! the same function for every `mₖ = i`: the pair's posterior at `k + 1` is its own
//! prediction times `βⱼ`, and its weight the prediction's integral against `βⱼ`. This is
//! the information a two-filter smoother carries backwards (Helmick, Blair & Hoffman
//! 1995), obtained from the RTS moments instead of a backward-time filter. Kim's own
//! weights (`Zₖ₊₁:ₙ` ignored given `mₖ₊₁`) and Barber's (2006) expectation-correction
//! weights (the pair's predicted density at mode `j`'s smoothed *mean*) are kept as
//! [`PairWeights::Kim`] and [`PairWeights::ExpectationCorrection`], both aiming every
//! pair `(i, j)` at mode `j`'s smoothed estimate.
//!
//! Why: checked against the exact smoother (every mode sequence of a short track
//! enumerated, `tests/smoothing_exact.rs`), the backward-likelihood pass stays close to it
//! with a matched and with a 10× too large measurement noise; the expectation-correction
//! weights end farther from it than the *filter* when the noise is too large (a point
//! density of a tight CV prediction at a broad smoothed mean rejects the right pair), and
//! Kim's weights are far off in both (docs/smoothing.md has the numbers).
//!
//! It was chosen over the two-filter smoothers themselves (Helmick, Blair & Hoffman 1995;
//! Blom & Bar-Shalom) because those need a backward-time IMM on inverted dynamics (`Fⱼ⁻¹`,
//! a backward prior of infinite covariance, i.e. information-form filters), which the
//! workspace's moment-form filters do not have; the RTS form reuses the forward filters'
//! stored moments and [`argus_filters::rts_step`], so it works for KF, EKF and UKF modes
//! alike. Cost per step: `R²` predictions in the forward record; backward `R` mixtures
//! for the mode predictions, `R²` pair posteriors, `R²` RTS steps and `R + 1` mixtures.
//!
//! A first version used only `R` steps, each mode's filtered estimate through its own
//! model (the reading of Nadarajah et al. 2012 tried first). On seed 000's Gimpo
//! trajectory it made the smoothed error 5 times the filtered one: across a mode switch
//! the transition into `k + 1` is the model of `mₖ₊₁`, not of `mₖ`.
//!
//! # Forward pass
//! Per step, [`ImmTrack`] keeps the IMM's posterior (`x̂ⁱₖ, Pⁱₖ, μⁱₖ`) and, for the
//! transition into step `k + 1`, every mode's filtered estimate predicted through every
//! model with the cross covariance ([`argus_filters::SmoothingFilter::predict_with_cross`]:
//! `x̂ⁱʲₖ₊₁|ₖ, Pⁱʲₖ₊₁|ₖ, Cⁱʲₖ₊₁`, model `j` applied to mode `i`).
//!
//! # Backward pass
//! From the last step (the filter's `x̂ⁱₙ, Pⁱₙ, μⁱₙ`), for `k = n − 1, …, 0`:
//!
//! ```text
//! bᵢ|ⱼ ∝ πᵢⱼ μⁱₖ · N(x̂ʲₖ₊₁|ₙ; x̂ⁱʲₖ₊₁|ₖ, Pⁱʲₖ₊₁|ₖ)   (Σᵢ bᵢ|ⱼ = 1)   P(mₖ=i | mₖ₊₁=j, Z₁:ₙ)  (1)
//! μⁱₖ|ₙ = Σⱼ bᵢ|ⱼ μʲₖ₊₁|ₙ                                             smoothed mode prob.   (2)
//! wⱼ|ᵢ  = bᵢ|ⱼ μʲₖ₊₁|ₙ / μⁱₖ|ₙ                                         P(mₖ₊₁=j | mₖ=i, Z₁:ₙ) (3)
//! Gⁱʲ   = Cⁱʲₖ₊₁ (Pⁱʲₖ₊₁|ₖ)⁻¹                                                               (4)
//! x̂ⁱʲ  = x̂ⁱₖ + Gⁱʲ (x̂ʲₖ₊₁|ₙ − x̂ⁱʲₖ₊₁|ₖ),  Pⁱʲ = Pⁱₖ + Gⁱʲ (Pʲₖ₊₁|ₙ − Pⁱʲₖ₊₁|ₖ) Gⁱʲᵀ         (5)
//! x̂ⁱₖ|ₙ, Pⁱₖ|ₙ = Σⱼ wⱼ|ᵢ N(x̂ⁱʲ, Pⁱʲ)      collapse (moment matched)                        (6)
//! x̂ₖ|ₙ, Pₖ|ₙ   = Σᵢ μⁱₖ|ₙ N(x̂ⁱₖ|ₙ, Pⁱₖ|ₙ)  combined output                                 (7)
//! ```
//!
//! With [`PairWeights::Kim`] the Gaussian factor of (1) is dropped (`bᵢ|ⱼ = πᵢⱼ μⁱₖ /
//! μ̄ʲₖ₊₁`, Kim's approximation that the future plots say nothing about `mₖ` once `mₖ₊₁`
//! is given). With [`PairWeights::BackwardLikelihood`] (the default) eqs (1) and (5)
//! become
//!
//! ```text
//! N(x̄ʲ, P̄ʲ) = Σᵢ (πᵢⱼ μⁱₖ / μ̄ʲₖ₊₁) N(x̂ⁱʲₖ₊₁|ₖ, Pⁱʲₖ₊₁|ₖ)   the IMM's mode-j prediction  (0b)
//! βⱼ(x) ∝ N(x; x̂ʲₖ₊₁|ₙ, Pʲₖ₊₁|ₙ) / N(x; x̄ʲ, P̄ʲ)                                       (βb)
//! bᵢ|ⱼ ∝ πᵢⱼ μⁱₖ ∫ N(x; x̂ⁱʲₖ₊₁|ₖ, Pⁱʲₖ₊₁|ₖ) βⱼ(x) dx                                  (1b)
//! N(x̃ⁱʲ, P̃ⁱʲ) ∝ N(x; x̂ⁱʲₖ₊₁|ₖ, Pⁱʲₖ₊₁|ₖ) βⱼ(x)    the pair's smoothed estimate at k + 1
//! x̂ⁱʲ  = x̂ⁱₖ + Gⁱʲ (x̃ⁱʲ − x̂ⁱʲₖ₊₁|ₖ),  Pⁱʲ = Pⁱₖ + Gⁱʲ (P̃ⁱʲ − Pⁱʲₖ₊₁|ₖ) Gⁱʲᵀ               (5b)
//! ```
//!
//! (0b) is, for linear models, the prediction of the IMM's mixed estimate (seed 000 eqs
//! (1)–(3)). In information form `βⱼ(x) = exp(−½ yᵀ Λ y + ηᵀ y)`, `y = x − x̂ʲₖ₊₁|ₙ`,
//! `Λ = (Pʲₖ₊₁|ₙ)⁻¹ − (P̄ʲ)⁻¹` (negative eigenvalues clipped to zero), `η = (P̄ʲ)⁻¹
//! (x̂ʲₖ₊₁|ₙ − x̄ʲ)`; (1b) and the pair posterior are closed-form Gaussian integrals
//! (`likelihood.rs`). With identical modes, one mode or `π = I`, `P̃ⁱʲ = Pʲₖ₊₁|ₙ` and the
//! pass is the RTS smoother of each mode (tested). (5) is the RTS step of the pair;
//! (6)–(7) are moment matches as in the IMM (seed 000 eqs 2, 7). The numbering is this
//! module's; the sources are Kim (1994) §3 (the smoothing algorithm: joint mode
//! probabilities, pairwise smoothed states and their collapse) and Barber (2006) §3
//! (expectation correction, the mean approximation of `⟨p(hₜ₊₁ | sₜ, sₜ₊₁, v₁:ₜ)⟩`);
//! their equation numbers were not re-checked against the originals here. Probabilities
//! are kept as logarithms (log-sum-exp), so a mode of probability `e^{-2000}` does not
//! underflow.
//!
//! # References
//! - C.-J. Kim (1994), "Dynamic linear models with Markov-switching", J. Econometrics 60,
//!   1–22.
//! - D. Barber (2006), "Expectation correction for smoothed inference in switching linear
//!   dynamical systems", J. Machine Learning Research 7, 2515–2540.
//! - N. Nadarajah, R. Tharmarasa, M. McDonald, T. Kirubarajan (2012), "IMM forward
//!   filtering and backward smoothing estimator for maneuvering target tracking", IEEE
//!   Trans. Aerospace and Electronic Systems 48(3), 2673–2678.
//! - R. E. Helmick, W. D. Blair, S. A. Hoffman (1995), "Fixed-interval smoothing for
//!   Markovian switching systems", IEEE Trans. Information Theory 41(6), 1845–1855 (the
//!   two-filter form, whose backward information the default weights recover from the
//!   RTS moments).
//!
//! # Example
//! ```
//! use argus_core_math::{Gaussian, Matrix, Vector};
//! use argus_filters::Kf;
//! use argus_imm::{Imm, ImmEstimate, ImmTrack, MarkovMatrix};
//! use argus_motion_models::Cv2D;
//! use argus_sensors::CartesianPosition;
//!
//! // Two CV modes of different process noise.
//! let imm = Imm::new(
//!     [Kf::new(Cv2D::discrete(0.1)?), Kf::new(Cv2D::discrete(3.0)?)],
//!     MarkovMatrix::new([[0.95, 0.05], [0.1, 0.9]])?,
//! )?;
//! let pos = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 100.0)?;
//! let g = Gaussian::new(Vector::<4>::zeros(), Matrix::<4, 4>::identity() * 1e4)?;
//! let mut track = ImmTrack::new(*imm.markov(), 0.0, ImmEstimate::from_common(g, [0.5, 0.5])?)?;
//! for k in 1..=30 {
//!     let t = 2.0 * f64::from(k);
//!     track.step(&imm, t, &pos, &Vector::<2>::new(30.0 * t, 0.0))?;
//! }
//! let smoothed = track.smooth()?;
//! assert_eq!(smoothed.len(), 31);
//! let mu: f64 = smoothed[10].mode_probabilities.iter().sum();
//! assert!((mu - 1.0).abs() < 1e-12);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod backward;
mod error;
#[cfg(feature = "gibbs")]
pub mod gibbs;
mod likelihood;
mod mode_track;
mod record;
mod step;
mod track;

pub use backward::{ImmSmoothed, PairWeights, imm_smooth};
pub use error::ImmSmoothError;
pub(crate) use likelihood::BackwardLikelihood;
pub use mode_track::{ForwardRecord, ModeTrack};
pub(crate) use record::{Record, RecordedStep, backward_pass};
pub use step::{ImmStep, ImmTransition};
pub use track::ImmTrack;

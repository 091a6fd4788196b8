//! A smoother of the jump-Markov linear system behind an IMM that tends to its exact
//! posterior mean: blocked Gibbs sampling of the mode sequence with the Gaussian part
//! integrated out (Carter & Kohn 1996; Doucet & Andrieu 2001). Behind the cargo feature
//! `gibbs` (it needs a random generator; the IMM smoother of [`crate::smooth`] does not).
//!
//! # Model
//! [`GibbsProblem`]: `m₀ ~ μ₀`, `mₖ | mₖ₋₁ ~ π`, `x₀ ~ g₀` at `t₀`,
//! `xₖ = F_{mₖ}(Δₖ) xₖ₋₁ + w`, `w ~ N(0, Q_{mₖ}(Δₖ))`, `zₖ = Hₖ xₖ + v`, `v ~ N(0, Rₖ)` for `k = 1 … n` — the IMM's
//! own Kalman modes, Markov matrix and per-step linear measurement models. Generic over
//! the state dimension `N`, the plot's `D` and the number of modes `R`; linear models only
//! (`F`, `Q`, `H`, `R` tabulated once per problem).
//!
//! # The sampler
//! The full conditional of a block `b = mₖ … mₖ₊ₗ₋₁` given every other mode is
//!
//! ```text
//! p(b | m₋b, Z) ∝ π(mₖ₋₁, b₀) ⋯ π(b_{L−1}, mₖ₊ₗ) Πᵢ N(zₖ₊ᵢ; ẑ, S along b) ∫ N(x; x̂ₖ₊ₗ₋₁|ₖ₊ₗ₋₁, P) βₖ₊ₗ₋₁(x) dx
//! ```
//!
//! with the Kalman filter along `m₀ … mₖ₋₁` continued along `b`, and `βₖ(x) =
//! p(zₖ₊₁:ₙ | xₖ = x, mₖ₊₁:ₙ) ∝ exp(−½ xᵀ Ω x + ηᵀ x)` the backward information filter along
//! the modes after the block (its constant does not depend on `b`):
//!
//! ```text
//! Ω' = Ωₖ₊₁ + Hᵀ R⁻¹ H,  η' = ηₖ₊₁ + Hᵀ R⁻¹ zₖ₊₁          (plot k + 1)
//! Ωₖ = Fᵀ Ω' (I + Q Ω')⁻¹ F,  ηₖ = Fᵀ (I + Ω' Q)⁻¹ η'      (F, Q of mₖ₊₁; no Q⁻¹ needed)
//! ∫ N(x; μ, P) exp(−½ xᵀ Ω x + ηᵀ x) dx = |I + P Ω|^(−½) exp(−½ μᵀ Ω μ + ηᵀ μ + ½ bᵀ (I + P Ω)⁻¹ P b),
//! b = η − Ω μ
//! ```
//!
//! (completing the square; the Woodbury identity turns `(Ω'⁻¹ + Q)⁻¹` into `Ω' (I + Q
//! Ω')⁻¹`). All `R^L` paths of a block are weighed by a tree of Kalman steps (paths of zero
//! prior cut). A sweep recomputes `β` along the current sequence, draws `m₀`, then the
//! blocks forwards (the forward filter follows the new draws; the first block's length
//! cycles through `1 … L` so that boundaries move from sweep to sweep), and RTS-smooths the
//! sequence drawn. The estimate is the average over recorded sweeps of each sequence's
//! smoothed moments (`E[x]`, `E[P + x xᵀ]`) and of the block conditionals for the mode
//! probabilities (Rao–Blackwellised). As the sweeps grow it tends to the exact posterior
//! mean of the model — which no IMM smoother (one Gaussian per mode and step) can beat in
//! mean squared error on the model's own data; the Monte Carlo error of a finite average
//! adds to its squared error (and to its NEES).
//!
//! Single sites (`L = 1`) mix badly on manoeuvring tracks (a chain started from all CV
//! stays on it through a turn); blocks of 4 are the documented choice (docs/smoothing.md).
//!
//! # Cost
//! Per sweep `n` backward information steps, about `(R + R² + … + R^L) / L` Kalman steps
//! and `R^L / L` integrals per plot, and an RTS pass when recording; all on stack matrices
//! in buffers the chain allocates once ([`GibbsChain::new`]).
//!
//! # References
//! - C. K. Carter, R. Kohn (1996), "Markov chain Monte Carlo in conditionally Gaussian
//!   state space models", Biometrika 83(3), 589–601.
//! - A. Doucet, C. Andrieu (2001), "Iterative algorithms for state estimation of jump
//!   Markov linear systems", IEEE Trans. Signal Processing 49(6), 1216–1227.
//!
//! # Example
//! ```
//! use argus_core_math::{Gaussian, Matrix, Vector};
//! use argus_filters::Kf;
//! use argus_imm::{Imm, MarkovMatrix};
//! use argus_imm::smooth::gibbs::{GibbsConfig, GibbsProblem, gibbs_smooth};
//! use argus_motion_models::Cv2D;
//! use argus_sensors::CartesianPosition;
//!
//! let imm = Imm::new(
//!     [Kf::new(Cv2D::discrete(0.1)?), Kf::new(Cv2D::discrete(3.0)?)],
//!     MarkovMatrix::new([[0.95, 0.05], [0.1, 0.9]])?,
//! )?;
//! let pos = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 100.0)?;
//! let start = Gaussian::new(Vector::<4>::zeros(), Matrix::<4, 4>::identity() * 1e4)?;
//! let times: Vec<f64> = (0..=20).map(|k| 2.0 * f64::from(k)).collect();
//! let plots: Vec<_> = times[1..].iter().map(|t| (pos, Vector::<2>::new(30.0 * t, 0.0))).collect();
//! let problem = GibbsProblem::new(&imm, [0.5, 0.5], &start, &times, &plots)?;
//! let config = GibbsConfig { block: 3, burn_in: 5, sweeps: 20, seed: 1 };
//! let smoothed = gibbs_smooth(&problem, &config, None)?;
//! assert_eq!(smoothed.len(), 21);
//! assert!((smoothed[10].mode_probabilities.iter().sum::<f64>() - 1.0).abs() < 1e-12);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod chain;
mod check;
mod config;
mod error;
mod estimate;
mod kalman;
mod problem;
mod step_model;
mod tree;

pub use chain::GibbsChain;
pub use config::{GibbsConfig, MAX_BLOCK_PATHS};
pub use error::GibbsError;
pub use estimate::{GibbsSmoothed, gibbs_smooth, pooled};
pub use problem::GibbsProblem;

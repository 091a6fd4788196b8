//! Fixed-interval (and, by windows, fixed-lag) smoothing of the aircraft IMM: the IMM
//! smoother of [`crate::smooth`] — Kim's pairwise RTS form with the backward-likelihood
//! pair weights — across the unequal state sizes of the CV modes (`[x, vx, y, vy]`, 4)
//! and the CT mode (`[x, vx, y, vy, ω]`, 5).
//!
//! # The pair maps
//! A pair `(mₖ = i, mₖ₊₁ = j)` starts from mode `i`'s filtered estimate `N(x̂ⁱₖ, Pⁱₖ)`
//! (size `nᵢ`), brought into mode `j`'s state by the map the forward pass's mixing uses
//! ([`super`], eqs M2–M3), and predicted through model `j`:
//!
//! ```text
//! CV i → CV j   identity                    x⁰ = x̂ⁱₖ,            P⁰ = Pⁱₖ
//! CT   → CV j   the marginal [I₄ 0]         x⁰ = [I₄ 0] x̂ᶜₖ,     P⁰ = P ᶜₖ,₄₄
//! CV i → CT     the augmentation            x⁰ = [x̂ⁱₖ; ω̂ᵃ],      P⁰ = diag(Pⁱₖ, σᵃ²)
//! CT   → CT     identity
//! ```
//!
//! with `(ω̂ᵃ, σᵃ²)` the IMM's own [`crate::Augmentation`] of step `k`'s CT estimate
//! (`Unbiased`: `ω̂_CT, P_CT,ωω`; `Fixed`: `0, σ²`), independent of `xⁱₖ` under both.
//! The prediction `x̂ⁱʲₖ₊₁|ₖ, Pⁱʲₖ₊₁|ₖ` (size `nⱼ`) and the cross covariance
//! `Cⁱʲ = Cov(xⁱₖ, xₖ₊₁ | Z₁:ₖ)` (`nᵢ × nⱼ`) are
//!
//! ```text
//! CV i → CV j, CT → CT   C = the filter's own cross covariance (P Fᵀ for the EKF, the
//!                        sigma-point sum for the UKF: SmoothingFilter::predict_with_cross)
//! CV i → CT              C = rows 0–3 of the 5 × 5 cross covariance of the augmented
//!                        prior (xⁱₖ is its first four components)
//! CT → CV j              C = [C₄; P_ω4 P₄₄⁻¹ C₄], C₄ the marginal's 4 × 4 cross covariance
//!                        (E[ω | x₄] is linear in x₄ for a Gaussian, so
//!                        Cov(ω, g(x₄)) = P_ω4 P₄₄⁻¹ Cov(x₄, g(x₄)); = P_ω4 Fᵀ for CV)
//! ```
//!
//! # The backward pass
//! Exactly [`crate::smooth`]'s eqs (0b)–(7), each quantity in the space it belongs to:
//! the IMM's mode-`j` prediction (0b), `βⱼ` (βb), the pair weight `bᵢ|ⱼ` (1b) and the
//! pair's smoothed target `N(x̃ⁱʲ, P̃ⁱʲ)` in mode `j`'s space (`nⱼ`); the gain
//! `Gⁱʲ = Cⁱʲ (Pⁱʲₖ₊₁|ₖ)⁻¹` (`nᵢ × nⱼ`) and the pair's correction
//! `x̂ⁱʲ = x̂ⁱₖ + Gⁱʲ (x̃ⁱʲ − x̂ⁱʲₖ₊₁|ₖ)`, `Pⁱʲ = Pⁱₖ + Gⁱʲ (P̃ⁱʲ − Pⁱʲₖ₊₁|ₖ) Gⁱʲᵀ` in mode
//! `i`'s (`nᵢ`); the collapse (6) per mode in its own space; the combined output (7) on
//! `[x, vx, y, vy]` with the CT mode by its marginal. The CT mode's smoothed estimate
//! keeps its turn rate ([`AircraftSmoothed::turn_rate`]). With `Π = I` each mode is the
//! RTS smoother (EKF) or URTS (UKF) of its own filter (tested to 1e-9).
//!
//! # The forward record, and in which sense it is exact
//! [`AircraftTrack`] recomputes each transition from the recorded posterior of the step
//! before (`C² + 2C + 1` predictions), as [`crate::ImmTrack`] does: the pair quantities
//! are not computed by the forward pass at all (it predicts each mode's *mixed*
//! estimate), and the pair maps and `(ω̂ᵃ, σᵃ²)` are deterministic functions of the
//! recorded posterior and the IMM's own filters and augmentation rule, so the record is
//! the one any caller holding the posteriors gets — a tracker's rows included. For the
//! CV modes (linear prediction) the mixture of the pair predictions with `μᵢ|ⱼ` is the
//! forward pass's mode-`j` prediction to round-off; for the CT mode (an EKF or UKF
//! linearised at each pair's mean instead of at the mixed mean) it is the usual
//! approximation of the IMM smoother with nonlinear modes.
//!
//! # Errors
//! Every failure is an [`crate::ImmSmoothError`] naming the step: a failed forward step
//! or pair prediction (`ForwardFailed`, recorded: nothing later is smoothed), time not
//! increasing, a missing transition, posteriors and times of different lengths
//! ([`AircraftTrack::from_posteriors`]), a numerical failure of the backward pass
//! (`Backward`, with the mode). A track is smoothed whole or not at all.
//!
//! # References
//! As [`crate::smooth`] (Kim 1994; Helmick, Blair & Hoffman 1995), with the mixing maps of
//! Granström, Willett & Bar-Shalom (2015) and the cross covariances of Särkkä (2008).

mod backward;
mod mode_track;
mod pair;
mod step;
mod track;

#[cfg(test)]
mod tests;

pub use backward::{AircraftSmoothed, aircraft_smooth};
pub use pair::PairTransition;
pub use step::{AircraftStep, AircraftTransition};
pub use track::AircraftTrack;

//! An IMM for aircraft: `C` constant-velocity (CV) modes on `[x, vx, y, vy]` beside one
//! coordinated-turn (CT) mode with the turn rate as a state, `[x, vx, y, vy, ω]`
//! ([`argus_motion_models::CoordinatedTurnRate`], run by an EKF or a UKF) — an IMM of
//! unequal state sizes — updated with (range, azimuth) plots of a 2-D radar.
//!
//! # The cycle
//! Modes `i, j ∈ {0 … C}` (CV modes `0..C`, CT mode `C`), transition matrix `Π = [πᵢⱼ]`
//! per plot, mode probabilities `μᵢ`:
//!
//! ```text
//! M1  μ̄ⱼ = Σᵢ πᵢⱼ μᵢ,   μᵢ|ⱼ = πᵢⱼ μᵢ / μ̄ⱼ                       (predicted, mixing weights)
//! M2  into a CV mode j:  x̂⁰ⱼ, P⁰ⱼ = moments of Σᵢ μᵢ|ⱼ N(Aᵢ x̂ᵢ, Aᵢ Pᵢ Aᵢᵀ)
//!     with Aᵢ = I₄ for a CV mode and Aᵢ = [I₄ 0] (ω dropped: the marginal) for the CT mode
//! M3  into the CT mode:  x̂⁰, P⁰ = moments of Σᵢ μᵢ|C N(x̂ᵢᵃ, Pᵢᵃ)
//!     with x̂ᵢᵃ = [x̂ᵢ; ω̂ᵃ], Pᵢᵃ = diag(Pᵢ, σᵃ²) for a CV mode and the CT estimate itself,
//!     (ω̂ᵃ, σᵃ²) = (ω̂_CT, P_CT,ωω) by Granström et al.'s unbiased rule ([`Augmentation`])
//! P   x̂ⱼ⁻, Pⱼ⁻ = the mode's filter prediction of x̂⁰ⱼ, P⁰ⱼ over T
//! U   the mode's filter update with z = [r, θ] (h = [√(Δx² + Δy²), atan2(Δy, Δx)],
//!     R = diag(σr², σθ²)); Λⱼ = N(ν; 0, Sⱼ) with the wrapped residual ν
//! W   μⱼ = μ̄ⱼ Λⱼ / Λ,   Λ = Σⱼ μ̄ⱼ Λⱼ                            (in log space)
//! O   x̂ = Σⱼ μⱼ Aⱼ x̂ⱼ,  P = Σⱼ μⱼ [Aⱼ Pⱼ Aⱼᵀ + (Aⱼ x̂ⱼ − x̂)(…)ᵀ]  (output on [x, vx, y, vy])
//! ```
//!
//! "Moments of" is the moment-matched Gaussian of a mixture, `x = Σ wᵢ xᵢ`,
//! `P = Σ wᵢ [Pᵢ + (xᵢ − x)(xᵢ − x)ᵀ]` ([`argus_core_math::Gaussian::mixture`]).
//!
//! # The mixing rule (M2, M3)
//! Into the smaller CV state the CT estimate is marginalised (exact for a Gaussian). Into
//! the larger CT state a CV estimate has no turn rate; the common fixes extend it with a
//! fixed value — zero padding (`ω = 0`, variance 0) or `ω = 0` with a set variance
//! ([`Augmentation::Fixed`]) — which biases the mixed turn rate towards 0 by the CV modes'
//! weight (`ω̂⁰ = μ_C|C ω̂_CT`) and adds a spurious spread term `μ (1 − μ) ω̂_CT²` to its
//! variance, so that every revisit in a turn the CT mode restarts from a weaker turn.
//! Granström, Willett & Bar-Shalom (2015) instead extend the smaller state with the
//! moments of the missing components held by the larger mode(s); with one CT mode that is
//! the CT mode's own `ω̂_CT`, `P_CT,ωω`, so the mixed turn rate is `ω̂_CT` exactly and its
//! variance `P_CT,ωω` (the default, [`Augmentation::Unbiased`]). On the simulated flights
//! of docs/aircraft-imm.md zero padding raises the ANEES from 4.0 to 4.6 (out of the
//! band) and the position RMSE by 2 %.
//!
//! # Measurements
//! The filters update in (range, azimuth) directly ([`AircraftRadar`]); converted
//! Cartesian plots serve only the two-point start ([`two_point_start`]), which gives the
//! CT mode the turn-rate prior `ω ~ N(0, σ_ω₀²)`.
//!
//! # Tuning
//! [`AircraftTuning`]; its default (two CV modes, σ_a = 0.3 and 2 m/s²; CT σ_a = 0.5 m/s²,
//! σ_ω = 0.1 °/s²; `Π` per 5-s revisit; σ_ω₀ = 2 °/s) is documented value by value there.
//!
//! # References
//! - K. Granström, P. Willett & Y. Bar-Shalom, "Systematic approach to IMM mixing for
//!   unequal dimension states", IEEE Trans. Aerospace and Electronic Systems 51(4),
//!   2975–2986, 2015 (the mixing rule).
//! - Y. Bar-Shalom, X. R. Li & T. Kirubarajan, *Estimation with Applications to Tracking
//!   and Navigation*, Wiley 2001: §11.6 (the IMM cycle), §11.7.2 (coordinated turn with the
//!   rate as a state), §11.7.3 (IMM of CV and CT models of different dimension), §5.5.3
//!   (two-point differencing), §5.4.2 (NEES and its chi-square band).
//! - Mo Longbin et al., "Unbiased converted measurements for tracking", IEEE TAES 34(3),
//!   1998 (the start's conversion).
//!
//! # Example
//! ```
//! use argus_core_math::Vector;
//! use argus_imm::{AircraftRadar, AircraftTuning};
//! use argus_sensors::RadarNoise;
//!
//! // Seed 000's radar: σr = 70 m, σθ = 0.08°, at the origin.
//! let radar = AircraftRadar::new([0.0, 0.0], RadarNoise::constant(70.0, 0.08_f64.to_radians(), 0.0)?)?;
//! let tuning = AircraftTuning::<2, 3>::default();
//! let imm = tuning.build()?;
//! // Plots [r, θ] of an aircraft flying +x at 200 m/s, 5 s apart.
//! let plot = |x: f64, y: f64| Vector::<2>::new(x.hypot(y), y.atan2(x));
//! let mut est = tuning.start(&radar, &plot(50_000.0, 30_000.0), &plot(51_000.0, 30_000.0), 5.0)?;
//! for k in 2..20 {
//!     let z = plot(50_000.0 + 1_000.0 * k as f64, 30_000.0);
//!     est = imm.step(&est, 5.0, &radar, &z)?.estimate;
//! }
//! let x = est.combined()?;
//! assert!((x.mean()[1] - 200.0).abs() < 5.0); // vx
//! let mu = est.mode_probabilities();
//! assert!((mu.iter().sum::<f64>() - 1.0).abs() < 1e-12);
//! # Ok::<(), argus_imm::ImmError>(())
//! ```

mod estimate;
mod estimator;
mod mixing;
mod radar;
mod smooth;
mod start;
mod tuning;

#[cfg(test)]
mod tests;

pub use estimate::{AircraftEstimate, AircraftPrediction};
pub use estimator::{AircraftImm, AircraftUpdate};
pub use mixing::Augmentation;
pub use radar::AircraftRadar;
pub use smooth::{
    AircraftSmoothed, AircraftStep, AircraftTrack, AircraftTransition, PairTransition,
    aircraft_smooth,
};
pub use start::{start_from_cv, two_point_start};
pub use tuning::{AircraftEkf, AircraftTuning};

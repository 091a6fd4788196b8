//! The noise-free GLRT statistic after each switch of a run, given the state the adaptive
//! filter actually has at that switch (issue 17 §1): its corrected estimate and covariance,
//! its carried input and its GLRT window. The statistic of the true onset is non-central
//! χ²(1); its non-centrality `λ(τ)`, conditional on that state, is the statistic of a copy
//! of the track that sees the noise-free truth from the switch on with detection turned off.
//! `Φ(√λ(τ) − √η)` is then the chance of a detection by `τ` (the running maximum over
//! the plots up to `τ`, since the detector fires at the first plot above η).
//!
//! The filter and the GLRT are linear in the data (their gains do not depend on it), so
//! a carried input `ĉ` with a true input `u` gives the innovations of the plain filter
//! on a truth with input `u − ĉ`: [`mismatch_statistic`] follows that plain filter from
//! its steady running, the deterministic part of the derivation in
//! `docs/papers/001-maneuver-1d.md`.

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::Kf;
use argus_motion_models::{Cv1D, CvNoise};
use argus_sensors::CartesianPosition;

use argus_adaptive::{AdaptiveError, Compensation, ManeuverFilter, ManeuverState, ModelInput};

use super::{Maneuver1dConfig, Run1d, accel_on, validate_windows, within_derived};

/// Plots followed after a switch (1.2 s: every switch's next one is at least that far).
pub const FOLLOW: usize = 24;

type Adaptive = ManeuverFilter<Kf<Cv1D>, ModelInput<Cv1D, 2, 1>>;

fn adaptive(cfg: &Maneuver1dConfig, compensation: Compensation) -> Result<Adaptive, AdaptiveError> {
    let model = Cv1D::new(CvNoise::VelocityPerStep { q: cfg.q })?;
    Ok(ManeuverFilter::new(
        Kf::new(model),
        ModelInput::new(model, Matrix::<2, 1>::new(0.0, 1.0))?,
        compensation,
    ))
}

fn meas(cfg: &Maneuver1dConfig) -> Result<CartesianPosition<2, 1>, AdaptiveError> {
    Ok(CartesianPosition::<2, 1>::new(
        [0],
        Matrix::<1, 1>::new(cfg.r),
    )?)
}

/// One switch of one run: the state the adaptive filter has just before it and the
/// noise-free statistic after it.
#[derive(Debug, Clone, PartialEq)]
pub struct SwitchState {
    /// Switch time, s.
    pub switch: f64,
    /// The carried input at the switch (`None`: the plain filter), m/s².
    pub carried: Option<f64>,
    /// The filter's estimate minus the truth at the switch, `[m, m/s]`.
    pub error: Vector<2>,
    /// The filter's covariance at the switch (GLRT corrections included).
    pub cov: Matrix<2, 2>,
    /// Hypotheses in the GLRT window at the switch.
    pub window: usize,
    /// `λ` at the plots `T, 2T, …, FOLLOW·T` after the switch.
    pub lambda: Vec<f64>,
}

impl SwitchState {
    /// `λ(τ)` at `τ` after the switch (NaN when `τ` is not one of the followed plots).
    #[must_use]
    pub fn lambda_at(&self, dt: f64, tau: f64) -> f64 {
        let j = (tau / dt).round() as usize;
        j.checked_sub(1)
            .and_then(|i| self.lambda.get(i))
            .copied()
            .unwrap_or(f64::NAN)
    }

    /// The derived chance of a detection within `τ` of the switch: the largest
    /// `Φ(√λ − √η)` over the plots up to `τ` (plots younger than `N` steps cannot fire).
    #[must_use]
    pub fn within(&self, cfg: &Maneuver1dConfig, eta: f64, tau: f64) -> f64 {
        let last = (tau / cfg.dt).round() as usize;
        self.lambda
            .iter()
            .enumerate()
            .take(last)
            .skip(cfg.min_age)
            .map(|(_, &l)| within_derived(l, eta))
            .fold(0.0, f64::max)
    }

    /// The derived mean delay, `Σ_k T · P(no detection by plot k)` over the followed
    /// plots plus the first (s).
    #[must_use]
    pub fn mean_delay(&self, cfg: &Maneuver1dConfig, eta: f64) -> f64 {
        let mut best = 0.0f64;
        let mut mean = cfg.dt;
        for (j, &l) in self.lambda.iter().enumerate() {
            if j >= cfg.min_age {
                best = best.max(within_derived(l, eta));
            }
            mean += cfg.dt * (1.0 - best);
        }
        mean
    }
}

/// Runs the adaptive filter (threshold `eta`) on `run` and, at every switch of
/// `windows`, records its state and the noise-free statistic of a copy that follows the
/// true (noise-free) trajectory from the switch with detection off.
///
/// # Errors
/// [`AdaptiveError`] for a bad configuration or windows, or a failed filter step.
pub fn switch_states(
    cfg: &Maneuver1dConfig,
    windows: &[(f64, f64)],
    run: &Run1d,
    eta: f64,
    compensation: Compensation,
) -> Result<Vec<SwitchState>, AdaptiveError> {
    validate_windows(windows)?;
    cfg.validate(eta)?;
    let ad = adaptive(cfg, compensation)?;
    let me = meas(cfg)?;
    let t = cfg.dt;
    let phi = Matrix::<2, 2>::new(1.0, t, 0.0, 1.0);
    let gamma = Vector::<2>::new(0.5 * t * t, t);
    let mut st = ManeuverState::<2, 1, 1>::new(run.initial, cfg.glrt(eta)?);
    let mut out = Vec::new();
    let switches: Vec<f64> = windows.iter().flat_map(|&(on, off)| [on, off]).collect();
    let mut prev = Vector::<2>::new(cfg.x0, cfg.v0);
    for (k, (x, z)) in run.truth.iter().zip(&run.plots).enumerate() {
        let tk = k as f64 * t;
        if let Some(&sw) = switches.iter().find(|&&s| (tk - s).abs() < 1e-9) {
            let mut copy = st.clone().with_threshold(f64::MAX)?;
            let mut xt = prev;
            let mut lambda = Vec::with_capacity(FOLLOW);
            for j in k..k + FOLLOW {
                let a = if accel_on(windows, j as f64 * t) {
                    cfg.accel
                } else {
                    0.0
                };
                xt = phi * xt + gamma * a;
                let rep = ad.step(&mut copy, t, &me, &Vector::<1>::new(xt[0]))?;
                lambda.push(rep.max_statistic.map_or(f64::NAN, |m| m.0));
            }
            out.push(SwitchState {
                switch: sw,
                carried: st.input_estimate().map(|u| u[0]),
                error: st.filter_estimate().mean() - prev,
                cov: *st.filter_estimate().cov(),
                window: st.glrt().len(),
                lambda,
            });
        }
        ad.step(&mut st, t, &me, &Vector::<1>::new(*z))?;
        prev = *x;
    }
    Ok(out)
}

/// The noise-free statistic of the plain filter (window `M`, `N` of `cfg`, detection off)
/// started exactly at `x₀` with `P₀`, on a truth whose input is `levels[i].1` from time
/// `levels[i].0` on (0 before the first): `λ` at every plot up to `t_end` (s).
///
/// # Errors
/// [`AdaptiveError`] for a bad configuration or a failed filter step.
pub fn mismatch_statistic(
    cfg: &Maneuver1dConfig,
    levels: &[(f64, f64)],
    t_end: f64,
) -> Result<Vec<f64>, AdaptiveError> {
    cfg.validate(1.0)?;
    let ad = adaptive(cfg, Compensation::Glrt)?;
    let me = meas(cfg)?;
    let t = cfg.dt;
    let phi = Matrix::<2, 2>::new(1.0, t, 0.0, 1.0);
    let gamma = Vector::<2>::new(0.5 * t * t, t);
    let x0 = Vector::<2>::new(cfg.x0, cfg.v0);
    let initial = Gaussian::new(x0, Matrix::<2, 2>::identity() * cfg.p0)?;
    let mut st = ManeuverState::<2, 1, 1>::new(initial, cfg.glrt(f64::MAX)?);
    let mut x = x0;
    let mut out = Vec::new();
    let steps = (t_end / t).round() as usize;
    for k in 0..steps {
        let tk = k as f64 * t;
        let a = levels
            .iter()
            .rev()
            .find(|&&(from, _)| tk >= from - 1e-9)
            .map_or(0.0, |l| l.1);
        x = phi * x + gamma * a;
        let rep = ad.step(&mut st, t, &me, &Vector::<1>::new(x[0]))?;
        out.push(rep.max_statistic.map_or(f64::NAN, |m| m.0));
    }
    Ok(out)
}

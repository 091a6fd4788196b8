//! The "maneuver-1d" experiment of seed 001 (§5.1, Figs. 3–4): a 1-D constant-velocity
//! target that switches an acceleration on and off, tracked by the plain Kalman filter
//! and by the GLRT adaptive filter ([`ManeuverFilter`]) for several thresholds η.
//!
//! # Scenario (SPEC 001)
//! State `[x, v]`, `T` = 0.05 s, 160 plots (8 s), truth from `x₀ = [2000 m, 70 m/s]` with
//! velocity noise `Q = diag(0, 0.5)` (m/s)² per step ([`CvNoise::VelocityPerStep`]), plots
//! `y = x + v`, `R = (6 m)²`; every filter starts from `x₀ + N(0, P₀)`, `P₀ = diag(100, 100)`.
//! The acceleration `a` (default 210 m/s², SPEC's reading of "three times the velocity")
//! is held over `[t_k, t_k + T)` for every `t_k` inside a window `[on, off)`: case 1 on
//! 2.0–6.0 s, case 2 on 2.0–3.8 s and 5.0–6.4 s. The adaptive filter looks for a
//! persistent input through `B = [0, 1]ᵀ` (`Γ = [T²/2, T]ᵀ`) with window `M`, `N`.
//!
//! Seeds: run `i` draws from `ChaCha8Rng::seed_from_u64(i)`: the two prior draws, then per
//! step the velocity noise and the plot noise.
//!
//! # References
//! Lee & Kim (1987), seed 001, §5.1 and Figs. 3–4; SPEC.md section 001 ("maneuver-1d").

pub mod after_switch;

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{GaussianFilter, Kf};
use argus_motion_models::{Cv1D, CvNoise};
use argus_sensors::CartesianPosition;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

use argus_adaptive::{
    AdaptiveError, Compensation, FailureKind, GlrtConfig, ManeuverFilter, ManeuverState, ModelInput,
};

/// Case 1: acceleration on 2.0–6.0 s.
pub const CASE1: &[(f64, f64)] = &[(2.0, 6.0)];
/// Case 2: acceleration on 2.0–3.8 s and 5.0–6.4 s.
pub const CASE2: &[(f64, f64)] = &[(2.0, 3.8), (5.0, 6.4)];

/// The experiment's parameters (defaults: SPEC 001).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Maneuver1dConfig {
    /// Plot interval `T`, s.
    pub dt: f64,
    /// Number of plots.
    pub steps: usize,
    /// Initial true position, m.
    pub x0: f64,
    /// Initial true velocity, m/s.
    pub v0: f64,
    /// Prior variance of position and velocity (`P₀ = diag(p0, p0)`), m² and (m/s)².
    pub p0: f64,
    /// Velocity noise variance per step, (m/s)².
    pub q: f64,
    /// Plot noise variance, m².
    pub r: f64,
    /// Acceleration while a window is on, m/s².
    pub accel: f64,
    /// GLRT window `M` (steps).
    pub max_age: usize,
    /// GLRT shortest onset age `N` (steps).
    pub min_age: usize,
}

impl Default for Maneuver1dConfig {
    fn default() -> Self {
        Self {
            dt: 0.05,
            steps: 160,
            x0: 2000.0,
            v0: 70.0,
            p0: 100.0,
            q: 0.5,
            r: 36.0,
            accel: 210.0,
            max_age: 20,
            min_age: 5,
        }
    }
}

impl Maneuver1dConfig {
    /// Checks every field and that `η` is a valid threshold.
    ///
    /// # Errors
    /// [`AdaptiveError::InvalidParameter`] naming the first bad field;
    /// [`AdaptiveError::InvalidWindow`] for `N > M`.
    pub fn validate(&self, eta: f64) -> Result<(), AdaptiveError> {
        let bad = |what, value, reason| AdaptiveError::InvalidParameter {
            what,
            value,
            reason,
        };
        for (what, v) in [("dt", self.dt), ("p0", self.p0), ("r", self.r)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(bad(what, v, "must be finite and positive"));
            }
        }
        if !(self.q.is_finite() && self.q >= 0.0) {
            return Err(bad("q", self.q, "must be finite and non-negative"));
        }
        for (what, v) in [("x0", self.x0), ("v0", self.v0), ("accel", self.accel)] {
            if !v.is_finite() {
                return Err(bad(what, v, "must be finite"));
            }
        }
        if self.steps == 0 || self.steps > 10_000_000 {
            return Err(bad("steps", self.steps as f64, "must be between 1 and 1e7"));
        }
        self.glrt(eta)?;
        Ok(())
    }

    /// The GLRT configuration for threshold `eta`.
    ///
    /// # Errors
    /// As [`GlrtConfig::new`].
    pub fn glrt(&self, eta: f64) -> Result<GlrtConfig, AdaptiveError> {
        GlrtConfig::new(self.max_age, self.min_age, eta, FailureKind::Persistent)
    }

    /// Time of plot `k` (0-based): `(k + 1) T`.
    #[must_use]
    pub fn time(&self, k: usize) -> f64 {
        (k + 1) as f64 * self.dt
    }
}

/// Checks a set of acceleration windows: finite, `on < off`, increasing, not overlapping.
///
/// # Errors
/// [`AdaptiveError::InvalidParameter`] naming the bad bound.
pub fn validate_windows(windows: &[(f64, f64)]) -> Result<(), AdaptiveError> {
    let mut last = f64::NEG_INFINITY;
    for &(on, off) in windows {
        if !(on.is_finite() && off.is_finite() && on < off && on >= last) {
            return Err(AdaptiveError::InvalidParameter {
                what: "maneuver window (on, off)",
                value: on,
                reason: "bounds must be finite, on < off, windows increasing and disjoint",
            });
        }
        last = off;
    }
    Ok(())
}

/// Whether the acceleration is on over `[t, t + T)` (`t = k T`).
fn accel_on(windows: &[(f64, f64)], t: f64) -> bool {
    windows
        .iter()
        .any(|&(on, off)| t >= on - 1e-9 && t < off - 1e-9)
}

/// Whether plot time `t` lies inside a maneuver window, `t ∈ (on, off]`.
#[must_use]
pub fn inside(windows: &[(f64, f64)], t: f64) -> bool {
    windows
        .iter()
        .any(|&(on, off)| t > on + 1e-9 && t <= off + 1e-9)
}

/// One run's truth, plots and prior.
#[derive(Debug, Clone, PartialEq)]
pub struct Run1d {
    /// True states after each step.
    pub truth: Vec<Vector<2>>,
    /// Position plots.
    pub plots: Vec<f64>,
    /// The filters' common prior.
    pub initial: Gaussian<2>,
}

/// Simulates run `seed` (see the module docs for the draw order).
///
/// # Errors
/// [`AdaptiveError`] for a bad configuration or windows.
pub fn simulate(
    cfg: &Maneuver1dConfig,
    windows: &[(f64, f64)],
    seed: u64,
) -> Result<Run1d, AdaptiveError> {
    validate_windows(windows)?;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut n = || -> f64 { StandardNormal.sample(&mut rng) };
    let sd0 = cfg.p0.sqrt();
    let init_mean = Vector::<2>::new(cfg.x0 + sd0 * n(), cfg.v0 + sd0 * n());
    let t = cfg.dt;
    let phi = Matrix::<2, 2>::new(1.0, t, 0.0, 1.0);
    let gamma = Vector::<2>::new(0.5 * t * t, t);
    let mut x = Vector::<2>::new(cfg.x0, cfg.v0);
    let mut truth = Vec::with_capacity(cfg.steps);
    let mut plots = Vec::with_capacity(cfg.steps);
    for k in 0..cfg.steps {
        let a = if accel_on(windows, k as f64 * t) {
            cfg.accel
        } else {
            0.0
        };
        x = phi * x + gamma * a + Vector::<2>::new(0.0, cfg.q.sqrt() * n());
        truth.push(x);
        plots.push(x[0] + cfg.r.sqrt() * n());
    }
    Ok(Run1d {
        truth,
        plots,
        initial: Gaussian::new(init_mean, Matrix::<2, 2>::identity() * cfg.p0)?,
    })
}

/// The plain KF's and the adaptive filter's position errors, and the detections (part
/// of the scenario's per-run record).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Outcome1d {
    /// Plain KF position error per plot, m.
    pub kf_err: Vec<f64>,
    /// Adaptive filter position error per plot, m.
    pub ad_err: Vec<f64>,
    /// Plot indices (0-based) at which the adaptive filter applied a detection.
    pub detections: Vec<usize>,
}

/// Runs the plain KF and the adaptive filter (threshold `eta`, `compensation`) on `run`.
///
/// # Errors
/// [`AdaptiveError`] for a bad configuration or a failed filter step.
pub fn run_filters(
    cfg: &Maneuver1dConfig,
    run: &Run1d,
    eta: f64,
    compensation: Compensation,
) -> Result<Outcome1d, AdaptiveError> {
    cfg.validate(eta)?;
    let model = Cv1D::new(CvNoise::VelocityPerStep { q: cfg.q })?;
    let kf = Kf::new(model);
    let meas = CartesianPosition::<2, 1>::new([0], Matrix::<1, 1>::new(cfg.r))?;
    let ad = ManeuverFilter::new(
        kf,
        ModelInput::new(model, Matrix::<2, 1>::new(0.0, 1.0))?,
        compensation,
    );
    let mut est = run.initial;
    let mut st = ManeuverState::<2, 1, 1>::new(run.initial, cfg.glrt(eta)?);
    let mut out = Outcome1d {
        kf_err: Vec::with_capacity(run.plots.len()),
        ad_err: Vec::with_capacity(run.plots.len()),
        detections: Vec::new(),
    };
    for (k, (x, z)) in run.truth.iter().zip(&run.plots).enumerate() {
        let zv = Vector::<1>::new(*z);
        let pred = kf.predict(&est, cfg.dt)?;
        est = kf.update(&pred, &meas, &zv)?.0;
        let rep = ad.step(&mut st, cfg.dt, &meas, &zv)?;
        if rep.detection.is_some() {
            out.detections.push(k);
        }
        out.kf_err.push(est.mean()[0] - x[0]);
        out.ad_err.push(st.estimate().mean()[0] - x[0]);
    }
    Ok(out)
}

/// Monte Carlo statistics of one (windows, η, compensation) campaign.
#[derive(Debug, Clone, PartialEq)]
pub struct Stats1d {
    /// Runs.
    pub runs: usize,
    /// RMS position error of the KF over plots inside the windows, m.
    pub rms_in_kf: f64,
    /// RMS position error of the adaptive filter inside the windows, m.
    pub rms_in_ad: f64,
    /// RMS position error of the KF outside the windows, m.
    pub rms_out_kf: f64,
    /// RMS position error of the adaptive filter outside the windows, m.
    pub rms_out_ad: f64,
    /// Switch times (on, off, on, off, …), s.
    pub switches: Vec<f64>,
    /// Per switch, per run: first detection after the switch (before the next one)
    /// minus the switch time, s; `None` when missed.
    pub delays: Vec<Vec<Option<f64>>>,
    /// Detections at or before the first switch, summed over runs (all detections when
    /// there is no window).
    pub false_alarms: usize,
    /// Per-time RMS over runs (KF, adaptive), m.
    pub rms_per_time: Vec<(f64, f64)>,
}

impl Stats1d {
    /// Reduces outcomes of the same configuration.
    #[must_use]
    pub fn from_outcomes(
        cfg: &Maneuver1dConfig,
        windows: &[(f64, f64)],
        outcomes: &[Outcome1d],
    ) -> Self {
        let switches: Vec<f64> = windows.iter().flat_map(|&(on, off)| [on, off]).collect();
        let (mut in_kf, mut in_ad, mut out_kf, mut out_ad, mut n_in, mut n_out) =
            (0.0, 0.0, 0.0, 0.0, 0usize, 0usize);
        let mut per_time = vec![(0.0, 0.0); cfg.steps];
        let mut delays = vec![Vec::with_capacity(outcomes.len()); switches.len()];
        let mut false_alarms = 0;
        let first = switches.first().copied().unwrap_or(f64::INFINITY);
        for o in outcomes {
            for (k, (ek, ea)) in o.kf_err.iter().zip(&o.ad_err).enumerate() {
                if inside(windows, cfg.time(k)) {
                    in_kf += ek * ek;
                    in_ad += ea * ea;
                    n_in += 1;
                } else {
                    out_kf += ek * ek;
                    out_ad += ea * ea;
                    n_out += 1;
                }
                if let Some(p) = per_time.get_mut(k) {
                    p.0 += ek * ek;
                    p.1 += ea * ea;
                }
            }
            let times: Vec<f64> = o.detections.iter().map(|&k| cfg.time(k)).collect();
            false_alarms += times.iter().filter(|&&t| t <= first + 1e-9).count();
            for (i, &s) in switches.iter().enumerate() {
                let next = switches.get(i + 1).copied().unwrap_or(f64::INFINITY);
                let d = times
                    .iter()
                    .find(|&&t| t > s + 1e-9 && t <= next + 1e-9)
                    .map(|t| t - s);
                if let Some(v) = delays.get_mut(i) {
                    v.push(d);
                }
            }
        }
        let rms = |s: f64, n: usize| {
            if n == 0 {
                f64::NAN
            } else {
                (s / n as f64).sqrt()
            }
        };
        let m = outcomes.len();
        Self {
            runs: m,
            rms_in_kf: rms(in_kf, n_in),
            rms_in_ad: rms(in_ad, n_in),
            rms_out_kf: rms(out_kf, n_out),
            rms_out_ad: rms(out_ad, n_out),
            switches,
            delays,
            false_alarms,
            rms_per_time: per_time
                .iter()
                .map(|&(a, b)| (rms(a, m), rms(b, m)))
                .collect(),
        }
    }

    /// The delays of switch `i` that were detected, sorted, s.
    #[must_use]
    pub fn detected_delays(&self, i: usize) -> Vec<f64> {
        let mut d: Vec<f64> = self
            .delays
            .get(i)
            .map(|v| v.iter().flatten().copied().collect())
            .unwrap_or_default();
        d.sort_by(f64::total_cmp);
        d
    }

    /// Runs in which switch `i` was missed.
    #[must_use]
    pub fn missed(&self, i: usize) -> usize {
        self.delays
            .get(i)
            .map_or(0, |v| v.iter().filter(|d| d.is_none()).count())
    }

    /// Over all switches and runs: the fraction detected within `limit` seconds
    /// (a missed switch counts as not within).
    #[must_use]
    pub fn fraction_within(&self, limit: f64) -> f64 {
        let all: Vec<&Option<f64>> = self.delays.iter().flatten().collect();
        let hit = all
            .iter()
            .filter(|d| d.is_some_and(|d| d <= limit + 1e-9))
            .count();
        hit as f64 / all.len().max(1) as f64
    }

    /// The mean of switch `i`'s detected delays, s (NaN when none was detected). A missed
    /// switch is not in the mean: see [`Stats1d::missed`] and [`Stats1d::delay_p95`].
    #[must_use]
    pub fn delay_mean(&self, i: usize) -> f64 {
        let d = self.detected_delays(i);
        if d.is_empty() {
            f64::NAN
        } else {
            d.iter().sum::<f64>() / d.len() as f64
        }
    }

    /// The 95th percentile (nearest rank) of switch `i`'s delay over all runs, a missed
    /// switch counting as never detected: `+∞` when more than 5 % of the runs missed it.
    #[must_use]
    pub fn delay_p95(&self, i: usize) -> f64 {
        let mut d: Vec<f64> = self
            .delays
            .get(i)
            .map(|v| v.iter().map(|d| d.unwrap_or(f64::INFINITY)).collect())
            .unwrap_or_default();
        d.sort_by(f64::total_cmp);
        quantile(&d, 0.95)
    }

    /// The `p`-quantile (nearest rank, `0 ≤ p ≤ 1`) of the detected delays pooled over
    /// switches, s (NaN when nothing was detected).
    #[must_use]
    pub fn delay_quantile(&self, p: f64) -> f64 {
        let mut d: Vec<f64> = self.delays.iter().flatten().flatten().copied().collect();
        d.sort_by(f64::total_cmp);
        quantile(&d, p)
    }
}

/// The noise-free GLRT statistic `λ(τ)` a time `τ` after an onset at `on` (s) from the
/// steady running of the plain filter: the plots are the noise-free truth with the
/// acceleration switched on at `on`, the detector never fires (η = ∞ in effect) and its
/// window is the whole run (`N = 0`), so `λ` is the largest statistic over all onsets,
/// that of the true onset up to the filter's start-up. The statistic at the true onset is
/// non-central χ²(1) with non-centrality `λ`, so a detection by `τ` has probability
/// ≈ `Φ(√λ − √η)` ([`within_derived`]).
///
/// # Errors
/// [`AdaptiveError`] for a bad configuration or when `on + τ` is not a plot time of the run.
pub fn noise_free_statistic(
    cfg: &Maneuver1dConfig,
    on: f64,
    tau: f64,
) -> Result<f64, AdaptiveError> {
    let windows = [(on, f64::MAX)];
    validate_windows(&windows)?;
    let target = on + tau;
    let k_end = (0..cfg.steps)
        .find(|&k| (cfg.time(k) - target).abs() < 1e-9)
        .ok_or(AdaptiveError::InvalidParameter {
            what: "noise-free statistic time (on + tau)",
            value: target,
            reason: "must be a plot time of the run",
        })?;
    let quiet = Maneuver1dConfig {
        q: 0.0,
        max_age: k_end + 1,
        min_age: 0,
        ..*cfg
    };
    let model = Cv1D::new(CvNoise::VelocityPerStep { q: cfg.q })?;
    let meas = CartesianPosition::<2, 1>::new([0], Matrix::<1, 1>::new(cfg.r))?;
    let ad = ManeuverFilter::new(
        Kf::new(model),
        ModelInput::new(model, Matrix::<2, 1>::new(0.0, 1.0))?,
        Compensation::Glrt,
    );
    let x0 = Vector::<2>::new(cfg.x0, cfg.v0);
    let initial = Gaussian::new(x0, Matrix::<2, 2>::identity() * cfg.p0)?;
    let mut st = ManeuverState::<2, 1, 1>::new(initial, quiet.glrt(f64::MAX)?);
    let t = cfg.dt;
    let phi = Matrix::<2, 2>::new(1.0, t, 0.0, 1.0);
    let gamma = Vector::<2>::new(0.5 * t * t, t);
    let mut x = x0;
    let mut lambda = f64::NAN;
    for k in 0..=k_end {
        let a = if accel_on(&windows, k as f64 * t) {
            cfg.accel
        } else {
            0.0
        };
        x = phi * x + gamma * a;
        let rep = ad.step(&mut st, t, &meas, &Vector::<1>::new(x[0]))?;
        lambda = rep.max_statistic.map_or(f64::NAN, |m| m.0);
    }
    Ok(lambda)
}

/// The standard normal CDF `Φ(x)` (from the χ²(1) CDF: `Φ(x) = ½ (1 + sign x · F_χ²₁(x²))`).
#[must_use]
pub fn normal_cdf(x: f64) -> f64 {
    if !x.is_finite() {
        return if x > 0.0 {
            1.0
        } else if x < 0.0 {
            0.0
        } else {
            f64::NAN
        };
    }
    let c = argus_core_math::chi2_cdf(x * x, 1.0).unwrap_or(f64::NAN);
    0.5 * (1.0 + x.signum() * c)
}

/// The derived chance of a detection within `τ` of a switch, `Φ(√λ(τ) − √η)`, from the
/// noise-free statistic `λ(τ)` ([`noise_free_statistic`]).
#[must_use]
pub fn within_derived(lambda: f64, eta: f64) -> f64 {
    normal_cdf(lambda.sqrt() - eta.sqrt())
}

/// Nearest-rank quantile of sorted data (NaN when empty).
#[must_use]
pub fn quantile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() || !p.is_finite() {
        return f64::NAN;
    }
    let rank = (p.clamp(0.0, 1.0) * sorted.len() as f64).ceil() as usize;
    sorted
        .get(rank.saturating_sub(1))
        .copied()
        .unwrap_or(f64::NAN)
}

/// Runs `runs` seeds sequentially and reduces them (for tests; the CLI runs in parallel).
///
/// # Errors
/// As [`simulate`] and [`run_filters`].
pub fn monte_carlo(
    cfg: &Maneuver1dConfig,
    windows: &[(f64, f64)],
    eta: f64,
    compensation: Compensation,
    runs: std::ops::Range<u64>,
) -> Result<Stats1d, AdaptiveError> {
    let outcomes = runs
        .map(|s| simulate(cfg, windows, s).and_then(|r| run_filters(cfg, &r, eta, compensation)))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Stats1d::from_outcomes(cfg, windows, &outcomes))
}

//! The "drag-bearing" experiment of seed 001 (§5.2, Figs. 5–7): a planar target with
//! quadratic drag seen by a bearing-only sensor at the origin, tracked by a
//! continuous–discrete EKF and a truncated second-order filter, each plain and each
//! with GLRT maneuver detection plus MRAS input estimation.
//!
//! # Scenario (every open choice is ours and stated here)
//! - Motion (seed 001 §5.2): `v̇ = −α v |v| + u + w`, state `[x, vx, y, vy]`, SI units
//!   (the paper's feet converted: 1 ft = 0.3048 m). α is not given in the paper: we take
//!   [`DragBearingConfig::alpha`] = 0.01 1/m, which makes the turn settle in ≈ 15 s
//!   (velocity time constants `1/(2α|v|)` ≈ 4 s along and `1/(α|v|)` ≈ 8 s across the
//!   track at the final speed).
//! - Truth: start at (10 000, 10 000) ft = (3048, 3048) m with velocity (20, 20) ft/s
//!   (20√2 ft/s heading 45°). The target cruises: its thrust balances the drag,
//!   `u₀ = α |v₀| v₀`. At [`DragBearingConfig::turn_time`] (50 s, "about 50 s") the thrust
//!   steps to `u₁ = α |v₁| v₁`, `v₁` = (30, −30) ft/s (30√2 ft/s, 90° to the right), whose
//!   terminal velocity under drag is `v₁`: the turn is the drag-limited response to a
//!   persistent input change `Δu = u₁ − u₀` — exactly the GLRT's persistent-input
//!   hypothesis, with `B = [[0,0],[1,0],[0,0],[0,1]]` as in the paper's equation.
//!   Velocity white noise of spectral density `q` (Euler–Maruyama on 0.05 s substeps
//!   after an RK4 drift step).
//! - Sensor: bearing `atan2(y, x) + v`, `v ~ N(0, σ²)`, every `dt`.
//! - Filters: all use the true α and `q` and carry the cruise thrust `u₀` as a known
//!   input (the target was tracked in cruise before the scenario starts); the unknown
//!   input is the thrust change. The range is not observable before the turn (the
//!   target moves along the line of sight), so every filter starts from a prior drawn
//!   around the truth: mean `x₀ + N(0, P₀)`, `P₀ = diag(σp², σv², σp², σv²)`.
//!   EKF = [`CdEkf`] first order; TSOF = [`CdEkf`] with the drift correction and the
//!   second-order update (the truncated second-order filter, Gelb Table 6.1-2).
//! - Detector: persistent input `P = 2`, window `M`, `N`, threshold `η`
//!   ([`DragBearingConfig`]), [`Compensation::GlrtMras`].
//!
//! A run is a pure function of its seed ([`simulate_run`]); `McSummary` (in `statistics.rs`) reduces runs.
//!
//! # References
//! Lee & Kim (1987), seed 001, §5.2 and Figs. 5–7; SPEC.md section 001 ("drag-bearing").

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{CdEkf, GaussianFilter};
use argus_motion_models::{MotionModel, QuadraticDrag};
use argus_sensors::Bearing2D;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

use argus_adaptive::{
    AdaptiveError, Compensation, FailureKind, GlrtConfig, ManeuverFilter, ManeuverState, ModelInput,
};

/// Feet to metres.
pub const FT: f64 = 0.3048;

/// Truth substep for the simulation, seconds.
const TRUTH_STEP: f64 = 0.05;

/// The experiment's parameters (defaults: see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DragBearingConfig {
    /// Plot interval, s.
    pub dt: f64,
    /// Length of a run, s.
    pub duration: f64,
    /// Time of the thrust change, s.
    pub turn_time: f64,
    /// Drag coefficient α, 1/m.
    pub alpha: f64,
    /// Velocity white-noise spectral density `q`, m²/s³ (truth and filters).
    pub q: f64,
    /// Bearing noise standard deviation, rad.
    pub sigma_bearing: f64,
    /// Prior position standard deviation per axis, m.
    pub sigma_pos0: f64,
    /// Prior velocity standard deviation per axis, m/s.
    pub sigma_vel0: f64,
    /// RK4 substeps per filter prediction.
    pub substeps: usize,
    /// GLRT window `M` (steps).
    pub max_age: usize,
    /// GLRT shortest onset age `N` (steps).
    pub min_age: usize,
    /// GLRT threshold η.
    pub eta: f64,
    /// Prior standard deviation of each thrust-change component, m/s²: the detector's
    /// estimate is `(C + I/σu²)⁻¹ d` (seed 001 eq 4-6 with `L(0) = σu² I`), since the
    /// along-line-of-sight component is barely observable from bearings.
    pub sigma_input: f64,
}

impl Default for DragBearingConfig {
    fn default() -> Self {
        Self {
            dt: 1.0,
            duration: 120.0,
            turn_time: 50.0,
            alpha: 0.01,
            q: 1e-4,
            sigma_bearing: 0.2_f64.to_radians(),
            sigma_pos0: 100.0,
            sigma_vel0: 0.5,
            substeps: 10,
            max_age: 20,
            min_age: 2,
            eta: 20.0,
            sigma_input: 2.0,
        }
    }
}

fn positive(what: &'static str, value: f64) -> Result<f64, AdaptiveError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(AdaptiveError::InvalidParameter {
            what,
            value,
            reason: "must be finite and positive",
        })
    }
}

impl DragBearingConfig {
    /// Checks every field.
    ///
    /// # Errors
    /// [`AdaptiveError::InvalidParameter`] naming the first bad field (non-finite, not
    /// positive, the turn outside the run, fewer than one plot, zero substeps);
    /// [`AdaptiveError::InvalidWindow`] / [`AdaptiveError::InvalidParameter`] for the GLRT
    /// window and threshold.
    pub fn validate(&self) -> Result<(), AdaptiveError> {
        positive("dt", self.dt)?;
        positive("duration", self.duration)?;
        positive("sigma_bearing", self.sigma_bearing)?;
        positive("sigma_pos0", self.sigma_pos0)?;
        positive("sigma_vel0", self.sigma_vel0)?;
        positive("sigma_input", self.sigma_input)?;
        for (what, v) in [("alpha", self.alpha), ("q", self.q)] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(AdaptiveError::InvalidParameter {
                    what,
                    value: v,
                    reason: "must be finite and non-negative",
                });
            }
        }
        if !(self.turn_time.is_finite() && self.turn_time > 0.0 && self.turn_time < self.duration) {
            return Err(AdaptiveError::InvalidParameter {
                what: "turn_time",
                value: self.turn_time,
                reason: "must lie inside (0, duration)",
            });
        }
        if self.steps() == 0 || self.steps() > 1_000_000 {
            return Err(AdaptiveError::InvalidParameter {
                what: "duration / dt",
                value: self.duration / self.dt,
                reason: "must give between 1 and 1e6 plots",
            });
        }
        if self.substeps == 0 || self.substeps > argus_filters::MAX_SUBSTEPS {
            return Err(AdaptiveError::InvalidParameter {
                what: "substeps",
                value: self.substeps as f64,
                reason: "must be between 1 and MAX_SUBSTEPS",
            });
        }
        self.glrt()?;
        Ok(())
    }

    /// The number of plots `⌊duration / dt⌋` (plots at `t_k = k dt`, `k = 1..=steps`).
    #[must_use]
    pub fn steps(&self) -> usize {
        let n = (self.duration / self.dt + 1e-9).floor();
        if n.is_finite() && n >= 0.0 {
            n as usize
        } else {
            0
        }
    }

    /// The GLRT configuration (persistent input).
    ///
    /// # Errors
    /// As [`GlrtConfig::new`].
    pub fn glrt(&self) -> Result<GlrtConfig, AdaptiveError> {
        GlrtConfig::new(
            self.max_age,
            self.min_age,
            self.eta,
            FailureKind::Persistent,
        )
    }

    /// The initial true state `[x, vx, y, vy]`: (10 000, 10 000) ft, (20, 20) ft/s.
    #[must_use]
    pub fn initial_truth(&self) -> Vector<4> {
        Vector::<4>::new(10_000.0 * FT, 20.0 * FT, 10_000.0 * FT, 20.0 * FT)
    }

    /// The final cruise velocity (30, −30) ft/s.
    #[must_use]
    pub fn final_velocity(&self) -> Vector<2> {
        Vector::<2>::new(30.0 * FT, -30.0 * FT)
    }

    /// The cruise thrust `α |v| v` that balances the drag at velocity `v`.
    #[must_use]
    pub fn cruise_thrust(&self, v: &Vector<2>) -> Vector<2> {
        v * (self.alpha * v.norm())
    }

    /// The thrust before the turn, `u₀`.
    #[must_use]
    pub fn thrust_before(&self) -> Vector<2> {
        let x0 = self.initial_truth();
        self.cruise_thrust(&Vector::<2>::new(x0[1], x0[3]))
    }

    /// The thrust after the turn, `u₁`.
    #[must_use]
    pub fn thrust_after(&self) -> Vector<2> {
        self.cruise_thrust(&self.final_velocity())
    }

    /// The prior covariance `P₀`.
    #[must_use]
    pub fn prior_cov(&self) -> Matrix<4, 4> {
        let (p, v) = (self.sigma_pos0.powi(2), self.sigma_vel0.powi(2));
        Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(p, v, p, v))
    }

    /// The filters' motion model: drag α, noise `q`, known input `u₀`.
    ///
    /// # Errors
    /// [`AdaptiveError::Motion`] for a bad α or `q`.
    pub fn filter_model(&self) -> Result<QuadraticDrag, AdaptiveError> {
        Ok(QuadraticDrag::new(self.alpha, self.q)?.with_input(self.thrust_before())?)
    }

    /// The bearing sensor at the origin.
    ///
    /// # Errors
    /// [`AdaptiveError::Sensor`] for a bad σ.
    pub fn sensor(&self) -> Result<Bearing2D<4>, AdaptiveError> {
        Ok(Bearing2D::cv([0.0, 0.0], self.sigma_bearing)?)
    }
}

/// The filters compared.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DragFilter {
    /// Continuous–discrete EKF, no maneuver detection.
    Ekf,
    /// Truncated second-order filter, no maneuver detection.
    Tsof,
    /// EKF with GLRT detection and MRAS input estimation.
    EkfGlrtMras,
    /// Truncated second-order filter with GLRT detection and MRAS input estimation.
    TsofGlrtMras,
}

impl DragFilter {
    /// All filters, in report order ([`DragFilter::index`]).
    pub const ALL: [Self; 4] = [Self::Ekf, Self::Tsof, Self::EkfGlrtMras, Self::TsofGlrtMras];

    /// Position in [`DragFilter::ALL`].
    #[must_use]
    pub fn index(self) -> usize {
        match self {
            Self::Ekf => 0,
            Self::Tsof => 1,
            Self::EkfGlrtMras => 2,
            Self::TsofGlrtMras => 3,
        }
    }

    /// Short name.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Ekf => "EKF",
            Self::Tsof => "TSOF",
            Self::EkfGlrtMras => "EKF+GLRT+MRAS",
            Self::TsofGlrtMras => "TSOF+GLRT+MRAS",
        }
    }

    /// Whether it detects and estimates the input.
    #[must_use]
    pub fn adaptive(self) -> bool {
        matches!(self, Self::EkfGlrtMras | Self::TsofGlrtMras)
    }

    fn second_order(self) -> bool {
        matches!(self, Self::Tsof | Self::TsofGlrtMras)
    }
}

/// One run: the truth, every filter's estimates and the adaptive filters' detections.
#[derive(Debug, Clone, PartialEq)]
pub struct DragRun {
    /// Plot times `t_k = k dt`, s.
    pub times: Vec<f64>,
    /// True states at the plot times.
    pub truth: Vec<Vector<4>>,
    /// Per filter ([`DragFilter::index`]), the estimated mean after each plot.
    pub estimates: [Vec<Vector<4>>; 4],
    /// Per filter, the plot indices (0-based) at which a detection was applied.
    pub detections: [Vec<usize>; 4],
    /// Per filter, the final input estimate (the carried thrust change), if any.
    pub final_input: [Option<Vector<2>>; 4],
    /// Per filter, the first plot index at which its step failed (the filter then
    /// coasts on predictions), if any.
    pub failed_at: [Option<usize>; 4],
}

impl DragRun {
    /// Position error `|p̂ − p|` of `filter` at plot `k`.
    #[must_use]
    pub fn position_error(&self, filter: DragFilter, k: usize) -> Option<f64> {
        let x = self.truth.get(k)?;
        let e = self.estimates.get(filter.index())?.get(k)?;
        Some((e[0] - x[0]).hypot(e[2] - x[2]))
    }

    /// Range error `|p̂| − |p|` of `filter` at plot `k`.
    #[must_use]
    pub fn range_error(&self, filter: DragFilter, k: usize) -> Option<f64> {
        let x = self.truth.get(k)?;
        let e = self.estimates.get(filter.index())?.get(k)?;
        Some(e[0].hypot(e[2]) - x[0].hypot(x[2]))
    }
}

type Adaptive = ManeuverFilter<CdEkf<QuadraticDrag>, ModelInput<QuadraticDrag, 4, 2>>;

fn inner_filter(
    cfg: &DragBearingConfig,
    model: QuadraticDrag,
    second_order: bool,
) -> Result<CdEkf<QuadraticDrag>, AdaptiveError> {
    Ok(CdEkf::new(model, cfg.substeps)?
        .with_drift_correction(second_order)
        .with_second_order_update(second_order))
}

/// The simulated part of a run.
struct Simulated {
    times: Vec<f64>,
    truth: Vec<Vector<4>>,
    plots: Vec<f64>,
    prior_mean: Vector<4>,
}

/// Simulates the truth and the plots of run `seed`, and the prior's mean.
fn simulate_truth(
    cfg: &DragBearingConfig,
    rng: &mut ChaCha8Rng,
) -> Result<Simulated, AdaptiveError> {
    let mut n = || -> f64 { StandardNormal.sample(rng) };
    let before = QuadraticDrag::new(cfg.alpha, 0.0)?.with_input(cfg.thrust_before())?;
    let after = QuadraticDrag::new(cfg.alpha, 0.0)?.with_input(cfg.thrust_after())?;
    let steps = cfg.steps();
    let sub = (cfg.dt / TRUTH_STEP).ceil().max(1.0);
    let h = cfg.dt / sub;
    let sub = sub as usize;
    let sd_w = (cfg.q * h).sqrt();
    let x0 = cfg.initial_truth();
    let p0 = cfg.prior_cov();
    let prior_mean = Vector::<4>::from_fn(|i, _| x0[i] + p0[(i, i)].sqrt() * n());
    let mut x = x0;
    let mut t = 0.0_f64;
    let (mut times, mut truth, mut plots) = (
        Vec::with_capacity(steps),
        Vec::with_capacity(steps),
        Vec::with_capacity(steps),
    );
    for k in 1..=steps {
        for _ in 0..sub {
            let model = if t + 1e-9 < cfg.turn_time {
                &before
            } else {
                &after
            };
            x = model.propagate(&x, h);
            x[1] += sd_w * n();
            x[3] += sd_w * n();
            t += h;
        }
        let tk = k as f64 * cfg.dt;
        argus_core_math::check_finite_vector(&x, "simulated true state")?;
        times.push(tk);
        truth.push(x);
        plots.push(x[2].atan2(x[0]) + cfg.sigma_bearing * n());
    }
    Ok(Simulated {
        times,
        truth,
        plots,
        prior_mean,
    })
}

/// The noise-free true states at the plot times `k dt`, `k = 0..=steps` (the first is
/// the initial state): the reference trajectory of Figs. 5–7.
///
/// # Errors
/// [`AdaptiveError`] for an invalid configuration.
pub fn reference_trajectory(cfg: &DragBearingConfig) -> Result<Vec<Vector<4>>, AdaptiveError> {
    cfg.validate()?;
    let quiet = DragBearingConfig { q: 0.0, ..*cfg };
    let sim = simulate_truth(&quiet, &mut ChaCha8Rng::seed_from_u64(0))?;
    let mut out = Vec::with_capacity(sim.truth.len() + 1);
    out.push(cfg.initial_truth());
    out.extend(sim.truth);
    Ok(out)
}

/// One Monte Carlo run with seed `seed` (`ChaCha8Rng::seed_from_u64(seed)`): truth,
/// plots, and the four filters of [`DragFilter::ALL`] from the same prior.
///
/// A filter whose step fails (a non-PD covariance after a wild input estimate, say) is
/// recorded in [`DragRun::failed_at`] and from then on coasts on predictions (its last
/// estimate is kept if even the prediction fails); the run itself does not fail.
///
/// # Errors
/// [`AdaptiveError`] for an invalid configuration or a non-finite simulated state.
pub fn simulate_run(cfg: &DragBearingConfig, seed: u64) -> Result<DragRun, AdaptiveError> {
    cfg.validate()?;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let Simulated {
        times,
        truth,
        plots,
        prior_mean,
    } = simulate_truth(cfg, &mut rng)?;
    let prior = Gaussian::new(prior_mean, cfg.prior_cov())?;
    let model = cfg.filter_model()?;
    let sensor = cfg.sensor()?;
    #[rustfmt::skip]
    let b = Matrix::<4, 2>::new(
        0.0, 0.0,
        1.0, 0.0,
        0.0, 0.0,
        0.0, 1.0,
    );
    let glrt = cfg.glrt()?;
    let mut estimates: [Vec<Vector<4>>; 4] =
        std::array::from_fn(|_| Vec::with_capacity(plots.len()));
    let mut detections: [Vec<usize>; 4] = std::array::from_fn(|_| Vec::new());
    let mut final_input = [None; 4];
    let mut failed_at = [None; 4];
    for f in DragFilter::ALL {
        let i = f.index();
        let inner = inner_filter(cfg, model, f.second_order())?;
        let (Some(est_i), Some(det_i), Some(fail_i), Some(inp_i)) = (
            estimates.get_mut(i),
            detections.get_mut(i),
            failed_at.get_mut(i),
            final_input.get_mut(i),
        ) else {
            continue;
        };
        if f.adaptive() {
            let ad: Adaptive =
                ManeuverFilter::new(inner, ModelInput::new(model, b)?, Compensation::GlrtMras);
            let mut st = ManeuverState::<4, 1, 2>::new(prior, glrt)
                .with_input_prior(Matrix::<2, 2>::identity() / cfg.sigma_input.powi(2))?;
            for (k, z) in plots.iter().enumerate() {
                let zv = Vector::<1>::new(*z);
                if fail_i.is_none() {
                    match ad.step(&mut st, cfg.dt, &sensor, &zv) {
                        Ok(rep) => {
                            if rep.detection.is_some() {
                                det_i.push(k);
                            }
                            est_i.push(*st.estimate().mean());
                            continue;
                        }
                        Err(_) => *fail_i = Some(k),
                    }
                }
                let last = est_i.last().copied().unwrap_or(*prior.mean());
                est_i.push(model.propagate(&last, cfg.dt));
            }
            *inp_i = st.input_estimate();
        } else {
            let mut est = prior;
            for (k, z) in plots.iter().enumerate() {
                let zv = Vector::<1>::new(*z);
                let step = inner
                    .predict(&est, cfg.dt)
                    .and_then(|p| inner.update(&p, &sensor, &zv));
                match (step, fail_i.is_none()) {
                    (Ok((post, _)), true) => est = post,
                    (_, true) => {
                        *fail_i = Some(k);
                        est = inner.predict(&est, cfg.dt).unwrap_or(est);
                    }
                    (_, false) => est = inner.predict(&est, cfg.dt).unwrap_or(est),
                }
                est_i.push(*est.mean());
            }
        }
    }
    Ok(DragRun {
        times,
        truth,
        estimates,
        detections,
        final_input,
        failed_at,
    })
}

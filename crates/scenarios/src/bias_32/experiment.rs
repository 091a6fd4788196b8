//! The bias-32 scenario of SPEC §004 and its generalisation to `S` sensors and `N`
//! targets, as a library function: one Monte Carlo run of truth, biased plots, the
//! proposed registration, EXX and compensation, with the caller supplying standard
//! normal draws (so the library needs no random-number crate), plus the aggregation of
//! runs into RMSE and NEES time series.
//!
//! Truth: each target moves in a straight line at constant velocity (no process noise;
//! the filters' DCWNA `q̃` is their model only), so EXX's state elimination is exact.

use argus_core_math::{Gaussian, Matrix, SpdFactor, Vector};

use argus_registration::{
    BiasedTrack, Initiation, Linearization, PolarSensor, Registrar, RegistrarConfig,
    RegistrationError, position_matrix,
};

use argus_registration::{check_finite as finite, check_positive as positive};
use argus_sensors::PolarBias;

/// One sensor of the scenario: the radar, its true bias and its schedule.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SensorSetup {
    /// The radar.
    pub sensor: PolarSensor,
    /// Its true bias.
    pub bias: PolarBias,
    /// Scan period (s).
    pub period: f64,
    /// Time of its first plot (s).
    pub offset: f64,
}

/// A registration scenario.
#[derive(Debug, Clone, PartialEq)]
pub struct ScenarioConfig {
    /// The sensors.
    pub sensors: Vec<SensorSetup>,
    /// Initial target states `[x, vx, y, vy]` at `t = 0`, in target-number order.
    pub targets: Vec<Vector<4>>,
    /// Last plot time (s).
    pub duration: f64,
    /// Local filters' DCWNA PSD `q̃` (m²/s³).
    pub q_tilde: f64,
    /// Prior bias covariance of each sensor (prior mean 0).
    pub prior_cov: Matrix<4, 4>,
    /// Covariance of the bias-free initial track error (initiation [`Initiation::Given`]).
    pub init_cov: Matrix<4, 4>,
    /// Where `B`, `C`, `R` are evaluated.
    pub linearization: Linearization,
    /// How local tracks start.
    pub initiation: Initiation,
    /// Run the EXX baseline too.
    pub run_exx: bool,
    /// Targets (0-based) whose sensor-0 track errors are recorded.
    pub recorded: Vec<usize>,
}

impl ScenarioConfig {
    /// The bias-32 scenario of SPEC §004: sensors at (0, 0) and (10 km, 0), period 1 s,
    /// first plots at 1 s and 0.5 s (none at the start t = 0), σr = 10 m, σθ = 1 mrad,
    /// β = [20 m, 2 mrad, 3e-5, 2e-4] for
    /// both; 32 targets at (20, 20) m/s on the 4 × 8 grid numbered by distance from sensor
    /// 1; q̃ = 6; Σ₀ = diag(100², 0.2², 0.01², 0.1²); bias-free starts from
    /// N(truth, diag(10², 5², 10², 5²)) (the paper's `diag(10², 10², 5², 5²)` in
    /// `[x, y, vx, vy]` order); 300 s; tracks 1 and 32 recorded.
    ///
    /// # Errors
    /// Never for these constants; kept fallible because the constructors are.
    pub fn bias32() -> Result<Self, RegistrationError> {
        let mut c = Self::grid(2, 32)?;
        c.recorded = vec![0, 31];
        Ok(c)
    }

    /// `sensors` sensors at (10 km·s, 0), period 1 s, offsets `s / sensors` s (sensor 0:
    /// 1 s, its first scan after the start, not t = 0), and `targets`
    /// targets on an 8-column grid (`x₀ = 1 km + 2 km·c`, `y₀ = 5 km + 10 km·r`) numbered by
    /// distance from sensor 1; every other setting as [`Self::bias32`]. Only target 0 is recorded.
    ///
    /// # Errors
    /// [`RegistrationError::Empty`] for zero sensors or targets.
    pub fn grid(sensors: usize, targets: usize) -> Result<Self, RegistrationError> {
        if sensors == 0 {
            return Err(RegistrationError::Empty { what: "sensor set" });
        }
        if targets == 0 {
            return Err(RegistrationError::Empty { what: "target set" });
        }
        let bias = PolarBias::new(20.0, 2e-3, 3e-5, 2e-4)?;
        let sensors = (0..sensors)
            .map(|s| {
                Ok(SensorSetup {
                    sensor: PolarSensor::new(
                        Vector::<2>::new(10_000.0 * s as f64, 0.0),
                        10.0,
                        1e-3,
                    )?,
                    bias,
                    period: 1.0,
                    // First plot one scan after the tracks start at t = 0 (SPEC §004:
                    // 300 plots per radar in 300 s; sensor 2 at 0.5 s, …, 299.5 s).
                    offset: if s == 0 {
                        1.0
                    } else {
                        s as f64 / sensors as f64
                    },
                })
            })
            .collect::<Result<Vec<_>, RegistrationError>>()?;
        let mut pts: Vec<Vector<4>> = (0..targets)
            .map(|k| {
                let (r, c) = (k / 8, k % 8);
                Vector::<4>::new(
                    1_000.0 + 2_000.0 * c as f64,
                    20.0,
                    5_000.0 + 10_000.0 * r as f64,
                    20.0,
                )
            })
            .collect();
        pts.sort_by(|a, b| (a[0].hypot(a[2])).total_cmp(&b[0].hypot(b[2])));
        Ok(Self {
            sensors,
            targets: pts,
            duration: 300.0,
            q_tilde: 6.0,
            prior_cov: Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(1e4, 0.04, 1e-4, 1e-2)),
            init_cov: Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(100.0, 25.0, 100.0, 25.0)),
            linearization: Linearization::default(),
            initiation: Initiation::Given,
            run_exx: true,
            recorded: vec![0],
        })
    }

    /// Checks the configuration.
    ///
    /// # Errors
    /// [`RegistrationError::Empty`], [`RegistrationError::NonFinite`],
    /// [`RegistrationError::InvalidParameter`], [`RegistrationError::Math`] naming the field.
    pub fn validate(&self) -> Result<(), RegistrationError> {
        if self.sensors.is_empty() {
            return Err(RegistrationError::Empty { what: "sensor set" });
        }
        if self.targets.is_empty() {
            return Err(RegistrationError::Empty { what: "target set" });
        }
        for s in &self.sensors {
            positive("sensor period", s.period)?;
            finite("sensor offset", s.offset)?;
        }
        for x in &self.targets {
            argus_core_math::check_finite_vector(x, "target initial state")?;
        }
        positive("duration", self.duration)?;
        SpdFactor::new(&self.init_cov, "initial track covariance")?;
        SpdFactor::new(&self.prior_cov, "prior bias covariance")?;
        for &r in &self.recorded {
            if r >= self.targets.len() {
                return Err(RegistrationError::InvalidParameter {
                    what: "recorded target",
                    value: r as f64,
                    reason: "out of range",
                });
            }
        }
        Ok(())
    }

    /// The true state of target `t` at `time`.
    #[must_use]
    pub fn truth(&self, t: usize, time: f64) -> Vector<4> {
        let x = self
            .targets
            .get(t)
            .copied()
            .unwrap_or_else(Vector::<4>::zeros);
        Vector::<4>::new(x[0] + x[1] * time, x[1], x[2] + x[3] * time, x[3])
    }

    /// All plot events `(time, sensor)` in time order (ties by sensor index).
    #[must_use]
    pub fn events(&self) -> Vec<(f64, usize)> {
        let mut ev = Vec::new();
        for (s, setup) in self.sensors.iter().enumerate() {
            let mut k = 0u32;
            loop {
                let t = setup.offset + f64::from(k) * setup.period;
                if t > self.duration + 1e-9 {
                    break;
                }
                if t >= 0.0 {
                    ev.push((t, s));
                }
                k += 1;
            }
        }
        ev.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        ev
    }

    /// The stacked true bias `[β₁; …; β_S]`.
    #[must_use]
    pub fn true_stacked_bias(&self) -> Vec<f64> {
        self.sensors
            .iter()
            .flat_map(|s| s.bias.as_vector().iter().copied().collect::<Vec<_>>())
            .collect()
    }
}

/// Squared errors of one recorded sensor-0 track at sensor 0's plot times.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TrackRecord {
    /// The target (0-based).
    pub target: usize,
    /// Times (s).
    pub times: Vec<f64>,
    /// Squared position error of the biased track `X̂ᵇ`.
    pub pos_biased: Vec<f64>,
    /// Squared position error of the compensated track `X̂ᵇ − G β̂`.
    pub pos_compensated: Vec<f64>,
    /// Squared position error of the same filter on bias-free plots (same noise).
    pub pos_reference: Vec<f64>,
    /// Squared velocity error of the biased track.
    pub vel_biased: Vec<f64>,
    /// Squared velocity error of the compensated track.
    pub vel_compensated: Vec<f64>,
    /// Squared velocity error of the reference filter.
    pub vel_reference: Vec<f64>,
    /// NEES of the compensated track (4 degrees of freedom).
    pub nees_compensated: Vec<f64>,
}

/// What one Monte Carlo run produced (the scenario's per-run record, per cell).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RunRecord {
    /// Event times (s), after all plots of that time were processed.
    pub times: Vec<f64>,
    /// Per time, per bias component: squared error summed over sensors (proposed).
    pub proposed_sq: Vec<[f64; 4]>,
    /// Per time: NEES of the stacked proposed estimate (`4S` degrees of freedom).
    pub proposed_nees: Vec<f64>,
    /// Per time, per bias component: the proposed estimator's own variance `Σ_kk`
    /// summed over sensors (what it predicts for `proposed_sq`).
    pub proposed_var: Vec<[f64; 4]>,
    /// As `proposed_sq`, for EXX (empty when EXX does not run).
    pub exx_sq: Vec<[f64; 4]>,
    /// As `proposed_nees`, for EXX.
    pub exx_nees: Vec<f64>,
    /// The stacked error `b − b̂` of the proposed estimate after the last plot (`4S`).
    pub proposed_final_error: Vec<f64>,
    /// The recorded tracks.
    pub tracks: Vec<TrackRecord>,
    /// Number of plots processed.
    pub plots: usize,
    /// Number of pseudo-measurement updates of the proposed estimator.
    pub proposed_updates: usize,
}

fn sq_by_component(est: &argus_registration::BiasEstimator, truth: &[f64]) -> [f64; 4] {
    let b = est.stacked();
    let mut out = [0.0; 4];
    for (i, t) in truth.iter().enumerate() {
        let e = t - b[(i, 0)];
        if let Some(o) = out.get_mut(i % 4) {
            *o += e * e;
        }
    }
    out
}

fn var_by_component(est: &argus_registration::BiasEstimator) -> [f64; 4] {
    let sig = est.covariance();
    let mut out = [0.0; 4];
    for i in 0..sig.nrows() {
        if let Some(o) = out.get_mut(i % 4) {
            *o += sig[(i, i)];
        }
    }
    out
}

fn pos_vel_sq(x: &Vector<4>, truth: &Vector<4>) -> (f64, f64) {
    let e = x - truth;
    (e[0] * e[0] + e[2] * e[2], e[1] * e[1] + e[3] * e[3])
}

/// Runs the scenario once. `normal` must return independent standard normal draws.
///
/// # Errors
/// As [`ScenarioConfig::validate`] and [`Registrar::process`].
pub fn run(
    config: &ScenarioConfig,
    normal: &mut impl FnMut() -> f64,
) -> Result<RunRecord, RegistrationError> {
    config.validate()?;
    let n = config.targets.len();
    let s_count = config.sensors.len();
    let mut reg = Registrar::new(RegistrarConfig {
        sensors: config.sensors.iter().map(|s| s.sensor).collect(),
        targets: n,
        q_tilde: config.q_tilde,
        prior_cov: config.prior_cov,
        linearization: config.linearization,
        initiation: config.initiation,
        run_exx: config.run_exx,
    })?;
    let l = SpdFactor::new(&config.init_cov, "initial track covariance")?.l();
    let draw4 = |normal: &mut dyn FnMut() -> f64| Vector::<4>::from_fn(|_, _| normal());
    // Reference tracks on bias-free plots for the recorded targets (sensor 0).
    let mut reference: Vec<Option<BiasedTrack>> = vec![None; config.recorded.len()];
    let mut ref_pending: Vec<Option<argus_registration::ConvertedPlot>> =
        vec![None; config.recorded.len()];
    if config.initiation == Initiation::Given {
        for s in 0..s_count {
            for t in 0..n {
                let x = config.truth(t, 0.0) + l * draw4(normal);
                let tr = BiasedTrack::bias_free(Gaussian::new(x, config.init_cov)?, 0.0)?;
                reg.set_track(s, t, tr)?;
                if s == 0
                    && let Some(k) = config.recorded.iter().position(|&r| r == t)
                    && let Some(slot) = reference.get_mut(k)
                {
                    *slot = Some(tr);
                }
            }
        }
    }
    let truth_bias = config.true_stacked_bias();
    let mut rec = RunRecord {
        tracks: config
            .recorded
            .iter()
            .map(|&t| TrackRecord {
                target: t,
                ..TrackRecord::default()
            })
            .collect(),
        ..RunRecord::default()
    };
    let zero = PolarBias::zero();
    let filter = *reg.filter();
    for (time, s) in config.events() {
        let Some(setup) = config.sensors.get(s) else {
            continue;
        };
        for t in 0..n {
            let x = config.truth(t, time);
            let p = Vector::<2>::new(x[0], x[2]);
            let (nr, nt) = (normal(), normal());
            let plot = setup.sensor.biased_plot(&p, &setup.bias, nr, nt)?;
            reg.process(s, t, time, &plot)?;
            rec.plots += 1;
            if s != 0 {
                continue;
            }
            let Some(k) = config.recorded.iter().position(|&r| r == t) else {
                continue;
            };
            // Reference: same noise, no bias.
            let clean = setup.sensor.biased_plot(&p, &zero, nr, nt)?;
            let (Some(slot), Some(pend), Some(tr_rec)) = (
                reference.get_mut(k),
                ref_pending.get_mut(k),
                rec.tracks.get_mut(k),
            ) else {
                continue;
            };
            let at = match (config.linearization, slot.as_ref()) {
                (Linearization::AtPrediction, Some(r)) => {
                    Some(position_matrix() * filter.predict(r, time)?.estimate().mean())
                }
                _ => None,
            };
            let conv = setup.sensor.convert(time, &clean, at.as_ref())?;
            *slot = match (slot.as_ref(), pend.as_ref()) {
                (Some(r), _) => Some(filter.update(r, &conv)?),
                (None, Some(first)) => Some(BiasedTrack::two_point(first, &conv)?),
                (None, None) => {
                    *pend = Some(conv);
                    None
                }
            };
            let (Some(track), Some(comp), Some(refr)) =
                (reg.track(0, t), reg.compensated(0, t)?, slot.as_ref())
            else {
                continue;
            };
            let (pb, vb) = pos_vel_sq(track.estimate().mean(), &x);
            let (pc, vc) = pos_vel_sq(comp.mean(), &x);
            let (pr, vr) = pos_vel_sq(refr.estimate().mean(), &x);
            tr_rec.times.push(time);
            tr_rec.pos_biased.push(pb);
            tr_rec.vel_biased.push(vb);
            tr_rec.pos_compensated.push(pc);
            tr_rec.vel_compensated.push(vc);
            tr_rec.pos_reference.push(pr);
            tr_rec.vel_reference.push(vr);
            tr_rec.nees_compensated.push(comp.mahalanobis_sq(&x));
        }
        rec.times.push(time);
        rec.proposed_sq
            .push(sq_by_component(reg.proposed(), &truth_bias));
        rec.proposed_nees.push(reg.proposed().nees(&truth_bias)?);
        rec.proposed_var.push(var_by_component(reg.proposed()));
        if let Some(e) = reg.exx() {
            rec.exx_sq.push(sq_by_component(e, &truth_bias));
            rec.exx_nees.push(e.nees(&truth_bias)?);
        }
    }
    rec.proposed_updates = reg.proposed().updates();
    let b = reg.proposed().stacked();
    rec.proposed_final_error = truth_bias
        .iter()
        .enumerate()
        .map(|(i, t)| t - b[(i, 0)])
        .collect();
    Ok(rec)
}

/// Monte Carlo averages over runs of one scenario.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Summary {
    /// Event times (s).
    pub times: Vec<f64>,
    /// Per time: RMSE of each bias component over runs and sensors (proposed).
    pub proposed_rmse: Vec<[f64; 4]>,
    /// Per time: the RMSE the proposed estimator predicts for itself, `sqrt(mean Σ_kk)`
    /// over runs and sensors, per bias component.
    pub proposed_predicted: Vec<[f64; 4]>,
    /// Per time: average NEES of the stacked proposed estimate.
    pub proposed_anees: Vec<f64>,
    /// As `proposed_rmse`, for EXX.
    pub exx_rmse: Vec<[f64; 4]>,
    /// As `proposed_anees`, for EXX.
    pub exx_anees: Vec<f64>,
    /// Per recorded track: times and RMSE series (position biased / compensated /
    /// reference, velocity likewise) and the average compensated NEES.
    pub tracks: Vec<TrackSummary>,
    /// Runs averaged.
    pub runs: usize,
    /// Stacked bias dimension `4S` (the NEES degrees of freedom).
    pub bias_dim: usize,
}

/// RMSE series of one recorded track.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TrackSummary {
    /// The target (0-based).
    pub target: usize,
    /// Times (s).
    pub times: Vec<f64>,
    /// Position RMSE of the biased track.
    pub pos_biased: Vec<f64>,
    /// Position RMSE after compensation.
    pub pos_compensated: Vec<f64>,
    /// Position RMSE of the filter on bias-free plots.
    pub pos_reference: Vec<f64>,
    /// Velocity RMSE of the biased track.
    pub vel_biased: Vec<f64>,
    /// Velocity RMSE after compensation.
    pub vel_compensated: Vec<f64>,
    /// Velocity RMSE of the filter on bias-free plots.
    pub vel_reference: Vec<f64>,
    /// Average NEES of the compensated track.
    pub anees_compensated: Vec<f64>,
}

impl Summary {
    /// The index of the last time not after `time` (0 if none).
    #[must_use]
    pub fn index_at(&self, time: f64) -> usize {
        self.times
            .iter()
            .rposition(|&t| t <= time + 1e-9)
            .unwrap_or(0)
    }
}

//! Tracker configuration, validated once by [`crate::Tracker::new`].

use argus_imm::{AircraftTuning, Augmentation, PROBABILITY_SUM_TOL};

use crate::field::{AssociationField, ConfigField, EstimatorField, ScoreField, SensorField};
use crate::{Rotation, SensorId, TrackerError};

/// Everything the tracker needs to know. Build it with [`TrackerConfig::new`] (the
/// defaults below) and change the public fields; [`crate::Tracker::new`] validates it.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackerConfig {
    /// The sensors whose plots are accepted (at least one, ids distinct): where each
    /// stands and, for polar plots, its noise.
    pub sensors: Vec<SensorConfig>,
    /// White-noise acceleration standard deviation of each track's CV model (m/s²).
    /// Default 2.
    pub sigma_a: f64,
    /// Gate probability `P_G` of the chi-square gate on the 2-D innovation. Default 0.99.
    pub gate_probability: f64,
    /// Largest target speed for two-point initiation (m/s). Default 350.
    pub max_speed: f64,
    /// Noise allowance of the velocity gate, in standard deviations of the plot
    /// difference: a plot pair `(z₁, z₂)` seeds a track when
    /// `‖z₂ − z₁‖ ≤ v_max Δt + k √tr(R₁ + R₂)`. Default 3.
    pub velocity_gate_sigmas: f64,
    /// Oldest unused plot kept as the first point of a two-point initiation (s).
    /// Default 12 (two scans at 5 s, with margin).
    pub max_initiation_interval: f64,
    /// Confirmation by M of the first N opportunities (the two initiating plots count
    /// as the first two hits). Default 3.
    pub confirm_m: u32,
    /// See [`TrackerConfig::confirm_m`]. Default 4.
    pub confirm_n: u32,
    /// A confirmed track is deleted at this many consecutive misses. Default 3.
    pub max_misses: u32,
    /// Any track is deleted when the standard deviation along its worst position axis
    /// (the square root of the largest eigenvalue of the position covariance) exceeds
    /// this (m). Default 5000.
    pub max_position_sigma: f64,
    /// Side of the square cells of the plot grid used for gating (m). About the gate
    /// size of a confirmed track is best; a poor value costs time, never correctness.
    /// Default 2000.
    pub grid_cell: f64,
    /// Track-score (SPRT) management instead of M-of-N when `Some`. Default `None`.
    pub score: Option<ScoreConfig>,
    /// The estimator each track runs. Default [`EstimatorConfig::Kf`].
    pub estimator: EstimatorConfig,
    /// How confirmed tracks use the plots. Default [`AssociationConfig::Gnn`].
    pub association: AssociationConfig,
    /// The fraction of a revolution of a rotating sensor ([`SensorConfig::rotation`])
    /// processed as one sector, in (0, 1]. Default 1/8. Unused without rotating sensors.
    pub sector_fraction: f64,
}

/// One sensor: its id, its position and, if it sends polar plots, their noise.
///
/// A [`crate::Plot::cartesian`] plot is a global position with its own covariance and does
/// not use the position or the noise. A [`crate::Plot::polar`] plot `(r, θ)` is relative to
/// [`SensorConfig::position`] (θ counter-clockwise from +x) with the standard deviations of
/// [`SensorConfig::polar_noise`]; a sensor without them cannot send polar plots.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SensorConfig {
    /// Its id.
    pub id: SensorId,
    /// Its position `(x, y)` (m), finite.
    pub position: [f64; 2],
    /// The noise of its polar plots (`None`: it sends Cartesian plots only).
    pub polar_noise: Option<PolarNoise>,
    /// `Some` for a rotating radar whose plots each have their own time (processed by
    /// sectors, see the crate docs); `None` (the default) for a sensor whose plots come
    /// in synchronous scans (all plots of a scan at one time).
    pub rotation: Option<Rotation>,
}

/// Standard deviations of a polar plot's range and azimuth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PolarNoise {
    /// `σ_r` (m), finite and positive.
    pub sigma_range: f64,
    /// `σ_θ` (rad), finite and positive.
    pub sigma_azimuth: f64,
}

impl SensorConfig {
    /// A sensor of Cartesian plots only (position: the origin, unused).
    #[must_use]
    pub fn cartesian(id: SensorId) -> Self {
        Self {
            id,
            position: [0.0, 0.0],
            polar_noise: None,
            rotation: None,
        }
    }

    /// A polar radar at `position` (m) with `σ_r` (m) and `σ_θ` (rad); it may also send
    /// Cartesian plots. Checked by [`crate::Tracker::new`].
    #[must_use]
    pub fn polar(id: SensorId, position: [f64; 2], sigma_range: f64, sigma_azimuth: f64) -> Self {
        Self {
            id,
            position,
            polar_noise: Some(PolarNoise {
                sigma_range,
                sigma_azimuth,
            }),
            rotation: None,
        }
    }

    /// This sensor as a rotating radar ([`SensorConfig::rotation`]).
    #[must_use]
    pub fn with_rotation(self, rotation: Rotation) -> Self {
        Self {
            rotation: Some(rotation),
            ..self
        }
    }

    fn validate(&self) -> Result<(), TrackerError> {
        let bad = |field, value: f64, reason| {
            Err(TrackerError::InvalidConfig {
                field,
                value,
                reason,
            })
        };
        for v in self.position {
            if !v.is_finite() {
                return bad(
                    ConfigField::Sensor(SensorField::Position),
                    v,
                    "must be finite",
                );
            }
        }
        if let Some(n) = &self.polar_noise {
            for (field, v) in [
                (ConfigField::Sensor(SensorField::SigmaRange), n.sigma_range),
                (
                    ConfigField::Sensor(SensorField::SigmaAzimuth),
                    n.sigma_azimuth,
                ),
            ] {
                if !(v.is_finite() && v > 0.0) {
                    return bad(field, v, "must be finite and positive");
                }
            }
        }
        if let Some(r) = &self.rotation {
            r.validate()?;
        }
        Ok(())
    }
}

impl From<SensorId> for SensorConfig {
    /// [`SensorConfig::cartesian`].
    fn from(id: SensorId) -> Self {
        Self::cartesian(id)
    }
}

/// Association of plots to confirmed tracks (tentative tracks always use GNN).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AssociationConfig {
    /// Global nearest neighbour: optimal 2-D assignment per cluster.
    Gnn,
    /// Joint probabilistic data association per cluster of tracks sharing plots:
    /// exact events up to `max_exact_events` per cluster, Fitzgerald's cheap JPDA beyond
    /// (see the crate docs). Every plot in a confirmed track's gate is spent (no track is
    /// initiated from it). A track is updated with the moment-matched mixture of its
    /// per-plot Kalman (or EKF) updates and its prediction, weighted by the marginals.
    /// With [`EstimatorConfig::ImmCv2`] and [`EstimatorConfig::Aircraft`] this is
    /// IMM-JPDA (see the crate docs); not available with [`EstimatorConfig::MultiImm`].
    Jpda {
        /// Detection probability `P_D` in (0, 1].
        p_detection: f64,
        /// Clutter density `λ` (false plots per m² per scan), > 0.
        clutter_density: f64,
        /// Largest number of joint events enumerated exactly for one cluster (≥ 1).
        max_exact_events: usize,
    },
}

/// The per-track estimator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EstimatorConfig {
    /// A Kalman filter on the CV model with [`TrackerConfig::sigma_a`], updated with the
    /// (converted) Cartesian plots.
    Kf,
    /// An extended Kalman filter on the same CV model ([`argus_filters::Ekf`]): polar plots
    /// update it directly in `(r, θ)` through [`argus_sensors::Polar2D`] at the sensor's
    /// position, and are gated with its own `S`; Cartesian plots use the linear update.
    Ekf,
    /// A two-mode IMM of CV Kalman filters, a quiet mode (`sigma_a_low`) and a
    /// manoeuvre mode (`sigma_a_high`), with probability `p_stay` of staying in a mode
    /// from one scan to the next, both modes equally likely at initiation. A plot is
    /// gated when it is in some mode's gate (GNN's cost is its smallest normalised
    /// distance over the modes); the score uses the IMM's total likelihood.
    ImmCv2 {
        /// Acceleration standard deviation of the quiet mode (m/s²).
        sigma_a_low: f64,
        /// Acceleration standard deviation of the manoeuvre mode (m/s²).
        sigma_a_high: f64,
        /// Probability of staying in a mode, in (0, 1).
        p_stay: f64,
    },
    /// Seed 000's multi-IMM measurement-noise estimator ([`argus_imm::MultiImm`]) per
    /// track: [`crate::MULTI_IMM_HYPOTHESES`] IMMs (each the two-mode CV IMM of
    /// [`EstimatorConfig::ImmCv2`]) assume the variances `(1 + (m − 2) p) σ²_ref`
    /// (eq 14, [`argus_imm::NoiseGrid::common`]); each polar plot updates all of them
    /// and moves the track's reference `σ²_ref` (eq 13), which starts at the configured
    /// polar noise of the sensor of its initiating plot and is read by
    /// [`crate::EstimatorState::noise_estimate`]. Every sensor must have polar noise and every plot
    /// must be polar; all sensors feeding a track share its one estimate. Gating and
    /// initiation use the plot converted with the configured noise; GNN only.
    MultiImm {
        /// Acceleration standard deviation of the quiet mode (m/s²).
        sigma_a_low: f64,
        /// Acceleration standard deviation of the manoeuvre mode (m/s²).
        sigma_a_high: f64,
        /// Probability of staying in a mode, in (0, 1).
        p_stay: f64,
        /// Grid spacing `p` of the noise hypotheses, in (0, 0.5) (the paper: 0.1).
        grid_spacing: f64,
        /// Largest relative change of the reference per plot, in (0, 1), or `None`
        /// (the paper: 5 %).
        clip: Option<f64>,
    },
    /// The aircraft IMM ([`argus_imm::AircraftImm`], docs/aircraft-imm.md) per track: two
    /// CV modes on `[x, vx, y, vy]` and a coordinated turn with the turn rate as a state
    /// `[x, vx, y, vy, ω]`, mixed by Granström et al.'s rule, EKFs updated with the polar
    /// plot itself in `(r, θ)`. A plot is gated when it is in some mode's `(r, θ)` gate
    /// (GNN's cost: its smallest normalised distance over the modes); its likelihood, for
    /// the score, is the mode mixture `Σⱼ μ̄ⱼ N(νⱼ; 0, Sⱼ)` divided by the Jacobian `r`
    /// (per m², as the EKF's). A track starts from the two-point estimate of its
    /// initiating plots ([`argus_imm::AircraftTuning::start_from_cv`]).
    /// [`crate::TrackerConfig::sigma_a`] is not used. Every sensor must have polar noise
    /// and every plot must be polar. With JPDA each mode is updated with its own PDA
    /// mixture of its EKF updates, as the two-CV IMM's IMM-JPDA (see the crate docs).
    Aircraft {
        /// Its tuning (`AircraftTuning::default()` is the documented one).
        tuning: AircraftTuning<2, 3>,
    },
}

/// Track-score management: each track carries the log-likelihood ratio `L` of "target"
/// against "false track", tested sequentially (Wald's SPRT).
///
/// - first plot: `L = ln(β_NT / λ)`; second plot (initiation): `+ ln(P_D / (λ V_v))`, with
///   `V_v = π r²` the velocity gate's area (no velocity prior, so the second plot is
///   taken as uniform over it: an approximation);
/// - each later scan: a hit adds `ln(P_D / λ) + ln N(ν; 0, S)`, a miss adds
///   `ln(1 − P_D P_G)`;
/// - a tentative track is confirmed at `L ≥ ln((1 − β)/α)` and deleted at
///   `L ≤ ln(β/(1 − α))`; a confirmed track is deleted when `L` falls `delete_drop` below
///   its peak (and still by misses and covariance growth).
///
/// For a false track `exp(L)` after initiation is a non-negative supermartingale under
/// Poisson clutter of density `λ` (a hit's expected factor is `P_D P_G`, a miss's
/// `1 − P_D P_G`), so by Ville's inequality it is confirmed with probability at most
/// `exp(L₀ − ln((1 − β)/α))`, `L₀` its score at initiation.
///
/// # References
/// S. Blackman, R. Popoli, *Design and Analysis of Modern Tracking Systems*, Artech
/// House 1999, §6.2 (track score, eq. 6.11–6.13; SPRT thresholds); A. Wald,
/// *Sequential Analysis*, 1947.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScoreConfig {
    /// Detection probability `P_D` in (0, 1].
    pub p_detection: f64,
    /// Clutter density `λ` (false plots per m² per scan), > 0.
    pub clutter_density: f64,
    /// New-target density `β_NT` (per m² per scan), > 0.
    pub new_target_density: f64,
    /// `α`: probability of confirming a false track, in (0, 0.5).
    pub false_confirm: f64,
    /// `β`: probability of dropping a true tentative track, in (0, 0.5).
    pub missed_confirm: f64,
    /// A confirmed track is deleted when its score is this far below its peak (> 0).
    pub delete_drop: f64,
}

impl ScoreConfig {
    /// The confirmation threshold `ln((1 − β)/α)`.
    #[must_use]
    pub fn confirm_threshold(&self) -> f64 {
        ((1.0 - self.missed_confirm) / self.false_confirm).ln()
    }

    /// The tentative deletion threshold `ln(β/(1 − α))`.
    #[must_use]
    pub fn delete_threshold(&self) -> f64 {
        (self.missed_confirm / (1.0 - self.false_confirm)).ln()
    }

    fn validate(&self) -> Result<(), TrackerError> {
        let bad = |field, value: f64, reason| {
            Err(TrackerError::InvalidConfig {
                field,
                value,
                reason,
            })
        };
        let pd = self.p_detection;
        if !(pd.is_finite() && pd > 0.0 && pd <= 1.0) {
            return bad(
                ConfigField::Score(ScoreField::PDetection),
                pd,
                "must lie in (0, 1]",
            );
        }
        for (field, v) in [
            (
                ConfigField::Score(ScoreField::ClutterDensity),
                self.clutter_density,
            ),
            (
                ConfigField::Score(ScoreField::NewTargetDensity),
                self.new_target_density,
            ),
            (ConfigField::Score(ScoreField::DeleteDrop), self.delete_drop),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return bad(field, v, "must be finite and positive");
            }
        }
        for (field, v) in [
            (
                ConfigField::Score(ScoreField::FalseConfirm),
                self.false_confirm,
            ),
            (
                ConfigField::Score(ScoreField::MissedConfirm),
                self.missed_confirm,
            ),
        ] {
            if !(v.is_finite() && v > 0.0 && v < 0.5) {
                return bad(field, v, "must lie in (0, 0.5)");
            }
        }
        Ok(())
    }
}

impl TrackerConfig {
    /// The defaults listed on each field, for the given sensors (a [`SensorId`] alone is
    /// a Cartesian sensor, [`SensorConfig::cartesian`]).
    #[must_use]
    pub fn new<S: Into<SensorConfig>>(sensors: impl IntoIterator<Item = S>) -> Self {
        Self {
            sensors: sensors.into_iter().map(Into::into).collect(),
            sigma_a: 2.0,
            gate_probability: 0.99,
            max_speed: 350.0,
            velocity_gate_sigmas: 3.0,
            max_initiation_interval: 12.0,
            confirm_m: 3,
            confirm_n: 4,
            max_misses: 3,
            max_position_sigma: 5000.0,
            grid_cell: 2000.0,
            score: None,
            estimator: EstimatorConfig::Kf,
            association: AssociationConfig::Gnn,
            sector_fraction: 0.125,
        }
    }

    /// Checks every field.
    ///
    /// # Errors
    /// [`TrackerError::InvalidConfig`] naming the first bad field.
    pub fn validate(&self) -> Result<(), TrackerError> {
        let bad = |field, value: f64, reason| {
            Err(TrackerError::InvalidConfig {
                field,
                value,
                reason,
            })
        };
        if self.sensors.is_empty() {
            return bad(ConfigField::Sensors, 0.0, "at least one sensor is needed");
        }
        for (i, s) in self.sensors.iter().enumerate() {
            s.validate()?;
            if self.sensors[..i].iter().any(|o| o.id == s.id) {
                return bad(
                    ConfigField::Sensor(SensorField::Id),
                    f64::from(s.id.0),
                    "sensor ids must be distinct",
                );
            }
        }
        let positive = [
            (ConfigField::MaxSpeed, self.max_speed),
            (
                ConfigField::MaxInitiationInterval,
                self.max_initiation_interval,
            ),
            (ConfigField::MaxPositionSigma, self.max_position_sigma),
            (ConfigField::GridCell, self.grid_cell),
        ];
        for (field, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return bad(field, v, "must be finite and positive");
            }
        }
        for (field, v) in [
            (ConfigField::SigmaA, self.sigma_a),
            (ConfigField::VelocityGateSigmas, self.velocity_gate_sigmas),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return bad(field, v, "must be finite and non-negative");
            }
        }
        let p = self.gate_probability;
        if !(p.is_finite() && p > 0.0 && p < 1.0) {
            return bad(ConfigField::GateProbability, p, "must lie in (0, 1)");
        }
        if !(2..=32).contains(&self.confirm_n) {
            return bad(
                ConfigField::ConfirmN,
                f64::from(self.confirm_n),
                "must lie in 2..=32",
            );
        }
        if !(2..=self.confirm_n).contains(&self.confirm_m) {
            return bad(
                ConfigField::ConfirmM,
                f64::from(self.confirm_m),
                "must lie in 2..=confirm_n",
            );
        }
        if self.max_misses == 0 {
            return bad(ConfigField::MaxMisses, 0.0, "must be at least 1");
        }
        let f = self.sector_fraction;
        if !(f.is_finite() && f > 0.0 && f <= 1.0) {
            return bad(ConfigField::SectorFraction, f, "must lie in (0, 1]");
        }
        if let Some(score) = &self.score {
            score.validate()?;
        }
        let motion = match self.estimator {
            EstimatorConfig::Kf | EstimatorConfig::Ekf => None,
            EstimatorConfig::ImmCv2 {
                sigma_a_low,
                sigma_a_high,
                p_stay,
            } => Some((sigma_a_low, sigma_a_high, p_stay)),
            EstimatorConfig::MultiImm {
                sigma_a_low,
                sigma_a_high,
                p_stay,
                grid_spacing,
                clip,
            } => {
                if !(grid_spacing.is_finite() && grid_spacing > 0.0 && grid_spacing < 0.5) {
                    return bad(
                        ConfigField::Estimator(EstimatorField::GridSpacing),
                        grid_spacing,
                        "must lie in (0, 0.5)",
                    );
                }
                if let Some(c) = clip
                    && !(c.is_finite() && c > 0.0 && c < 1.0)
                {
                    return bad(
                        ConfigField::Estimator(EstimatorField::Clip),
                        c,
                        "must lie in (0, 1)",
                    );
                }
                if let Some(s) = self.sensors.iter().find(|s| s.polar_noise.is_none()) {
                    return bad(
                        ConfigField::Sensor(SensorField::PolarNoise),
                        f64::from(s.id.0),
                        "the multi-IMM needs every sensor's polar noise",
                    );
                }
                if let Some(r) = self.sensors.iter().find_map(|s| s.rotation) {
                    return bad(
                        ConfigField::Sensor(SensorField::RevolutionPeriod),
                        r.period,
                        "the multi-IMM with rotating sensors is not built",
                    );
                }
                Some((sigma_a_low, sigma_a_high, p_stay))
            }
            EstimatorConfig::Aircraft { tuning } => {
                validate_aircraft(&tuning)?;
                if let Some(s) = self.sensors.iter().find(|s| s.polar_noise.is_none()) {
                    return bad(
                        ConfigField::Sensor(SensorField::PolarNoise),
                        f64::from(s.id.0),
                        "the aircraft IMM needs every sensor's polar noise",
                    );
                }
                None
            }
        };
        if let Some((sigma_a_low, sigma_a_high, p_stay)) = motion {
            for (field, v) in [
                (
                    ConfigField::Estimator(EstimatorField::SigmaALow),
                    sigma_a_low,
                ),
                (
                    ConfigField::Estimator(EstimatorField::SigmaAHigh),
                    sigma_a_high,
                ),
            ] {
                if !(v.is_finite() && v >= 0.0) {
                    return bad(field, v, "must be finite and non-negative");
                }
            }
            if !(p_stay.is_finite() && p_stay > 0.0 && p_stay < 1.0) {
                return bad(
                    ConfigField::Estimator(EstimatorField::PStay),
                    p_stay,
                    "must lie in (0, 1)",
                );
            }
        }
        if let AssociationConfig::Jpda {
            p_detection,
            clutter_density,
            max_exact_events,
        } = self.association
        {
            if !(p_detection.is_finite() && p_detection > 0.0 && p_detection <= 1.0) {
                return bad(
                    ConfigField::Association(AssociationField::PDetection),
                    p_detection,
                    "must lie in (0, 1]",
                );
            }
            if !(clutter_density.is_finite() && clutter_density > 0.0) {
                return bad(
                    ConfigField::Association(AssociationField::ClutterDensity),
                    clutter_density,
                    "must be finite and positive",
                );
            }
            if max_exact_events == 0 {
                return bad(
                    ConfigField::Association(AssociationField::MaxExactEvents),
                    0.0,
                    "must be at least 1",
                );
            }
            if matches!(self.estimator, EstimatorConfig::MultiImm { .. }) {
                return bad(
                    ConfigField::Association(AssociationField::Kind),
                    0.0,
                    "JPDA with the multi-IMM estimator is not built",
                );
            }
        }
        Ok(())
    }
}

/// Checks the aircraft IMM's tuning field by field (what
/// [`argus_imm::AircraftTuning::build`] checks, each with its own [`EstimatorField`]).
fn validate_aircraft(t: &AircraftTuning<2, 3>) -> Result<(), TrackerError> {
    let bad = |field, value: f64, reason| {
        Err(TrackerError::InvalidConfig {
            field: ConfigField::Estimator(field),
            value,
            reason,
        })
    };
    let positive = t
        .cv_sigma_a
        .iter()
        .map(|&v| (EstimatorField::CvSigmaA, v))
        .chain([
            (EstimatorField::CtSigmaA, t.ct_sigma_a),
            (EstimatorField::CtSigmaOmega, t.ct_sigma_omega),
            (EstimatorField::StartSigmaOmega, t.start_sigma_omega),
        ]);
    for (field, v) in positive {
        if !(v.is_finite() && v > 0.0) {
            return bad(field, v, "must be finite and positive");
        }
    }
    for row in &t.markov {
        if let Some(&v) = row
            .iter()
            .find(|v| !(v.is_finite() && (0.0..=1.0).contains(*v)))
        {
            return bad(EstimatorField::Markov, v, "entries must lie in [0, 1]");
        }
        let sum: f64 = row.iter().sum();
        if (sum - 1.0).abs() > PROBABILITY_SUM_TOL {
            return bad(EstimatorField::Markov, sum, "each row must sum to 1");
        }
    }
    if let Some(&v) = t.start_mu.iter().find(|v| !(v.is_finite() && **v >= 0.0)) {
        return bad(
            EstimatorField::StartMu,
            v,
            "must be finite and non-negative",
        );
    }
    let sum: f64 = t.start_mu.iter().sum();
    if (sum - 1.0).abs() > PROBABILITY_SUM_TOL {
        return bad(EstimatorField::StartMu, sum, "must sum to 1");
    }
    if t.augmentation.validate().is_err() {
        let value = match t.augmentation {
            Augmentation::Fixed { sigma } => sigma,
            _ => f64::NAN,
        };
        return bad(
            EstimatorField::Augmentation,
            value,
            "its turn-rate sigma must be finite and positive",
        );
    }
    Ok(())
}

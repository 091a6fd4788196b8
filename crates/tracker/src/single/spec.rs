//! What the single-target engine is built from: the estimator's specification (checked by
//! the caller, e.g. `argus track`'s configuration, with every default filled in) and the
//! sensors the plots come from.

use argus_imm::AircraftTuning;
use argus_motion_models::PlanarModel;

/// A checked estimator: its kind and the CV model's white-acceleration σ (m/s²), or the
/// IMM (and multi-IMM) description. The KF and EKF are built for the plots' dimension
/// (2-D or 3-D CV); the IMMs are 2-D.
#[derive(Debug, Clone, PartialEq)]
pub enum EstimatorSpec {
    /// A Kalman filter on the CV model updated with converted plots (polar and spherical
    /// plots by the unbiased conversion), white-acceleration σ (m/s²).
    KfConverted(f64),
    /// An EKF on the CV model updated with polar (2-D) or spherical (3-D) plots
    /// themselves (Cartesian reports as converted plots), white-acceleration σ (m/s²).
    Ekf(f64),
    /// An IMM of Kalman filters on converted 2-D plots.
    Imm(ImmSpec),
    /// Seed 000's multi-IMM around the IMM, over one polar radar's plots.
    MultiImm(ImmSpec, MultiSpec),
    /// The aircraft IMM (two CV modes and the coordinated turn with its rate) over one
    /// 2-D radar's polar plots.
    Aircraft(AircraftTuning<2, 3>),
}

/// The largest number of motion models an IMM of [`EstimatorSpec::Imm`] may have (the
/// mode count is a compile-time size; 1 … 5 are built).
pub const MAX_MODELS: usize = argus_imm::MAX_PLANAR_MODES;

/// A checked IMM description: one planar motion model per mode, the Markov matrix (rows
/// of `models.len()` entries) and the initial mode probabilities.
#[derive(Debug, Clone, PartialEq)]
pub struct ImmSpec {
    /// The mode-matched models (CV or fixed-rate CT), each in a Kalman filter.
    pub models: Vec<PlanarModel>,
    /// `π_ij`, row by row.
    pub markov: Vec<Vec<f64>>,
    /// `μ₀`.
    pub initial: Vec<f64>,
}

/// The multi-IMM's parameters (seed 000 eqs (12)–(14), generalised).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MultiSpec {
    /// Hypotheses per axis (`n` IMMs with one common scale, `n²` with `per_axis`).
    pub n: usize,
    /// Grid spacing `p`.
    pub p: f64,
    /// Per-step clip of the reference's relative change (`None`: unclipped).
    pub clip: Option<f64>,
    /// Range and azimuth variances on an independent `n × n` grid.
    pub per_axis: bool,
}

impl MultiSpec {
    /// The defaults: the paper's five hypotheses on one scale, `p = 0.1`, ±5 % clip.
    pub const DEFAULT: Self = Self {
        n: 5,
        p: 0.1,
        clip: Some(0.05),
        per_axis: false,
    };
}

/// A sensor as the single-target engine sees it: its id, its position and the standard
/// deviations of its polar / spherical plots.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SingleSensor {
    /// Its number (the plots' [`argus_sensors::SensorId`]).
    pub id: u32,
    /// `[x, y, z]` (m; z = 0 for a sensor given in the plane).
    pub position: [f64; 3],
    /// Range σ (m), azimuth σ (rad); `None`: it sends Cartesian reports only.
    pub polar: Option<(f64, f64)>,
    /// Elevation σ (rad); `None`: it sends no spherical plots.
    pub sigma_elevation: Option<f64>,
}

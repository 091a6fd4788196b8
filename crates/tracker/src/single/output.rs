//! What a single-target run yields: one [`Estimate`] per row (one per plot from the
//! second, the two-point start's first), and which values the rows have ([`Columns`]).

use argus_core_math::Gaussian;
use argus_imm::NoiseVariances;

/// A plot fed to the engine with the caller's tag (e.g. its line in a plot file), by
/// which errors name it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TaggedPlot {
    /// The caller's tag.
    pub tag: u64,
    /// The plot.
    pub plot: argus_sensors::Plot,
}

impl TaggedPlot {
    /// Its time (s).
    pub(super) fn time(&self) -> f64 {
        self.plot.time()
    }

    /// Its sensor's number.
    pub(super) fn sensor(&self) -> u32 {
        self.plot.sensor().0
    }

    /// What it measured.
    pub(super) fn measurement(&self) -> &argus_sensors::Measurement {
        self.plot.measurement()
    }
}

/// One row's values: the estimate at a time (`N = 4`: `[x, vx, y, vy]`; `N = 6`:
/// `[x, vx, y, vy, z, vz]`) and what the estimator says beside it.
#[derive(Debug, Clone, PartialEq)]
pub struct Estimate<const N: usize> {
    /// The time (s): the row's plot's.
    pub time: f64,
    /// The (combined, for the IMMs) filtered estimate.
    pub state: Gaussian<N>,
    /// The IMMs' mode probabilities.
    pub modes: Option<Vec<f64>>,
    /// The multi-IMM's measurement-noise estimate.
    pub noise: Option<NoiseVariances>,
    /// The aircraft IMM's CT-mode turn rate and its σ (rad/s).
    pub turn_rate: Option<(f64, f64)>,
    /// With smoothing, the row's step's smoothed estimate (rows of one time share it).
    pub smoothed: Option<Gaussian<N>>,
    /// With smoothing, the IMMs' smoothed mode probabilities.
    pub smoothed_modes: Option<Vec<f64>>,
}

impl<const N: usize> Estimate<N> {
    /// The estimate `state` at `time`, with nothing beside it.
    pub(super) fn new(time: f64, state: Gaussian<N>) -> Self {
        Self {
            time,
            state,
            modes: None,
            noise: None,
            turn_rate: None,
            smoothed: None,
            smoothed_modes: None,
        }
    }
}

/// The rows of a run: 2-D or 3-D estimates.
#[derive(Debug, Clone, PartialEq)]
pub enum Estimates {
    /// 2-D plots: `[x, vx, y, vy]`.
    Planar(Vec<Estimate<4>>),
    /// 3-D plots (spherical or Cartesian 3-D): `[x, vx, y, vy, z, vz]`.
    Spatial(Vec<Estimate<6>>),
}

impl Estimates {
    /// The number of rows.
    #[must_use]
    pub fn len(&self) -> usize {
        match self {
            Self::Planar(e) => e.len(),
            Self::Spatial(e) => e.len(),
        }
    }

    /// No rows.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// Which values every row of a run has.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Columns {
    /// Position axes of the state (2 or 3).
    pub axes: usize,
    /// Mode probabilities per row (0 for the KF / EKF).
    pub modes: usize,
    /// The multi-IMM's noise estimate.
    pub noise: bool,
    /// The aircraft IMM's turn rate.
    pub turn_rate: bool,
    /// The smoothed estimate (and `modes` smoothed mode probabilities).
    pub smoothed: bool,
}

/// A single-target run's output.
#[derive(Debug, Clone, PartialEq)]
pub struct SingleRun {
    /// Which values the rows have.
    pub columns: Columns,
    /// One per row, in plot order.
    pub estimates: Estimates,
}

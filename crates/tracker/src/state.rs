//! Each track's estimator state ([`EstimatorState`]), one variant per kind of estimator.

use argus_imm::{AircraftEstimate, ImmEstimate, MultiImmEstimate, NoiseVariances};

/// Number of noise hypotheses `K` of [`crate::EstimatorConfig::MultiImm`] (seed 000: 5).
pub const MULTI_IMM_HYPOTHESES: usize = 5;

/// A track's multi-IMM state ([`EstimatorState::MultiImm`], boxed: it is large).
pub(crate) type MultiState = MultiImmEstimate<4, 2, MULTI_IMM_HYPOTHESES>;

/// A track's aircraft-IMM state ([`EstimatorState::Aircraft`]): two CV modes and the CT mode (boxed in the track: at
/// 584 bytes it would almost double every other estimator's track if it were inline).
pub(crate) type AircraftState = AircraftEstimate<2, 3>;

/// The most modes a track's estimator has (the aircraft IMM's three).
const MAX_MODES: usize = 3;

/// A track's IMM mode probabilities, in the estimator's mode order: (quiet, manoeuvre)
/// for [`crate::EstimatorConfig::ImmCv2`] and [`crate::EstimatorConfig::MultiImm`],
/// (CV quiet, CV manoeuvre, CT) for [`crate::EstimatorConfig::Aircraft`]. Read it as a
/// slice (`Deref<Target = [f64]>`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModeProbabilities {
    mu: [f64; MAX_MODES],
    len: usize,
}

impl ModeProbabilities {
    /// The first [`MAX_MODES`] of `p` (every estimator here has at most that many).
    fn of(p: &[f64]) -> Self {
        let len = p.len().min(MAX_MODES);
        let mut mu = [0.0; MAX_MODES];
        mu[..len].copy_from_slice(&p[..len]);
        Self { mu, len }
    }

    /// The probabilities as a slice.
    #[must_use]
    pub fn as_slice(&self) -> &[f64] {
        &self.mu[..self.len]
    }
}

impl std::ops::Deref for ModeProbabilities {
    type Target = [f64];
    fn deref(&self) -> &[f64] {
        self.as_slice()
    }
}

/// What a track's estimator keeps between scans besides the track's (combined) estimate
/// ([`crate::Track::estimate`]), one variant per [`crate::EstimatorConfig`] kind: read
/// it as [`crate::Track::state`] or on a session's snapshot
/// ([`crate::TrackSnapshot::state`]).
///
/// Each state is the estimator's at the track's time: after a plot the posterior (with
/// JPDA: the per-mode PDA moments), after a miss the mode predictions with `μ̄` as
/// probabilities. It is what a smoother of the track's forward pass needs (`argus track
/// --smooth`).
///
/// The IMM state stays inline, as it was in the track before this enum: boxing it would
/// add an allocation per track and an indirection per scan on the IMM path, and KF tracks
/// carried the same unused space in an `Option` then.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
pub enum EstimatorState {
    /// KF and EKF ([`crate::EstimatorConfig::Kf`], [`crate::EstimatorConfig::Ekf`]): the
    /// track's estimate is the whole state.
    Plain,
    /// The two-mode CV IMM ([`crate::EstimatorConfig::ImmCv2`]): the mode-conditioned
    /// estimates `x̂ⁱ, Pⁱ` and probabilities `μⁱ` (quiet, manoeuvre) of which the track's
    /// estimate is the moment match.
    Imm(ImmEstimate<4, 2>),
    /// The multi-IMM ([`crate::EstimatorConfig::MultiImm`]): its
    /// [`MULTI_IMM_HYPOTHESES`] IMM estimates, the noise-mode probabilities `νᵐ` and the
    /// noise reference ([`MultiImmEstimate::merged`]: the posterior merged over the noise
    /// hypotheses).
    MultiImm(Box<MultiImmEstimate<4, 2, MULTI_IMM_HYPOTHESES>>),
    /// The aircraft IMM ([`crate::EstimatorConfig::Aircraft`]): the CV modes' estimates on
    /// `[x, vx, y, vy]`, the CT mode's on `[x, vx, y, vy, ω]` and the mode probabilities
    /// (CV quiet, CV manoeuvre, CT).
    Aircraft(Box<AircraftEstimate<2, 3>>),
}

/// A copy of a track's estimator state taken out of its box, so that saving it and
/// restoring it allocates nothing (the sector's look prediction; see
/// `Tracker::saved`). Only the aircraft IMM needs it: the multi-IMM, whose state also
/// becomes its prediction, is refused with rotating sensors.
pub(crate) type SavedState = AircraftState;

impl EstimatorState {
    /// A copy of the aircraft IMM's state (`None` for every other estimator).
    pub(crate) fn save(&self) -> Option<SavedState> {
        match self {
            Self::Aircraft(a) => Some(**a),
            Self::Plain | Self::Imm(_) | Self::MultiImm(_) => None,
        }
    }

    /// Puts back a state [`Self::save`] copied (into the same box: nothing allocated).
    pub(crate) fn restore(&mut self, saved: SavedState) {
        if let Self::Aircraft(a) = self {
            **a = saved;
        }
    }

    /// The IMM mode probabilities when the estimator is an IMM (quiet, manoeuvre), a
    /// multi-IMM (the same, `Σₘ νᵐ μⱼᵐ`) or the aircraft IMM (CV quiet, CV manoeuvre,
    /// CT); `None` for KF and EKF.
    #[must_use]
    pub fn mode_probabilities(&self) -> Option<ModeProbabilities> {
        match self {
            Self::Plain => None,
            Self::Imm(imm) => Some(ModeProbabilities::of(&imm.mode_probabilities())),
            Self::MultiImm(m) => Some(ModeProbabilities::of(&m.mode_probabilities())),
            Self::Aircraft(a) => Some(ModeProbabilities::of(&a.mode_probabilities())),
        }
    }

    /// The multi-IMM's current measurement-noise estimate `(σ_r², σ_θ²)` (its reference
    /// variances, seed 000 eq 13); `None` for the other estimators.
    #[must_use]
    pub fn noise_estimate(&self) -> Option<NoiseVariances> {
        match self {
            Self::Plain | Self::Imm(_) | Self::Aircraft(_) => None,
            Self::MultiImm(m) => Some(*m.reference()),
        }
    }

    /// The aircraft IMM's turn-rate estimate and its standard deviation (rad/s,
    /// counter-clockwise positive): the CT mode's `ω̂` and `√P_ωω`, conditional on the CT
    /// mode; `None` for the other estimators.
    #[must_use]
    pub fn turn_rate(&self) -> Option<(f64, f64)> {
        match self {
            Self::Aircraft(a) => Some(a.turn_rate()),
            Self::Plain | Self::Imm(_) | Self::MultiImm(_) => None,
        }
    }
}

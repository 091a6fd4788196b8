//! Each track's estimator state, one variant per kind of [`crate::estimator::Estimator`].

use argus_imm::{AircraftEstimate, ImmEstimate, MultiImmEstimate, NoiseVariances};

/// Number of noise hypotheses `K` of [`crate::EstimatorConfig::MultiImm`] (seed 000: 5).
pub const MULTI_IMM_HYPOTHESES: usize = 5;

/// A track's multi-IMM state (boxed in the track: it is large).
pub(crate) type MultiState = MultiImmEstimate<4, 2, MULTI_IMM_HYPOTHESES>;

/// A track's aircraft-IMM state: two CV modes and the CT mode (boxed in the track: at
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

/// What a track's estimator keeps between scans besides the track's (combined) estimate.
///
/// The IMM state stays inline, as it was in the track before this enum: boxing it would
/// add an allocation per track and an indirection per scan on the IMM path, and KF tracks
/// carried the same unused space in an `Option` then.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum TrackState {
    /// KF and EKF: the track's estimate is the whole state.
    Single,
    /// The two-mode IMM's mode-conditioned estimates and probabilities.
    Imm(ImmEstimate<4, 2>),
    /// The multi-IMM's hypotheses and noise reference.
    Multi(Box<MultiState>),
    /// The aircraft IMM's modes and probabilities (between the prediction and the update
    /// of a scan: the predicted modes, with `μ̄` as probabilities).
    Aircraft(Box<AircraftState>),
}

/// A copy of a track's estimator state taken out of its box, so that saving it and
/// restoring it allocates nothing (the sector's look prediction; see
/// `Tracker::saved`). Only the aircraft IMM needs it: the multi-IMM, whose state also
/// becomes its prediction, is refused with rotating sensors.
pub(crate) type SavedState = AircraftState;

impl TrackState {
    /// A copy of the aircraft IMM's state (`None` for every other estimator).
    pub(crate) fn save(&self) -> Option<SavedState> {
        match self {
            Self::Aircraft(a) => Some(**a),
            Self::Single | Self::Imm(_) | Self::Multi(_) => None,
        }
    }

    /// Puts back a state [`Self::save`] copied (into the same box: nothing allocated).
    pub(crate) fn restore(&mut self, saved: SavedState) {
        if let Self::Aircraft(a) = self {
            **a = saved;
        }
    }

    /// The mode probabilities of an IMM, multi-IMM or aircraft-IMM state.
    pub(crate) fn mode_probabilities(&self) -> Option<ModeProbabilities> {
        match self {
            Self::Single => None,
            Self::Imm(imm) => Some(ModeProbabilities::of(&imm.mode_probabilities())),
            Self::Multi(m) => Some(ModeProbabilities::of(&m.mode_probabilities())),
            Self::Aircraft(a) => Some(ModeProbabilities::of(&a.mode_probabilities())),
        }
    }

    /// The two-mode CV IMM's mode-conditioned estimates and probabilities.
    pub(crate) fn imm_estimate(&self) -> Option<&ImmEstimate<4, 2>> {
        match self {
            Self::Imm(imm) => Some(imm),
            Self::Single | Self::Multi(_) | Self::Aircraft(_) => None,
        }
    }

    /// The multi-IMM's state: its `K` IMM estimates and noise-mode probabilities.
    pub(crate) fn multi_imm_estimate(&self) -> Option<&MultiState> {
        match self {
            Self::Multi(m) => Some(m),
            Self::Single | Self::Imm(_) | Self::Aircraft(_) => None,
        }
    }

    /// The aircraft IMM's mode-conditioned estimates and probabilities.
    pub(crate) fn aircraft_estimate(&self) -> Option<&AircraftState> {
        match self {
            Self::Aircraft(a) => Some(a),
            Self::Single | Self::Imm(_) | Self::Multi(_) => None,
        }
    }

    /// The multi-IMM's measurement-noise reference.
    pub(crate) fn noise_estimate(&self) -> Option<NoiseVariances> {
        match self {
            Self::Single | Self::Imm(_) | Self::Aircraft(_) => None,
            Self::Multi(m) => Some(*m.reference()),
        }
    }

    /// The aircraft IMM's CT-mode turn rate and its standard deviation (rad/s).
    pub(crate) fn turn_rate(&self) -> Option<(f64, f64)> {
        match self {
            Self::Aircraft(a) => Some(a.turn_rate()),
            Self::Single | Self::Imm(_) | Self::Multi(_) => None,
        }
    }
}

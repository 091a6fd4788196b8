//! Each track's estimator state, one variant per kind of [`crate::estimator::Estimator`].

use argus_imm::{ImmEstimate, MultiImmEstimate, NoiseVariances};

/// Number of noise hypotheses `K` of [`crate::EstimatorConfig::MultiImm`] (seed 000: 5).
pub const MULTI_IMM_HYPOTHESES: usize = 5;

/// A track's multi-IMM state (boxed in the track: it is large).
pub(crate) type MultiState = MultiImmEstimate<4, 2, MULTI_IMM_HYPOTHESES>;

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
}

impl TrackState {
    /// The mode probabilities (quiet, manoeuvre) of an IMM or multi-IMM state.
    pub(crate) fn mode_probabilities(&self) -> Option<[f64; 2]> {
        match self {
            Self::Single => None,
            Self::Imm(imm) => Some(imm.mode_probabilities()),
            Self::Multi(m) => Some(m.mode_probabilities()),
        }
    }

    /// The multi-IMM's measurement-noise reference.
    pub(crate) fn noise_estimate(&self) -> Option<NoiseVariances> {
        match self {
            Self::Single | Self::Imm(_) => None,
            Self::Multi(m) => Some(*m.reference()),
        }
    }
}

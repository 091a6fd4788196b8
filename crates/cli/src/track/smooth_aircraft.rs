//! `argus track --smooth` / `--smooth-lag` for the aircraft IMM (`aircraft-imm`): its
//! forward pass recorded one step per time ([`argus_imm::AircraftTrack`]) and smoothed by
//! `argus_imm`'s aircraft-IMM smoother ([`argus_imm::aircraft_smooth`]: Kim's pairwise
//! RTS form with backward-likelihood weights across the CV modes' 4 and the CT mode's 5
//! states), fixed interval or, by windows of the same backward pass, fixed lag — as
//! [`super::smooth_imm::ImmRecorder`] does for the `imm` kind.
//!
//! The record is formed from the posteriors (each transition recomputed from the
//! posterior of the time before with the IMM's own filters and mixing maps), so a
//! tracker's track rows give the same record as the single-target run over the same
//! plots.

use argus_imm::{AircraftEstimate, AircraftTrack};

use super::mode_record::ModeRecorder;

/// An aircraft-IMM forward pass being recorded for smoothing.
pub(super) type AircraftRecorder = ModeRecorder<AircraftTrack<2, 3>, AircraftEstimate<2, 3>>;

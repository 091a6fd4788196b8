//! An IMM for aircraft: constant-velocity modes on `[x, vx, y, vy]` beside a coordinated
//! turn with the turn rate as a state, `[x, vx, y, vy, ω]` — an IMM of unequal state
//! sizes.
//!
//! (Module docs are completed below.)

mod estimate;
mod estimator;
mod mixing;
mod radar;
mod start;
mod tuning;

#[cfg(test)]
mod tests;

pub use estimate::AircraftEstimate;
pub use estimator::{AircraftImm, AircraftPrediction, AircraftUpdate};
pub use mixing::Augmentation;
pub use radar::AircraftRadar;
pub use start::two_point_start;
pub use tuning::{AircraftEkf, AircraftTuning};

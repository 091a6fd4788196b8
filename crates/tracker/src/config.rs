//! Tracker configuration, validated once by [`crate::Tracker::new`].

use crate::{SensorId, TrackerError};

/// Everything the tracker needs to know. Build it with [`TrackerConfig::new`] (the
/// defaults below) and change the public fields; [`crate::Tracker::new`] validates it.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackerConfig {
    /// The sensors whose plots are accepted (at least one).
    pub sensors: Vec<SensorId>,
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
}

impl TrackerConfig {
    /// The defaults listed on each field, for the given sensors.
    #[must_use]
    pub fn new(sensors: Vec<SensorId>) -> Self {
        Self {
            sensors,
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
            return bad("sensors", 0.0, "at least one sensor is needed");
        }
        let positive = [
            ("max_speed", self.max_speed),
            ("max_initiation_interval", self.max_initiation_interval),
            ("max_position_sigma", self.max_position_sigma),
            ("grid_cell", self.grid_cell),
        ];
        for (field, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return bad(field, v, "must be finite and positive");
            }
        }
        for (field, v) in [
            ("sigma_a", self.sigma_a),
            ("velocity_gate_sigmas", self.velocity_gate_sigmas),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return bad(field, v, "must be finite and non-negative");
            }
        }
        let p = self.gate_probability;
        if !(p.is_finite() && p > 0.0 && p < 1.0) {
            return bad("gate_probability", p, "must lie in (0, 1)");
        }
        if !(2..=32).contains(&self.confirm_n) {
            return bad("confirm_n", f64::from(self.confirm_n), "must lie in 2..=32");
        }
        if !(2..=self.confirm_n).contains(&self.confirm_m) {
            return bad(
                "confirm_m",
                f64::from(self.confirm_m),
                "must lie in 2..=confirm_n",
            );
        }
        if self.max_misses == 0 {
            return bad("max_misses", 0.0, "must be at least 1");
        }
        Ok(())
    }
}

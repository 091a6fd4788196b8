//! The one sensor identifier of the workspace.

/// A sensor's id: which radar (or other sensor) made a plot. Plots, simulated sensors
/// and the tracker's sensor list all name sensors by it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct SensorId(pub u32);

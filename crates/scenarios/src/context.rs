//! What a scenario run gets: the run range, the seed, the parameters and a progress
//! handle.

use std::ops::Range;

use crate::params::Params;

/// Progress of a campaign, ticked once per run (from rayon's threads, hence `Sync`).
/// The command draws a bar with it; [`NoProgress`] ignores it.
pub trait Progress: Sync {
    /// One step done.
    fn tick(&self);
    /// The campaign is done (called once, after the last tick).
    fn finish(&self) {}
}

/// A [`Progress`] that does nothing.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoProgress;

impl Progress for NoProgress {
    fn tick(&self) {}
}

/// What a scenario run gets.
#[derive(Clone)]
pub struct RunContext<'a> {
    /// Run indices to compute (`0..N`, or a sub-range of a split campaign).
    pub runs: Range<u64>,
    /// Base seed.
    pub seed: u64,
    /// Validated parameters.
    pub params: Params,
    /// Progress handle: ticked once per run.
    pub progress: &'a dyn Progress,
}

impl std::fmt::Debug for RunContext<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RunContext")
            .field("runs", &self.runs)
            .field("seed", &self.seed)
            .field("params", &self.params)
            .finish_non_exhaustive()
    }
}

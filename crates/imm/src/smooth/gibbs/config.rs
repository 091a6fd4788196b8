//! The sampler's settings.

use super::error::GibbsError;

/// Largest number of mode paths a block may enumerate (`R^block`): the tree search is
/// exhaustive, so a block must stay small.
pub const MAX_BLOCK_PATHS: usize = 1 << 16;

/// How a Gibbs chain is run: blocks of `block` consecutive modes drawn jointly, `burn_in`
/// sweeps discarded, then `sweeps` sweeps averaged; the chain draws from `seed`
/// (ChaCha8), so a result depends on the seed only, not on threads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GibbsConfig {
    /// Consecutive modes drawn jointly (1 = the single-site sampler, which mixes badly on
    /// manoeuvring tracks; 4 is the documented choice).
    pub block: usize,
    /// Sweeps discarded before recording.
    pub burn_in: usize,
    /// Sweeps recorded (≥ 1).
    pub sweeps: usize,
    /// Seed of the chain's generator.
    pub seed: u64,
}

impl Default for GibbsConfig {
    /// Blocks of 4, 20 sweeps of burn-in, 100 recorded, seed 0.
    fn default() -> Self {
        Self {
            block: 4,
            burn_in: 20,
            sweeps: 100,
            seed: 0,
        }
    }
}

/// Checks a block length against `R` modes.
///
/// # Errors
/// [`GibbsError::InvalidConfig`] for `block = 0` or `R^block > MAX_BLOCK_PATHS`.
pub(super) fn check_block(block: usize, modes: usize) -> Result<(), GibbsError> {
    let paths = u32::try_from(block)
        .ok()
        .and_then(|b| modes.checked_pow(b))
        .filter(|&p| p <= MAX_BLOCK_PATHS);
    if block == 0 || paths.is_none() {
        return Err(GibbsError::InvalidConfig {
            what: "block",
            value: block,
            domain: "1 ≤ block, modes^block ≤ 65 536",
        });
    }
    Ok(())
}

impl GibbsConfig {
    /// Checks the settings for `modes` modes.
    ///
    /// # Errors
    /// [`GibbsError::InvalidConfig`] for a bad block length or no recorded sweep.
    pub fn validate(&self, modes: usize) -> Result<(), GibbsError> {
        check_block(self.block, modes)?;
        if self.sweeps == 0 {
            return Err(GibbsError::InvalidConfig {
                what: "sweeps",
                value: 0,
                domain: "≥ 1",
            });
        }
        Ok(())
    }
}

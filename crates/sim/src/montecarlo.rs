//! The Monte Carlo runner: seeded, parallel, and independent of the thread count.

use std::ops::Range;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use crate::error::SimError;

/// The random generator of run `run` of a campaign with base seed `seed`.
///
/// Mixing function: the ChaCha8 key is `ChaCha8Rng::seed_from_u64(seed)` (rand_core's
/// PCG32 expansion of the 64-bit seed into the 256-bit key) and the ChaCha stream
/// (64-bit nonce) is the run index. Runs are therefore independent streams of one key,
/// and run `i` can be replayed alone: `run_rng(seed, i)` gives the same numbers whether
/// it is computed in a campaign of 1 run or of 10 000, on any machine.
#[must_use]
pub fn run_rng(seed: u64, run: u64) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(run);
    rng
}

/// Runs `f(run_index, rng)` for every run index in `runs`, in parallel on rayon's
/// current pool, and returns the results **in run order** whatever the number of
/// threads (rayon's indexed `collect` keeps order). Reduce the returned vector in order
/// and the campaign's numbers do not depend on the thread count. `on_done` is called once
/// per finished run (from any thread), for a progress bar.
///
/// To split a campaign, run disjoint ranges (`0..500`, `500..1000`) and concatenate.
///
/// # Errors
/// [`SimError::EmptyRunRange`] for an empty range; otherwise the first error (in run
/// order) returned by `f`.
pub fn monte_carlo<T, E, F, P>(seed: u64, runs: Range<u64>, f: F, on_done: P) -> Result<Vec<T>, E>
where
    T: Send,
    E: Send + From<SimError>,
    F: Fn(u64, &mut ChaCha8Rng) -> Result<T, E> + Sync,
    P: Fn() + Sync,
{
    if runs.is_empty() {
        return Err(SimError::EmptyRunRange {
            start: runs.start,
            end: runs.end,
        }
        .into());
    }
    let results: Vec<Result<T, E>> = runs
        .into_par_iter()
        .map(|i| {
            let mut rng = run_rng(seed, i);
            let r = f(i, &mut rng);
            on_done();
            r
        })
        .collect();
    results.into_iter().collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::RngExt;

    #[test]
    fn runs_are_replayable_and_distinct() {
        // Replaying run 7 alone gives the numbers it had inside a campaign.
        let campaign: Vec<f64> =
            monte_carlo::<_, SimError, _, _>(42, 0..16, |_, rng| Ok(rng.random::<f64>()), || {})
                .unwrap();
        let alone: f64 = run_rng(42, 7).random();
        assert_eq!(campaign[7].to_bits(), alone.to_bits());
        assert_ne!(campaign[6].to_bits(), campaign[7].to_bits());
        // A split campaign concatenates to the whole one.
        let tail: Vec<f64> =
            monte_carlo::<_, SimError, _, _>(42, 8..16, |_, rng| Ok(rng.random::<f64>()), || {})
                .unwrap();
        assert_eq!(&campaign[8..], &tail[..]);
        assert!(matches!(
            monte_carlo::<f64, SimError, _, _>(42, 3..3, |_, _| Ok(0.0), || {}),
            Err(SimError::EmptyRunRange { .. })
        ));
    }
}

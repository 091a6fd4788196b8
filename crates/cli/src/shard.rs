//! How a campaign's runs are cut into shards: shard `i` of `K` of runs `A..B` holds
//! `A + ⌊n·i/K⌋ .. A + ⌊n·(i+1)/K⌋` (`n = B − A`), so the K shards cover `A..B` exactly
//! once and their sizes differ by at most one run. `argus run --shards K --shard i` and
//! the job files of `argus campaign plan` both use it.

use std::ops::Range;

use crate::error::CliError;

/// Shard `index` of `count` of `runs`.
///
/// # Errors
/// [`CliError::Usage`] for no shard, more shards than runs (a shard would be empty) or an
/// index outside `0..count`.
pub(crate) fn shard_range(
    runs: &Range<u64>,
    count: u64,
    index: u64,
) -> Result<Range<u64>, CliError> {
    let n = runs.end.saturating_sub(runs.start);
    if count == 0 || count > n {
        return Err(CliError::Usage(format!(
            "--shards {count}: expected 1 ..= {n} shards for runs {}..{}",
            runs.start, runs.end
        )));
    }
    if index >= count {
        return Err(CliError::Usage(format!(
            "--shard {index}: expected an index in 0..{count}"
        )));
    }
    // u128: n · i cannot overflow.
    let cut = |i: u64| runs.start + (u128::from(n) * u128::from(i) / u128::from(count)) as u64;
    Ok(cut(index)..cut(index + 1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_cover_the_runs_exactly_once() {
        for (runs, k) in [(0..10, 4), (0..8, 8), (5..105, 3), (0..1, 1), (7..20, 13)] {
            let mut next = runs.start;
            for i in 0..k {
                let r = shard_range(&runs, k, i).unwrap();
                assert_eq!(
                    r.start,
                    next,
                    "{runs:?} / {k}: shard {i} starts where {} ended",
                    i.max(1) - 1
                );
                assert!(!r.is_empty(), "{runs:?} / {k}: shard {i} empty");
                let n = runs.end - runs.start;
                assert!(r.end - r.start <= n.div_ceil(k), "balanced");
                next = r.end;
            }
            assert_eq!(
                next, runs.end,
                "{runs:?} / {k}: the last shard ends the campaign"
            );
        }
        assert!(shard_range(&(0..3), 4, 0).is_err(), "more shards than runs");
        assert!(shard_range(&(0..3), 0, 0).is_err(), "no shard");
        assert!(shard_range(&(0..3), 3, 3).is_err(), "index out of range");
    }
}

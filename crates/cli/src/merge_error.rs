//! What `argus merge` finds wrong with a campaign as a whole (a shard or runs missing or
//! given twice), each with the fix: re-running a shard gives identical output, so the
//! fix of a missing shard is to re-submit its index.

use std::ops::Range;
use std::path::PathBuf;

fn range(r: &Range<u64>) -> String {
    format!("{}..{}", r.start, r.end)
}

/// A campaign that is not whole.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum MergeError {
    /// Shard `index` of a planned campaign (`--shards count --shard index`) is in no
    /// directory given.
    #[error(
        "shard {index} of {count} (runs {}) is missing: re-submit index {index}{}",
        range(runs),
        if *more > 0 { format!(" (and {more} more shards are missing)") } else { String::new() }
    )]
    MissingShard {
        /// The shard index.
        index: u64,
        /// The campaign's shard count.
        count: u64,
        /// Its runs.
        runs: Range<u64>,
        /// How many other shards are missing too.
        more: usize,
    },
    /// Shard `index` is given twice.
    #[error(
        "shard {index} is given twice ({} and {}): merge one copy (re-submitting index {index} gives identical output)",
        first.display(),
        second.display()
    )]
    DuplicateShard {
        /// The shard index.
        index: u64,
        /// The first file holding it.
        first: PathBuf,
        /// The second.
        second: PathBuf,
    },
    /// Runs that no file holds (between two files, or before or after all of them when the
    /// campaign's range is known).
    #[error(
        "runs {} are in no per-run file: re-submit index {} (`argus run {scenario} --seed {seed} --runs {}` into another directory, then merge it too)",
        range(runs),
        range(runs),
        range(runs)
    )]
    MissingRuns {
        /// The scenario.
        scenario: String,
        /// The base seed.
        seed: u64,
        /// The runs missing.
        runs: Range<u64>,
    },
    /// Runs held by two files.
    #[error(
        "runs {} are in both {} and {}: each run must come once (merge one copy)",
        range(runs),
        first.display(),
        second.display()
    )]
    DuplicateRuns {
        /// The runs held twice.
        runs: Range<u64>,
        /// The first file.
        first: PathBuf,
        /// The second.
        second: PathBuf,
    },
}

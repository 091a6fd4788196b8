//! The per-run files of split campaigns (`runs/<A>-<B>.jsonl`, format in
//! `docs/FORMATS.md`): their layout and how `argus run` and `argus merge` write them.
//! Reading them back, with the campaign's checks, is [`crate::campaign_scan`].
//!
//! ```text
//! {"argus_runs":2,"argus_version":"0.1.0","scenario":"gimpo","seed":1,"runs":[0,25],"params":{...},"shard":{"index":0,"count":4,"campaign":[0,100]}}
//! {"run":0,"record":...}
//! {"run":1,"record":...}
//! ```

use std::collections::BTreeMap;
use std::io::Write;
use std::ops::Range;
use std::path::{Path, PathBuf};

use argus_scenarios::Params;
use serde::{Deserialize, Serialize};

use crate::error::CliError;

/// Version of the per-run file layout (the header's `argus_runs` value). 2 added the
/// Argus version and the shard of a planned campaign.
pub(crate) const RUNS_FORMAT: u32 = 2;

/// The version of this `argus`, written into every header and required of every file a
/// merge reads (a record's layout may change between versions).
pub(crate) const ARGUS_VERSION: &str = env!("CARGO_PKG_VERSION");

/// Which shard of a planned campaign a file holds (`argus run --shards K --shard i`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ShardInfo {
    /// The shard's index, `0..count`.
    pub(crate) index: u64,
    /// Number of shards of the campaign.
    pub(crate) count: u64,
    /// The whole campaign's runs `[start, end)`.
    pub(crate) campaign: [u64; 2],
}

/// First line of a per-run file.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct Header {
    pub(crate) argus_runs: u32,
    pub(crate) argus_version: String,
    pub(crate) scenario: String,
    pub(crate) seed: u64,
    pub(crate) runs: [u64; 2],
    pub(crate) params: BTreeMap<String, f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(crate) shard: Option<ShardInfo>,
}

impl Header {
    /// The header of runs `runs` of `scenario` written by this `argus`.
    pub(crate) fn new(
        scenario: &str,
        seed: u64,
        runs: &Range<u64>,
        params: &Params,
        shard: Option<ShardInfo>,
    ) -> Self {
        Self {
            argus_runs: RUNS_FORMAT,
            argus_version: ARGUS_VERSION.to_owned(),
            scenario: scenario.to_owned(),
            seed,
            runs: [runs.start, runs.end],
            params: params.as_map().clone(),
            shard,
        }
    }

    /// The run range.
    pub(crate) fn range(&self) -> Range<u64> {
        self.runs[0]..self.runs[1]
    }
}

/// Every later line (the record kept as its JSON text).
#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct Line {
    pub(crate) run: u64,
    pub(crate) record: Box<serde_json::value::RawValue>,
}

/// The per-run file's name for runs `A..B`: `runs/<A>-<B>.jsonl` under `dir`.
pub(crate) fn runs_file(dir: &Path, runs: &Range<u64>) -> PathBuf {
    dir.join("runs")
        .join(format!("{}-{}.jsonl", runs.start, runs.end))
}

fn header_line(header: &Header) -> Result<String, CliError> {
    let mut s = serde_json::to_string(header)
        .map_err(|e| CliError::Usage(format!("per-run header: {e}")))?;
    s.push('\n');
    Ok(s)
}

/// The text of a per-run file: header and one line per record (`records[i]` is run
/// `header.runs[0] + i`).
///
/// # Errors
/// [`CliError::Usage`] if the record count does not match the range (a framework bug,
/// reported rather than writing a wrong file).
pub(crate) fn runs_text(header: &Header, records: &[String]) -> Result<String, CliError> {
    let runs = header.range();
    if records.len() as u64 != runs.end - runs.start {
        return Err(CliError::Usage(format!(
            "{} records for runs {}..{}",
            records.len(),
            runs.start,
            runs.end
        )));
    }
    let mut s = header_line(header)?;
    for (run, rec) in runs.zip(records) {
        s.push_str(&format!("{{\"run\":{run},\"record\":{rec}}}\n"));
    }
    Ok(s)
}

/// Writes the per-run file of `header` at `path`, its run lines copied from `lines`
/// (already checked, in run order) as they come: the merged file is never held whole.
/// Atomic like [`crate::output::write_atomic`]: a temporary sibling, then a rename.
///
/// # Errors
/// [`CliError::Io`] for the directory, the temporary file or the rename; the first error
/// of `lines`.
pub(crate) fn write_streamed(
    path: &Path,
    header: &Header,
    lines: &mut dyn Iterator<Item = Result<String, CliError>>,
) -> Result<(), CliError> {
    let dir = path
        .parent()
        .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
    std::fs::create_dir_all(&dir).map_err(|e| CliError::io(&dir, e))?;
    let name = path
        .file_name()
        .map_or_else(|| "runs".into(), |n| n.to_string_lossy().into_owned());
    let tmp = dir.join(format!(".{name}.tmp-{}", std::process::id()));
    let result = (|| -> Result<(), CliError> {
        let f = std::fs::File::create(&tmp).map_err(|e| CliError::io(&tmp, e))?;
        let mut w = std::io::BufWriter::new(f);
        let io = |e| CliError::io(&tmp, e);
        w.write_all(header_line(header)?.as_bytes()).map_err(io)?;
        for l in lines {
            w.write_all(l?.as_bytes()).map_err(io)?;
            w.write_all(b"\n").map_err(io)?;
        }
        let f = w
            .into_inner()
            .map_err(|e| CliError::io(&tmp, e.into_error()))?;
        f.sync_all().map_err(io)?;
        std::fs::rename(&tmp, path).map_err(|e| CliError::io(path, e))
    })();
    if result.is_err() {
        // Best effort: do not leave the temporary behind.
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn record_count_must_match_range() {
        let params = Params::from_settings(&[], &[]).unwrap();
        let h = Header::new("t", 1, &(0..3), &params, None);
        assert!(runs_text(&h, &["1".into(), "2".into()]).is_err());
        let text = runs_text(&h, &["1".into(), "2".into(), "3".into()]).unwrap();
        assert_eq!(text.lines().count(), 4, "{text}");
        assert!(
            text.lines().nth(3).unwrap().starts_with("{\"run\":2,"),
            "{text}"
        );
    }
}

//! `argus merge`'s reading of per-run files: a first pass checks the campaign whole
//! (every header: layout, Argus version, scenario, seed, parameters, shard; every line:
//! its run index in order; then every run index exactly once across the files) reading
//! line by line and keeping no record; a second pass streams the records, file after file
//! in run order, to the reduce step. Memory does not grow with the number of runs.

use std::collections::BTreeMap;
use std::io::BufRead;
use std::ops::Range;
use std::path::{Path, PathBuf};

use argus_scenarios::{ParamSpec, Params, RecordText, ScenarioError};
use serde::Deserialize;

use crate::error::CliError;
use crate::merge_error::MergeError;
use crate::runs_file::{ARGUS_VERSION, Header, Line, RUNS_FORMAT, ShardInfo};

/// A checked campaign: what the merged report is of, and the files in run order.
#[derive(Debug)]
pub(crate) struct Scanned {
    /// The common base seed.
    pub(crate) seed: u64,
    /// The run indices covered, `start..end`, each exactly once.
    pub(crate) runs: Range<u64>,
    /// The common parameters, validated against the scenario's specs.
    pub(crate) params: Params,
    /// The per-run files, in run order (each a contiguous range).
    pub(crate) files: Vec<PathBuf>,
}

/// A run line checked without keeping its record.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LineCheck {
    run: u64,
    #[allow(dead_code)]
    record: serde::de::IgnoredAny,
}

fn open(f: &Path) -> Result<std::io::Lines<std::io::BufReader<std::fs::File>>, std::io::Error> {
    Ok(std::io::BufReader::new(std::fs::File::open(f)?).lines())
}

/// Reads and checks one file: its header and that its lines hold its runs in order.
fn check_file(f: &Path, scenario: &str) -> Result<Header, CliError> {
    let mut lines = open(f).map_err(|e| CliError::io(f, e))?;
    let head = lines
        .next()
        .ok_or_else(|| CliError::input(f, Some(1), None, "empty per-run file"))?
        .map_err(|e| CliError::io(f, e))?;
    let h: Header = serde_json::from_str(&head)
        .map_err(|e| CliError::input(f, Some(1), None, format!("not a per-run header: {e}")))?;
    let at = |field: &str, message: String| CliError::input(f, Some(1), Some(field), message);
    if h.argus_runs != RUNS_FORMAT {
        return Err(at(
            "argus_runs",
            format!(
                "layout version {} (this argus reads {RUNS_FORMAT})",
                h.argus_runs
            ),
        ));
    }
    if h.argus_version != ARGUS_VERSION {
        return Err(at(
            "argus_version",
            format!(
                "written by argus {}, this is argus {ARGUS_VERSION}: re-run the campaign with one version",
                h.argus_version
            ),
        ));
    }
    if h.scenario != scenario {
        return Err(at(
            "scenario",
            format!("runs of '{}', not '{scenario}'", h.scenario),
        ));
    }
    let range = h.range();
    if range.is_empty() {
        return Err(at(
            "runs",
            format!("empty run range {}..{}", range.start, range.end),
        ));
    }
    if let Some(s) = h.shard {
        let campaign = s.campaign[0]..s.campaign[1];
        let want = crate::shard::shard_range(&campaign, s.count, s.index).ok();
        if want.as_ref() != Some(&range) {
            return Err(at(
                "shard",
                format!(
                    "shard {} of {} of runs {}..{} is not runs {}..{}",
                    s.index, s.count, campaign.start, campaign.end, range.start, range.end
                ),
            ));
        }
    }
    let mut next = range.start;
    for (i, l) in lines.enumerate() {
        let line = i as u64 + 2;
        let l = l.map_err(|e| CliError::io(f, e))?;
        if l.trim().is_empty() {
            continue;
        }
        let rec: LineCheck = serde_json::from_str(&l)
            .map_err(|e| CliError::input(f, Some(line), None, format!("not a run line: {e}")))?;
        if rec.run != next || !range.contains(&rec.run) {
            return Err(CliError::input(
                f,
                Some(line),
                Some("run"),
                format!(
                    "run {} where run {next} of {}..{} was due (runs come once each, in order)",
                    rec.run, range.start, range.end
                ),
            ));
        }
        next += 1;
    }
    if next != range.end {
        return Err(CliError::input(
            f,
            None,
            Some("runs"),
            format!(
                "{} run lines for runs {}..{} (truncated file?)",
                next - range.start,
                range.start,
                range.end
            ),
        ));
    }
    Ok(h)
}

/// The `runs/*.jsonl` files of `dirs`.
fn list_files(dirs: &[PathBuf]) -> Result<Vec<PathBuf>, CliError> {
    let mut files = Vec::new();
    for d in dirs {
        let rd = d.join("runs");
        let entries = std::fs::read_dir(&rd).map_err(|e| CliError::io(&rd, e))?;
        let mut found: Vec<PathBuf> = entries
            .filter_map(Result::ok)
            .map(|e| e.path())
            .filter(|p| p.extension().is_some_and(|x| x == "jsonl"))
            .collect();
        if found.is_empty() {
            return Err(CliError::Usage(format!(
                "{}: no per-run file (runs/<A>-<B>.jsonl, written by `argus run`)",
                d.display()
            )));
        }
        found.sort();
        files.extend(found);
    }
    Ok(files)
}

/// Checks that every shard of a planned campaign is present exactly once.
fn check_shards(headers: &[(PathBuf, Header)]) -> Result<(), CliError> {
    let Some((f0, h0)) = headers.first() else {
        return Ok(());
    };
    let Some(s0) = h0.shard else {
        if let Some((f, _)) = headers.iter().find(|(_, h)| h.shard.is_some()) {
            return Err(CliError::input(
                f,
                Some(1),
                Some("shard"),
                format!("a shard of a planned campaign, {} is not", f0.display()),
            ));
        }
        return Ok(());
    };
    let mut by_index: BTreeMap<u64, &PathBuf> = BTreeMap::new();
    for (f, h) in headers {
        let same = |s: ShardInfo| s.count == s0.count && s.campaign == s0.campaign;
        match h.shard {
            Some(s) if same(s) => {
                if let Some(first) = by_index.insert(s.index, f) {
                    return Err(MergeError::DuplicateShard {
                        index: s.index,
                        first: first.clone(),
                        second: f.clone(),
                    }
                    .into());
                }
            }
            _ => {
                return Err(CliError::input(
                    f,
                    Some(1),
                    Some("shard"),
                    format!(
                        "not a shard of the campaign of {} ({} shards of runs {}..{})",
                        f0.display(),
                        s0.count,
                        s0.campaign[0],
                        s0.campaign[1]
                    ),
                ));
            }
        }
    }
    let campaign = s0.campaign[0]..s0.campaign[1];
    let missing: Vec<u64> = (0..s0.count)
        .filter(|i| !by_index.contains_key(i))
        .collect();
    if let Some(&index) = missing.first() {
        let runs = crate::shard::shard_range(&campaign, s0.count, index)?;
        return Err(MergeError::MissingShard {
            index,
            count: s0.count,
            runs,
            more: missing.len() - 1,
        }
        .into());
    }
    Ok(())
}

/// Reads every `runs/*.jsonl` in `dirs` for scenario `scenario` and checks the campaign
/// whole before anything is reduced: the same layout, Argus version, seed and parameters
/// in every file, each planned shard once, each run index exactly once without gap.
///
/// # Errors
/// [`CliError::Input`] naming the file, line and field of a bad header or line or of a
/// mismatch; [`CliError::Merge`] for a missing or duplicated shard or runs;
/// [`CliError::Usage`] for a directory without per-run files; [`CliError::Io`].
pub(crate) fn scan(
    scenario: &str,
    specs: &[ParamSpec],
    dirs: &[PathBuf],
) -> Result<Scanned, CliError> {
    let files = list_files(dirs)?;
    let mut headers: Vec<(PathBuf, Header)> = Vec::with_capacity(files.len());
    for f in &files {
        let h = check_file(f, scenario)?;
        if let Some((f0, h0)) = headers.first() {
            if h.seed != h0.seed {
                return Err(CliError::input(
                    f,
                    Some(1),
                    Some("seed"),
                    format!(
                        "seed {} differs from {} in {}",
                        h.seed,
                        h0.seed,
                        f0.display()
                    ),
                ));
            }
            let same = h0.params.len() == h.params.len()
                && h0
                    .params
                    .iter()
                    .zip(h.params.iter())
                    .all(|((k0, v0), (k1, v1))| k0 == k1 && v0.to_bits() == v1.to_bits());
            if !same {
                return Err(CliError::input(
                    f,
                    Some(1),
                    Some("params"),
                    format!("parameters differ from those in {}", f0.display()),
                ));
            }
        }
        headers.push((f.clone(), h));
    }
    check_shards(&headers)?;
    headers.sort_by_key(|(_, h)| (h.runs[0], h.runs[1]));
    let (Some((_, first)), Some((_, last))) = (headers.first(), headers.last()) else {
        return Err(CliError::Usage("no per-run file given".into()));
    };
    let seed = first.seed;
    let (start, mut end) = (first.runs[0], first.runs[0]);
    let mut prev: Option<&PathBuf> = None;
    for (f, h) in &headers {
        let r = h.range();
        if r.start < end {
            return Err(MergeError::DuplicateRuns {
                runs: r.start..end.min(r.end),
                first: prev.cloned().unwrap_or_default(),
                second: f.clone(),
            }
            .into());
        }
        if r.start > end {
            return Err(MergeError::MissingRuns {
                scenario: scenario.to_owned(),
                seed,
                runs: end..r.start,
            }
            .into());
        }
        end = r.end;
        prev = Some(f);
    }
    debug_assert_eq!(end, last.runs[1]);
    // Revalidate the parameters against the scenario (the file may have been edited).
    let settings: Vec<String> = first
        .params
        .iter()
        .map(|(k, v)| format!("{k}={v}"))
        .collect();
    let params = Params::from_settings(specs, &settings)?;
    if params.as_map().len() != settings.len() {
        return Err(CliError::Usage(
            "the per-run files lack some of the scenario's parameters".into(),
        ));
    }
    Ok(Scanned {
        seed,
        runs: start..end,
        params,
        files: headers.into_iter().map(|(f, _)| f).collect(),
    })
}

/// The run lines of `files` (header skipped, blank lines dropped), in order, each with
/// its file and 1-based line number: read one at a time.
fn run_lines(
    files: &[PathBuf],
) -> impl Iterator<Item = Result<(PathBuf, u64, String), (PathBuf, u64, std::io::Error)>> + '_ {
    files.iter().flat_map(|f| {
        let it: Box<dyn Iterator<Item = _>> = match open(f) {
            Ok(lines) => Box::new(
                lines
                    .enumerate()
                    .skip(1)
                    .map(move |(i, l)| match l {
                        Ok(l) => Ok((f.clone(), i as u64 + 1, l)),
                        Err(e) => Err((f.clone(), i as u64 + 1, e)),
                    })
                    .filter(|r| r.as_ref().map_or(true, |(_, _, l)| !l.trim().is_empty())),
            ),
            Err(e) => Box::new(std::iter::once(Err((f.clone(), 1, e)))),
        };
        it
    })
}

/// The records of the checked files as a stream, in run order, for the reduce step.
pub(crate) fn records(
    files: &[PathBuf],
) -> impl Iterator<Item = Result<RecordText, ScenarioError>> + '_ {
    run_lines(files).map(|r| {
        let (file, line, text) = r.map_err(|(file, line, e)| ScenarioError::Record {
            file,
            line,
            message: e.to_string(),
        })?;
        let l: Line = serde_json::from_str(&text).map_err(|e| ScenarioError::Record {
            file: file.clone(),
            line,
            message: e.to_string(),
        })?;
        Ok(RecordText {
            json: l.record.get().to_owned(),
            file,
            line,
        })
    })
}

/// The run lines of the checked files, verbatim and in run order, for the merged file.
pub(crate) fn lines(files: &[PathBuf]) -> impl Iterator<Item = Result<String, CliError>> + '_ {
    run_lines(files).map(|r| {
        r.map(|(_, _, l)| l)
            .map_err(|(f, _, e)| CliError::io(&f, e))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::runs_file::{runs_file, runs_text};

    #[test]
    fn per_run_file_round_trips_every_f64_exactly() {
        // Values whose shortest decimal form needs care when parsed back: serde_json
        // without `float_roundtrip` may miss them by one ulp.
        let tricky: Vec<f64> = vec![
            0.1 + 0.2,
            1.0 / 3.0,
            2.225_073_858_507_201e-308,
            5e-324,
            f64::MAX,
            -1.797_693_134_862_315_7e308,
            9_007_199_254_740_993.0,
            20.946_123_456_789_012,
        ];
        let texts: Vec<String> = tricky
            .iter()
            .map(|v| serde_json::to_string(&vec![*v]).unwrap())
            .collect();
        let runs = 3..3 + tricky.len() as u64;
        let params = Params::from_settings(&[], &[]).unwrap();
        let text = runs_text(&Header::new("t", 7, &runs, &params, None), &texts).unwrap();
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(dir.path().join("runs")).unwrap();
        std::fs::write(runs_file(dir.path(), &runs), text).unwrap();
        let m = scan("t", &[], &[dir.path().to_path_buf()]).unwrap();
        assert_eq!(m.seed, 7);
        assert_eq!(m.runs, runs);
        let got: Vec<RecordText> = records(&m.files).collect::<Result<_, _>>().unwrap();
        assert_eq!(got.len(), tricky.len());
        for (rec, want) in got.iter().zip(&tricky) {
            let v: Vec<f64> = serde_json::from_str(&rec.json).unwrap();
            assert_eq!(v[0].to_bits(), want.to_bits(), "{want:e}");
        }
        // The run lines come back verbatim, for the merged file.
        let lines: Vec<String> = lines(&m.files).collect::<Result<_, _>>().unwrap();
        assert!(lines[0].starts_with("{\"run\":3,"), "{}", lines[0]);
        // Another scenario's name is refused, naming the header field.
        let e = scan("other", &[], &[dir.path().to_path_buf()]).unwrap_err();
        assert!(
            matches!(&e, CliError::Input { at, .. } if at.line == Some(1) && at.field.as_deref() == Some("scenario")),
            "{e}"
        );
    }
}

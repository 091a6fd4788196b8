//! The per-run files of splittable campaigns (`runs/<A>-<B>.jsonl`, format in
//! `docs/FORMATS.md`): written by `argus run`, read back and checked by `argus merge`.
//!
//! ```text
//! {"argus_runs":1,"scenario":"cv-polar","seed":1,"runs":[0,40],"params":{...}}
//! {"run":0,"record":...}
//! {"run":1,"record":...}
//! ```

use std::collections::BTreeMap;
use std::ops::Range;
use std::path::{Path, PathBuf};

use argus_scenarios::{ParamSpec, Params, RecordText};
use serde::{Deserialize, Serialize};

use crate::error::CliError;

/// Version of the per-run file layout (the header's `argus_runs` value).
pub(crate) const RUNS_FORMAT: u32 = 1;

/// First line of a per-run file.
#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Header {
    argus_runs: u32,
    scenario: String,
    seed: u64,
    runs: [u64; 2],
    params: BTreeMap<String, f64>,
}

/// Every later line.
#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Line {
    run: u64,
    record: Box<serde_json::value::RawValue>,
}

/// The per-run file's name for runs `A..B`: `runs/<A>-<B>.jsonl` under `dir`.
pub(crate) fn runs_file(dir: &Path, runs: &Range<u64>) -> PathBuf {
    dir.join("runs")
        .join(format!("{}-{}.jsonl", runs.start, runs.end))
}

/// The text of a per-run file: header and one line per record (`records[i]` is run
/// `runs.start + i`).
///
/// # Errors
/// [`CliError::Usage`] if the record count does not match the range (a framework bug,
/// reported rather than writing a wrong file).
pub(crate) fn runs_text(
    scenario: &str,
    seed: u64,
    runs: &Range<u64>,
    params: &Params,
    records: &[String],
) -> Result<String, CliError> {
    if records.len() as u64 != runs.end - runs.start {
        return Err(CliError::Usage(format!(
            "{} records for runs {}..{}",
            records.len(),
            runs.start,
            runs.end
        )));
    }
    let header = Header {
        argus_runs: RUNS_FORMAT,
        scenario: scenario.to_owned(),
        seed,
        runs: [runs.start, runs.end],
        params: params.as_map().clone(),
    };
    let to_err = |e: serde_json::Error| CliError::Usage(format!("per-run file: {e}"));
    let mut s = serde_json::to_string(&header).map_err(to_err)?;
    s.push('\n');
    for (run, rec) in runs.clone().zip(records) {
        s.push_str(&format!("{{\"run\":{run},\"record\":{rec}}}\n"));
    }
    Ok(s)
}

/// The union of the per-run files found in `dirs`, checked and ordered.
#[derive(Debug)]
pub(crate) struct Merged {
    /// The common base seed.
    pub(crate) seed: u64,
    /// The run indices covered, `start..end` without gap.
    pub(crate) runs: Range<u64>,
    /// The common parameters, validated against the scenario's specs.
    pub(crate) params: Params,
    /// The records in run order.
    pub(crate) records: Vec<RecordText>,
    /// The files read.
    pub(crate) files: Vec<PathBuf>,
}

/// Reads every `runs/*.jsonl` in `dirs` for scenario `scenario` and checks that they share
/// the seed and parameters, hold each run once, and together cover `A..B` without gap.
///
/// # Errors
/// [`CliError::Input`] naming the file, line and field of a bad header or line, a
/// second copy of a run, another scenario, seed or parameter set; [`CliError::Usage`]
/// for a directory without per-run files or a gap in the runs; [`CliError::Io`].
pub(crate) fn read_dirs(
    scenario: &str,
    specs: &[ParamSpec],
    dirs: &[PathBuf],
) -> Result<Merged, CliError> {
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
    // (seed, params, file) of the first file, to compare the others with.
    let mut first: Option<(u64, BTreeMap<String, f64>, PathBuf)> = None;
    let mut by_run: BTreeMap<u64, RecordText> = BTreeMap::new();
    for f in &files {
        let text = std::fs::read_to_string(f).map_err(|e| CliError::io(f, e))?;
        let mut lines = text.lines().enumerate();
        let (_, head) = lines
            .next()
            .ok_or_else(|| CliError::input(f, Some(1), None, "empty per-run file"))?;
        let h: Header = serde_json::from_str(head)
            .map_err(|e| CliError::input(f, Some(1), None, format!("not a per-run header: {e}")))?;
        if h.argus_runs != RUNS_FORMAT {
            return Err(CliError::input(
                f,
                Some(1),
                Some("argus_runs"),
                format!(
                    "layout version {} (this argus reads {RUNS_FORMAT})",
                    h.argus_runs
                ),
            ));
        }
        if h.scenario != scenario {
            return Err(CliError::input(
                f,
                Some(1),
                Some("scenario"),
                format!("runs of '{}', not '{scenario}'", h.scenario),
            ));
        }
        match &first {
            None => first = Some((h.seed, h.params.clone(), f.clone())),
            Some((seed, params, f0)) => {
                if *seed != h.seed {
                    return Err(CliError::input(
                        f,
                        Some(1),
                        Some("seed"),
                        format!("seed {} differs from {} in {}", h.seed, seed, f0.display()),
                    ));
                }
                let same = params.len() == h.params.len()
                    && params
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
        }
        let range = h.runs[0]..h.runs[1];
        let mut count = 0u64;
        for (i, l) in lines {
            let line = i as u64 + 1;
            if l.trim().is_empty() {
                continue;
            }
            let rec: Line = serde_json::from_str(l).map_err(|e| {
                CliError::input(f, Some(line), None, format!("not a run line: {e}"))
            })?;
            if !range.contains(&rec.run) {
                return Err(CliError::input(
                    f,
                    Some(line),
                    Some("run"),
                    format!(
                        "run {} outside the header's {}..{}",
                        rec.run, range.start, range.end
                    ),
                ));
            }
            let text = RecordText {
                json: rec.record.get().to_owned(),
                file: f.clone(),
                line,
            };
            if let Some(prev) = by_run.insert(rec.run, text) {
                return Err(CliError::input(
                    f,
                    Some(line),
                    Some("run"),
                    format!(
                        "run {} also in {}:{} (each run must come once)",
                        rec.run,
                        prev.file.display(),
                        prev.line
                    ),
                ));
            }
            count += 1;
        }
        if count != range.end.saturating_sub(range.start) {
            return Err(CliError::input(
                f,
                None,
                Some("runs"),
                format!(
                    "{count} run lines for runs {}..{} (truncated file?)",
                    range.start, range.end
                ),
            ));
        }
    }
    let Some((seed, params, _)) = first else {
        return Err(CliError::Usage("no per-run file given".into()));
    };
    let (Some(&start), Some(&last)) = (by_run.keys().next(), by_run.keys().next_back()) else {
        return Err(CliError::Usage("the per-run files hold no run".into()));
    };
    let end = last + 1;
    if end - start != by_run.len() as u64 {
        let missing: Vec<String> = (start..end)
            .filter(|r| !by_run.contains_key(r))
            .take(5)
            .map(|r| r.to_string())
            .collect();
        return Err(CliError::Usage(format!(
            "runs {start}..{end} have gaps (missing run {} …): merge only complete ranges",
            missing.join(", ")
        )));
    }
    // Revalidate the parameters against the scenario (the file may have been edited).
    let settings: Vec<String> = params.iter().map(|(k, v)| format!("{k}={v}")).collect();
    let params = Params::from_settings(specs, &settings)?;
    if params.as_map().len() != settings.len() {
        return Err(CliError::Usage(
            "the per-run files lack some of the scenario's parameters".into(),
        ));
    }
    Ok(Merged {
        seed,
        runs: start..end,
        params,
        records: by_run.into_values().collect(),
        files,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

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
        let records: Vec<String> = tricky
            .iter()
            .map(|v| serde_json::to_string(&vec![*v]).unwrap())
            .collect();
        let runs = 3..3 + tricky.len() as u64;
        let params = Params::from_settings(&[], &[]).unwrap();
        let text = runs_text("t", 7, &runs, &params, &records).unwrap();
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(dir.path().join("runs")).unwrap();
        std::fs::write(runs_file(dir.path(), &runs), text).unwrap();
        let m = read_dirs("t", &[], &[dir.path().to_path_buf()]).unwrap();
        assert_eq!(m.seed, 7);
        assert_eq!(m.runs, runs);
        for (rec, want) in m.records.iter().zip(&tricky) {
            let got: Vec<f64> = serde_json::from_str(&rec.json).unwrap();
            assert_eq!(got[0].to_bits(), want.to_bits(), "{want:e}");
        }
        // Another scenario's name is refused, naming the header field.
        let e = read_dirs("other", &[], &[dir.path().to_path_buf()]).unwrap_err();
        assert!(
            matches!(&e, CliError::Input { at, .. } if at.line == Some(1) && at.field.as_deref() == Some("scenario")),
            "{e}"
        );
    }

    #[test]
    fn record_count_must_match_range() {
        let params = Params::from_settings(&[], &[]).unwrap();
        assert!(runs_text("t", 1, &(0..3), &params, &["1".into(), "2".into()]).is_err());
    }
}

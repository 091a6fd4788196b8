//! `argus track` runs of the multi-target tracker over plot text written by the test,
//! and the check of a refused configuration (tests/track_multi.rs,
//! tests/track_rotating.rs).

// Each test binary uses a part of these helpers.
#![allow(dead_code)]

use std::path::Path;

use super::argus;

/// What one `argus track` run gave.
pub(crate) struct Run {
    /// The exit code.
    pub(crate) code: Option<i32>,
    /// The standard error.
    pub(crate) stderr: String,
    /// The tracks CSV (empty when not written).
    pub(crate) csv: String,
    /// The summary (Null when not written).
    pub(crate) summary: serde_json::Value,
}

/// Writes `config` to `dir/<config_file>` and `plots` to `dir/plots.csv`, and runs
/// `argus track --config <config_file> --plots plots.csv --out tracks.csv` in `dir`
/// (a previous run's tracks and summary removed first).
///
/// # Panics
/// When a file cannot be written or the summary is not JSON (a test failure).
#[allow(clippy::unwrap_used)]
pub(crate) fn run(dir: &Path, config_file: &str, config: &str, plots: &str) -> Run {
    std::fs::write(dir.join(config_file), config).unwrap();
    std::fs::write(dir.join("plots.csv"), plots).unwrap();
    let _ = std::fs::remove_file(dir.join("tracks.csv"));
    let _ = std::fs::remove_file(dir.join("tracks.summary.json"));
    let o = argus(
        &[
            "track",
            "--config",
            config_file,
            "--plots",
            "plots.csv",
            "--out",
            "tracks.csv",
        ],
        dir,
    );
    let csv = std::fs::read_to_string(dir.join("tracks.csv")).unwrap_or_default();
    let summary = std::fs::read_to_string(dir.join("tracks.summary.json"))
        .map_or(serde_json::Value::Null, |s| {
            serde_json::from_str(&s).unwrap()
        });
    Run {
        code: o.status.code(),
        stderr: String::from_utf8_lossy(&o.stderr).into_owned(),
        csv,
        summary,
    }
}

/// `run` was refused with exit code 2, naming `at` (`file:line`) and `field`, and wrote
/// no tracks.
pub(crate) fn assert_config_error(run: &Run, at: &str, field: &str) {
    assert_eq!(run.code, Some(2), "{}", run.stderr);
    assert!(
        run.stderr.contains(&format!("{at}: field '{field}'")),
        "expected {at} and field '{field}' in: {}",
        run.stderr
    );
    assert!(run.csv.is_empty(), "nothing written on error");
}

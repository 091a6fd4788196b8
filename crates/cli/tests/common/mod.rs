//! What the binary-driving tests share.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::{Command, Output};

pub(crate) mod smoothed_track;
pub(crate) mod tracker_run;

/// Runs the real `argus` binary with `args` in `cwd`.
///
/// # Panics
/// When the binary cannot be started (a test failure).
#[allow(clippy::unwrap_used)]
pub(crate) fn argus(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_argus"))
        .args(args)
        .current_dir(cwd)
        .output()
        .unwrap()
}

/// Runs `argus` with `args` in `dir` and asserts success; returns stdout.
///
/// # Panics
/// When the command fails (a test failure), with its arguments and stderr.
#[allow(dead_code)]
pub(crate) fn ok(args: &[&str], dir: &Path) -> String {
    let o = argus(args, dir);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The text of the file `f` in `dir`.
///
/// # Panics
/// When it cannot be read (a test failure).
#[allow(clippy::unwrap_used, dead_code)]
pub(crate) fn read(dir: &Path, f: &str) -> String {
    std::fs::read_to_string(dir.join(f)).unwrap()
}

/// Runs `argus track` with `config` (text, written to `dir/c.toml`) over `plots` and
/// `extra` flags: exit code, stderr, the tracks CSV (`dir/t.csv`; empty when not written).
///
/// # Panics
/// When a file cannot be written or a path is not UTF-8 (a test failure).
#[allow(clippy::unwrap_used, dead_code)]
pub(crate) fn track(
    dir: &Path,
    config: &str,
    plots: &Path,
    extra: &[&str],
) -> (Option<i32>, String, String) {
    let cfg = dir.join("c.toml");
    std::fs::write(&cfg, config).unwrap();
    let out = dir.join("t.csv");
    let _ = std::fs::remove_file(&out);
    let mut args = vec![
        "track",
        "--config",
        cfg.to_str().unwrap(),
        "--plots",
        plots.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let o = argus(&args, dir);
    let csv = std::fs::read_to_string(&out).unwrap_or_default();
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
        csv,
    )
}

/// One CSV row, by column name.
pub(crate) type Row = BTreeMap<String, String>;

/// The rows of a CSV text with a header line (no quoting: Argus's CSVs have none).
///
/// # Panics
/// When the text is empty (a test failure).
#[allow(clippy::unwrap_used, dead_code)]
pub(crate) fn rows(text: &str) -> Vec<Row> {
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    lines
        .map(|l| {
            header
                .iter()
                .zip(l.split(','))
                .map(|(h, v)| ((*h).to_owned(), v.to_owned()))
                .collect()
        })
        .collect()
}

/// Column `k` of a row as a number.
///
/// # Panics
/// When the column is missing or not a number (a test failure), naming it.
#[allow(clippy::panic, dead_code)]
pub(crate) fn num(r: &Row, k: &str) -> f64 {
    r.get(k)
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("column {k}: {:?}", r.get(k)))
}

/// The index of column `name` in a CSV header.
///
/// # Panics
/// When the header has no such column (a test failure).
#[allow(clippy::unwrap_used, dead_code)]
pub(crate) fn col(head: &[String], name: &str) -> usize {
    head.iter().position(|h| h == name).unwrap()
}

/// A refused command: exit code 2, one line of stderr naming every one of `needles`, no
/// panic.
#[allow(dead_code)]
pub(crate) fn assert_error(code: Option<i32>, err: &str, needles: &[&str]) {
    assert_eq!(code, Some(2), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(err.lines().count(), 1, "one message expected: {err}");
    for n in needles {
        assert!(err.contains(n), "missing '{n}' in: {err}");
    }
}

/// Runs `argus simulate gimpo --seed <seed>` in `dir`: plots `dir/sim.csv`, truth
/// `dir/sim.truth.csv`.
///
/// # Panics
/// When the command fails (a test failure), with its stderr.
#[allow(dead_code)]
pub(crate) fn simulate_gimpo(dir: &Path, seed: u64) {
    let s = seed.to_string();
    let o = argus(
        &["simulate", "gimpo", "--seed", &s, "--out", "sim.csv"],
        dir,
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// The position RMSE of the filtered (`x, y`) and smoothed (`xs, ys`) columns of a tracks
/// CSV against `dir/sim.truth.csv`, leaving out the first 6 rows (the two-point start's
/// transient).
///
/// # Panics
/// When the truth file cannot be read or has no row at a track row's time (a test failure).
#[allow(clippy::unwrap_used, clippy::panic, dead_code)]
pub(crate) fn rmse_pair(csv: &str, dir: &Path) -> (f64, f64) {
    let truth = rows(&std::fs::read_to_string(dir.join("sim.truth.csv")).unwrap());
    let at = |t: &str| {
        truth
            .iter()
            .find(|r| r["t"] == t)
            .map(|r| (num(r, "x"), num(r, "y")))
            .unwrap_or_else(|| panic!("no truth at {t}"))
    };
    let (mut f, mut s, mut n) = (0.0, 0.0, 0.0);
    for r in rows(csv).iter().skip(6) {
        let (x, y) = at(&r["t"]);
        f += (num(r, "x") - x).powi(2) + (num(r, "y") - y).powi(2);
        s += (num(r, "xs") - x).powi(2) + (num(r, "ys") - y).powi(2);
        n += 1.0;
    }
    ((f / n).sqrt(), (s / n).sqrt())
}

/// gimpo seed 4 (simulated into `dir`) tracked with `config` and `--smooth`: the
/// [`rmse_pair`] of its tracks, printed.
///
/// # Panics
/// When a command fails (a test failure), with its stderr.
#[allow(dead_code)]
pub(crate) fn gimpo_rmse_pair(dir: &Path, config: &str) -> (f64, f64) {
    simulate_gimpo(dir, 4);
    let (code, err, csv) = track(dir, config, &dir.join("sim.csv"), &["--smooth"]);
    assert_eq!(code, Some(0), "{err}");
    let (f, s) = rmse_pair(&csv, dir);
    println!("gimpo seed 4: position RMSE filtered {f:.1} m, smoothed {s:.1} m");
    (f, s)
}

//! Project automation for Argus.
//!
//! - `cargo xtask test`: `cargo fmt --all --check`, `cargo clippy --workspace --all-targets -- -D warnings`,
//!   `cargo doc --workspace --no-deps` with `RUSTDOCFLAGS=-D warnings` (no broken or private
//!   intra-doc link), `cargo test --workspace`, then the Python package's tests: a venv in
//!   `<target>/py-venv` with `python/requirements-test.txt`, `pip install ./python` (the
//!   wheel built with the dev profile, reusing the test build), `pytest python/tests` (with
//!   the `argus` binary and the `asterix_json` example of argus-asterix built for them) —
//!   the README's test command and what CI runs.
//! - `cargo xtask bench [--quick] [FILTER]`: runs the criterion benches and writes `docs/BENCHMARKS.md`
//!   (bench, median, machine) from criterion's `estimates.json` files.
//! - `cargo xtask cluster-test [--runs N] [--keep]`: a 4-shard `argus run gimpo` campaign and
//!   its merge on a one-node Slurm started on localhost ([`cluster_test`]).
//! - `cargo xtask mutate [--count N] [--seed S] [FILE...]`: the full ASTERIX mutation run,
//!   10⁶ mutated records by default, over the samples of every category and any raw block
//!   files given ([`mutate`]).

mod cluster_test;
mod mutate;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("test") => test(),
        Some("cluster-test") => cluster_test::cluster_test(&workspace_root(), &args[1..]),
        Some("mutate") => mutate::mutate(&args[1..]),
        Some("bench") => {
            let quick = args.iter().any(|a| a == "--quick");
            let filter = args
                .iter()
                .skip(1)
                .find(|a| !a.starts_with("--"))
                .map(String::as_str);
            bench(filter, quick)
        }
        _ => Err("usage: cargo xtask <test | bench [--quick] [FILTER] | cluster-test [--runs N] [--keep] | mutate [--count N] [--seed S] [FILE...]>".to_owned()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("xtask: {e}");
            ExitCode::FAILURE
        }
    }
}

/// The workspace of the checkout being run: `cargo run` sets `CARGO_MANIFEST_DIR` at run time
/// too, and that is the one to trust. The compile-time value is only the fallback: with a
/// target directory shared by two checkouts, cargo can reuse an xtask binary built from the
/// other one (its sources are the same), which would then test and bench that other tree.
fn workspace_root() -> PathBuf {
    let manifest_dir = std::env::var_os("CARGO_MANIFEST_DIR")
        .map_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")), PathBuf::from);
    manifest_dir
        .parent()
        .map_or_else(|| PathBuf::from("."), Path::to_path_buf)
}

fn cargo(args: &[&str]) -> Result<(), String> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_owned());
    eprintln!("xtask: cargo {}", args.join(" "));
    let status = Command::new(&cargo)
        .args(args)
        .current_dir(workspace_root())
        .status()
        .map_err(|e| format!("cannot run {cargo}: {e}"))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!("`cargo {}` failed ({status})", args.join(" ")))
    }
}

fn test() -> Result<(), String> {
    cargo(&["fmt", "--all", "--check"])?;
    cargo(&[
        "clippy",
        "--workspace",
        "--all-targets",
        "--",
        "-D",
        "warnings",
    ])?;
    let cargo_bin = std::env::var_os("CARGO").map_or_else(|| PathBuf::from("cargo"), PathBuf::from);
    run(
        &cargo_bin,
        &["doc", "--workspace", "--no-deps"],
        &[("RUSTDOCFLAGS", std::ffi::OsStr::new("-D warnings"))],
    )?;
    cargo(&["test", "--workspace"])?;
    python_tests()
}

/// The target directory of this run (`CARGO_TARGET_DIR` or `<workspace>/target`).
fn target_dir() -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map_or_else(|| workspace_root().join("target"), PathBuf::from)
}

fn run(program: &Path, args: &[&str], envs: &[(&str, &std::ffi::OsStr)]) -> Result<(), String> {
    eprintln!("xtask: {} {}", program.display(), args.join(" "));
    let status = Command::new(program)
        .args(args)
        .envs(envs.iter().copied())
        .current_dir(workspace_root())
        .status()
        .map_err(|e| format!("cannot run {}: {e}", program.display()))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!(
            "`{} {}` failed ({status})",
            program.display(),
            args.join(" ")
        ))
    }
}

/// The Python phase: the `argus` binary for the comparisons, a venv made from the
/// project's files, the package installed from `python/`, and pytest.
fn python_tests() -> Result<(), String> {
    cargo(&["build", "-p", "argus-cli"])?;
    // The ASTERIX cross-check's Argus side (python/tests/test_asterix_crosscheck.py).
    cargo(&["build", "-p", "argus-asterix", "--example", "asterix_json"])?;
    let target = target_dir();
    let venv = target.join("py-venv");
    let python = venv.join("bin").join("python");
    if !python.exists() {
        let system =
            std::env::var_os("PYTHON").map_or_else(|| PathBuf::from("python3"), PathBuf::from);
        let venv_arg = venv.to_string_lossy().into_owned();
        run(&system, &["-m", "venv", &venv_arg], &[])?;
    }
    run(
        &python,
        &[
            "-m",
            "pip",
            "install",
            "-q",
            "-r",
            "python/requirements-test.txt",
        ],
        &[],
    )?;
    // The dev profile (optimised, see the workspace's Cargo.toml) shares the artifacts of
    // `cargo test`; users' `pip install ./python` builds in release.
    let dev = std::ffi::OsStr::new("--profile dev");
    run(
        &python,
        &[
            "-m",
            "pip",
            "install",
            "-q",
            "--no-build-isolation",
            "--no-deps",
            "--force-reinstall",
            "./python",
        ],
        &[("MATURIN_PEP517_ARGS", dev)],
    )?;
    let bin = target.join("debug").join("argus");
    let asterix_json = target.join("debug").join("examples").join("asterix_json");
    run(
        &python,
        &["-m", "pytest", "-q", "python/tests"],
        &[
            ("ARGUS_BIN", bin.as_os_str()),
            ("ARGUS_ASTERIX_JSON", asterix_json.as_os_str()),
        ],
    )
}

fn bench(filter: Option<&str>, quick: bool) -> Result<(), String> {
    let mut args = vec!["bench", "-p", "argus-benches", "--"];
    if quick {
        // Shorter runs for a quick table: 1 s warm-up, 2 s measurement per bench.
        args.extend(["--warm-up-time", "1", "--measurement-time", "2"]);
    }
    if let Some(f) = filter {
        args.push(f);
    }
    cargo(&args)?;
    let root = workspace_root();
    let criterion_dir = std::env::var_os("CARGO_TARGET_DIR")
        .map_or_else(|| root.join("target"), PathBuf::from)
        .join("criterion");
    let mut rows = Vec::new();
    collect_estimates(&criterion_dir, &criterion_dir, &mut rows);
    rows.sort_by(|a, b| a.0.cmp(&b.0));
    let mut table = render(&rows, &machine());
    let out = root.join("docs").join("BENCHMARKS.md");
    // The Python section is written by hand from python/bench/bench.py: keep it.
    if let Ok(old) = std::fs::read_to_string(&out)
        && let Some(at) = old.find(PYTHON_SECTION)
    {
        table.push('\n');
        table.push_str(&old[at..]);
    }
    std::fs::create_dir_all(root.join("docs")).map_err(|e| e.to_string())?;
    std::fs::write(&out, table).map_err(|e| format!("cannot write {}: {e}", out.display()))?;
    eprintln!("xtask: wrote {} ({} benches)", out.display(), rows.len());
    Ok(())
}

/// The heading of docs/BENCHMARKS.md's Python section, which `cargo xtask bench` keeps.
const PYTHON_SECTION: &str = "## Python";

/// Walks `target/criterion/**/new/estimates.json` and reads the median point estimate (ns).
fn collect_estimates(base: &Path, dir: &Path, rows: &mut Vec<(String, f64)>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if !path.is_dir() {
            continue;
        }
        if path.file_name().is_some_and(|n| n == "new") {
            let est = path.join("estimates.json");
            if let (Ok(text), Some(parent)) = (std::fs::read_to_string(&est), path.parent())
                && let Some(median) = median_ns(&text)
            {
                let name = parent
                    .strip_prefix(base)
                    .unwrap_or(parent)
                    .to_string_lossy()
                    .replace('\\', "/");
                rows.push((name, median));
            }
        } else if path
            .file_name()
            .is_none_or(|n| n != "report" && n != "base" && n != "change")
        {
            collect_estimates(base, &path, rows);
        }
    }
}

/// Extracts `"median":{"confidence_interval":{...},"point_estimate":X` without a JSON crate.
fn median_ns(json: &str) -> Option<f64> {
    let start = json.find("\"median\"")?;
    let rest = &json[start..];
    let pe = rest.find("\"point_estimate\":")?;
    let num = &rest[pe + "\"point_estimate\":".len()..];
    let end = num.find([',', '}'])?;
    num[..end].trim().parse().ok()
}

fn human(ns: f64) -> String {
    if ns < 1e3 {
        format!("{ns:.1} ns")
    } else if ns < 1e6 {
        format!("{:.2} µs", ns / 1e3)
    } else if ns < 1e9 {
        format!("{:.2} ms", ns / 1e6)
    } else {
        format!("{:.2} s", ns / 1e9)
    }
}

fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .map(|l| l.split(':').nth(1).unwrap_or("").trim().to_owned())
        })
        .unwrap_or_else(|| "unknown CPU".to_owned());
    let cores = std::thread::available_parallelism().map_or(0, std::num::NonZero::get);
    let rustc = Command::new("rustc")
        .arg("--version")
        .output()
        .ok()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_owned())
        .unwrap_or_default();
    format!(
        "{cpu}, {cores} cores, {} {}, {rustc}",
        std::env::consts::OS,
        std::env::consts::ARCH
    )
}

fn render(rows: &[(String, f64)], machine: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# Benchmarks\n");
    let _ = writeln!(
        s,
        "Written by `cargo xtask bench` from criterion's median estimates. Do not edit by hand.\n"
    );
    let _ = writeln!(s, "Machine: {machine}\n");
    let _ = writeln!(s, "| bench | median |\n|---|---|");
    for (name, ns) in rows {
        let _ = writeln!(s, "| `{name}` | {} |", human(*ns));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_criterion_median() {
        let json = r#"{"mean":{"confidence_interval":{"confidence_level":0.95,"lower_bound":1.0,"upper_bound":2.0},"point_estimate":1.5,"standard_error":0.1},"median":{"confidence_interval":{"confidence_level":0.95,"lower_bound":100.0,"upper_bound":130.0},"point_estimate":123.25,"standard_error":0.1}}"#;
        assert_eq!(median_ns(json).map(f64::to_bits), Some(123.25f64.to_bits()));
        assert_eq!(human(123.25), "123.2 ns");
        assert_eq!(human(1500.0), "1.50 µs");
    }
}

//! `cargo xtask mutate [--count N] [--seed S] [FILE...]`: the full ASTERIX
//! mutation run (default 10⁶ mutated records, seed 0x00a57e41) over the
//! Argus-written samples of every category (CAT048, CAT034, CAT021, CAT062)
//! and over any raw ASTERIX block files given, each file its own run of
//! `count` steps. A watchdog fails the run if 10 000 steps take over 60 s (an
//! infinite loop); the report gives the time, the steps per mutation and the
//! skips per typed reason.

use std::fmt::Write as _;
use std::sync::mpsc;
use std::time::Duration;

use argus_asterix::mutation::{self, MutationReport, OPS};
use argus_asterix::samples;

/// No heartbeat for this long means a decode does not terminate.
const WATCHDOG: Duration = Duration::from_secs(60);

pub(crate) fn mutate(args: &[String]) -> Result<(), String> {
    let mut count: u64 = 1_000_000;
    let mut seed: u64 = 0x00a5_7e41;
    let mut files = Vec::new();
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut number = |name: &str| -> Result<u64, String> {
            let v = it.next().ok_or_else(|| format!("{name} needs a value"))?;
            let v = v.strip_prefix("0x").map_or_else(
                || v.parse::<u64>().map_err(|e| e.to_string()),
                |h| u64::from_str_radix(h, 16).map_err(|e| e.to_string()),
            );
            v.map_err(|e| format!("{name}: {e}"))
        };
        match a.as_str() {
            "--count" => count = number("--count")?,
            "--seed" => seed = number("--seed")?,
            f if f.starts_with("--") => return Err(format!("mutate: unknown option {f}")),
            f => files.push(f.to_owned()),
        }
    }
    let mut inputs = vec![(
        "Argus samples (CAT048, CAT034, CAT021, CAT062)".to_owned(),
        samples::all_categories().map_err(|e| e.to_string())?,
    )];
    for f in files {
        let bytes = std::fs::read(&f).map_err(|e| format!("{f}: {e}"))?;
        inputs.push((f, bytes));
    }
    for (name, bytes) in inputs {
        eprintln!("xtask: mutate {name}: {count} steps, seed {seed:#x}");
        let report = watched(bytes, seed, count)?;
        println!("{}", render(&name, &report));
    }
    Ok(())
}

/// Runs on a worker thread; the main thread waits for its heartbeats.
fn watched(bytes: Vec<u8>, seed: u64, count: u64) -> Result<MutationReport, String> {
    let (beat, heard) = mpsc::channel::<u64>();
    let worker = std::thread::spawn(move || {
        mutation::run(&bytes, seed, count, &mut |n| {
            // The receiver outlives the run unless the watchdog fired.
            let _ = beat.send(n);
        })
    });
    let mut last = 0;
    loop {
        match heard.recv_timeout(WATCHDOG) {
            Ok(n) => last = n,
            // The sender is dropped when the run ends (or panics).
            Err(mpsc::RecvTimeoutError::Disconnected) => break,
            Err(mpsc::RecvTimeoutError::Timeout) => {
                return Err(format!(
                    "mutate: no progress for {WATCHDOG:?} after step {last}: a decode does not terminate"
                ));
            }
        }
    }
    let result = worker
        .join()
        .map_err(|_| "mutate: the run panicked outside a decode".to_owned())?;
    result.map_err(|f| {
        let hex: String = f.input.iter().fold(String::new(), |mut s, b| {
            let _ = write!(s, "{b:02x}");
            s
        });
        format!("{f}\ninput ({} bytes): {hex}", f.input.len())
    })
}

fn render(name: &str, r: &MutationReport) -> String {
    let mut s = String::new();
    let secs = r.elapsed.as_secs_f64();
    // Counts below 2^53: exact in f64.
    #[allow(clippy::cast_precision_loss)]
    let rate = r.inputs as f64 / secs.max(1e-9);
    let _ = writeln!(
        s,
        "{name}: {} mutated records in {secs:.2} s ({rate:.0}/s), slowest decode {:?}, {} records kept",
        r.inputs, r.max_decode, r.records_kept
    );
    for (op, n) in OPS.iter().zip(r.per_op) {
        let _ = writeln!(s, "  mutation {op}: {n}");
    }
    for (reason, n) in &r.skips {
        let _ = writeln!(s, "  skip {reason}: {n}");
    }
    s
}

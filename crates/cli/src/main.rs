//! The `argus` command: paper scenarios (Monte Carlo, table, figures), plot simulation
//! and tracking a user's plot file. File formats: `docs/FORMATS.md`.
//!
//! Errors are printed once (`error: <file>:<line>: field '<f>': <what>`) and the process
//! exits with code 2; nothing a user feeds in panics.

use std::process::ExitCode;

fn main() -> ExitCode {
    argus_cli::run_command_line()
}

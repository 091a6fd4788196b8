//! What the binary-driving tests share.

use std::path::Path;
use std::process::{Command, Output};

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

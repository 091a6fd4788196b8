//! The campaign's progress bar: an indicatif bar on a terminal's stderr, silent
//! otherwise. Safe to tick from rayon's threads.

use argus_scenarios::Progress;
use indicatif::{ProgressBar, ProgressStyle};

/// A bar of runs, or nothing when stderr is not a terminal.
#[derive(Debug, Clone)]
pub(crate) struct Bar(Option<ProgressBar>);

impl Bar {
    /// A bar of `len` steps if `visible`, else a silent handle.
    #[must_use]
    pub(crate) fn new(len: u64, visible: bool) -> Self {
        if !visible {
            return Self(None);
        }
        let bar = ProgressBar::new(len);
        if let Ok(style) =
            ProgressStyle::with_template("{bar:40} {pos}/{len} runs  {elapsed_precise} (eta {eta})")
        {
            bar.set_style(style);
        }
        Self(Some(bar))
    }
}

impl Progress for Bar {
    fn tick(&self) {
        if let Some(b) = &self.0 {
            b.inc(1);
        }
    }

    fn finish(&self) {
        if let Some(b) = &self.0 {
            b.finish_and_clear();
        }
    }
}

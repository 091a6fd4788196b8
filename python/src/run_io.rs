//! A batch filter run's outputs and failure, shared by the step-by-step run
//! ([`crate::filter_core`]) and the run that reuses the covariance recursion
//! ([`crate::memo_run`]).

use argus_filters::FilterError;

/// A batch run's output arrays (numpy's memory, written with the GIL released),
/// row-major: `n × N` states, `n × N × N` covariances, `n` NIS.
#[derive(Debug)]
pub(crate) struct RunSlices<'a> {
    pub(crate) x: &'a mut [f64],
    pub(crate) p: &'a mut [f64],
    pub(crate) nis: &'a mut [f64],
}

/// A smoother's outputs, row-major: `n × N` states, `n × N × N` covariances, `n` NIS.
#[derive(Debug, Default)]
pub(crate) struct RunOut {
    pub(crate) x: Vec<f64>,
    pub(crate) p: Vec<f64>,
    pub(crate) nis: Vec<f64>,
}

/// A batch run's failure: at step `index`, or the starting estimate.
#[derive(Debug)]
pub(crate) enum RunFail {
    /// The starting estimate is invalid.
    Start(argus_core_math::MathError),
    /// The step at plot `index` failed.
    Step(usize, FilterError),
}

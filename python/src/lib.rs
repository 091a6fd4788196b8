//! `argus_tracking._native`: the Rust side of the `argus_tracking` Python package (see
//! `python/argus_tracking/__init__.py` for the public API and `python/README.md`). Its
//! modules are private (`cargo doc --document-private-items` shows them):
//!
//! - `filters`: `KalmanFilter`, `ExtendedKalmanFilter`, `UnscentedKalmanFilter`
//!   (`filter_build` makes them, `filter_core` runs them, `memo_run` is the KF's
//!   batch run reusing its covariance recursion).
//! - `imm`: `Imm`, `MultiImm`, `DifferenceImm`.
//! - `track`: `argus track`'s pipeline on plot tables and as a stream (`track_run`
//!   calls the job runner).
//! - `scenarios`: the scenario list and campaigns.
//! - `metrics`: NEES / NIS, chi-square intervals, OSPA, GOSPA.
//! - `score`: the real-traffic track scoring (`argus score`).
//! - `errors`: Rust errors as the package's Python exceptions.
//! - `arrays`: numpy arrays in (checked, named) and out.

mod arrays;
mod errors;
mod filter_build;
mod filter_core;
mod filters;
mod imm;
mod imm_core;
mod memo_run;
mod metrics;
mod run_io;
mod scenarios;
mod score;
mod track;
mod track_run;

use pyo3::prelude::*;

/// The native module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<filters::Filter>()?;
    m.add_class::<filters::KalmanFilter>()?;
    m.add_class::<filters::ExtendedKalmanFilter>()?;
    m.add_class::<filters::UnscentedKalmanFilter>()?;
    m.add_class::<imm::ImmBase>()?;
    m.add_class::<imm::Imm_>()?;
    m.add_class::<imm::MultiImm_>()?;
    m.add_class::<imm::DifferenceImm_>()?;
    m.add_class::<track::TrackerStream>()?;
    m.add_function(wrap_pyfunction!(track::track_columns, m)?)?;
    m.add_function(wrap_pyfunction!(track::tracks_text_columns, m)?)?;
    m.add_function(wrap_pyfunction!(track::toml_from_json, m)?)?;
    m.add_function(wrap_pyfunction!(scenarios::list_scenarios_json, m)?)?;
    m.add_function(wrap_pyfunction!(scenarios::run_scenario_json, m)?)?;
    m.add_function(wrap_pyfunction!(metrics::nees_py, m)?)?;
    m.add_function(wrap_pyfunction!(metrics::chi2_interval, m)?)?;
    m.add_function(wrap_pyfunction!(metrics::ospa, m)?)?;
    m.add_function(wrap_pyfunction!(metrics::gospa, m)?)?;
    m.add_function(wrap_pyfunction!(score::score_json, m)?)?;
    Ok(())
}

//! Helpers shared by the scenario tests.

/// The value Argus reports in the row `key` of a run's report.
pub(crate) fn row(out: &argus_scenarios::RunOutput, key: &str) -> f64 {
    out.report
        .rows
        .iter()
        .find(|r| r.key == key)
        .unwrap_or_else(|| panic!("no row {key}"))
        .ours
}

//! `list_scenarios()` and `run_scenario(...)`: the scenarios crate's listing and Monte
//! Carlo campaigns, returned as JSON text that the Python side loads (the same document
//! as the command's `summary.json`, without the file list, plus the series).

use std::collections::BTreeMap;

use argus_scenarios::{NoProgress, Params, ScenarioError};
use pyo3::prelude::*;

use crate::errors::{Kind, invalid, raise, rust_name};

fn scenario_error(e: &ScenarioError) -> PyErr {
    match e {
        ScenarioError::UnknownScenario { .. } => raise(
            Kind::UnknownScenario,
            &rust_name("ScenarioError", e),
            e.to_string(),
        ),
        ScenarioError::Param { .. } => invalid("ScenarioError", "parameter", e),
        _ => raise(
            Kind::Numerical,
            &rust_name("ScenarioError", e),
            e.to_string(),
        ),
    }
}

/// Every scenario as JSON: `[{name, description, default_runs, params: [{key, default,
/// min, max, help}]}]`.
#[pyfunction]
pub(crate) fn list_scenarios_json() -> String {
    let list: Vec<serde_json::Value> = argus_scenarios::list()
        .into_iter()
        .map(|s| {
            let params: Vec<serde_json::Value> = s
                .params
                .iter()
                .map(|p| {
                    serde_json::json!({
                        "key": p.key, "default": p.default, "min": p.min, "max": p.max, "help": p.help,
                    })
                })
                .collect();
            serde_json::json!({
                "name": s.name,
                "description": s.description,
                "default_runs": s.default_runs,
                "params": params,
            })
        })
        .collect();
    serde_json::Value::Array(list).to_string()
}

/// Runs scenario `name` over runs `start..end` with base `seed` and the `key=value`
/// `settings` (the command's `--set`), with the GIL released. Returns the JSON document
/// `{scenario, seed, runs, params, results, notes, series}`.
#[pyfunction]
pub(crate) fn run_scenario_json(
    py: Python<'_>,
    name: &str,
    start: u64,
    end: Option<u64>,
    seed: u64,
    settings: Vec<String>,
) -> PyResult<String> {
    let out = py.detach(|| -> Result<Result<String, String>, ScenarioError> {
        let sc = argus_scenarios::find(name)?;
        let end = end.unwrap_or_else(|| sc.default_runs());
        if end <= start {
            return Ok(Err(format!(
                "argument 'runs': the range {start}..{end} is empty"
            )));
        }
        let params = Params::from_settings(&sc.params(), &settings)?;
        let run = argus_scenarios::run(sc.as_ref(), start..end, seed, params.clone(), &NoProgress)?;
        let report = run.report;
        let results: BTreeMap<&str, &argus_scenarios::Row> =
            report.rows.iter().map(|r| (r.key.as_str(), r)).collect();
        let series: BTreeMap<&str, serde_json::Value> = report
            .series
            .iter()
            .map(|s| {
                (
                    s.name.as_str(),
                    serde_json::json!({"columns": s.columns, "rows": s.rows}),
                )
            })
            .collect();
        let doc = serde_json::json!({
            "scenario": sc.name(),
            "seed": seed,
            "runs": [start, end],
            "params": params.as_map(),
            "results": results,
            "notes": report.notes,
            "series": series,
        });
        Ok(Ok(doc.to_string()))
    });
    match out {
        Ok(Ok(text)) => Ok(text),
        Ok(Err(message)) => Err(crate::errors::input(message)),
        Err(e) => Err(scenario_error(&e)),
    }
}

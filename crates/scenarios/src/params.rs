//! The parameters a scenario accepts: their specs ([`ParamSpec`]) and validated values
//! ([`Params`]).

use std::collections::BTreeMap;

use crate::error::{ParamProblem, ScenarioError};

/// A numeric parameter a scenario accepts through `--set key=value`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParamSpec {
    /// Key.
    pub key: &'static str,
    /// Default value.
    pub default: f64,
    /// Smallest allowed value (inclusive).
    pub min: f64,
    /// Largest allowed value (inclusive).
    pub max: f64,
    /// Unit and meaning, one line.
    pub help: &'static str,
}

impl ParamSpec {
    /// A parameter `key` with its default, allowed range and one-line help.
    pub const fn new(
        key: &'static str,
        default: f64,
        min: f64,
        max: f64,
        help: &'static str,
    ) -> Self {
        Self {
            key,
            default,
            min,
            max,
            help,
        }
    }
}

/// Validated parameter values (every key of the scenario's specs is present).
///
/// `--set key=a,b,c` gives a key a list of values (each checked like a single one): the
/// map holds the first, [`Params::list`] all of them, and [`Params::get`] refuses a key
/// set to a list, so only a scenario that reads the key with [`Params::list`] accepts one.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Params(BTreeMap<String, f64>, BTreeMap<String, Vec<f64>>);

impl Params {
    /// The defaults overridden by `key=value` settings, each checked against `specs`.
    ///
    /// # Errors
    /// [`ScenarioError::Param`] for a setting without `=`, an unknown key (with the known
    /// ones), a non-numeric or non-finite value, or a value outside `[min, max]` (for a
    /// comma list: any of its values).
    pub fn from_settings(specs: &[ParamSpec], settings: &[String]) -> Result<Self, ScenarioError> {
        let mut map: BTreeMap<String, f64> = specs
            .iter()
            .map(|p| (p.key.to_owned(), p.default))
            .collect();
        let mut lists: BTreeMap<String, Vec<f64>> = BTreeMap::new();
        for s in settings {
            let (k, v) = s
                .split_once('=')
                .ok_or_else(|| ScenarioError::param(s.as_str(), ParamProblem::Syntax))?;
            let (k, v) = (k.trim(), v.trim());
            let spec = specs.iter().find(|p| p.key == k).ok_or_else(|| {
                let known = specs.iter().map(|p| p.key).collect();
                ScenarioError::param(k, ParamProblem::Unknown { known })
            })?;
            let mut xs = Vec::new();
            for item in v.split(',').map(str::trim) {
                let x: f64 = item.parse().map_err(|_| {
                    let (value, item) = (v.to_owned(), item.to_owned());
                    ScenarioError::param(k, ParamProblem::NotANumber { value, item })
                })?;
                if !x.is_finite() || x < spec.min || x > spec.max {
                    let problem = ParamProblem::OutOfRange {
                        value: v.to_owned(),
                        item: item.to_owned(),
                        min: spec.min,
                        max: spec.max,
                        help: spec.help,
                    };
                    return Err(ScenarioError::param(k, problem));
                }
                xs.push(x);
            }
            if let Some(&first) = xs.first() {
                map.insert(k.to_owned(), first);
            }
            if xs.len() > 1 {
                lists.insert(k.to_owned(), xs);
            } else {
                lists.remove(k);
            }
        }
        Ok(Self(map, lists))
    }

    /// The value of `key`.
    ///
    /// # Errors
    /// [`ScenarioError::Param`]: [`ParamProblem::List`] for a key set to a list,
    /// [`ParamProblem::Undeclared`] if the scenario asks for a key it did not declare (a
    /// bug in the scenario, reported rather than panicking).
    pub fn get(&self, key: &str) -> Result<f64, ScenarioError> {
        if let Some(xs) = self.1.get(key) {
            return Err(ScenarioError::param(
                key,
                ParamProblem::List { len: xs.len() },
            ));
        }
        self.0
            .get(key)
            .copied()
            .ok_or_else(|| ScenarioError::param(key, ParamProblem::Undeclared))
    }

    /// All values of `key`: the list given as `--set key=a,b,…`, else its one value.
    ///
    /// # Errors
    /// [`ParamProblem::Undeclared`] if the scenario asks for a key it did not declare.
    pub fn list(&self, key: &str) -> Result<Vec<f64>, ScenarioError> {
        match self.1.get(key) {
            Some(xs) => Ok(xs.clone()),
            None => self
                .0
                .get(key)
                .map(|&x| vec![x])
                .ok_or_else(|| ScenarioError::param(key, ParamProblem::Undeclared)),
        }
    }

    /// All values.
    #[must_use]
    pub fn as_map(&self) -> &BTreeMap<String, f64> {
        &self.0
    }
}

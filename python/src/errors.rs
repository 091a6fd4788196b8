//! Rust errors as Python exceptions. The classes are defined in Python
//! (`argus_tracking/errors.py`, so `InvalidInputError` can be both an `ArgusError` and a
//! `ValueError`); each instance carries the message and, as `rust_error`, the Rust error's
//! type and variant (e.g. `FilterError::Math::NotPositiveDefinite`).

use std::fmt::{Debug, Display};

use pyo3::prelude::*;
use pyo3::types::PyType;

/// Which Python class an error is raised as.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    /// Bad input (shape, dtype, NaN, non-PD covariance, time order, bad parameter):
    /// `InvalidInputError(ArgusError, ValueError)`.
    InvalidInput,
    /// A filter step that failed on valid input (e.g. a singular innovation covariance):
    /// `NumericalError(ArgusError, ArithmeticError)`.
    Numerical,
    /// An unknown scenario name: `UnknownScenarioError(InvalidInputError, KeyError)`.
    UnknownScenario,
    /// A file could not be read or written: `ArgusOSError(ArgusError, OSError)`.
    Io,
}

impl Kind {
    fn class_name(self) -> &'static str {
        match self {
            Self::InvalidInput => "InvalidInputError",
            Self::Numerical => "NumericalError",
            Self::UnknownScenario => "UnknownScenarioError",
            Self::Io => "ArgusOSError",
        }
    }
}

/// The Rust type and variant path of `e` from its `Debug` form: `Math(NotPositiveDefinite
/// { .. })` of a `FilterError` gives `FilterError::Math::NotPositiveDefinite`.
pub(crate) fn rust_name<E: Debug>(type_name: &str, e: &E) -> String {
    let debug = format!("{e:?}");
    let mut out = type_name.to_owned();
    let mut rest = debug.as_str();
    loop {
        let end = rest
            .find(|c: char| !(c.is_alphanumeric() || c == '_'))
            .unwrap_or(rest.len());
        let ident = &rest[..end];
        if ident.is_empty() || !ident.starts_with(|c: char| c.is_ascii_uppercase()) {
            break;
        }
        out.push_str("::");
        out.push_str(ident);
        if rest[end..].starts_with('(') {
            rest = &rest[end + 1..];
        } else {
            break;
        }
    }
    out
}

/// A Python exception of `kind` with `message` and the Rust error name `rust_error`.
pub(crate) fn raise(kind: Kind, rust_error: &str, message: impl Into<String>) -> PyErr {
    let message = message.into();
    Python::attach(|py| {
        let made = py
            .import("argus_tracking.errors")
            .and_then(|m| m.getattr(kind.class_name()))
            .and_then(|c| Ok(c.cast_into::<PyType>()?))
            .and_then(|c| c.call1((message.clone(), rust_error)));
        match made {
            Ok(instance) => PyErr::from_value(instance),
            Err(e) => e,
        }
    })
}

/// Bad input, with the Rust error `e` (of type `type_name`) as the cause: `context` says
/// which argument or step (e.g. `argument 'P'`), then the Rust error's text.
pub(crate) fn invalid<E: Debug + Display>(type_name: &str, context: &str, e: &E) -> PyErr {
    raise(
        Kind::InvalidInput,
        &rust_name(type_name, e),
        format!("{context}: {e}"),
    )
}

/// Bad input found by the bindings themselves (shape, dtype, NaN, time order).
pub(crate) fn input(message: impl Into<String>) -> PyErr {
    raise(Kind::InvalidInput, "argus_python::InputError", message)
}

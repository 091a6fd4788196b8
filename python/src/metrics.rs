//! Metrics: NEES / NIS per row with the chi-square interval of their average, OSPA and
//! GOSPA between point sets.

use argus_core_math::{Gaussian, Matrix, Vector, anees_interval};
use argus_sim::{Gospa, Ospa, SimError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays::{finite, out_array, read};
use crate::errors::{input, invalid};

/// `(x − truth)ᵀ P⁻¹ (x − truth)` for one row of size `D`.
fn one<const D: usize>(x: &[f64], p: &[f64], t: &[f64]) -> Result<f64, argus_core_math::MathError> {
    let g = Gaussian::new(
        Vector::<D>::from_column_slice(x),
        Matrix::<D, D>::from_row_slice(p),
    )?;
    Ok(g.mahalanobis_sq(&Vector::<D>::from_column_slice(t)))
}

/// The normalised squared error of every row: `x` (`n × d`), `P` (`n × d × d`) against
/// `truth` (`n × d`); for the NIS pass the innovations as `x`, `S` as `P` and zeros as
/// `truth` (or use `nis`). `d` from 1 to 6.
#[pyfunction]
#[pyo3(name = "nees")]
pub(crate) fn nees_py<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    #[allow(non_snake_case)] P: &Bound<'py, PyAny>,
    truth: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let (xv, shape) = read(x, "x", &[None, None])?;
    let (n, d) = (shape[0], shape[1]);
    let (pv, _) = read(P, "P", &[Some(n), Some(d), Some(d)])?;
    let (tv, _) = read(truth, "truth", &[Some(n), Some(d)])?;
    let mut out = Vec::with_capacity(n);
    for k in 0..n {
        let (xs, ps, ts) = (
            &xv[k * d..(k + 1) * d],
            &pv[k * d * d..(k + 1) * d * d],
            &tv[k * d..(k + 1) * d],
        );
        let v = match d {
            1 => one::<1>(xs, ps, ts),
            2 => one::<2>(xs, ps, ts),
            3 => one::<3>(xs, ps, ts),
            4 => one::<4>(xs, ps, ts),
            5 => one::<5>(xs, ps, ts),
            6 => one::<6>(xs, ps, ts),
            _ => {
                return Err(input(format!(
                    "argument 'x': dimension {d} (1 to 6 supported)"
                )));
            }
        }
        .map_err(|e| invalid("MathError", &format!("argument 'P': P[{k}]"), &e))?;
        out.push(v);
    }
    Ok(out_array(py, out, &[n])?.into_any())
}

/// The two-sided `confidence` interval `(lower, upper)` of the average of `runs`
/// independent NEES (or NIS) values of a `dim`-dimensional statistic:
/// `χ²_{dim·runs}((1 ∓ confidence)/2) / runs` (Bar-Shalom, Li & Kirubarajan 2001 §5.4.2).
#[pyfunction]
#[pyo3(signature = (dim, runs=1, confidence=0.95))]
pub(crate) fn chi2_interval(dim: usize, runs: usize, confidence: f64) -> PyResult<(f64, f64)> {
    let iv = anees_interval(dim, runs, confidence)
        .map_err(|e| invalid("MathError", "chi2_interval", &e))?;
    Ok((iv.lower, iv.upper))
}

fn points<const D: usize>(v: &[f64]) -> Vec<Vector<D>> {
    v.chunks_exact(D)
        .map(Vector::<D>::from_column_slice)
        .collect()
}

fn sets(
    truth: &Bound<'_, PyAny>,
    estimates: &Bound<'_, PyAny>,
) -> PyResult<(Vec<f64>, Vec<f64>, usize)> {
    let (t, ts) = read(truth, "truth", &[None, None])?;
    let d = ts[1];
    let (e, _) = read(estimates, "estimates", &[None, Some(d)])?;
    if !(1..=3).contains(&d) {
        return Err(input(format!(
            "argument 'truth': dimension {d} (1 to 3 supported)"
        )));
    }
    Ok((t, e, d))
}

fn sim_error(e: &SimError) -> PyErr {
    invalid("SimError", "metric", e)
}

/// OSPA (Schuhmacher, Vo & Vo 2008) between `truth` (`m × d`) and `estimates` (`n × d`),
/// `d` from 1 to 3: a dict with `distance`, `localisation` and `cardinality`.
#[pyfunction]
#[pyo3(signature = (truth, estimates, cutoff, order=1.0))]
pub(crate) fn ospa<'py>(
    py: Python<'py>,
    truth: &Bound<'py, PyAny>,
    estimates: &Bound<'py, PyAny>,
    cutoff: f64,
    order: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let (t, e, d) = sets(truth, estimates)?;
    let o =
        Ospa::new(finite(cutoff, "cutoff")?, finite(order, "order")?).map_err(|e| sim_error(&e))?;
    let v = match d {
        1 => o.distance(&points::<1>(&t), &points::<1>(&e)),
        2 => o.distance(&points::<2>(&t), &points::<2>(&e)),
        _ => o.distance(&points::<3>(&t), &points::<3>(&e)),
    }
    .map_err(|e| sim_error(&e))?;
    let out = PyDict::new(py);
    out.set_item("distance", v.distance)?;
    out.set_item("localisation", v.localisation)?;
    out.set_item("cardinality", v.cardinality)?;
    Ok(out)
}

/// GOSPA with α = 2 (Rahmathullah, García-Fernández & Svensson 2017) between `truth` and
/// `estimates`: a dict with `distance`, `localisation`, `missed`, `false_targets`,
/// `assigned`, `missed_count`, `false_count`.
#[pyfunction]
#[pyo3(signature = (truth, estimates, cutoff, order=2.0))]
pub(crate) fn gospa<'py>(
    py: Python<'py>,
    truth: &Bound<'py, PyAny>,
    estimates: &Bound<'py, PyAny>,
    cutoff: f64,
    order: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let (t, e, d) = sets(truth, estimates)?;
    let g = Gospa::new(finite(cutoff, "cutoff")?, finite(order, "order")?)
        .map_err(|e| sim_error(&e))?;
    let v = match d {
        1 => g.distance(&points::<1>(&t), &points::<1>(&e)),
        2 => g.distance(&points::<2>(&t), &points::<2>(&e)),
        _ => g.distance(&points::<3>(&t), &points::<3>(&e)),
    }
    .map_err(|e| sim_error(&e))?;
    let out = PyDict::new(py);
    out.set_item("distance", v.distance)?;
    out.set_item("localisation", v.localisation)?;
    out.set_item("missed", v.missed)?;
    out.set_item("false_targets", v.false_targets)?;
    out.set_item("assigned", v.assigned)?;
    out.set_item("missed_count", v.missed_count)?;
    out.set_item("false_count", v.false_count)?;
    Ok(out)
}

//! numpy arrays in and out. Inputs may be float64 arrays of any memory layout (strided
//! views are read through their strides), integer or boolean arrays, or nested
//! sequences; anything else, a wrong shape or a NaN is an `InvalidInputError` naming the
//! argument, the index and the problem. Outputs are new C-contiguous float64 arrays.

use std::borrow::Cow;

use argus_core_math::{Matrix, Vector};
use numpy::{PyArray1, PyArray2, PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArray};
use numpy::{PyArrayDescrMethods, PyUntypedArrayMethods, dtype};
use pyo3::prelude::*;
use pyo3::types::{PyList, PyTuple};

use crate::errors::input;

/// `obj` as a read-only float64 array: float64 arrays as they are, other real dtypes and
/// sequences converted with `numpy.asarray(obj, dtype=float64)`.
fn float_array<'py>(obj: &Bound<'py, PyAny>, name: &str) -> PyResult<PyReadonlyArrayDyn<'py, f64>> {
    if let Ok(a) = obj.cast::<PyArrayDyn<f64>>() {
        return Ok(a.readonly());
    }
    let py = obj.py();
    if let Ok(a) = obj.cast::<PyUntypedArray>() {
        let kind = a.dtype().kind();
        if !matches!(kind, b'f' | b'i' | b'u' | b'b') {
            return Err(input(format!(
                "argument '{name}': dtype {} is not a real number type (float64 expected)",
                a.dtype()
            )));
        }
    }
    let np = py.import("numpy")?;
    let converted = np
        .getattr("asarray")?
        .call1((obj, dtype::<f64>(py)))
        .map_err(|e| {
            input(format!(
                "argument '{name}': cannot be read as a float64 array ({e})"
            ))
        })?;
    let a = converted
        .cast_into::<PyArrayDyn<f64>>()
        .map_err(|_| input(format!("argument '{name}': not a float64 array")))?;
    Ok(a.readonly())
}

/// The shape text of `shape`, e.g. `(3, 4)`.
fn shape_text(shape: &[usize]) -> String {
    let inner: Vec<String> = shape.iter().map(usize::to_string).collect();
    if shape.len() == 1 {
        format!("({},)", inner[0])
    } else {
        format!("({})", inner.join(", "))
    }
}

/// `obj` as a read-only float64 array of exactly `shape` (`None` = any length on that
/// axis), converted if it is not one already.
pub(crate) fn array<'py>(
    obj: &Bound<'py, PyAny>,
    name: &str,
    shape: &[Option<usize>],
) -> PyResult<PyReadonlyArrayDyn<'py, f64>> {
    let a = float_array(obj, name)?;
    let got = a.shape();
    let ok = got.len() == shape.len()
        && got
            .iter()
            .zip(shape)
            .all(|(g, s)| s.is_none_or(|s| s == *g));
    if !ok {
        let want: Vec<String> = shape
            .iter()
            .map(|s| s.map_or_else(|| "n".to_owned(), |v| v.to_string()))
            .collect();
        let want = if want.len() == 1 {
            format!("({},)", want[0])
        } else {
            format!("({})", want.join(", "))
        };
        return Err(input(format!(
            "argument '{name}': expected shape {want}, got {}",
            shape_text(got)
        )));
    }
    Ok(a)
}

/// The entries of `a` in row-major order — its own memory when it is C-contiguous, a
/// copy otherwise — checked finite.
pub(crate) fn values<'a>(
    a: &'a PyReadonlyArrayDyn<'_, f64>,
    name: &str,
) -> PyResult<Cow<'a, [f64]>> {
    let values: Cow<'a, [f64]> = match a.as_slice() {
        Ok(s) => Cow::Borrowed(s),
        Err(_) => Cow::Owned(a.as_array().iter().copied().collect()),
    };
    // `0 v` is ±0 for a finite `v` and NaN otherwise, so the sum is NaN exactly when an
    // entry is not finite: one pass the compiler vectorises; the entry is looked for only
    // then.
    let all_finite = values.iter().fold(0.0, |acc, v| acc + 0.0 * v) == 0.0;
    if !all_finite && let Some(i) = values.iter().position(|v| !v.is_finite()) {
        return Err(input(format!(
            "argument '{name}': entry {} is {} (every entry must be finite)",
            index_text(i, a.shape()),
            values[i]
        )));
    }
    Ok(values)
}

/// Reads `obj` as an array of exactly `shape` (`None` = any length on that axis), in
/// row-major order, checking every entry is finite. Returns the values and the shape.
pub(crate) fn read(
    obj: &Bound<'_, PyAny>,
    name: &str,
    shape: &[Option<usize>],
) -> PyResult<(Vec<f64>, Vec<usize>)> {
    let a = array(obj, name, shape)?;
    let v = values(&a, name)?.into_owned();
    Ok((v, a.shape().to_vec()))
}

/// The multi-index of flat row-major position `i` in `shape`, e.g. `[1, 2]`.
pub(crate) fn index_text(mut i: usize, shape: &[usize]) -> String {
    let mut idx = vec![0; shape.len()];
    for (k, n) in shape.iter().enumerate().rev() {
        if *n > 0 {
            idx[k] = i % n;
            i /= n;
        }
    }
    let parts: Vec<String> = idx.iter().map(usize::to_string).collect();
    format!("[{}]", parts.join(", "))
}

/// A length-`N` vector argument.
pub(crate) fn vector<const N: usize>(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Vector<N>> {
    let (v, _) = read(obj, name, &[Some(N)])?;
    Ok(Vector::<N>::from_column_slice(&v))
}

/// A length-`M` vector argument on the per-call path of the stateful filters: a 1-D
/// float64 array of length `M` (any stride) is read element by element and a list or
/// tuple of `M` floats item by item, neither converted through numpy nor allocated;
/// anything else, and any value that fails a check, takes [`vector`]'s general path,
/// which converts it or raises its error (so the errors are the same).
pub(crate) fn small_vector<const M: usize>(
    obj: &Bound<'_, PyAny>,
    name: &str,
) -> PyResult<Vector<M>> {
    let mut v = Vector::<M>::zeros();
    let read_all = |v: &mut Vector<M>, get: &dyn Fn(usize) -> Option<f64>| {
        (0..M).all(|i| match get(i) {
            Some(x) if x.is_finite() => {
                v[i] = x;
                true
            }
            _ => false,
        })
    };
    let fast = if let Ok(a) = obj.cast::<PyArray1<f64>>() {
        a.len() == M && read_all(&mut v, &|i| a.get_owned([i]))
    } else if let Ok(t) = obj.cast::<PyTuple>() {
        t.len() == M && read_all(&mut v, &|i| t.get_item(i).ok()?.extract::<f64>().ok())
    } else if let Ok(l) = obj.cast::<PyList>() {
        l.len() == M && read_all(&mut v, &|i| l.get_item(i).ok()?.extract::<f64>().ok())
    } else {
        false
    };
    if fast { Ok(v) } else { vector::<M>(obj, name) }
}

/// An `R × C` matrix argument (row-major in numpy).
pub(crate) fn matrix<const R: usize, const C: usize>(
    obj: &Bound<'_, PyAny>,
    name: &str,
) -> PyResult<Matrix<R, C>> {
    let (v, _) = read(obj, name, &[Some(R), Some(C)])?;
    Ok(Matrix::<R, C>::from_row_slice(&v))
}

/// A float scalar argument that must be finite.
pub(crate) fn finite(value: f64, name: &str) -> PyResult<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(input(format!("argument '{name}': {value} is not finite")))
    }
}

/// A new 1-D array of `v`.
pub(crate) fn out_vector<'py, const N: usize>(
    py: Python<'py>,
    v: &Vector<N>,
) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_slice(py, v.as_slice())
}

/// A new `R × C` array of `m` (row-major).
pub(crate) fn out_matrix<'py, const R: usize, const C: usize>(
    py: Python<'py>,
    m: &Matrix<R, C>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let t = m.transpose();
    PyArray1::from_slice(py, t.as_slice()).reshape([R, C])
}

/// A new float64 array of `shape` to be written whole by a batch run: `numpy.empty`
/// (not zeroed: filling 10⁵ steps' covariances with zeros first cost a sixth of the run;
/// every bit pattern is a valid float64, and the run writes every entry), from numpy's
/// allocator (large arrays get huge pages where the system offers them).
pub(crate) fn empty<'py>(
    py: Python<'py>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let np = py.import("numpy")?;
    let a = np
        .getattr("empty")?
        .call1((shape.to_vec(), dtype::<f64>(py)))?;
    Ok(a.cast_into::<PyArrayDyn<f64>>()?)
}

/// A new array of `shape` from row-major `values`.
pub(crate) fn out_array<'py>(
    py: Python<'py>,
    values: Vec<f64>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    PyArray1::from_vec(py, values).reshape(shape.to_vec())
}

//! One filter with its measurement model behind a trait object, so the three Python
//! filter classes share the predict / update / step / batch-run code for every motion
//! model (CV, CA, CT) and sensor (Cartesian position, polar radar).

use argus_core_math::{Gaussian, Vector};
use argus_filters::{FilterError, RtsTrack, SmoothError, SmoothingFilter};
use argus_sensors::MeasurementModel;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;

use crate::arrays::{matrix, out_matrix, out_vector, vector};
use crate::errors::{Kind, invalid, raise, rust_name};

/// An estimate `(x, P)` handed back to Python.
pub(crate) type Estimate<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray2<f64>>);

/// A filter step's error: bad input (an interval, a parameter) or a numerical failure.
pub(crate) fn filter_error(context: &str, e: &FilterError) -> PyErr {
    match e {
        FilterError::InvalidInterval { .. } | FilterError::InvalidParameter { .. } => {
            invalid("FilterError", context, e)
        }
        _ => raise(
            Kind::Numerical,
            &rust_name("FilterError", e),
            format!("{context}: {e}"),
        ),
    }
}

/// The estimate `(x, P)` given by the caller as `Gaussian`, naming the arguments.
fn estimate<const N: usize>(x: &Bound<'_, PyAny>, p: &Bound<'_, PyAny>) -> PyResult<Gaussian<N>> {
    let mean = vector::<N>(x, "x")?;
    let cov = matrix::<N, N>(p, "P")?;
    Gaussian::new(mean, cov).map_err(|e| invalid("MathError", "argument 'P'", &e))
}

/// A batch run's outputs, row-major: `n × N` states, `n × N × N` covariances, `n` NIS.
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

/// A filter and its sensor with the state size `n()` and measurement size `m()` fixed.
pub(crate) trait DynFilter: Send + Sync {
    /// State size.
    fn n(&self) -> usize;
    /// Measurement size.
    fn m(&self) -> usize;
    /// `(x, P)` predicted over `dt`.
    fn predict<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
        p: &Bound<'py, PyAny>,
        dt: f64,
    ) -> PyResult<Estimate<'py>>;
    /// `(x, P)` updated with `z`.
    fn update<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
        p: &Bound<'py, PyAny>,
        z: &Bound<'py, PyAny>,
    ) -> PyResult<Estimate<'py>>;
    /// Predict over `dt` (skipped when `dt == 0`), then update with `z`.
    fn step<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
        p: &Bound<'py, PyAny>,
        dt: f64,
        z: &Bound<'py, PyAny>,
    ) -> PyResult<Estimate<'py>>;
    /// The batch run (no Python objects: called with the GIL released). `x0` and `p0`
    /// row-major; `dts[k]` the interval before plot `k` (0: no prediction).
    fn run(&self, x0: &[f64], p0: &[f64], dts: &[f64], plots: &[f64]) -> Result<RunOut, RunFail>;
    /// The fixed-interval RTS smoother (unscented RTS for the UKF) of the same run from
    /// `(x0, P0)` at `t0` over plots at `times` (strictly after `t0`, increasing): the
    /// smoothed estimate at each plot, with the forward pass's NIS.
    fn smooth(
        &self,
        start: (&[f64], &[f64], f64),
        times: &[f64],
        plots: &[f64],
    ) -> Result<RunOut, SmoothFail>;
}

/// A smoothing failure: the starting estimate, or the smoother's error.
#[derive(Debug)]
pub(crate) enum SmoothFail {
    /// The starting estimate is invalid.
    Start(argus_core_math::MathError),
    /// The forward or backward pass failed.
    Smooth(SmoothError),
}

/// The concrete pair: filter `F` on an `N`-state, sensor `Me` of `M` components.
pub(crate) struct Typed<F, Me, const N: usize, const M: usize> {
    pub(crate) filter: F,
    pub(crate) meas: Me,
}

impl<const N: usize, const M: usize, F, Me> DynFilter for Typed<F, Me, N, M>
where
    F: SmoothingFilter<N> + Send + Sync,
    Me: MeasurementModel<N, M> + Send + Sync,
{
    fn n(&self) -> usize {
        N
    }

    fn m(&self) -> usize {
        M
    }

    fn predict<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
        p: &Bound<'py, PyAny>,
        dt: f64,
    ) -> PyResult<Estimate<'py>> {
        let g = estimate::<N>(x, p)?;
        let out = self
            .filter
            .predict(&g, dt)
            .map_err(|e| filter_error(&format!("predict over dt = {dt}"), &e))?;
        Ok((out_vector(py, out.mean()), out_matrix(py, out.cov())?))
    }

    fn update<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
        p: &Bound<'py, PyAny>,
        z: &Bound<'py, PyAny>,
    ) -> PyResult<Estimate<'py>> {
        let g = estimate::<N>(x, p)?;
        let z = vector::<M>(z, "z")?;
        let (out, _) = self
            .filter
            .update(&g, &self.meas, &z)
            .map_err(|e| filter_error("update", &e))?;
        Ok((out_vector(py, out.mean()), out_matrix(py, out.cov())?))
    }

    fn step<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
        p: &Bound<'py, PyAny>,
        dt: f64,
        z: &Bound<'py, PyAny>,
    ) -> PyResult<Estimate<'py>> {
        let mut g = estimate::<N>(x, p)?;
        let z = vector::<M>(z, "z")?;
        if dt != 0.0 {
            g = self
                .filter
                .predict(&g, dt)
                .map_err(|e| filter_error(&format!("predict over dt = {dt}"), &e))?;
        }
        let (out, _) = self
            .filter
            .update(&g, &self.meas, &z)
            .map_err(|e| filter_error("update", &e))?;
        Ok((out_vector(py, out.mean()), out_matrix(py, out.cov())?))
    }

    fn run(&self, x0: &[f64], p0: &[f64], dts: &[f64], plots: &[f64]) -> Result<RunOut, RunFail> {
        let n = dts.len();
        let mut est = Gaussian::new(
            Vector::<N>::from_column_slice(x0),
            argus_core_math::Matrix::<N, N>::from_row_slice(p0),
        )
        .map_err(RunFail::Start)?;
        let mut out = RunOut {
            x: Vec::with_capacity(n * N),
            p: Vec::with_capacity(n * N * N),
            nis: Vec::with_capacity(n),
        };
        for (k, dt) in dts.iter().enumerate() {
            if *dt != 0.0 {
                self.filter
                    .predict_in_place(&mut est, *dt)
                    .map_err(|e| RunFail::Step(k, e))?;
            }
            let z = Vector::<M>::from_column_slice(&plots[k * M..(k + 1) * M]);
            let innov = self
                .filter
                .update_in_place(&mut est, &self.meas, &z)
                .map_err(|e| RunFail::Step(k, e))?;
            out.x.extend_from_slice(est.mean().as_slice());
            out.p.extend_from_slice(est.cov().transpose().as_slice());
            out.nis.push(innov.nis);
        }
        Ok(out)
    }

    fn smooth(
        &self,
        (x0, p0, t0): (&[f64], &[f64], f64),
        times: &[f64],
        plots: &[f64],
    ) -> Result<RunOut, SmoothFail> {
        let start = Gaussian::new(
            Vector::<N>::from_column_slice(x0),
            argus_core_math::Matrix::<N, N>::from_row_slice(p0),
        )
        .map_err(SmoothFail::Start)?;
        let mut track = RtsTrack::new(t0, start).map_err(SmoothFail::Smooth)?;
        let mut nis = Vec::with_capacity(times.len());
        for (k, t) in times.iter().enumerate() {
            let z = Vector::<M>::from_column_slice(&plots[k * M..(k + 1) * M]);
            track
                .predict(&self.filter, *t)
                .map_err(SmoothFail::Smooth)?;
            let innov = track
                .update(&self.filter, &self.meas, &z)
                .map_err(SmoothFail::Smooth)?;
            nis.push(innov.nis);
        }
        let smoothed = track.smooth().map_err(SmoothFail::Smooth)?;
        let mut out = RunOut {
            x: Vec::with_capacity(times.len() * N),
            p: Vec::with_capacity(times.len() * N * N),
            nis,
        };
        // Step 0 is the start at t0; the plots' steps follow.
        for g in smoothed.iter().skip(1) {
            out.x.extend_from_slice(g.mean().as_slice());
            out.p.extend_from_slice(g.cov().transpose().as_slice());
        }
        Ok(out)
    }
}

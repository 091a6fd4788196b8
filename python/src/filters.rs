//! `KalmanFilter`, `ExtendedKalmanFilter`, `UnscentedKalmanFilter` on the CV, CA and CT
//! motion models (and the 3-D CV, CA) with a Cartesian position, polar or spherical radar
//! sensor. Two forms: functional (the estimate is passed in and a new one returned) and
//! stateful like FilterPy's (the object owns `x` and `P`; `predict(dt)` / `update(z)`
//! change them in place); a batch `run` filters a whole plot array in one call with the
//! GIL released.

use argus_filters::{CovarianceForm, UtParams};
use numpy::{PyArray1, PyArray2};
use numpy::{PyArrayMethods, PyUntypedArrayMethods};
use pyo3::PyClassInitializer;
use pyo3::prelude::*;

use crate::arrays::{array, empty, finite, out_array, read, values};
use crate::errors::{Kind, input, invalid, raise, rust_name};
use crate::filter_build::{FilterKind, SensorArgs, make, model_dimension, sensor_spec};
use crate::filter_core::{DynFilter, Estimate, SmoothFail, filter_error};
use crate::run_io::{RunFail, RunSlices};

/// The base of the three filter classes. Stateful like FilterPy (the object owns `x` and
/// `P`: `predict(dt)`, `update(z)`, the `x` / `P` / `nis` properties, `set_state`) and
/// functional (`predict(x, P, dt)`, `update(x, P, z)`, `step`, `run`, `smooth`: the own
/// state is not touched).
#[pyclass(subclass, frozen, module = "argus_tracking._native")]
pub(crate) struct Filter {
    inner: Box<dyn DynFilter>,
    model: String,
}

/// The intervals before each plot: `times[0] - t0`, then the differences; time must not
/// go backwards (equal times update twice without a prediction).
pub(crate) fn intervals(times: &[f64], t0: f64) -> PyResult<Vec<f64>> {
    // `dts[k] = times[k] − times[k − 1]` (`t0` before the first) in one pass the compiler
    // vectorises (an exact-size map, no per-element capacity check or early exit), then one
    // vectorised test for a negative interval; the offending index is looked for only
    // then. The same subtractions as a step-by-step loop, so the same bits.
    let mut dts = Vec::with_capacity(times.len());
    if let Some(first) = times.first() {
        dts.push(first - t0);
        dts.extend(times[1..].iter().zip(times).map(|(t, p)| t - p));
    }
    if dts.iter().fold(false, |bad, d| bad | (*d < 0.0))
        && let Some(k) = dts.iter().position(|d| *d < 0.0)
    {
        let (t, prev) = (times[k], if k == 0 { t0 } else { times[k - 1] });
        return Err(input(if k == 0 {
            format!("argument 'times': times[0] = {t} is before t0 = {prev}")
        } else {
            format!(
                "argument 'times': times[{k}] = {t} is before times[{}] = {prev} (time goes backwards)",
                k - 1
            )
        }));
    }
    Ok(dts)
}

#[pymethods]
impl Filter {
    /// State size (4 for CV and CT `[x, vx, y, vy]`, 6 for CA `[x, vx, ax, y, vy, ay]`).
    #[getter]
    fn dim_x(&self) -> usize {
        self.inner.n()
    }

    /// Measurement size (2 for Cartesian 2-D and polar, 3 for Cartesian 3-D and spherical).
    #[getter]
    fn dim_z(&self) -> usize {
        self.inner.m()
    }

    /// The motion model's name.
    #[getter]
    fn model(&self) -> &str {
        &self.model
    }

    /// The filter's own state mean (a new array; FilterPy's `kf.x`).
    #[getter]
    fn x<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.state_x(py)
    }

    /// Sets the own state mean (checked; the object is unchanged on an error).
    #[setter]
    fn set_x(&self, x: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.set_state(Some(x), None)
    }

    /// The filter's own state covariance (a new array; FilterPy's `kf.P`).
    #[getter(P)]
    fn p<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.inner.state_p(py)
    }

    /// Sets the own state covariance (checked symmetric positive definite; the object is
    /// unchanged on an error).
    #[setter(P)]
    fn set_p(&self, p: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.set_state(None, Some(p))
    }

    /// The NIS of the last stateful `update(z)` (`None` before the first, and after the
    /// state is set).
    #[getter]
    fn nis(&self) -> Option<f64> {
        self.inner.state_nis()
    }

    /// Sets the own estimate `(x, P)` at once (checked together; unchanged on an error).
    #[pyo3(signature = (x, P))]
    fn set_state(
        &self,
        x: &Bound<'_, PyAny>,
        #[allow(non_snake_case)] P: &Bound<'_, PyAny>,
    ) -> PyResult<()> {
        self.inner.set_state(Some(x), Some(P))
    }

    /// Two forms. `predict(dt)`: predicts the filter's own `(x, P)` over `dt` seconds in
    /// place and returns `None` (FilterPy's `kf.predict()`). `predict(x, P, dt)`: predicts
    /// the given `(x, P)` and returns the new `(x, P)`; the own state is not touched.
    #[pyo3(signature = (x=None, P=None, dt=None))]
    fn predict<'py>(
        &self,
        py: Python<'py>,
        x: Option<&Bound<'py, PyAny>>,
        #[allow(non_snake_case)] P: Option<&Bound<'py, PyAny>>,
        dt: Option<f64>,
    ) -> PyResult<Option<Estimate<'py>>> {
        match (x, P, dt) {
            (Some(x), Some(p), Some(dt)) => self.inner.predict(py, x, p, dt).map(Some),
            (None, None, Some(dt)) => self.inner.predict_state(dt).map(|()| None),
            (Some(dt), None, None) => {
                let dt = dt
                    .extract::<f64>()
                    .map_err(|_| input("argument 'dt': predict(dt) needs a number (seconds)"))?;
                self.inner.predict_state(dt).map(|()| None)
            }
            _ => Err(input(
                "predict takes (dt) for the filter's own state or (x, P, dt) for a given one",
            )),
        }
    }

    /// Two forms. `update(z)`: updates the filter's own `(x, P)` with the plot `z` in
    /// place and returns `None` (FilterPy's `kf.update(z)`; the NIS is in `nis`).
    /// `update(x, P, z)`: updates the given `(x, P)` and returns the new `(x, P)`.
    #[pyo3(signature = (x=None, P=None, z=None))]
    fn update<'py>(
        &self,
        py: Python<'py>,
        x: Option<&Bound<'py, PyAny>>,
        #[allow(non_snake_case)] P: Option<&Bound<'py, PyAny>>,
        z: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Option<Estimate<'py>>> {
        match (x, P, z) {
            (Some(x), Some(p), Some(z)) => self.inner.update(py, x, p, z).map(Some),
            (None, None, Some(z)) | (Some(z), None, None) => {
                self.inner.update_state(z).map(|()| None)
            }
            _ => Err(input(
                "update takes (z) for the filter's own state or (x, P, z) for a given one",
            )),
        }
    }

    /// `predict` over `dt` (none when `dt == 0`) then `update` with `z`, in one call.
    fn step<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
        #[allow(non_snake_case)] P: &Bound<'py, PyAny>,
        dt: f64,
        z: &Bound<'py, PyAny>,
    ) -> PyResult<Estimate<'py>> {
        self.inner.step(py, x, P, dt, z)
    }

    /// Filters `plots` (`n × dim_z`) at `times` (`n`, not decreasing) from `(x0, P0)` at
    /// `t0` (default `times[0]`: the first plot updates the start without a prediction).
    /// Returns `(x, P, nis)`: `n × dim_x`, `n × dim_x × dim_x`, `n`. The GIL is released.
    /// The filter's own state is not touched. With `reuse_gain` (default) the
    /// `KalmanFilter` reuses the covariance recursion of an earlier step with the same
    /// `dt` and bit-identical prior covariance (the gain and posterior covariance do not
    /// depend on the plots): the result is the same to the bit as with `reuse_gain=False`.
    #[pyo3(signature = (times, plots, x0, P0, t0=None, *, reuse_gain=true))]
    #[allow(clippy::too_many_arguments)]
    fn run<'py>(
        &self,
        py: Python<'py>,
        times: &Bound<'py, PyAny>,
        plots: &Bound<'py, PyAny>,
        x0: &Bound<'py, PyAny>,
        #[allow(non_snake_case)] P0: &Bound<'py, PyAny>,
        t0: Option<f64>,
        reuse_gain: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let (n, m) = (self.inner.n(), self.inner.m());
        let times_a = array(times, "times", &[None])?;
        let times = values(&times_a, "times")?;
        let plots_a = array(plots, "plots", &[None, Some(m)])?;
        if plots_a.shape()[0] != times.len() {
            return Err(input(format!(
                "argument 'plots': {} rows for {} times",
                plots_a.shape()[0],
                times.len()
            )));
        }
        let plots = values(&plots_a, "plots")?;
        let (x0, _) = read(x0, "x0", &[Some(n)])?;
        let (p0, _) = read(P0, "P0", &[Some(n), Some(n)])?;
        let t0 = match t0 {
            Some(t) => finite(t, "t0")?,
            None => times.first().copied().unwrap_or(0.0),
        };
        let dts = intervals(&times, t0)?;
        let steps = times.len();
        let x = empty(py, &[steps, n])?;
        let p = empty(py, &[steps, n, n])?;
        let nis = empty(py, &[steps])?;
        {
            let (mut xw, mut pw, mut nw) =
                (x.try_readwrite()?, p.try_readwrite()?, nis.try_readwrite()?);
            let out = RunSlices {
                x: xw.as_slice_mut()?,
                p: pw.as_slice_mut()?,
                nis: nw.as_slice_mut()?,
            };
            let inner = &self.inner;
            py.detach(|| inner.run(&x0, &p0, &dts, &plots, reuse_gain, out))
                .map_err(|f| match f {
                    RunFail::Start(e) => invalid("MathError", "argument 'P0'", &e),
                    RunFail::Step(k, e) => {
                        filter_error(&format!("step {k} (times[{k}] = {})", times[k]), &e)
                    }
                })?;
        }
        let cls = py.import("argus_tracking._results")?.getattr("FilterRun")?;
        cls.call1((x, p, nis))
    }

    /// Fixed-interval smoothing (RTS; the unscented RTS for the UKF) of the run over
    /// `plots` at `times` from `(x0, P0)` at `t0` (before `times[0]`; times increasing).
    /// Returns `FilterRun(x, P, nis)`: the smoothed estimate at each plot and the forward
    /// pass's NIS. The GIL is released.
    #[pyo3(signature = (times, plots, x0, P0, t0))]
    fn smooth<'py>(
        &self,
        py: Python<'py>,
        times: &Bound<'py, PyAny>,
        plots: &Bound<'py, PyAny>,
        x0: &Bound<'py, PyAny>,
        #[allow(non_snake_case)] P0: &Bound<'py, PyAny>,
        t0: f64,
    ) -> PyResult<Bound<'py, PyAny>> {
        let (n, m) = (self.inner.n(), self.inner.m());
        let (times, _) = read(times, "times", &[None])?;
        let (plots, shape) = read(plots, "plots", &[None, Some(m)])?;
        if shape[0] != times.len() {
            return Err(input(format!(
                "argument 'plots': {} rows for {} times",
                shape[0],
                times.len()
            )));
        }
        let (x0, _) = read(x0, "x0", &[Some(n)])?;
        let (p0, _) = read(P0, "P0", &[Some(n), Some(n)])?;
        let t0 = finite(t0, "t0")?;
        let inner = &self.inner;
        let out = py
            .detach(|| inner.smooth((&x0, &p0, t0), &times, &plots))
            .map_err(|e| smooth_error(&e))?;
        let steps = times.len();
        let x = out_array(py, out.x, &[steps, n])?;
        let p = out_array(py, out.p, &[steps, n, n])?;
        let nis = out_array(py, out.nis, &[steps])?;
        let cls = py.import("argus_tracking._results")?.getattr("FilterRun")?;
        cls.call1((x, p, nis))
    }
}

/// A smoother's error: time order and bad input as `InvalidInputError`, a failed step as
/// `NumericalError`, naming the step.
fn smooth_error(e: &SmoothFail) -> PyErr {
    match e {
        SmoothFail::Start(e) => invalid("MathError", "argument 'P0'", e),
        SmoothFail::Smooth(e @ argus_filters::SmoothError::ForwardFailed { .. }) => raise(
            Kind::Numerical,
            &rust_name("SmoothError", e),
            format!("smoother: {e}"),
        ),
        SmoothFail::Smooth(e) => invalid("SmoothError", "smoother", e),
    }
}

/// The base's initialiser: the filter, with its own estimate set from `x` / `P` if given.
fn base(
    inner: Box<dyn DynFilter>,
    model: &str,
    x: Option<&Bound<'_, PyAny>>,
    p: Option<&Bound<'_, PyAny>>,
) -> PyResult<PyClassInitializer<Filter>> {
    if x.is_some() || p.is_some() {
        inner.set_state(x, p)?;
    }
    Ok(PyClassInitializer::from(Filter {
        inner,
        model: model.to_owned(),
    }))
}

/// The covariance update form.
fn form(joseph: bool) -> CovarianceForm {
    if joseph {
        CovarianceForm::Joseph
    } else {
        CovarianceForm::Standard
    }
}

/// The linear Kalman filter on a Cartesian position sensor.
#[pyclass(extends = Filter, frozen, module = "argus_tracking._native")]
pub(crate) struct KalmanFilter;

#[pymethods]
impl KalmanFilter {
    #[new]
    #[pyo3(signature = (model="cv", q=1.0, R=None, *, omega=0.0, joseph=true, x=None, P=None))]
    fn new(
        model: &str,
        q: f64,
        #[allow(non_snake_case)] R: Option<&Bound<'_, PyAny>>,
        omega: f64,
        joseph: bool,
        x: Option<&Bound<'_, PyAny>>,
        #[allow(non_snake_case)] P: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<PyClassInitializer<Self>> {
        let args = SensorArgs {
            sensor: "cartesian",
            r: R,
            sigma_range: None,
            sigma_azimuth: None,
            sigma_elevation: None,
            sensor_position: None,
        };
        let sensor = sensor_spec(&args, model_dimension(model)?)?;
        let inner = make(FilterKind::Kf(form(joseph)), model, q, omega, sensor)?;
        Ok(base(inner, model, x, P)?.add_subclass(Self))
    }
}

/// The extended Kalman filter (polar or spherical radar, or a Cartesian sensor).
#[pyclass(extends = Filter, frozen, module = "argus_tracking._native")]
pub(crate) struct ExtendedKalmanFilter;

#[pymethods]
impl ExtendedKalmanFilter {
    #[new]
    #[pyo3(signature = (model="cv", q=1.0, *, sensor="polar", sigma_range=None, sigma_azimuth=None, sigma_elevation=None, sensor_position=None, R=None, omega=0.0, joseph=true, x=None, P=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        model: &str,
        q: f64,
        sensor: &str,
        sigma_range: Option<f64>,
        sigma_azimuth: Option<f64>,
        sigma_elevation: Option<f64>,
        sensor_position: Option<&Bound<'_, PyAny>>,
        #[allow(non_snake_case)] R: Option<&Bound<'_, PyAny>>,
        omega: f64,
        joseph: bool,
        x: Option<&Bound<'_, PyAny>>,
        #[allow(non_snake_case)] P: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<PyClassInitializer<Self>> {
        let args = SensorArgs {
            sensor,
            r: R,
            sigma_range,
            sigma_azimuth,
            sigma_elevation,
            sensor_position,
        };
        let spec = sensor_spec(&args, model_dimension(model)?)?;
        let inner = make(FilterKind::Ekf(form(joseph)), model, q, omega, spec)?;
        Ok(base(inner, model, x, P)?.add_subclass(Self))
    }
}

/// The unscented Kalman filter (scaled unscented transform with `alpha`, `beta`, `kappa`).
#[pyclass(extends = Filter, frozen, module = "argus_tracking._native")]
pub(crate) struct UnscentedKalmanFilter;

#[pymethods]
impl UnscentedKalmanFilter {
    #[new]
    #[pyo3(signature = (model="cv", q=1.0, *, sensor="polar", sigma_range=None, sigma_azimuth=None, sigma_elevation=None, sensor_position=None, R=None, omega=0.0, alpha=1.0, beta=2.0, kappa=0.0, x=None, P=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        model: &str,
        q: f64,
        sensor: &str,
        sigma_range: Option<f64>,
        sigma_azimuth: Option<f64>,
        sigma_elevation: Option<f64>,
        sensor_position: Option<&Bound<'_, PyAny>>,
        #[allow(non_snake_case)] R: Option<&Bound<'_, PyAny>>,
        omega: f64,
        alpha: f64,
        beta: f64,
        kappa: f64,
        x: Option<&Bound<'_, PyAny>>,
        #[allow(non_snake_case)] P: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<PyClassInitializer<Self>> {
        let args = SensorArgs {
            sensor,
            r: R,
            sigma_range,
            sigma_azimuth,
            sigma_elevation,
            sensor_position,
        };
        let spec = sensor_spec(&args, model_dimension(model)?)?;
        let params = UtParams { alpha, beta, kappa };
        let inner = make(FilterKind::Ukf(params), model, q, omega, spec)?;
        Ok(base(inner, model, x, P)?.add_subclass(Self))
    }
}

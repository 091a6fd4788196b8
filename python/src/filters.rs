//! `KalmanFilter`, `ExtendedKalmanFilter`, `UnscentedKalmanFilter`: stateless filters on
//! the CV, CA and CT motion models with a Cartesian position or a polar radar sensor.
//! The estimate is passed in and a new one returned; a batch `run` filters a whole plot
//! array in one call with the GIL released.

use argus_core_math::Matrix;
use argus_filters::{CovarianceForm, Ekf, Kf, Ukf, UtParams};
use argus_motion_models::{Ca2D, CoordinatedTurn, Cv2D, LinearMotionModel};
use argus_sensors::{CartesianPosition, Polar2D, RadarNoise};
use pyo3::PyClassInitializer;
use pyo3::prelude::*;

use crate::arrays::{finite, matrix, out_array, read};
use crate::errors::{Kind, input, invalid, raise, rust_name};
use crate::filter_core::{DynFilter, Estimate, RunFail, SmoothFail, Typed, filter_error};

/// Which filter.
#[derive(Debug, Clone, Copy)]
enum FilterKind {
    Kf(CovarianceForm),
    Ekf(CovarianceForm),
    Ukf(UtParams),
}

/// The sensor of a filter.
#[derive(Debug, Clone, Copy)]
enum SensorSpec {
    /// `z = (x, y)` with covariance `R`.
    Cartesian(Matrix<2, 2>),
    /// `z = (range, azimuth)` from `position`, azimuth from the x axis counter-clockwise.
    Polar {
        position: [f64; 2],
        sigma_range: f64,
        sigma_azimuth: f64,
    },
}

fn boxed<F, Me, const N: usize, const M: usize>(filter: F, meas: Me) -> Box<dyn DynFilter>
where
    Typed<F, Me, N, M>: DynFilter + 'static,
{
    Box::new(Typed::<F, Me, N, M> { filter, meas })
}

fn with_model<const N: usize, Mo>(
    kind: FilterKind,
    model: Mo,
    indices: [usize; 2],
    sensor: SensorSpec,
) -> PyResult<Box<dyn DynFilter>>
where
    Mo: LinearMotionModel<N> + Send + Sync + 'static,
{
    let sensor_err = |e: argus_sensors::SensorError| invalid("SensorError", "sensor", &e);
    match sensor {
        SensorSpec::Cartesian(r) => {
            let meas = CartesianPosition::<N, 2>::new(indices, r)
                .map_err(|e| invalid("SensorError", "argument 'R'", &e))?;
            Ok(match kind {
                FilterKind::Kf(form) => boxed::<_, _, N, 2>(Kf::with_form(model, form), meas),
                FilterKind::Ekf(form) => boxed::<_, _, N, 2>(Ekf::with_form(model, form), meas),
                FilterKind::Ukf(params) => boxed::<_, _, N, 2>(
                    Ukf::<N, Mo>::new(model, params)
                        .map_err(|e| filter_error("unscented transform", &e))?,
                    meas,
                ),
            })
        }
        SensorSpec::Polar {
            position,
            sigma_range,
            sigma_azimuth,
        } => {
            let noise =
                RadarNoise::constant(sigma_range, sigma_azimuth, 0.0).map_err(sensor_err)?;
            let meas = Polar2D::<N>::new(indices, position, noise).map_err(sensor_err)?;
            Ok(match kind {
                FilterKind::Kf(_) => {
                    return Err(input(
                        "KalmanFilter needs a linear (Cartesian) sensor: use \
                         ExtendedKalmanFilter or UnscentedKalmanFilter for polar plots",
                    ));
                }
                FilterKind::Ekf(form) => boxed::<_, _, N, 2>(Ekf::with_form(model, form), meas),
                FilterKind::Ukf(params) => boxed::<_, _, N, 2>(
                    Ukf::<N, Mo>::new(model, params)
                        .map_err(|e| filter_error("unscented transform", &e))?,
                    meas,
                ),
            })
        }
    }
}

/// Builds the filter of `model` (`cv`, `ca` or `ct`) with noise `q` and turn rate `omega`.
fn make(
    kind: FilterKind,
    model: &str,
    q: f64,
    omega: f64,
    sensor: SensorSpec,
) -> PyResult<Box<dyn DynFilter>> {
    let motion = |e: argus_motion_models::MotionError| invalid("MotionError", "model", &e);
    match model {
        "cv" => with_model::<4, _>(kind, Cv2D::discrete(q).map_err(motion)?, [0, 2], sensor),
        "ca" => with_model::<6, _>(kind, Ca2D::discrete(q).map_err(motion)?, [0, 3], sensor),
        "ct" => with_model::<4, _>(
            kind,
            CoordinatedTurn::new(omega, q).map_err(motion)?,
            [0, 2],
            sensor,
        ),
        other => Err(input(format!(
            "argument 'model': unknown motion model {other:?} (expected 'cv', 'ca' or 'ct')"
        ))),
    }
}

/// The sensor from the constructor's arguments.
fn sensor_spec(
    sensor: &str,
    r: Option<&Bound<'_, PyAny>>,
    sigma_range: Option<f64>,
    sigma_azimuth: Option<f64>,
    sensor_position: (f64, f64),
) -> PyResult<SensorSpec> {
    match sensor {
        "cartesian" => {
            let r = r.ok_or_else(|| input("argument 'R': a Cartesian sensor needs R (2 × 2)"))?;
            Ok(SensorSpec::Cartesian(matrix::<2, 2>(r, "R")?))
        }
        "polar" => {
            let sr = sigma_range
                .ok_or_else(|| input("argument 'sigma_range': a polar sensor needs it (m)"))?;
            let sa = sigma_azimuth
                .ok_or_else(|| input("argument 'sigma_azimuth': a polar sensor needs it (rad)"))?;
            Ok(SensorSpec::Polar {
                position: [
                    finite(sensor_position.0, "sensor_position")?,
                    finite(sensor_position.1, "sensor_position")?,
                ],
                sigma_range: sr,
                sigma_azimuth: sa,
            })
        }
        other => Err(input(format!(
            "argument 'sensor': unknown sensor {other:?} (expected 'cartesian' or 'polar')"
        ))),
    }
}

/// The base of the three filter classes: `predict`, `update`, `step` and `run`.
#[pyclass(subclass, frozen, module = "argus_tracking._native")]
pub(crate) struct Filter {
    inner: Box<dyn DynFilter>,
    model: String,
}

/// The intervals before each plot: `times[0] - t0`, then the differences; time must not
/// go backwards (equal times update twice without a prediction).
pub(crate) fn intervals(times: &[f64], t0: f64) -> PyResult<Vec<f64>> {
    let mut prev = t0;
    let mut dts = Vec::with_capacity(times.len());
    for (k, t) in times.iter().enumerate() {
        if *t < prev {
            return Err(input(if k == 0 {
                format!("argument 'times': times[0] = {t} is before t0 = {prev}")
            } else {
                format!(
                    "argument 'times': times[{k}] = {t} is before times[{}] = {prev} (time goes backwards)",
                    k - 1
                )
            }));
        }
        dts.push(t - prev);
        prev = *t;
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

    /// Measurement size (2).
    #[getter]
    fn dim_z(&self) -> usize {
        self.inner.m()
    }

    /// The motion model's name.
    #[getter]
    fn model(&self) -> &str {
        &self.model
    }

    /// Predicts `(x, P)` over `dt` seconds; returns the new `(x, P)`.
    fn predict<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
        #[allow(non_snake_case)] P: &Bound<'py, PyAny>,
        dt: f64,
    ) -> PyResult<Estimate<'py>> {
        self.inner.predict(py, x, P, dt)
    }

    /// Updates the predicted `(x, P)` with the plot `z`; returns the new `(x, P)`.
    fn update<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
        #[allow(non_snake_case)] P: &Bound<'py, PyAny>,
        z: &Bound<'py, PyAny>,
    ) -> PyResult<Estimate<'py>> {
        self.inner.update(py, x, P, z)
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

    /// Filters `plots` (`n × 2`) at `times` (`n`, not decreasing) from `(x0, P0)` at `t0`
    /// (default `times[0]`: the first plot updates the start without a prediction).
    /// Returns `(x, P, nis)`: `n × dim_x`, `n × dim_x × dim_x`, `n`. The GIL is released.
    #[pyo3(signature = (times, plots, x0, P0, t0=None))]
    fn run<'py>(
        &self,
        py: Python<'py>,
        times: &Bound<'py, PyAny>,
        plots: &Bound<'py, PyAny>,
        x0: &Bound<'py, PyAny>,
        #[allow(non_snake_case)] P0: &Bound<'py, PyAny>,
        t0: Option<f64>,
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
        let t0 = match t0 {
            Some(t) => finite(t, "t0")?,
            None => times.first().copied().unwrap_or(0.0),
        };
        let dts = intervals(&times, t0)?;
        let inner = &self.inner;
        let out = py
            .detach(|| inner.run(&x0, &p0, &dts, &plots))
            .map_err(|f| match f {
                RunFail::Start(e) => invalid("MathError", "argument 'P0'", &e),
                RunFail::Step(k, e) => {
                    filter_error(&format!("step {k} (times[{k}] = {})", times[k]), &e)
                }
            })?;
        let steps = times.len();
        let x = out_array(py, out.x, &[steps, n])?;
        let p = out_array(py, out.p, &[steps, n, n])?;
        let nis = out_array(py, out.nis, &[steps])?;
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

/// The linear Kalman filter on a Cartesian position sensor.
#[pyclass(extends = Filter, frozen, module = "argus_tracking._native")]
pub(crate) struct KalmanFilter;

#[pymethods]
impl KalmanFilter {
    #[new]
    #[pyo3(signature = (model="cv", q=1.0, R=None, *, omega=0.0, joseph=true))]
    fn new(
        model: &str,
        q: f64,
        #[allow(non_snake_case)] R: Option<&Bound<'_, PyAny>>,
        omega: f64,
        joseph: bool,
    ) -> PyResult<PyClassInitializer<Self>> {
        let form = if joseph {
            CovarianceForm::Joseph
        } else {
            CovarianceForm::Standard
        };
        let sensor = sensor_spec("cartesian", R, None, None, (0.0, 0.0))?;
        let inner = make(FilterKind::Kf(form), model, q, omega, sensor)?;
        Ok(PyClassInitializer::from(Filter {
            inner,
            model: model.to_owned(),
        })
        .add_subclass(Self))
    }
}

/// The extended Kalman filter (polar radar or Cartesian sensor).
#[pyclass(extends = Filter, frozen, module = "argus_tracking._native")]
pub(crate) struct ExtendedKalmanFilter;

#[pymethods]
impl ExtendedKalmanFilter {
    #[new]
    #[pyo3(signature = (model="cv", q=1.0, *, sensor="polar", sigma_range=None, sigma_azimuth=None, sensor_position=(0.0, 0.0), R=None, omega=0.0, joseph=true))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        model: &str,
        q: f64,
        sensor: &str,
        sigma_range: Option<f64>,
        sigma_azimuth: Option<f64>,
        sensor_position: (f64, f64),
        #[allow(non_snake_case)] R: Option<&Bound<'_, PyAny>>,
        omega: f64,
        joseph: bool,
    ) -> PyResult<PyClassInitializer<Self>> {
        let form = if joseph {
            CovarianceForm::Joseph
        } else {
            CovarianceForm::Standard
        };
        let spec = sensor_spec(sensor, R, sigma_range, sigma_azimuth, sensor_position)?;
        let inner = make(FilterKind::Ekf(form), model, q, omega, spec)?;
        Ok(PyClassInitializer::from(Filter {
            inner,
            model: model.to_owned(),
        })
        .add_subclass(Self))
    }
}

/// The unscented Kalman filter (scaled unscented transform with `alpha`, `beta`, `kappa`).
#[pyclass(extends = Filter, frozen, module = "argus_tracking._native")]
pub(crate) struct UnscentedKalmanFilter;

#[pymethods]
impl UnscentedKalmanFilter {
    #[new]
    #[pyo3(signature = (model="cv", q=1.0, *, sensor="polar", sigma_range=None, sigma_azimuth=None, sensor_position=(0.0, 0.0), R=None, omega=0.0, alpha=1.0, beta=2.0, kappa=0.0))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        model: &str,
        q: f64,
        sensor: &str,
        sigma_range: Option<f64>,
        sigma_azimuth: Option<f64>,
        sensor_position: (f64, f64),
        #[allow(non_snake_case)] R: Option<&Bound<'_, PyAny>>,
        omega: f64,
        alpha: f64,
        beta: f64,
        kappa: f64,
    ) -> PyResult<PyClassInitializer<Self>> {
        let spec = sensor_spec(sensor, R, sigma_range, sigma_azimuth, sensor_position)?;
        let params = UtParams { alpha, beta, kappa };
        let inner = make(FilterKind::Ukf(params), model, q, omega, spec)?;
        Ok(PyClassInitializer::from(Filter {
            inner,
            model: model.to_owned(),
        })
        .add_subclass(Self))
    }
}

//! `Imm`, `MultiImm` and `DifferenceImm`: IMMs of Kalman filters on CV and fixed-rate CT
//! models, run over a whole plot array in one call (GIL released), returning the
//! combined estimate, the mode probabilities and (for the noise estimators) the
//! measurement-noise estimate after every plot.

use argus_imm::{
    DifferenceNoiseImm, Imm, ImmError, MultiImm, NoiseGrid, NoiseVariances, PlanarImm, markov_rows,
    planar_filters,
};
use argus_motion_models::{CoordinatedTurn, Cv2D, PlanarModel};
use pyo3::PyClassInitializer;
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use crate::arrays::{finite, matrix, out_array, read};
use crate::errors::{Kind, input, invalid, raise};
use crate::filters::intervals;
use crate::imm_core::{Difference, DynImm, ImmFail, Multi, PlainImm, Plots};

/// The largest mode count built (`argus_imm::by_mode_count!`'s).
const MAX_MODES: usize = argus_imm::MAX_PLANAR_MODES;

/// The models of `models`: `("cv", q)` (q = σ of the white acceleration, m/s²) or
/// `("ct", q, omega)` (omega in rad/s).
fn planar_models(models: &Bound<'_, PyAny>) -> PyResult<Vec<PlanarModel>> {
    let mut out = Vec::new();
    for (i, m) in models.try_iter()?.enumerate() {
        let m = m?;
        let t = m.cast::<PyTuple>().map_err(|_| {
            input(format!(
                "argument 'models': models[{i}] must be a tuple ('cv', q) or ('ct', q, omega)"
            ))
        })?;
        let name: String = t.get_item(0)?.extract().map_err(|_| {
            input(format!(
                "argument 'models': models[{i}][0] must be 'cv' or 'ct'"
            ))
        })?;
        let num = |j: usize, what: &str| -> PyResult<f64> {
            t.get_item(j).and_then(|v| v.extract::<f64>()).map_err(|_| {
                input(format!(
                    "argument 'models': models[{i}] needs {what} at [{j}]"
                ))
            })
        };
        let motion = |e: argus_motion_models::MotionError| {
            invalid(
                "MotionError",
                &format!("argument 'models': models[{i}]"),
                &e,
            )
        };
        out.push(match (name.as_str(), t.len()) {
            ("cv", 2) => PlanarModel::from(Cv2D::discrete(num(1, "q")?).map_err(motion)?),
            ("ct", 3) => PlanarModel::from(
                CoordinatedTurn::new(num(2, "omega")?, num(1, "q")?).map_err(motion)?,
            ),
            _ => {
                return Err(input(format!(
                    "argument 'models': models[{i}] must be ('cv', q) or ('ct', q, omega), got {}",
                    m.repr()?
                )));
            }
        });
    }
    if out.is_empty() || out.len() > MAX_MODES {
        return Err(input(format!(
            "argument 'models': {} models (1 to {MAX_MODES} are built)",
            out.len()
        )));
    }
    Ok(out)
}

/// The IMM of `models` with the row-major `R × R` `transition`, built by the library
/// (`argus_imm::planar_filters`, `argus_imm::markov_rows`).
fn build_imm<const R: usize>(models: &[PlanarModel], transition: &[f64]) -> PyResult<PlanarImm<R>> {
    let filters =
        planar_filters::<R>(models).map_err(|_| input("argument 'models': count mismatch"))?;
    let rows: Vec<Vec<f64>> = transition.chunks(R).map(<[f64]>::to_vec).collect();
    let markov =
        markov_rows::<R>(&rows).map_err(|e| invalid("ImmError", "argument 'transition'", &e))?;
    Imm::new(filters, markov).map_err(|e| invalid("ImmError", "argument 'models'", &e))
}

/// Calls `$f::<R>(args…)` for the run-time mode count (`argus_imm::by_mode_count!`).
macro_rules! by_modes {
    ($r:expr, $f:ident, $($arg:expr),*) => {
        argus_imm::by_mode_count!(
            $r,
            |r| Err(input(format!("{r} models: 1 to {MAX_MODES} are built"))),
            $f,
            $($arg),*
        )
    };
}

fn plain<const R: usize>(m: &[PlanarModel], t: &[f64], plots: Plots) -> PyResult<Box<dyn DynImm>> {
    Ok(Box::new(PlainImm::<R> {
        imm: build_imm::<R>(m, t)?,
        plots,
    }))
}

fn multi<const R: usize>(
    m: &[PlanarModel],
    t: &[f64],
    (origin, reference, n, p, clip): ([f64; 2], NoiseVariances, usize, f64, Option<f64>),
) -> PyResult<Box<dyn DynImm>> {
    let imm = build_imm::<R>(m, t)?;
    let grid_err = |e: ImmError| invalid("ImmError", "argument 'p'", &e);
    let clip_err = |e: ImmError| invalid("ImmError", "argument 'clip'", &e);
    Ok(match n {
        3 => Box::new(Multi::<R, 3> {
            multi: MultiImm::new(imm, NoiseGrid::common(p).map_err(grid_err)?, clip)
                .map_err(clip_err)?,
            origin,
            reference,
        }),
        5 => Box::new(Multi::<R, 5> {
            multi: MultiImm::new(imm, NoiseGrid::common(p).map_err(grid_err)?, clip)
                .map_err(clip_err)?,
            origin,
            reference,
        }),
        other => {
            return Err(input(format!(
                "argument 'n': {other} noise hypotheses (3 or 5 are built)"
            )));
        }
    })
}

fn difference<const R: usize>(
    m: &[PlanarModel],
    t: &[f64],
    (origin, initial, forgetting, prior_count): ([f64; 2], NoiseVariances, f64, f64),
) -> PyResult<Box<dyn DynImm>> {
    let imm = build_imm::<R>(m, t)?;
    Ok(Box::new(Difference::<R> {
        imm: DifferenceNoiseImm::new(imm, forgetting)
            .map_err(|e| invalid("ImmError", "argument 'forgetting'", &e))?,
        origin,
        initial,
        prior_count,
    }))
}

/// The transition matrix argument, `R × R` row-major.
fn transition(obj: &Bound<'_, PyAny>, r: usize) -> PyResult<Vec<f64>> {
    Ok(read(obj, "transition", &[Some(r), Some(r)])?.0)
}

fn position(p: (f64, f64)) -> PyResult<[f64; 2]> {
    Ok([
        finite(p.0, "sensor_position")?,
        finite(p.1, "sensor_position")?,
    ])
}

fn variances(sigma_range: f64, sigma_azimuth: f64) -> PyResult<NoiseVariances> {
    NoiseVariances::from_sigmas(sigma_range, sigma_azimuth)
        .map_err(|e| invalid("ImmError", "arguments 'sigma_range' / 'sigma_azimuth'", &e))
}

/// The base of the three IMM classes: `run`.
#[pyclass(subclass, frozen, module = "argus_tracking._native")]
pub(crate) struct ImmBase {
    inner: Box<dyn DynImm>,
    noise: bool,
}

#[pymethods]
impl ImmBase {
    /// The number of motion modes.
    #[getter]
    fn modes(&self) -> usize {
        self.inner.modes()
    }

    /// Runs over `plots` (`n × 2`) at `times` (`n`, not decreasing) from `(x0, P0)` with
    /// mode probabilities `mu0` (default uniform) at `t0` (default `times[0]`). Returns
    /// `ImmRun(x, P, mode_probabilities, noise)`. The GIL is released.
    #[pyo3(signature = (times, plots, x0, P0, mu0=None, t0=None))]
    #[allow(clippy::too_many_arguments)]
    fn run<'py>(
        &self,
        py: Python<'py>,
        times: &Bound<'py, PyAny>,
        plots: &Bound<'py, PyAny>,
        x0: &Bound<'py, PyAny>,
        #[allow(non_snake_case)] P0: &Bound<'py, PyAny>,
        mu0: Option<&Bound<'py, PyAny>>,
        t0: Option<f64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let r = self.inner.modes();
        let (times, _) = read(times, "times", &[None])?;
        let (plots, shape) = read(plots, "plots", &[None, Some(2)])?;
        if shape[0] != times.len() {
            return Err(input(format!(
                "argument 'plots': {} rows for {} times",
                shape[0],
                times.len()
            )));
        }
        let (x0, _) = read(x0, "x0", &[Some(4)])?;
        let (p0, _) = read(P0, "P0", &[Some(4), Some(4)])?;
        #[allow(clippy::cast_precision_loss)]
        let mu0 = match mu0 {
            Some(m) => read(m, "mu0", &[Some(r)])?.0,
            None => vec![1.0 / r as f64; r],
        };
        let t0 = match t0 {
            Some(t) => finite(t, "t0")?,
            None => times.first().copied().unwrap_or(0.0),
        };
        let dts = intervals(&times, t0)?;
        let inner = &self.inner;
        let out = py
            .detach(|| inner.run((&x0, &p0, &mu0), &dts, &plots))
            .map_err(|f| match f {
                ImmFail::Start(arg, e) => invalid("ImmError", &format!("argument '{arg}'"), &e),
                ImmFail::Step(k, name, text) => {
                    let kind =
                        if name.contains("InvalidInterval") || name.starts_with("SensorError") {
                            Kind::InvalidInput
                        } else {
                            Kind::Numerical
                        };
                    raise(
                        kind,
                        &name,
                        format!("step {k} (times[{k}] = {}): {text}", times[k]),
                    )
                }
            })?;
        let n = times.len();
        let x = out_array(py, out.x, &[n, 4])?;
        let p = out_array(py, out.p, &[n, 4, 4])?;
        let mu = out_array(py, out.mu, &[n, r])?;
        let noise = match out.noise {
            Some(v) if self.noise => Some(out_array(py, v, &[n, 2])?),
            _ => None,
        };
        let cls = py.import("argus_tracking._results")?.getattr("ImmRun")?;
        cls.call1((x, p, mu, noise))
    }
}

/// An IMM of Kalman filters on Cartesian plots (covariance `R`) or polar plots
/// (`sigma_range`, `sigma_azimuth`, converted without bias).
#[pyclass(extends = ImmBase, frozen, module = "argus_tracking._native", name = "Imm")]
pub(crate) struct Imm_;

#[pymethods]
impl Imm_ {
    #[new]
    #[pyo3(signature = (models, transition, *, R=None, sigma_range=None, sigma_azimuth=None, sensor_position=(0.0, 0.0)))]
    fn new(
        models: &Bound<'_, PyAny>,
        transition: &Bound<'_, PyAny>,
        #[allow(non_snake_case)] R: Option<&Bound<'_, PyAny>>,
        sigma_range: Option<f64>,
        sigma_azimuth: Option<f64>,
        sensor_position: (f64, f64),
    ) -> PyResult<PyClassInitializer<Self>> {
        let m = planar_models(models)?;
        let t = self::transition(transition, m.len())?;
        let plots = match (R, sigma_range, sigma_azimuth) {
            (Some(r), None, None) => Plots::Cartesian(matrix::<2, 2>(r, "R")?),
            (None, Some(sr), Some(sa)) => {
                variances(sr, sa)?;
                Plots::Polar {
                    origin: position(sensor_position)?,
                    sigma_range: sr,
                    sigma_azimuth: sa,
                }
            }
            _ => {
                return Err(input(
                    "give either R (Cartesian plots) or sigma_range and sigma_azimuth (polar plots)",
                ));
            }
        };
        let inner = by_modes!(m.len(), plain, &m, &t, plots)?;
        Ok(PyClassInitializer::from(ImmBase {
            inner,
            noise: false,
        })
        .add_subclass(Self))
    }
}

/// Seed 000's multi-IMM: `n` IMMs under range/azimuth variances on a `±p` grid around a
/// reference that follows the data, over one polar radar's plots.
#[pyclass(extends = ImmBase, frozen, module = "argus_tracking._native", name = "MultiImm")]
pub(crate) struct MultiImm_;

#[pymethods]
impl MultiImm_ {
    #[new]
    #[pyo3(signature = (models, transition, *, sigma_range, sigma_azimuth, sensor_position=(0.0, 0.0), n=5, p=0.1, clip=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        models: &Bound<'_, PyAny>,
        transition: &Bound<'_, PyAny>,
        sigma_range: f64,
        sigma_azimuth: f64,
        sensor_position: (f64, f64),
        n: usize,
        p: f64,
        clip: Option<f64>,
    ) -> PyResult<PyClassInitializer<Self>> {
        let m = planar_models(models)?;
        let t = self::transition(transition, m.len())?;
        let args = (
            position(sensor_position)?,
            variances(sigma_range, sigma_azimuth)?,
            n,
            p,
            clip,
        );
        let inner = by_modes!(m.len(), multi, &m, &t, args)?;
        Ok(PyClassInitializer::from(ImmBase { inner, noise: true }).add_subclass(Self))
    }
}

/// One IMM whose range and azimuth variances come from third differences of the raw
/// polar plots (forgetting factor `forgetting`, the initial guess held with the weight of
/// `prior_count` differences).
#[pyclass(extends = ImmBase, frozen, module = "argus_tracking._native", name = "DifferenceImm")]
pub(crate) struct DifferenceImm_;

#[pymethods]
impl DifferenceImm_ {
    #[new]
    #[pyo3(signature = (models, transition, *, sigma_range, sigma_azimuth, sensor_position=(0.0, 0.0), forgetting=1.0, prior_count=2.0))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        models: &Bound<'_, PyAny>,
        transition: &Bound<'_, PyAny>,
        sigma_range: f64,
        sigma_azimuth: f64,
        sensor_position: (f64, f64),
        forgetting: f64,
        prior_count: f64,
    ) -> PyResult<PyClassInitializer<Self>> {
        let m = planar_models(models)?;
        let t = self::transition(transition, m.len())?;
        let args = (
            position(sensor_position)?,
            variances(sigma_range, sigma_azimuth)?,
            forgetting,
            finite(prior_count, "prior_count")?,
        );
        let inner = by_modes!(m.len(), difference, &m, &t, args)?;
        Ok(PyClassInitializer::from(ImmBase { inner, noise: true }).add_subclass(Self))
    }
}

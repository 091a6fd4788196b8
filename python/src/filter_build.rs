//! The filter classes' constructors: a motion model (`cv`, `ca`, `ct` in the plane,
//! `cv3`, `ca3` in space) and a sensor (Cartesian position of the model's dimension, a
//! polar radar for the planar models, a spherical radar for the spatial ones) made into
//! one type-erased [`DynFilter`].

use argus_core_math::Matrix;
use argus_filters::{CovarianceForm, Ekf, Kf, Ukf, UtParams};
use argus_motion_models::{Ca2D, Ca3D, CoordinatedTurn, Cv2D, Cv3D, LinearMotionModel};
use argus_sensors::{CartesianPosition, Polar2D, RadarNoise, Spherical3D};
use pyo3::prelude::*;

use crate::arrays::read;
use crate::errors::{input, invalid};
use crate::filter_core::{DynFilter, State, Typed, filter_error};

/// Which filter.
#[derive(Debug, Clone, Copy)]
pub(crate) enum FilterKind {
    Kf(CovarianceForm),
    Ekf(CovarianceForm),
    Ukf(UtParams),
}

/// The sensor of a filter.
#[derive(Debug, Clone)]
pub(crate) enum SensorSpec {
    /// `z` = the position (`(x, y)` or `(x, y, z)`) with covariance `R` (row-major).
    Cartesian(Vec<f64>),
    /// `z = (range, azimuth)` from `position`, azimuth from the x axis counter-clockwise.
    Polar {
        position: [f64; 2],
        sigma_range: f64,
        sigma_azimuth: f64,
    },
    /// `z = (range, azimuth, elevation)` from `position` (`argus_sensors::Spherical3D`).
    Spherical {
        position: [f64; 3],
        sigma_range: f64,
        sigma_azimuth: f64,
        sigma_elevation: f64,
    },
}

fn boxed<F, Me, const N: usize, const M: usize>(filter: F, meas: Me) -> PyResult<Box<dyn DynFilter>>
where
    Typed<F, Me, N, M>: DynFilter + 'static,
{
    let state = State::<N>::initial()
        .map_err(|e| invalid("MathError", "the initial estimate", &e))?
        .into();
    Ok(Box::new(Typed::<F, Me, N, M> {
        filter,
        meas,
        state,
    }))
}

/// The filter of `kind` on `model` with sensor `meas` (`M` components).
fn with_sensor<const N: usize, const M: usize, Mo, Me>(
    kind: FilterKind,
    model: Mo,
    meas: Me,
    nonlinear: bool,
) -> PyResult<Box<dyn DynFilter>>
where
    Mo: LinearMotionModel<N> + Send + Sync + 'static,
    Me: argus_sensors::MeasurementModel<N, M> + Send + Sync + 'static,
{
    match kind {
        FilterKind::Kf(_) if nonlinear => Err(input(
            "KalmanFilter needs a linear (Cartesian) sensor: use ExtendedKalmanFilter or \
             UnscentedKalmanFilter for polar or spherical plots",
        )),
        FilterKind::Kf(form) => boxed::<_, _, N, M>(Kf::with_form(model, form), meas),
        FilterKind::Ekf(form) => boxed::<_, _, N, M>(Ekf::with_form(model, form), meas),
        FilterKind::Ukf(params) => boxed::<_, _, N, M>(
            Ukf::<N, Mo>::new(model, params)
                .map_err(|e| filter_error("unscented transform", &e))?,
            meas,
        ),
    }
}

/// The filter on a planar model (position at `indices` of an `N`-state).
fn planar<const N: usize, Mo>(
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
            let meas = CartesianPosition::<N, 2>::new(indices, Matrix::<2, 2>::from_row_slice(&r))
                .map_err(|e| invalid("SensorError", "argument 'R'", &e))?;
            with_sensor::<N, 2, _, _>(kind, model, meas, false)
        }
        SensorSpec::Polar {
            position,
            sigma_range,
            sigma_azimuth,
        } => {
            let noise =
                RadarNoise::constant(sigma_range, sigma_azimuth, 0.0).map_err(sensor_err)?;
            let meas = Polar2D::<N>::new(indices, position, noise).map_err(sensor_err)?;
            with_sensor::<N, 2, _, _>(kind, model, meas, true)
        }
        SensorSpec::Spherical { .. } => Err(input(
            "argument 'sensor': a spherical radar needs a 3-D model ('cv3' or 'ca3')",
        )),
    }
}

/// The filter on a spatial model (position at `indices` of an `N`-state).
fn spatial<const N: usize, Mo>(
    kind: FilterKind,
    model: Mo,
    indices: [usize; 3],
    sensor: SensorSpec,
) -> PyResult<Box<dyn DynFilter>>
where
    Mo: LinearMotionModel<N> + Send + Sync + 'static,
{
    let sensor_err = |e: argus_sensors::SensorError| invalid("SensorError", "sensor", &e);
    match sensor {
        SensorSpec::Cartesian(r) => {
            let meas = CartesianPosition::<N, 3>::new(indices, Matrix::<3, 3>::from_row_slice(&r))
                .map_err(|e| invalid("SensorError", "argument 'R'", &e))?;
            with_sensor::<N, 3, _, _>(kind, model, meas, false)
        }
        SensorSpec::Spherical {
            position,
            sigma_range,
            sigma_azimuth,
            sigma_elevation,
        } => {
            let noise = RadarNoise::constant(sigma_range, sigma_azimuth, sigma_elevation)
                .map_err(sensor_err)?;
            let meas = Spherical3D::<N>::new(indices, position, noise).map_err(sensor_err)?;
            with_sensor::<N, 3, _, _>(kind, model, meas, true)
        }
        SensorSpec::Polar { .. } => Err(input(
            "argument 'sensor': a polar radar needs a planar model ('cv', 'ca' or 'ct'); \
             use sensor='spherical' with a 3-D model",
        )),
    }
}

/// The error for an unknown model name.
fn unknown_model(model: &str) -> PyErr {
    input(format!(
        "argument 'model': unknown motion model {model:?} (expected 'cv', 'ca', 'ct', 'cv3' \
         or 'ca3')"
    ))
}

/// The position dimension of `model` (2 or 3).
pub(crate) fn model_dimension(model: &str) -> PyResult<usize> {
    match model {
        "cv" | "ca" | "ct" => Ok(2),
        "cv3" | "ca3" => Ok(3),
        other => Err(unknown_model(other)),
    }
}

/// Builds the filter of `model` with noise `q` and turn rate `omega`.
pub(crate) fn make(
    kind: FilterKind,
    model: &str,
    q: f64,
    omega: f64,
    sensor: SensorSpec,
) -> PyResult<Box<dyn DynFilter>> {
    let motion = |e: argus_motion_models::MotionError| invalid("MotionError", "model", &e);
    match model {
        "cv" => planar::<4, _>(kind, Cv2D::discrete(q).map_err(motion)?, [0, 2], sensor),
        "ca" => planar::<6, _>(kind, Ca2D::discrete(q).map_err(motion)?, [0, 3], sensor),
        "ct" => planar::<4, _>(
            kind,
            CoordinatedTurn::new(omega, q).map_err(motion)?,
            [0, 2],
            sensor,
        ),
        "cv3" => spatial::<6, _>(kind, Cv3D::discrete(q).map_err(motion)?, [0, 2, 4], sensor),
        "ca3" => spatial::<9, _>(kind, Ca3D::discrete(q).map_err(motion)?, [0, 3, 6], sensor),
        other => Err(unknown_model(other)),
    }
}

/// The sensor's arguments as given to a constructor.
pub(crate) struct SensorArgs<'a, 'py> {
    pub(crate) sensor: &'a str,
    pub(crate) r: Option<&'a Bound<'py, PyAny>>,
    pub(crate) sigma_range: Option<f64>,
    pub(crate) sigma_azimuth: Option<f64>,
    pub(crate) sigma_elevation: Option<f64>,
    pub(crate) sensor_position: Option<&'a Bound<'py, PyAny>>,
}

/// The sensor from the constructor's arguments, for a model of position dimension `dim`.
pub(crate) fn sensor_spec(a: &SensorArgs<'_, '_>, dim: usize) -> PyResult<SensorSpec> {
    let needs = |v: Option<f64>, name: &str, unit: &str| {
        v.ok_or_else(|| {
            input(format!(
                "argument '{name}': a {} sensor needs it ({unit})",
                a.sensor
            ))
        })
    };
    match a.sensor {
        "cartesian" => {
            let r = a.r.ok_or_else(|| {
                input(format!(
                    "argument 'R': a Cartesian sensor needs R ({dim} × {dim})"
                ))
            })?;
            let (r, _) = read(r, "R", &[Some(dim), Some(dim)])?;
            Ok(SensorSpec::Cartesian(r))
        }
        "polar" | "spherical" => {
            let want = if a.sensor == "polar" { 2 } else { 3 };
            let pos = match a.sensor_position {
                Some(p) => read(p, "sensor_position", &[None])?.0,
                None => vec![0.0; want],
            };
            let position = match pos.len() {
                n if n == want => pos,
                n => {
                    return Err(input(format!(
                        "argument 'sensor_position': {n} coordinates for a {} sensor \
                         (expected {want})",
                        a.sensor
                    )));
                }
            };
            let sigma_range = needs(a.sigma_range, "sigma_range", "m")?;
            let sigma_azimuth = needs(a.sigma_azimuth, "sigma_azimuth", "rad")?;
            if a.sensor == "polar" {
                Ok(SensorSpec::Polar {
                    position: [position[0], position[1]],
                    sigma_range,
                    sigma_azimuth,
                })
            } else {
                Ok(SensorSpec::Spherical {
                    position: [position[0], position[1], position[2]],
                    sigma_range,
                    sigma_azimuth,
                    sigma_elevation: needs(a.sigma_elevation, "sigma_elevation", "rad")?,
                })
            }
        }
        other => Err(input(format!(
            "argument 'sensor': unknown sensor {other:?} (expected 'cartesian', 'polar' or \
             'spherical')"
        ))),
    }
}

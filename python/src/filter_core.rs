//! One filter with its measurement model behind a trait object, so the three Python
//! filter classes share the predict / update / step / batch-run code for every motion
//! model (CV, CA, CT and the 3-D CV, CA) and sensor (Cartesian position, polar and
//! spherical radar), and the filter's own estimate for the stateful calls.

use std::sync::{Mutex, MutexGuard, PoisonError};

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{Ekf, FilterError, Kf, RtsTrack, SmoothError, SmoothingFilter, Ukf};
use argus_motion_models::MotionModel;
use argus_sensors::MeasurementModel;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;

use crate::arrays::{matrix, out_matrix, out_vector, small_vector, vector};
use crate::errors::{Kind, invalid, raise, rust_name};
use crate::memo_run::run_reusing_gain;
use crate::run_io::{RunFail, RunOut, RunSlices};

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
    /// row-major; `dts[k]` the interval before plot `k` (0: no prediction). With
    /// `reuse_gain` (and a filter that allows it, [`MeanPrediction`]) the covariance
    /// recursion is memoised (`memo_run`); the result is the same to the bit.
    fn run(
        &self,
        x0: &[f64],
        p0: &[f64],
        dts: &[f64],
        plots: &[f64],
        reuse_gain: bool,
        out: RunSlices<'_>,
    ) -> Result<(), RunFail>;
    /// Replaces the filter's own estimate with `x` and / or `P` (the other kept), checked
    /// together; left unchanged on an error.
    fn set_state(&self, x: Option<&Bound<'_, PyAny>>, p: Option<&Bound<'_, PyAny>>)
    -> PyResult<()>;
    /// The own estimate's mean (a new array).
    fn state_x<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>>;
    /// The own estimate's covariance (a new array).
    fn state_p<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>>;
    /// The NIS of the last stateful update (`None` before the first).
    fn state_nis(&self) -> Option<f64>;
    /// Predicts the own estimate over `dt` in place (unchanged on an error).
    fn predict_state(&self, dt: f64) -> PyResult<()>;
    /// Updates the own estimate with `z` in place (unchanged on an error).
    fn update_state(&self, z: &Bound<'_, PyAny>) -> PyResult<()>;
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

/// The mean prediction `f(x, dt)` of a filter whose batch run may reuse its covariance
/// recursion (`memo_run`): the KF, built by this crate only with the Cartesian sensor
/// (constant `R`) on models whose `Q` does not depend on the state and whose
/// `predict_moments` mean is `propagate`. `None` for the EKF and the UKF.
pub(crate) trait MeanPrediction<const N: usize> {
    /// `f(x, dt)` when the recursion may be reused.
    fn mean_prediction(&self) -> Option<impl Fn(&Vector<N>, f64) -> Vector<N>>;
}

impl<const N: usize, Mo: MotionModel<N>> MeanPrediction<N> for Kf<Mo> {
    #[inline(always)]
    fn mean_prediction(&self) -> Option<impl Fn(&Vector<N>, f64) -> Vector<N>> {
        Some(|x: &Vector<N>, dt: f64| self.model().propagate(x, dt))
    }
}

impl<const N: usize, Mo> MeanPrediction<N> for Ekf<Mo> {
    fn mean_prediction(&self) -> Option<impl Fn(&Vector<N>, f64) -> Vector<N>> {
        None::<fn(&Vector<N>, f64) -> Vector<N>>
    }
}

impl<const N: usize, Mo> MeanPrediction<N> for Ukf<N, Mo> {
    fn mean_prediction(&self) -> Option<impl Fn(&Vector<N>, f64) -> Vector<N>> {
        None::<fn(&Vector<N>, f64) -> Vector<N>>
    }
}

/// The filter's own estimate (the stateful calls) and its last NIS.
#[derive(Debug, Clone, Copy)]
pub(crate) struct State<const N: usize> {
    estimate: Gaussian<N>,
    nis: Option<f64>,
}

impl<const N: usize> State<N> {
    /// FilterPy's default start: `x = 0`, `P = I`.
    ///
    /// # Errors
    /// None in practice (the identity is positive definite); the check is kept.
    pub(crate) fn initial() -> Result<Self, argus_core_math::MathError> {
        Ok(Self {
            estimate: Gaussian::from_lower_triangle(Vector::<N>::zeros(), Matrix::identity())?,
            nis: None,
        })
    }
}

/// The concrete pair: filter `F` on an `N`-state, sensor `Me` of `M` components, with
/// the filter's own estimate.
pub(crate) struct Typed<F, Me, const N: usize, const M: usize> {
    pub(crate) filter: F,
    pub(crate) meas: Me,
    pub(crate) state: Mutex<State<N>>,
}

impl<F, Me, const N: usize, const M: usize> Typed<F, Me, N, M> {
    /// The own estimate, locked (a poisoned lock is taken over: every update of the state
    /// is one assignment of a checked value, so it is never half-written).
    fn state(&self) -> MutexGuard<'_, State<N>> {
        self.state.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

impl<const N: usize, const M: usize, F, Me> DynFilter for Typed<F, Me, N, M>
where
    F: SmoothingFilter<N> + MeanPrediction<N> + Send + Sync,
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

    fn run(
        &self,
        x0: &[f64],
        p0: &[f64],
        dts: &[f64],
        plots: &[f64],
        reuse_gain: bool,
        out: RunSlices<'_>,
    ) -> Result<(), RunFail> {
        let mut est = Gaussian::new(
            Vector::<N>::from_column_slice(x0),
            argus_core_math::Matrix::<N, N>::from_row_slice(p0),
        )
        .map_err(RunFail::Start)?;
        if reuse_gain && let Some(propagate) = self.filter.mean_prediction() {
            return run_reusing_gain(&self.filter, propagate, &self.meas, est, dts, plots, out);
        }
        let rows = out
            .x
            .chunks_exact_mut(N)
            .zip(out.p.chunks_exact_mut(N * N))
            .zip(out.nis.iter_mut())
            .zip(dts.iter().zip(plots.chunks_exact(M)));
        for (k, (((x_out, p_out), nis_out), (dt, z))) in rows.enumerate() {
            if *dt != 0.0 {
                self.filter
                    .predict_in_place(&mut est, *dt)
                    .map_err(|e| RunFail::Step(k, e))?;
            }
            let z = Vector::<M>::from_column_slice(z);
            let innov = self
                .filter
                .update_in_place(&mut est, &self.meas, &z)
                .map_err(|e| RunFail::Step(k, e))?;
            x_out.copy_from_slice(est.mean().as_slice());
            p_out.copy_from_slice(est.cov().transpose().as_slice());
            *nis_out = innov.nis;
        }
        Ok(())
    }

    fn set_state(
        &self,
        x: Option<&Bound<'_, PyAny>>,
        p: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let mut state = self.state();
        let mean = x.map_or(Ok(*state.estimate.mean()), |x| vector::<N>(x, "x"))?;
        let cov = p.map_or(Ok(*state.estimate.cov()), |p| matrix::<N, N>(p, "P"))?;
        let estimate =
            Gaussian::new(mean, cov).map_err(|e| invalid("MathError", "argument 'P'", &e))?;
        *state = State {
            estimate,
            nis: None,
        };
        Ok(())
    }

    fn state_x<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        out_vector(py, self.state().estimate.mean())
    }

    fn state_p<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let cov = *self.state().estimate.cov();
        out_matrix(py, &cov)
    }

    fn state_nis(&self) -> Option<f64> {
        self.state().nis
    }

    fn predict_state(&self, dt: f64) -> PyResult<()> {
        let mut state = self.state();
        self.filter
            .predict_in_place(&mut state.estimate, dt)
            .map_err(|e| filter_error(&format!("predict over dt = {dt}"), &e))
    }

    fn update_state(&self, z: &Bound<'_, PyAny>) -> PyResult<()> {
        let z = small_vector::<M>(z, "z")?;
        let mut state = self.state();
        let innov = self
            .filter
            .update_in_place(&mut state.estimate, &self.meas, &z)
            .map_err(|e| filter_error("update", &e))?;
        state.nis = Some(innov.nis);
        Ok(())
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

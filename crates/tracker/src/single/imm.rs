//! The single-target IMM and multi-IMM over 2-D plots: an IMM of the configured CV /
//! fixed-rate CT Kalman filters on converted plots (polar plots by the unbiased
//! conversion with the sensor's σ, Cartesian reports as given), and seed 000's multi-IMM
//! around it over one polar radar's plots. The mode count `R` and the hypothesis count
//! `K` are compile-time sizes, picked here from the run-time configuration.
//!
//! With `--smooth` / `--smooth-lag` the IMM is smoothed by `argus_imm`'s IMM smoother
//! over its recorded forward pass ([`crate::smooth::ImmRecorder`]). The multi-IMM is smoothed the same
//! way over its recorded moments: its `K` IMMs share the dynamics (the models and the
//! Markov matrix) and differ only in `R`, so its posterior merged over the noise
//! hypotheses ([`MultiImmEstimate::merged`]) is an IMM posterior of the common dynamics,
//! and the IMM smoother runs over the sequence of merged posteriors. This smooths the
//! recorded merged moments, with the `R` the forward pass estimated at each plot; it is
//! not a smoother of the adaptive noise model, which has none (its grid moves with the
//! data), and the forward record it smooths is recomputed from the merged posterior, not
//! from each hypothesis (the usual smoother of a mixture filter's moment-matched output,
//! as for the tracker's IMM-JPDA tracks). The smoothed mode probabilities go to
//! `mu_1s …`, as for the IMM.

use argus_core_math::Gaussian;
use argus_filters::two_point_cv2;
use argus_imm::{
    Imm, ImmEstimate, MultiImm, MultiImmEstimate, NoiseGrid, NoiseVariances, PlanarImm,
    UnbiasedConversion, markov_rows, per_mode, planar_filters,
};
use argus_sensors::Measurement;

use super::error::{OneRadar, SingleError};
use super::estimator::position;
use super::output::{Columns, Estimate, Estimates, SingleRun, TaggedPlot};
use super::smoothed::smooth_run;
use super::spec::{ImmSpec, MultiSpec};
use super::start::{Ctx, two_point};
use crate::smooth::ImmRecorder;

/// Calls `$f::<R>(args…)` for the run-time mode count `R ∈ 1 … MAX_MODELS`
/// ([`argus_imm::by_mode_count!`]).
macro_rules! by_modes {
    ($r:expr, $f:ident, $($arg:expr),*) => {
        argus_imm::by_mode_count!($r, |count| Err(SingleError::ModeCount { count }), $f, $($arg),*)
    };
}

/// The IMM of `spec` over `plots`. Plots of the same instant are applied in turn without
/// mixing or prediction.
///
/// # Errors
/// As [`super::kf::run`].
pub(super) fn imm(
    ctx: &Ctx<'_>,
    spec: &ImmSpec,
    plots: &[TaggedPlot],
) -> Result<SingleRun, SingleError> {
    by_modes!(spec.models.len(), track_imm, ctx, spec, plots)
}

/// The multi-IMM of `multi` around the IMM of `spec` over the polar plots of one sensor.
///
/// # Errors
/// As [`super::kf::run`]; a plot of another sensor or a Cartesian report.
pub(super) fn multi_imm(
    ctx: &Ctx<'_>,
    spec: &ImmSpec,
    multi: MultiSpec,
    plots: &[TaggedPlot],
) -> Result<SingleRun, SingleError> {
    by_modes!(spec.models.len(), track_multi, ctx, spec, multi, plots)
}

/// The IMM of `spec` with `R` modes (`R = spec.models.len()`), Kalman filters on converted
/// plots.
///
/// # Errors
/// [`SingleError::Imm`] for an invalid Markov matrix or a mode count other than `R`.
fn build_imm<const R: usize>(spec: &ImmSpec) -> Result<PlanarImm<R>, SingleError> {
    Ok(Imm::new(
        planar_filters::<R>(&spec.models)?,
        markov_rows::<R>(&spec.markov)?,
    )?)
}

/// The IMM's start: every mode from the two-point start, with `spec`'s `μ₀`.
fn start_estimate<const R: usize>(
    spec: &ImmSpec,
    g: Gaussian<4>,
) -> Result<ImmEstimate<4, R>, SingleError> {
    let mu = per_mode::<R>(&spec.initial)?;
    Ok(ImmEstimate::from_common(g, mu)?)
}

fn track_imm<const R: usize>(
    ctx: &Ctx<'_>,
    spec: &ImmSpec,
    plots: &[TaggedPlot],
) -> Result<SingleRun, SingleError> {
    let imm = build_imm::<R>(spec)?;
    let start = two_point(plots, |p| ctx.convert2(p), two_point_cv2)?;
    let mut est = start_estimate::<R>(spec, start.estimate)?;
    let mut t = start.second.time();
    // With smoothing, the forward pass is recorded (one step per time).
    let mut record = ctx.smoothing.map(|_| ImmRecorder::new());
    let mut out: Vec<(f64, Gaussian<4>, [f64; R])> = Vec::with_capacity(start.rest.len() + 1);
    let fail = SingleError::Smoothing;
    if let Some(r) = &mut record {
        r.record(&imm, t, est).map_err(fail)?;
    }
    out.push((t, est.combined()?, est.mode_probabilities()));
    for p in start.rest {
        let (z, r) = ctx.convert2(p)?;
        let meas = position(r)?;
        let dt = p.time() - t;
        let upd = if dt == 0.0 {
            imm.update(&est.into_prediction(), &meas, &z)
        } else {
            imm.step(&est, dt, &meas, &z)
        };
        est = upd.map_err(ctx.imm_error(p))?.estimate;
        t = p.time();
        let c = est.combined().map_err(ctx.imm_error(p))?;
        if let Some(r) = &mut record {
            r.record(&imm, t, est).map_err(fail)?;
        }
        out.push((t, c, est.mode_probabilities()));
    }
    let times: Vec<f64> = out.iter().map(|o| o.0).collect();
    let smoothed = smooth_run(record, &imm, ctx.smoothing, &times)?;
    let columns = Columns {
        axes: 2,
        modes: R,
        noise: false,
        turn_rate: false,
        smoothed: smoothed.is_some(),
    };
    let mut rows = Vec::with_capacity(out.len());
    for (i, (t, c, mu)) in out.iter().enumerate() {
        let s = smoothed.as_ref().and_then(|s| s.at(i));
        rows.push(Estimate {
            modes: Some(mu.to_vec()),
            smoothed: s.map(|s| s.combined),
            smoothed_modes: s.map(|s| s.mode_probabilities.to_vec()),
            ..Estimate::new(*t, *c)
        });
    }
    Ok(SingleRun {
        columns,
        estimates: Estimates::Planar(rows),
    })
}

/// The multi-IMM around an IMM with `R` modes: picks the grid size from `multi`.
fn track_multi<const R: usize>(
    ctx: &Ctx<'_>,
    spec: &ImmSpec,
    multi: MultiSpec,
    plots: &[TaggedPlot],
) -> Result<SingleRun, SingleError> {
    let (p, c) = (multi.p, multi.clip);
    match (multi.per_axis, multi.n) {
        (false, 3) => track_multi_k::<R, 3>(ctx, spec, NoiseGrid::common(p)?, c, plots),
        (false, 5) => track_multi_k::<R, 5>(ctx, spec, NoiseGrid::common(p)?, c, plots),
        (false, 7) => track_multi_k::<R, 7>(ctx, spec, NoiseGrid::common(p)?, c, plots),
        (false, 9) => track_multi_k::<R, 9>(ctx, spec, NoiseGrid::common(p)?, c, plots),
        (true, 3) => track_multi_k::<R, 9>(ctx, spec, NoiseGrid::independent(p)?, c, plots),
        (true, 5) => track_multi_k::<R, 25>(ctx, spec, NoiseGrid::independent(p)?, c, plots),
        (_, n) => Err(SingleError::MultiSize { n }),
    }
}

/// The multi-IMM with `K` noise hypotheses over the polar plots of one sensor; the initial
/// reference is the sensor's configured σ.
fn track_multi_k<const R: usize, const K: usize>(
    ctx: &Ctx<'_>,
    spec: &ImmSpec,
    grid: NoiseGrid<K>,
    clip: Option<f64>,
    plots: &[TaggedPlot],
) -> Result<SingleRun, SingleError> {
    let multi = MultiImm::new(build_imm::<R>(spec)?, grid, clip)?;
    let first = plots.first().ok_or(SingleError::TooFewPlots)?;
    let sensor = ctx.sensor(first)?;
    let (sr, sa) = ctx.polar_sigmas(sensor)?;
    let conv = UnbiasedConversion::<4>::new(0, 2)?.at([sensor.position[0], sensor.position[1]])?;
    let reference = NoiseVariances::from_sigmas(sr, sa).map_err(|e| SingleError::SensorNoise {
        sensor: sensor.id,
        message: e.to_string(),
    })?;
    let start = two_point(plots, |p| ctx.convert2(p), two_point_cv2)?;
    let p2 = start.second;
    let mut est =
        MultiImmEstimate::<4, R, K>::new(start_estimate::<R>(spec, start.estimate)?, reference);
    let mut t = p2.time();
    // With smoothing, the posteriors merged over the noise hypotheses are recorded as an
    // IMM forward pass of the common dynamics (module docs).
    let mut record = ctx.smoothing.map(|_| ImmRecorder::new());
    let fail = SingleError::Smoothing;
    let mut out: Vec<(f64, Gaussian<4>, [f64; R], NoiseVariances)> =
        Vec::with_capacity(start.rest.len() + 1);
    if let Some(r) = &mut record {
        r.record(multi.imm(), t, est.merged()?).map_err(fail)?;
    }
    out.push((
        t,
        est.combined()?,
        est.mode_probabilities(),
        *est.reference(),
    ));
    // Every plot is checked, the first two (the start's) included, then skipped.
    for (i, p) in plots.iter().enumerate() {
        if p.sensor() != sensor.id {
            return Err(SingleError::OtherSensor {
                tag: p.tag,
                estimator: OneRadar::MultiImm,
                sensor: p.sensor(),
                first: sensor.id,
            });
        }
        let Measurement::Polar(plot) = p.measurement() else {
            return Err(SingleError::NotPolar {
                tag: p.tag,
                estimator: OneRadar::MultiImm,
            });
        };
        if i < 2 {
            continue;
        }
        let dt = p.time() - t;
        est = multi
            .step(&est, dt, plot, &conv)
            .map_err(ctx.imm_error(p))?
            .estimate;
        t = p.time();
        let c = est.combined().map_err(ctx.imm_error(p))?;
        if let Some(r) = &mut record {
            let merged = est.merged().map_err(ctx.imm_error(p))?;
            r.record(multi.imm(), t, merged).map_err(fail)?;
        }
        out.push((t, c, est.mode_probabilities(), *est.reference()));
    }
    let times: Vec<f64> = out.iter().map(|o| o.0).collect();
    let smoothed = smooth_run(record, multi.imm(), ctx.smoothing, &times)?;
    let columns = Columns {
        axes: 2,
        modes: R,
        noise: true,
        turn_rate: false,
        smoothed: smoothed.is_some(),
    };
    let mut rows = Vec::with_capacity(out.len());
    for (i, (t, c, mu, noise)) in out.iter().enumerate() {
        let s = smoothed.as_ref().and_then(|s| s.at(i));
        rows.push(Estimate {
            modes: Some(mu.to_vec()),
            noise: Some(*noise),
            smoothed: s.map(|s| s.combined),
            smoothed_modes: s.map(|s| s.mode_probabilities.to_vec()),
            ..Estimate::new(*t, *c)
        });
    }
    Ok(SingleRun {
        columns,
        estimates: Estimates::Planar(rows),
    })
}

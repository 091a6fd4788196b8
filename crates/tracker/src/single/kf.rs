//! The single-target run: one estimator over every plot, in order. 2-D plots get a 2-D
//! CV estimator (`[x, vx, y, vy]`), 3-D ones (spherical or Cartesian 3-D) a 3-D CV
//! estimator; the IMMs ([`super::imm`], [`super::aircraft`]) are 2-D. One row per
//! estimate.

use argus_core_math::Gaussian;
use argus_filters::SmoothingFilter;
use argus_sensors::Measurement;

use super::dim::{DIM2, DIM3, Dim};
use super::error::SingleError;
use super::estimator::{cv_ekf, cv_kf, cv3_ekf, cv3_kf, polar, spherical, step};
use super::output::{Columns, Estimate, Estimates, SingleRun, TaggedPlot};
use super::spec::EstimatorSpec;
use super::start::{Ctx, two_point};
use super::{aircraft, imm};
use crate::smooth;

/// Runs `estimator` over `plots` (in order).
///
/// # Errors
/// [`SingleError`] naming the tag of a plot the estimator cannot use, or the sensor of a
/// missing σ; the estimators' errors.
pub(super) fn run(
    ctx: &Ctx<'_>,
    estimator: &EstimatorSpec,
    plots: &[TaggedPlot],
) -> Result<SingleRun, SingleError> {
    let three_d = plots.first().is_some_and(|p| p.measurement().dim() == 3);
    match (estimator, three_d) {
        (EstimatorSpec::KfConverted(sa), false) => {
            let f = cv_kf(*sa)?;
            track_loop(ctx, plots, &DIM2, &f, Estimates::Planar, |x, dt, p| {
                DIM2.converted_step(ctx, &f, x, dt, p)
            })
        }
        (EstimatorSpec::Ekf(sa), false) => {
            let f = cv_ekf(*sa)?;
            track_loop(ctx, plots, &DIM2, &f, Estimates::Planar, |x, dt, p| {
                let Measurement::Polar(z) = p.measurement() else {
                    return DIM2.converted_step(ctx, &f, x, dt, p);
                };
                let s = ctx.sensor(p)?;
                let (sr, sa) = ctx.polar_sigmas(s)?;
                let m = polar([s.position[0], s.position[1]], sr, sa)?;
                Ok(step(&f, x, dt, &m, &z.to_vector())
                    .map_err(ctx.filter_error(p))?
                    .0)
            })
        }
        (EstimatorSpec::Imm(spec), false) => imm::imm(ctx, spec, plots),
        (EstimatorSpec::MultiImm(spec, multi), false) => imm::multi_imm(ctx, spec, *multi, plots),
        (EstimatorSpec::Aircraft(tuning), false) => aircraft::run(ctx, tuning, plots),
        (
            EstimatorSpec::Imm(_) | EstimatorSpec::MultiImm(..) | EstimatorSpec::Aircraft(_),
            true,
        ) => Err(SingleError::ImmNot2D),
        (EstimatorSpec::KfConverted(sa), true) => {
            let f = cv3_kf(*sa)?;
            track_loop(ctx, plots, &DIM3, &f, Estimates::Spatial, |x, dt, p| {
                DIM3.converted_step(ctx, &f, x, dt, p)
            })
        }
        (EstimatorSpec::Ekf(sa), true) => {
            let f = cv3_ekf(*sa)?;
            track_loop(ctx, plots, &DIM3, &f, Estimates::Spatial, |x, dt, p| {
                let Measurement::Spherical(z) = p.measurement() else {
                    return DIM3.converted_step(ctx, &f, x, dt, p);
                };
                let s = ctx.sensor(p)?;
                let m = spherical(s.position, ctx.spherical_sigmas(s)?)?;
                Ok(step(&f, x, dt, &m, &z.to_vector())
                    .map_err(ctx.filter_error(p))?
                    .0)
            })
        }
    }
}

/// The KF / EKF loop: the two-point start of `dim` on the first two plots, then one
/// predict + update per plot (`update(estimate, dt, plot)`), one row per estimate; with
/// `ctx.smoothing`, the rows smoothed by the RTS smoother of `filter` (the estimator's own
/// prediction, [`smooth::rts_rows`]); `wrap` makes the rows the run's [`Estimates`].
fn track_loop<const D: usize, const N: usize, F: SmoothingFilter<N>>(
    ctx: &Ctx<'_>,
    plots: &[TaggedPlot],
    dim: &Dim<D, N>,
    filter: &F,
    wrap: fn(Vec<Estimate<N>>) -> Estimates,
    update: impl Fn(&Gaussian<N>, f64, &TaggedPlot) -> Result<Gaussian<N>, SingleError>,
) -> Result<SingleRun, SingleError> {
    let start = two_point(plots, |p| (dim.convert)(ctx, p), dim.init)?;
    let mut est: Vec<(f64, Gaussian<N>)> = Vec::with_capacity(start.rest.len() + 1);
    let (mut x, mut t) = (start.estimate, start.second.time());
    est.push((t, x));
    for p in start.rest {
        x = update(&x, p.time() - t, p)?;
        t = p.time();
        est.push((t, x));
    }
    let smoothed = match ctx.smoothing {
        None => None,
        Some(how) => Some(smooth::rts_rows(filter, &est, how).map_err(SingleError::Smoothing)?),
    };
    let columns = Columns {
        axes: D,
        modes: 0,
        noise: false,
        turn_rate: false,
        smoothed: smoothed.is_some(),
    };
    let mut rows = Vec::with_capacity(est.len());
    for (i, (t, x)) in est.iter().enumerate() {
        let s = smoothed.as_ref().and_then(|s| s.get(i));
        rows.push(Estimate {
            smoothed: s.copied(),
            ..Estimate::new(*t, *x)
        });
    }
    Ok(SingleRun {
        columns,
        estimates: wrap(rows),
    })
}

//! The single-target job: one estimator over every plot of the file, in order. 2-D plot
//! files get a 2-D CV estimator (`[x, vx, y, vy]`), 3-D ones (spherical or Cartesian 3-D)
//! a 3-D CV estimator; the IMMs ([`super::single_imm`], [`super::single_aircraft`]) are
//! 2-D. One row per estimate.

use argus_config::Estimator;
use argus_core_math::Gaussian;
use argus_filters::SmoothingFilter;
use argus_io::plotfile::FilePlot;
use argus_io::rows::{Column, Point, TrackRows};
use argus_sensors::Measurement;

use super::single_dim::{DIM2, DIM3, Dim};
use super::smooth;
use super::start::{Ctx, two_point};
use super::{single_aircraft, single_imm};
use crate::error::CliError;
use crate::estimator::{cv_ekf, cv_kf, cv3_ekf, cv3_kf, polar, spherical, step};

/// Runs `estimator` over `plots` (in file order, already checked by `plotfile`).
///
/// # Errors
/// [`CliError::Input`] naming the plot file's line of a plot the estimator cannot use, or
/// the configuration's key of a missing σ; the estimators' errors.
pub(super) fn run(
    ctx: &Ctx<'_>,
    estimator: &Estimator,
    plots: &[FilePlot],
) -> Result<TrackRows, CliError> {
    let three_d = plots.first().is_some_and(|p| p.measurement().dim() == 3);
    match (estimator, three_d) {
        (Estimator::KfConverted(sa), false) => {
            let f = cv_kf(*sa)?;
            track_loop(ctx, plots, &DIM2, &f, |x, dt, p| {
                DIM2.converted_step(ctx, &f, x, dt, p)
            })
        }
        (Estimator::Ekf(sa), false) => {
            let f = cv_ekf(*sa)?;
            track_loop(ctx, plots, &DIM2, &f, |x, dt, p| {
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
        (Estimator::Imm(spec), false) => single_imm::imm(ctx, spec, plots),
        (Estimator::MultiImm(spec, multi), false) => {
            single_imm::multi_imm(ctx, spec, *multi, plots)
        }
        (Estimator::Aircraft(tuning), false) => single_aircraft::run(ctx, tuning, plots),
        (Estimator::Imm(_) | Estimator::MultiImm(..) | Estimator::Aircraft(_), true) => {
            Err(CliError::input(
                ctx.config,
                None,
                Some("estimator.kind"),
                format!(
                    "the IMM estimators track 2-D plots ([x, vx, y, vy]); {} holds 3-D plots",
                    ctx.plots_path.display()
                ),
            ))
        }
        (Estimator::KfConverted(sa), true) => {
            let f = cv3_kf(*sa)?;
            track_loop(ctx, plots, &DIM3, &f, |x, dt, p| {
                DIM3.converted_step(ctx, &f, x, dt, p)
            })
        }
        (Estimator::Ekf(sa), true) => {
            let f = cv3_ekf(*sa)?;
            track_loop(ctx, plots, &DIM3, &f, |x, dt, p| {
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
/// prediction, [`smooth::rts_rows`]).
fn track_loop<const D: usize, const N: usize, F: SmoothingFilter<N>>(
    ctx: &Ctx<'_>,
    plots: &[FilePlot],
    dim: &Dim<D, N>,
    filter: &F,
    update: impl Fn(&Gaussian<N>, f64, &FilePlot) -> Result<Gaussian<N>, CliError>,
) -> Result<TrackRows, CliError> {
    let start = two_point(ctx, plots, |p| (dim.convert)(ctx, p), dim.init)?;
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
        Some(how) => Some(smooth::rts_rows(filter, &est, how).map_err(|f| f.into_cli(1))?),
    };
    let mut columns = Column::single(D, 0, false);
    if smoothed.is_some() {
        columns.extend(Column::smoothed_single(D, 0));
    }
    let mut rows = TrackRows::with_reference(columns, ctx.reference);
    for (i, (t, x)) in est.iter().enumerate() {
        let s = smoothed.as_ref().and_then(|s| s.get(i));
        rows.push(&Point::new(*t, x).smoothed(s));
    }
    Ok(rows)
}

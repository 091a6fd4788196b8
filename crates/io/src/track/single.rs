//! The single-target job: the engine of `argus_tracker::single` over every plot of the
//! file, in order (each plot tagged with its line), its errors mapped to the command's
//! ([`Ctx::error`]) and its estimates written one per row.

use argus_tracker::single::{Estimate, Estimates, EstimatorSpec, SingleTarget, TaggedPlot};

use super::start::Ctx;
use crate::IoError;
use crate::plotfile::FilePlot;
use crate::rows::{Column, Point, TrackRows};

/// Runs `estimator` over `plots` (in file order, already checked by `plotfile`).
///
/// # Errors
/// [`IoError::Input`] naming the plot file's line of a plot the estimator cannot use, or
/// the configuration's key of a missing σ; [`IoError::Smooth`]; the estimators' errors.
pub(super) fn run(
    ctx: &Ctx<'_>,
    estimator: &EstimatorSpec,
    plots: &[FilePlot],
) -> Result<TrackRows, IoError> {
    let engine = SingleTarget::new(estimator.clone(), ctx.engine_sensors(), ctx.smoothing);
    let tagged: Vec<TaggedPlot> = plots
        .iter()
        .map(|p| TaggedPlot {
            tag: p.line,
            plot: p.plot,
        })
        .collect();
    let run = engine.run(&tagged).map_err(|e| ctx.error(e))?;
    let c = run.columns;
    let mut columns = Column::single(c.axes, c.modes, c.noise);
    if c.turn_rate {
        columns.extend(Column::TURN_RATE);
    }
    if c.smoothed {
        columns.extend(Column::smoothed_single(c.axes, c.modes));
    }
    let mut rows = TrackRows::with_reference(columns, ctx.reference);
    match &run.estimates {
        Estimates::Planar(e) => push_all(&mut rows, e),
        Estimates::Spatial(e) => push_all(&mut rows, e),
    }
    Ok(rows)
}

/// One row per estimate.
fn push_all<const N: usize>(rows: &mut TrackRows, estimates: &[Estimate<N>]) {
    for e in estimates {
        rows.push(
            &Point::new(e.time, &e.state)
                .modes(e.modes.as_deref())
                .noise(e.noise)
                .turn_rate(e.turn_rate)
                .smoothed(e.smoothed.as_ref())
                .smoothed_modes(e.smoothed_modes.as_deref()),
        );
    }
}

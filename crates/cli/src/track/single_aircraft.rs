//! The single-target aircraft IMM (`kind = "aircraft-imm"`): `argus_imm::AircraftImm`
//! with two CV modes and the coordinated turn with its rate, EKFs updated with the
//! (range, azimuth) plots of one 2-D radar, started by its own two-point start
//! (`AircraftTuning::start`: the unbiased conversion of the first two plots, then
//! differencing, the CT mode with its turn-rate prior). One row per plot from the second:
//! the combined state, its variances, the three mode probabilities and the CT mode's turn
//! rate. With `--smooth` / `--smooth-lag` the rows also get the aircraft-IMM smoother's
//! combined state, its variances and the smoothed mode probabilities
//! ([`super::smooth_aircraft`]).

use argus_config::Sensor;
use argus_core_math::Vector;
use argus_imm::{AircraftEstimate, AircraftRadar, AircraftSmoothed, AircraftTuning};
use argus_io::plotfile::FilePlot;
use argus_io::rows::{Column, Point, TrackRows};
use argus_sensors::{Measurement, RadarNoise};

use super::single_smooth::smooth_run;
use super::smooth::Failure;
use super::smooth_aircraft::AircraftRecorder;
use super::start::{Ctx, too_few};
use crate::error::CliError;

/// The aircraft IMM of `tuning` over the polar plots of one sensor. Plots of the same
/// instant are applied in turn without mixing or prediction.
///
/// # Errors
/// [`CliError::Input`] at the plot file's line of a plot of another sensor or a Cartesian
/// report, at the second plot when the start fails, at a plot whose step fails; at the
/// sensor's `sigma_range` for σ the radar model refuses (zero).
pub(super) fn run(
    ctx: &Ctx<'_>,
    tuning: &AircraftTuning<2, 3>,
    plots: &[FilePlot],
) -> Result<TrackRows, CliError> {
    let imm = tuning.build()?;
    let (Some(p1), Some(p2)) = (plots.first(), plots.get(1)) else {
        return Err(too_few(ctx));
    };
    let sensor = ctx.sensor(p1)?;
    let radar = radar(ctx, sensor)?;
    let plot = |p: &FilePlot| -> Result<Vector<2>, CliError> {
        let not_polar = |what: String| {
            CliError::input(
                ctx.plots_path,
                Some(p.line),
                Some("sensor"),
                format!("the aircraft IMM tracks one 2-D radar's polar plots: {what}"),
            )
        };
        if p.sensor() != sensor.id {
            return Err(not_polar(format!(
                "plot of sensor {} after sensor {}",
                p.sensor(),
                sensor.id
            )));
        }
        match p.measurement() {
            Measurement::Polar(m) => Ok(m.to_vector()),
            _ => Err(not_polar("not a (range, azimuth) plot".to_owned())),
        }
    };
    let mut est = tuning
        .start(&radar, &plot(p1)?, &plot(p2)?, p2.time() - p1.time())
        .map_err(|e| {
            CliError::input(
                ctx.plots_path,
                Some(p2.line),
                Some("t"),
                format!("two-point initialisation: {e}"),
            )
        })?;
    let mut t = p2.time();
    // With smoothing, the forward pass is recorded (one step per time).
    let mut record = ctx.smoothing.map(|_| AircraftRecorder::new());
    let fail = |f: Failure| f.into_cli(1);
    let mut out: Vec<(f64, AircraftEstimate<2, 3>, usize)> = Vec::with_capacity(plots.len());
    if let Some(r) = &mut record {
        r.record(&imm, t, est).map_err(fail)?;
    }
    out.push((t, est, 1));
    for (i, p) in plots.iter().enumerate().skip(2) {
        let z = plot(p)?;
        let dt = p.time() - t;
        let upd = if dt == 0.0 {
            imm.update(&est.into_prediction(), &radar, &z)
        } else {
            imm.step(&est, dt, &radar, &z)
        };
        est = upd.map_err(ctx.imm_error(p))?.estimate;
        t = p.time();
        if let Some(r) = &mut record {
            r.record(&imm, t, est).map_err(fail)?;
        }
        out.push((t, est, i));
    }
    let times: Vec<f64> = out.iter().map(|o| o.0).collect();
    let smoothed = smooth_run(record, &imm, ctx.smoothing, &times)?;
    let mut columns = Column::single(2, 3, false);
    columns.extend(Column::TURN_RATE);
    if smoothed.is_some() {
        columns.extend(Column::smoothed_single(2, 3));
    }
    let mut rows = TrackRows::with_reference(columns, ctx.reference);
    for (k, (t, est, i)) in out.iter().enumerate() {
        let s = smoothed.as_ref().and_then(|s| s.at(k));
        // The plot of the row (for an error's line).
        let p = &plots[*i];
        push(&mut rows, *t, est, s).map_err(ctx.imm_error(p))?;
    }
    Ok(rows)
}

/// The sensor as the aircraft IMM's radar.
fn radar(ctx: &Ctx<'_>, s: &Sensor) -> Result<AircraftRadar, CliError> {
    let (sr, sa) = ctx.polar_sigmas(s)?;
    let bad = |e: String| {
        CliError::input(
            ctx.config,
            None,
            Some("sigma_range"),
            format!("sensor {}: {e}", s.id),
        )
    };
    let noise = RadarNoise::constant(sr, sa, 0.0).map_err(|e| bad(e.to_string()))?;
    AircraftRadar::new([s.position[0], s.position[1]], noise).map_err(|e| bad(e.to_string()))
}

/// One row: the combined estimate, the mode probabilities, the turn rate; with
/// smoothing, the step's smoothed combined estimate and mode probabilities.
fn push(
    rows: &mut TrackRows,
    t: f64,
    est: &AircraftEstimate<2, 3>,
    smoothed: Option<&AircraftSmoothed<2, 3>>,
) -> Result<(), argus_imm::ImmError> {
    let c = est.combined()?;
    let mu = est.mode_probabilities();
    rows.push(
        &Point::new(t, &c)
            .modes(Some(&mu))
            .turn_rate(Some(est.turn_rate()))
            .smoothed(smoothed.map(|s| &s.combined))
            .smoothed_modes(smoothed.map(|s| s.mode_probabilities.as_slice())),
    );
    Ok(())
}

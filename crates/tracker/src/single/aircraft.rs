//! The single-target aircraft IMM (`kind = "aircraft-imm"`): `argus_imm::AircraftImm`
//! with two CV modes and the coordinated turn with its rate, EKFs updated with the
//! (range, azimuth) plots of one 2-D radar, started by its own two-point start
//! (`AircraftTuning::start`: the unbiased conversion of the first two plots, then
//! differencing, the CT mode with its turn-rate prior). One row per plot from the second:
//! the combined state, its variances, the three mode probabilities and the CT mode's turn
//! rate. With `--smooth` / `--smooth-lag` the rows also get the aircraft-IMM smoother's
//! combined state, its variances and the smoothed mode probabilities
//! ([`crate::smooth::AircraftRecorder`]).

use argus_core_math::Vector;
use argus_imm::{AircraftEstimate, AircraftRadar, AircraftSmoothed, AircraftTuning};
use argus_sensors::{Measurement, RadarNoise};

use super::error::{OneRadar, SingleError};
use super::output::{Columns, Estimate, Estimates, SingleRun, TaggedPlot};
use super::smoothed::smooth_run;
use super::spec::SingleSensor;
use super::start::Ctx;
use crate::smooth::AircraftRecorder;

/// The aircraft IMM of `tuning` over the polar plots of one sensor. Plots of the same
/// instant are applied in turn without mixing or prediction.
///
/// # Errors
/// [`SingleError`] at the tag of a plot of another sensor or a Cartesian report, at the
/// second plot when the start fails, at a plot whose step fails; at the sensor for σ the
/// radar model refuses (zero).
pub(super) fn run(
    ctx: &Ctx<'_>,
    tuning: &AircraftTuning<2, 3>,
    plots: &[TaggedPlot],
) -> Result<SingleRun, SingleError> {
    let imm = tuning.build()?;
    let (Some(p1), Some(p2)) = (plots.first(), plots.get(1)) else {
        return Err(SingleError::TooFewPlots);
    };
    let sensor = ctx.sensor(p1)?;
    let radar = radar(ctx, sensor)?;
    let plot = |p: &TaggedPlot| -> Result<Vector<2>, SingleError> {
        if p.sensor() != sensor.id {
            return Err(SingleError::OtherSensor {
                tag: p.tag,
                estimator: OneRadar::Aircraft,
                sensor: p.sensor(),
                first: sensor.id,
            });
        }
        match p.measurement() {
            Measurement::Polar(m) => Ok(m.to_vector()),
            _ => Err(SingleError::NotPolar {
                tag: p.tag,
                estimator: OneRadar::Aircraft,
            }),
        }
    };
    let mut est = tuning
        .start(&radar, &plot(p1)?, &plot(p2)?, p2.time() - p1.time())
        .map_err(|source| SingleError::AircraftStart {
            tag: p2.tag,
            source,
        })?;
    let mut t = p2.time();
    // With smoothing, the forward pass is recorded (one step per time).
    let mut record = ctx.smoothing.map(|_| AircraftRecorder::new());
    let fail = SingleError::Smoothing;
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
    let columns = Columns {
        axes: 2,
        modes: 3,
        noise: false,
        turn_rate: true,
        smoothed: smoothed.is_some(),
    };
    let mut rows = Vec::with_capacity(out.len());
    for (k, (t, est, i)) in out.iter().enumerate() {
        let s = smoothed.as_ref().and_then(|s| s.at(k));
        // The plot of the row (for an error's tag).
        let p = &plots[*i];
        rows.push(row(*t, est, s).map_err(ctx.imm_error(p))?);
    }
    Ok(SingleRun {
        columns,
        estimates: Estimates::Planar(rows),
    })
}

/// The sensor as the aircraft IMM's radar.
fn radar(ctx: &Ctx<'_>, s: &SingleSensor) -> Result<AircraftRadar, SingleError> {
    let (sr, sa) = ctx.polar_sigmas(s)?;
    let bad = |message: String| SingleError::SensorNoise {
        sensor: s.id,
        message,
    };
    let noise = RadarNoise::constant(sr, sa, 0.0).map_err(|e| bad(e.to_string()))?;
    AircraftRadar::new([s.position[0], s.position[1]], noise).map_err(|e| bad(e.to_string()))
}

/// One row: the combined estimate, the mode probabilities, the turn rate; with
/// smoothing, the step's smoothed combined estimate and mode probabilities.
fn row(
    t: f64,
    est: &AircraftEstimate<2, 3>,
    smoothed: Option<&AircraftSmoothed<2, 3>>,
) -> Result<Estimate<4>, argus_imm::ImmError> {
    let c = est.combined()?;
    let mu = est.mode_probabilities();
    Ok(Estimate {
        modes: Some(mu.to_vec()),
        turn_rate: Some(est.turn_rate()),
        smoothed: smoothed.map(|s| s.combined),
        smoothed_modes: smoothed.map(|s| s.mode_probabilities.to_vec()),
        ..Estimate::new(t, c)
    })
}

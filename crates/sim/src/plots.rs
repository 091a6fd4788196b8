//! Plot generation: noisy, biased, missed and cluttered measurements of the truth.

use std::f64::consts::{PI, TAU};

use argus_core_math::Vector;
use argus_sensors::{
    CartesianMeasurement, Measurement, Plot, PolarMeasurement, SensorId, SphericalMeasurement,
    wrap_angle,
};
use rand::Rng;
use rand::RngExt;
use rand_distr::{Distribution, Poisson, StandardNormal};

use crate::error::SimError;
use crate::sensor::{ClutterRegion, Detection, Schedule, SensorKind, SensorSpec};
use crate::truth::{TargetId, Trajectory, Truth};

/// The true origin of a plot, kept for scoring; never shown to a filter.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Origin {
    /// A detection of this target.
    Target(TargetId),
    /// A false alarm.
    Clutter,
}

/// A simulated plot: the plot a sensor reports ([`argus_sensors::Plot`]) and, for
/// scoring only, where it truly came from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LabelledPlot {
    /// The plot as a tracker sees it.
    pub plot: Plot,
    /// Where it truly came from.
    pub origin: Origin,
}

fn normal<R: Rng + ?Sized>(rng: &mut R) -> f64 {
    StandardNormal.sample(rng)
}

/// A polar or spherical measurement, or `None` for a range below zero (noise larger than
/// the range, or a clutter region reaching behind the sensor): no sensor reports one, so
/// the plot is dropped (its random draws are made all the same).
fn radar(
    range: f64,
    azimuth: f64,
    elevation: Option<f64>,
) -> Result<Option<Measurement>, SimError> {
    if range < 0.0 {
        return Ok(None);
    }
    Ok(Some(match elevation {
        None => PolarMeasurement::new(range, azimuth)?.into(),
        Some(e) => SphericalMeasurement::new(range, azimuth, e)?.into(),
    }))
}

/// Adds bias and white noise to the noise-free measurement `clean` (components as
/// [`crate::sensor::Model::h`] gives them); `None` for a range below zero.
///
/// # Errors
/// [`SimError::Sensor`] for a non-finite value.
fn corrupt<R: Rng + ?Sized>(
    sensor: &SensorSpec,
    clean: [f64; 3],
    rng: &mut R,
) -> Result<Option<Measurement>, SimError> {
    let b = &sensor.bias;
    let [c0, c1, c2] = clean;
    Ok(Some(match sensor.kind {
        SensorKind::Polar {
            sigma_range,
            sigma_azimuth,
        } => {
            let range = (1.0 + b.range_scale) * c0 + b.range_offset + sigma_range * normal(rng);
            let azimuth = wrap_angle(
                (1.0 + b.azimuth_scale) * c1 + b.azimuth_offset + sigma_azimuth * normal(rng),
            );
            return radar(range, azimuth, None);
        }
        SensorKind::Spherical {
            sigma_range,
            sigma_azimuth,
            sigma_elevation,
        } => {
            let range = (1.0 + b.range_scale) * c0 + b.range_offset + sigma_range * normal(rng);
            let azimuth = wrap_angle(
                (1.0 + b.azimuth_scale) * c1 + b.azimuth_offset + sigma_azimuth * normal(rng),
            );
            let elevation = c2 + b.elevation_offset + sigma_elevation * normal(rng);
            return radar(range, azimuth, Some(elevation));
        }
        SensorKind::Cartesian2d { cov } => {
            let n = Vector::<3>::new(normal(rng), normal(rng), 0.0);
            let e = sensor.chol * n;
            CartesianMeasurement::new(Vector::<2>::new(c0 + e.x, c1 + e.y), cov)?.into()
        }
        SensorKind::Cartesian3d { cov } => {
            let n = Vector::<3>::new(normal(rng), normal(rng), normal(rng));
            let e = sensor.chol * n;
            CartesianMeasurement::new(Vector::<3>::new(c0 + e.x, c1 + e.y, c2 + e.z), cov)?.into()
        }
    }))
}

/// Builds a measurement of the sensor's kind from raw components (clutter); `None` for
/// a range below zero.
///
/// # Errors
/// [`SimError::Sensor`] for a non-finite value.
fn from_components(sensor: &SensorSpec, c: [f64; 3]) -> Result<Option<Measurement>, SimError> {
    Ok(Some(match sensor.kind {
        SensorKind::Polar { .. } => return radar(c[0], wrap_angle(c[1]), None),
        SensorKind::Spherical { .. } => return radar(c[0], wrap_angle(c[1]), Some(c[2])),
        SensorKind::Cartesian2d { cov } => {
            CartesianMeasurement::new(Vector::<2>::new(c[0], c[1]), cov)?.into()
        }
        SensorKind::Cartesian3d { cov } => {
            CartesianMeasurement::new(Vector::<3>::new(c[0], c[1], c[2]), cov)?.into()
        }
    }))
}

/// Adds a sensor's plot with its amplitude and true origin (none for a dropped
/// measurement).
fn push(
    plots: &mut Vec<LabelledPlot>,
    (time, sensor): (f64, SensorId),
    measurement: Option<Measurement>,
    amplitude: Option<f64>,
    origin: Origin,
) -> Result<(), SimError> {
    if let Some(m) = measurement {
        plots.push(LabelledPlot {
            plot: Plot::new(time, sensor, m)?.with_amplitude(amplitude)?,
            origin,
        });
    }
    Ok(())
}

/// Rayleigh draw with scale² `s2`: `sqrt(−2 s2 ln U)`, `U` uniform on `(0, 1]`.
fn rayleigh<R: Rng + ?Sized>(s2: f64, rng: &mut R) -> f64 {
    let u: f64 = 1.0 - rng.random::<f64>();
    (-2.0 * s2 * u.ln()).sqrt()
}

/// Target detection: `(detected, amplitude)`.
fn detect_target<R: Rng + ?Sized>(det: &Detection, rng: &mut R) -> (bool, Option<f64>) {
    match *det {
        Detection::Probability(p) => (rng.random::<f64>() < p, None),
        Detection::Swerling1 { snr_db, threshold } => {
            let d = 10f64.powf(snr_db / 10.0);
            let a = rayleigh(1.0 + d, rng);
            (a >= threshold, Some(a))
        }
    }
}

/// Clutter amplitude above the threshold: `a² = τ² + 2 E`, `E ~ Exp(1)` (the Rayleigh
/// tail is memoryless in `a²`).
fn clutter_amplitude<R: Rng + ?Sized>(det: &Detection, rng: &mut R) -> Option<f64> {
    match *det {
        Detection::Probability(_) => None,
        Detection::Swerling1 { threshold, .. } => {
            let u: f64 = 1.0 - rng.random::<f64>();
            Some((threshold * threshold - 2.0 * u.ln()).sqrt())
        }
    }
}

/// Draws a Poisson count with mean `mean` (0 when `mean` is 0).
fn poisson<R: Rng + ?Sized>(mean: f64, rng: &mut R) -> u64 {
    if mean <= 0.0 {
        return 0;
    }
    match Poisson::new(mean) {
        // Poisson samples are whole numbers stored as f64; the cast saturates.
        Ok(p) => {
            let n: f64 = p.sample(rng);
            n as u64
        }
        Err(_) => 0,
    }
}

/// The times in `[from, to]` when a beam rotating counter-clockwise at `2π/period`,
/// at azimuth `az0` at `t = 0`, crosses the target's azimuth seen from `sensor`.
///
/// The angle `δ(t) = wrap(β(t) − θ(t))` of the beam past the target is sampled every
/// `period/36`; each upward zero crossing (not the ±π wrap) is refined by bisection to
/// 1e-9 s. Assumes the target's azimuth rate is far below the beam's.
///
/// # Errors
/// [`SimError::TimeOutOfSpan`] if `[from, to]` is not inside the trajectory's span.
pub fn beam_crossings(
    traj: &Trajectory,
    sensor: &Vector<3>,
    period: f64,
    az0: f64,
    from: f64,
    to: f64,
) -> Result<Vec<f64>, SimError> {
    let position = |t: f64| -> Result<[f64; 2], SimError> {
        let s = traj.state_at(t)?;
        Ok([s.position.x, s.position.y])
    };
    beam_crossings_along(
        position,
        [sensor.x, sensor.y],
        Rotation::Counterclockwise,
        period,
        az0,
        from,
        to,
    )
}

/// The sense in which a radar's beam turns, seen from above.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rotation {
    /// Azimuth (counter-clockwise from +x) increasing: `β(t) = az0 + 2π t / period`.
    Counterclockwise,
    /// Azimuth decreasing, as most surveillance radars turn (clockwise in bearing from
    /// north): `β(t) = az0 − 2π t / period`.
    Clockwise,
}

/// [`beam_crossings`] for any path `position(t) = [x, y]` and either sense of rotation:
/// the angle of the beam past the target, `δ(t) = wrap(β(t) − θ(t))` counter-clockwise or
/// `wrap(θ(t) − β(t))` clockwise, is sampled every `period/36` over `[from, to]` and each
/// upward zero crossing (not the ±π wrap) refined by bisection to 1e-9 s.
///
/// # Errors
/// Whatever `position` returns for a time it cannot place.
pub fn beam_crossings_along<E>(
    position: impl Fn(f64) -> Result<[f64; 2], E>,
    sensor: [f64; 2],
    rotation: Rotation,
    period: f64,
    az0: f64,
    from: f64,
    to: f64,
) -> Result<Vec<f64>, E> {
    let delta = |t: f64| -> Result<f64, E> {
        let p = position(t)?;
        let theta = (p[1] - sensor[1]).atan2(p[0] - sensor[0]);
        Ok(match rotation {
            Rotation::Counterclockwise => wrap_angle(az0 + TAU * t / period - theta),
            Rotation::Clockwise => wrap_angle(theta - (az0 - TAU * t / period)),
        })
    };
    let mut out = Vec::new();
    if from.is_nan() || to.is_nan() || to <= from {
        return Ok(out);
    }
    let h = period / 36.0;
    let n = ((to - from) / h).ceil().max(1.0) as u64;
    let mut ta = from;
    let mut da = delta(ta)?;
    if da == 0.0 {
        out.push(ta);
    }
    for k in 1..=n {
        let tb = (from + k as f64 * h).min(to);
        let db = delta(tb)?;
        if da < 0.0 && db >= 0.0 && db - da < PI {
            let (mut lo, mut hi) = (ta, tb);
            while hi - lo > 1e-9 {
                let mid = 0.5 * (lo + hi);
                if delta(mid)? < 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            out.push(hi);
        }
        ta = tb;
        da = db;
    }
    Ok(out)
}

/// One scheduled observation of a target: time and target index.
#[derive(Debug, Clone, Copy)]
struct Look {
    time: f64,
    target: usize,
}

/// The looks of a sensor grouped by scan (scan index, scan start time, looks in time order).
fn scans(sensor: &SensorSpec, truth: &Truth) -> Result<Vec<(i64, f64, Vec<Look>)>, SimError> {
    let Some((start, end)) = truth.span() else {
        return Ok(Vec::new());
    };
    let mut out: Vec<(i64, f64, Vec<Look>)> = Vec::new();
    match sensor.schedule {
        Schedule::Periodic { period, offset } => {
            let k0 = ((start - offset) / period).ceil() as i64;
            let k1 = ((end - offset) / period).floor() as i64;
            for k in k0..=k1 {
                let t = offset + k as f64 * period;
                let looks = truth
                    .targets()
                    .iter()
                    .enumerate()
                    .filter(|(_, (_, tr))| t >= tr.start() - 1e-9 && t <= tr.end() + 1e-9)
                    .map(|(i, _)| Look { time: t, target: i })
                    .collect();
                out.push((k, t, looks));
            }
        }
        Schedule::RotatingBeam {
            period,
            azimuth_at_zero,
        } => {
            let k0 = (start / period).floor() as i64;
            let k1 = (end / period).floor() as i64;
            for k in k0..=k1 {
                out.push((k, k as f64 * period, Vec::new()));
            }
            for (i, (_, tr)) in truth.targets().iter().enumerate() {
                let times = beam_crossings(
                    tr,
                    &sensor.position,
                    period,
                    azimuth_at_zero,
                    tr.start(),
                    tr.end(),
                )?;
                for t in times {
                    let k = (t / period).floor() as i64;
                    let slot = usize::try_from(k - k0).ok().and_then(|j| out.get_mut(j));
                    if let Some((_, _, looks)) = slot {
                        looks.push(Look { time: t, target: i });
                    }
                }
            }
            for (_, _, looks) in &mut out {
                looks.sort_by(|a, b| a.time.total_cmp(&b.time).then(a.target.cmp(&b.target)));
            }
        }
    }
    Ok(out)
}

/// Generates every sensor's plots of `truth` for one Monte Carlo run, sorted by time
/// (ties: sensor order as given, then generation order).
///
/// Random draws happen in a fixed, documented order, so a seed fixes the plots:
/// for each sensor in the order given, for each scan in time order, for each look at a
/// target in time order (target order on ties): the detection draw (uniform, or the
/// Rayleigh amplitude), then — if detected — the noise (range, azimuth[, elevation] or
/// the Cartesian components), then gate clutter around that target if configured
/// (count, then per plot its components in order and its amplitude); after the scan's
/// looks, box clutter (count, then per plot its components and amplitude).
///
/// # Errors
/// [`SimError::TimeOutOfSpan`] only on internal inconsistency (looks are drawn inside
/// each trajectory's span); [`SimError::Sensor`] for a non-finite measured value. A
/// polar or spherical plot whose range comes out below zero (noise larger than the range,
/// or a clutter region reaching behind the sensor) is dropped, after its random draws.
pub fn generate_plots<R: Rng + ?Sized>(
    truth: &Truth,
    sensors: &[SensorSpec],
    rng: &mut R,
) -> Result<Vec<LabelledPlot>, SimError> {
    let mut plots = Vec::new();
    for sensor in sensors {
        for (_, scan_start, looks) in scans(sensor, truth)? {
            for look in &looks {
                let Some((id, tr)) = truth.targets().get(look.target) else {
                    continue;
                };
                let state = tr.state_at(look.time)?;
                let clean = sensor.model.h(&state.position);
                let (detected, amplitude) = detect_target(&sensor.detection, rng);
                if detected {
                    let m = corrupt(sensor, clean, rng)?;
                    push(
                        &mut plots,
                        (look.time, sensor.id),
                        m,
                        amplitude,
                        Origin::Target(*id),
                    )?;
                }
                if let Some(c) = sensor.clutter
                    && let ClutterRegion::Gate { half_width } = c.region
                {
                    let (centre, dim) = (clean, sensor.kind.dim());
                    let volume: f64 = half_width.iter().take(dim).map(|h| 2.0 * h).product();
                    let n = poisson(c.density * volume, rng);
                    for _ in 0..n {
                        let mut z = centre;
                        for (zi, h) in z.iter_mut().zip(half_width.iter()).take(dim) {
                            *zi += h * (2.0 * rng.random::<f64>() - 1.0);
                        }
                        let m = from_components(sensor, z)?;
                        let a = clutter_amplitude(&sensor.detection, rng);
                        push(&mut plots, (look.time, sensor.id), m, a, Origin::Clutter)?;
                    }
                }
            }
            if let Some(c) = sensor.clutter
                && let ClutterRegion::Box { lower, upper } = c.region
            {
                let dim = sensor.kind.dim();
                let volume: f64 = lower
                    .iter()
                    .zip(upper.iter())
                    .take(dim)
                    .map(|(lo, hi)| hi - lo)
                    .product();
                let n = poisson(c.density * volume, rng);
                for _ in 0..n {
                    let mut z = [0.0; 3];
                    for ((zi, lo), hi) in z.iter_mut().zip(lower.iter()).zip(upper.iter()).take(dim)
                    {
                        *zi = lo + (hi - lo) * rng.random::<f64>();
                    }
                    let time = match sensor.schedule {
                        Schedule::RotatingBeam {
                            period,
                            azimuth_at_zero,
                        } if matches!(
                            sensor.kind,
                            SensorKind::Polar { .. } | SensorKind::Spherical { .. }
                        ) =>
                        {
                            scan_start
                                + period
                                    * (z[1] - azimuth_at_zero - TAU * scan_start / period)
                                        .rem_euclid(TAU)
                                    / TAU
                        }
                        _ => scan_start,
                    };
                    let m = from_components(sensor, z)?;
                    let a = clutter_amplitude(&sensor.detection, rng);
                    push(&mut plots, (time, sensor.id), m, a, Origin::Clutter)?;
                }
            }
        }
    }
    let order: Vec<SensorId> = sensors.iter().map(|s| s.id).collect();
    let rank = |id: SensorId| order.iter().position(|s| *s == id).unwrap_or(usize::MAX);
    // Stable sort keeps generation order among equal (time, sensor).
    plots.sort_by(|a, b| {
        (a.plot.time())
            .total_cmp(&b.plot.time())
            .then(rank(a.plot.sensor()).cmp(&rank(b.plot.sensor())))
    });
    Ok(plots)
}

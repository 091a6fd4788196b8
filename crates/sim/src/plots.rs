//! Plot generation: noisy, biased, missed and cluttered measurements of the truth.

use std::f64::consts::{PI, TAU};

use argus_core_math::Vector;
use rand::Rng;
use rand::RngExt;
use rand_distr::{Distribution, Poisson, StandardNormal};

use crate::SensorId;
use crate::error::SimError;
use crate::sensor::{ClutterRegion, Detection, Schedule, SensorKind, SensorSpec};
use crate::truth::{KinematicState, TargetId, Trajectory, Truth};

/// A measured value, in the sensor's own coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Measurement {
    /// Range (m) and azimuth (rad, `(−π, π]`) relative to the sensor.
    Polar {
        /// Range (m).
        range: f64,
        /// Azimuth (rad).
        azimuth: f64,
    },
    /// Range, azimuth and elevation relative to the sensor.
    Spherical {
        /// Range (m).
        range: f64,
        /// Azimuth (rad).
        azimuth: f64,
        /// Elevation (rad).
        elevation: f64,
    },
    /// A 2-D position report in global coordinates with its covariance `[r_xx, r_xy, r_yy]`.
    Cartesian2d {
        /// `[x, y]` (m).
        position: [f64; 2],
        /// `[r_xx, r_xy, r_yy]` (m²).
        cov: [f64; 3],
    },
    /// A 3-D position report with its covariance `[r_xx, r_xy, r_xz, r_yy, r_yz, r_zz]`.
    Cartesian3d {
        /// `[x, y, z]` (m).
        position: [f64; 3],
        /// Upper triangle, row by row (m²).
        cov: [f64; 6],
    },
}

impl Measurement {
    /// The measured components (range, azimuth[, elevation] or x, y[, z]) and their count.
    #[must_use]
    pub fn components(&self) -> ([f64; 3], usize) {
        match *self {
            Self::Polar { range, azimuth } => ([range, azimuth, 0.0], 2),
            Self::Spherical {
                range,
                azimuth,
                elevation,
            } => ([range, azimuth, elevation], 3),
            Self::Cartesian2d { position, .. } => ([position[0], position[1], 0.0], 2),
            Self::Cartesian3d { position, .. } => (position, 3),
        }
    }
}

/// The true origin of a plot, kept for scoring; never shown to a filter.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Origin {
    /// A detection of this target.
    Target(TargetId),
    /// A false alarm.
    Clutter,
}

/// One plot (detection report).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plot {
    /// Time (s).
    pub time: f64,
    /// The sensor that made it.
    pub sensor: SensorId,
    /// The measured value.
    pub measurement: Measurement,
    /// Normalised amplitude when the sensor's detection model has amplitudes.
    pub amplitude: Option<f64>,
    /// Where it truly came from.
    pub origin: Origin,
}

/// Wraps an angle to `(−π, π]`.
#[must_use]
pub fn wrap_angle(a: f64) -> f64 {
    let w = a.rem_euclid(TAU);
    if w > PI { w - TAU } else { w }
}

/// The noise-free measurement of `state` by `sensor` (no bias, no noise).
#[must_use]
pub fn true_measurement(sensor: &SensorSpec, state: &KinematicState) -> Measurement {
    let d = state.position - sensor.position;
    let horiz = d.x.hypot(d.y);
    match sensor.kind {
        SensorKind::Polar { .. } => Measurement::Polar {
            range: horiz,
            azimuth: d.y.atan2(d.x),
        },
        SensorKind::Spherical { .. } => Measurement::Spherical {
            range: d.norm(),
            azimuth: d.y.atan2(d.x),
            elevation: d.z.atan2(horiz),
        },
        SensorKind::Cartesian2d { cov } => Measurement::Cartesian2d {
            position: [state.position.x, state.position.y],
            cov: [cov[(0, 0)], cov[(0, 1)], cov[(1, 1)]],
        },
        SensorKind::Cartesian3d { cov } => Measurement::Cartesian3d {
            position: [state.position.x, state.position.y, state.position.z],
            cov: [
                cov[(0, 0)],
                cov[(0, 1)],
                cov[(0, 2)],
                cov[(1, 1)],
                cov[(1, 2)],
                cov[(2, 2)],
            ],
        },
    }
}

fn normal<R: Rng + ?Sized>(rng: &mut R) -> f64 {
    StandardNormal.sample(rng)
}

/// Adds bias and white noise to a noise-free measurement.
fn corrupt<R: Rng + ?Sized>(sensor: &SensorSpec, m: Measurement, rng: &mut R) -> Measurement {
    let b = &sensor.bias;
    match (sensor.kind, m) {
        (
            SensorKind::Polar {
                sigma_range,
                sigma_azimuth,
            },
            Measurement::Polar { range, azimuth },
        ) => Measurement::Polar {
            range: (1.0 + b.range_scale) * range + b.range_offset + sigma_range * normal(rng),
            azimuth: wrap_angle(
                (1.0 + b.azimuth_scale) * azimuth + b.azimuth_offset + sigma_azimuth * normal(rng),
            ),
        },
        (
            SensorKind::Spherical {
                sigma_range,
                sigma_azimuth,
                sigma_elevation,
            },
            Measurement::Spherical {
                range,
                azimuth,
                elevation,
            },
        ) => Measurement::Spherical {
            range: (1.0 + b.range_scale) * range + b.range_offset + sigma_range * normal(rng),
            azimuth: wrap_angle(
                (1.0 + b.azimuth_scale) * azimuth + b.azimuth_offset + sigma_azimuth * normal(rng),
            ),
            elevation: elevation + b.elevation_offset + sigma_elevation * normal(rng),
        },
        (_, Measurement::Cartesian2d { position, cov }) => {
            let n = Vector::<3>::new(normal(rng), normal(rng), 0.0);
            let e = sensor.chol * n;
            Measurement::Cartesian2d {
                position: [position[0] + e.x, position[1] + e.y],
                cov,
            }
        }
        (_, Measurement::Cartesian3d { position, cov }) => {
            let n = Vector::<3>::new(normal(rng), normal(rng), normal(rng));
            let e = sensor.chol * n;
            Measurement::Cartesian3d {
                position: [position[0] + e.x, position[1] + e.y, position[2] + e.z],
                cov,
            }
        }
        // Unreachable by construction (the measurement comes from the same sensor);
        // returned unchanged rather than panicking.
        (_, m) => m,
    }
}

/// Builds a measurement of the sensor's kind from raw components (clutter).
fn from_components(sensor: &SensorSpec, c: [f64; 3]) -> Measurement {
    match sensor.kind {
        SensorKind::Polar { .. } => Measurement::Polar {
            range: c[0],
            azimuth: wrap_angle(c[1]),
        },
        SensorKind::Spherical { .. } => Measurement::Spherical {
            range: c[0],
            azimuth: wrap_angle(c[1]),
            elevation: c[2],
        },
        SensorKind::Cartesian2d { cov } => Measurement::Cartesian2d {
            position: [c[0], c[1]],
            cov: [cov[(0, 0)], cov[(0, 1)], cov[(1, 1)]],
        },
        SensorKind::Cartesian3d { cov } => Measurement::Cartesian3d {
            position: c,
            cov: [
                cov[(0, 0)],
                cov[(0, 1)],
                cov[(0, 2)],
                cov[(1, 1)],
                cov[(1, 2)],
                cov[(2, 2)],
            ],
        },
    }
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
    let delta = |t: f64| -> Result<f64, SimError> {
        let s = traj.state_at(t)?;
        let d = s.position - sensor;
        Ok(wrap_angle(az0 + TAU * t / period - d.y.atan2(d.x)))
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
/// each trajectory's span).
pub fn generate_plots<R: Rng + ?Sized>(
    truth: &Truth,
    sensors: &[SensorSpec],
    rng: &mut R,
) -> Result<Vec<Plot>, SimError> {
    let mut plots = Vec::new();
    for sensor in sensors {
        for (_, scan_start, looks) in scans(sensor, truth)? {
            for look in &looks {
                let Some((id, tr)) = truth.targets().get(look.target) else {
                    continue;
                };
                let state = tr.state_at(look.time)?;
                let clean = true_measurement(sensor, &state);
                let (detected, amplitude) = detect_target(&sensor.detection, rng);
                if detected {
                    plots.push(Plot {
                        time: look.time,
                        sensor: sensor.id,
                        measurement: corrupt(sensor, clean, rng),
                        amplitude,
                        origin: Origin::Target(*id),
                    });
                }
                if let Some(c) = sensor.clutter
                    && let ClutterRegion::Gate { half_width } = c.region
                {
                    let (centre, dim) = clean.components();
                    let volume: f64 = half_width.iter().take(dim).map(|h| 2.0 * h).product();
                    let n = poisson(c.density * volume, rng);
                    for _ in 0..n {
                        let mut z = centre;
                        for (zi, h) in z.iter_mut().zip(half_width.iter()).take(dim) {
                            *zi += h * (2.0 * rng.random::<f64>() - 1.0);
                        }
                        plots.push(Plot {
                            time: look.time,
                            sensor: sensor.id,
                            measurement: from_components(sensor, z),
                            amplitude: clutter_amplitude(&sensor.detection, rng),
                            origin: Origin::Clutter,
                        });
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
                    plots.push(Plot {
                        time,
                        sensor: sensor.id,
                        measurement: from_components(sensor, z),
                        amplitude: clutter_amplitude(&sensor.detection, rng),
                        origin: Origin::Clutter,
                    });
                }
            }
        }
    }
    let order: Vec<SensorId> = sensors.iter().map(|s| s.id).collect();
    let rank = |id: SensorId| order.iter().position(|s| *s == id).unwrap_or(usize::MAX);
    // Stable sort keeps generation order among equal (time, sensor).
    plots.sort_by(|a, b| {
        a.time
            .total_cmp(&b.time)
            .then(rank(a.sensor).cmp(&rank(b.sensor)))
    });
    Ok(plots)
}

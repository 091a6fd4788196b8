//! The simulated rotating radar of `real-traffic`: a 2-D surveillance radar at the
//! origin of the local plane whose beam sweeps the ADS-B truth; each aircraft gives a plot
//! at the instant the beam crosses it (its own time), clutter plots at the instants the
//! beam crosses theirs.

use std::f64::consts::{FRAC_PI_2, TAU};

use argus_sensors::{Plot, SensorId, wrap_angle};
use argus_sim::{ChaCha8Rng, LabelledPlot, Origin, Rotation, TargetId, beam_crossings_along};
use rand::RngExt;
use rand_distr::{Distribution, Poisson, StandardNormal};

use super::truth::Path;
use crate::error::ScenarioError;

/// The radar: geometry, timing, noise, detection and clutter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Radar {
    /// Its sensor id in the plot file.
    pub(crate) sensor: SensorId,
    /// Revolution period (s).
    pub(crate) period: f64,
    /// Sense of rotation.
    pub(crate) rotation: Rotation,
    /// A time at which the beam points north (s).
    pub(crate) north_time: f64,
    /// Range noise σ (m).
    pub(crate) sigma_range: f64,
    /// Azimuth noise σ (rad).
    pub(crate) sigma_azimuth: f64,
    /// Detection probability per crossing.
    pub(crate) p_detection: f64,
    /// Mean clutter plots per revolution, uniform per m² over the coverage disc.
    pub(crate) clutter_per_revolution: f64,
    /// Coverage: plots between these ranges (m).
    pub(crate) min_range: f64,
    /// See [`Radar::min_range`].
    pub(crate) max_range: f64,
}

impl Radar {
    /// The beam's azimuth (Argus's convention, counter-clockwise from east) at `t = 0`.
    pub(crate) fn azimuth_at_zero(&self) -> f64 {
        let turned = TAU * self.north_time / self.period;
        match self.rotation {
            // β(t) = π/2 − 2π (t − t_n)/T
            Rotation::Clockwise => FRAC_PI_2 + turned,
            Rotation::Counterclockwise => FRAC_PI_2 - turned,
        }
    }

    /// Clutter density per m² per revolution.
    pub(crate) fn clutter_density(&self) -> f64 {
        self.clutter_per_revolution
            / (std::f64::consts::PI * (self.max_range.powi(2) - self.min_range.powi(2)))
    }

    /// The time in revolution `k` (which starts when the beam points north) at which the
    /// beam points at `azimuth`.
    fn time_in_revolution(&self, k: i64, azimuth: f64) -> f64 {
        // Bearing clockwise from north in [0, 2π).
        let bearing = (FRAC_PI_2 - azimuth).rem_euclid(TAU);
        let fraction = match self.rotation {
            Rotation::Clockwise => bearing / TAU,
            Rotation::Counterclockwise => (TAU - bearing).rem_euclid(TAU) / TAU,
        };
        self.north_time + (k as f64 + fraction) * self.period
    }
}

fn normal(rng: &mut ChaCha8Rng) -> f64 {
    StandardNormal.sample(rng)
}

/// Every plot of `[0, duration)`, in time order: for each path in order, each beam
/// crossing inside the coverage is detected with `p_detection` (one uniform draw) and
/// then given range and azimuth noise (two normal draws); then per revolution a Poisson
/// number of clutter plots, each with a radius (uniform per m² in the annulus) and an
/// azimuth. Targets are numbered by their index in `paths`.
///
/// # Errors
/// [`ScenarioError::Sensor`] if a plot cannot be built (not for finite inputs);
/// [`ScenarioError::Distribution`] for a bad clutter mean.
pub(crate) fn plots(
    radar: &Radar,
    paths: &[Path],
    duration: f64,
    rng: &mut ChaCha8Rng,
) -> Result<Vec<LabelledPlot>, ScenarioError> {
    let mut out = Vec::new();
    let az0 = radar.azimuth_at_zero();
    for (i, path) in paths.iter().enumerate() {
        let (Some(first), Some(last)) = (path.samples.first(), path.samples.last()) else {
            continue;
        };
        let to = last.t.min(duration);
        let position = |t: f64| path.position_at(t).ok_or(());
        let Ok(times) = beam_crossings_along(
            position,
            [0.0, 0.0],
            radar.rotation,
            radar.period,
            az0,
            first.t,
            to,
        ) else {
            continue;
        };
        let target = TargetId(u32::try_from(i).unwrap_or(u32::MAX));
        for t in times {
            if !(0.0..duration).contains(&t) {
                continue;
            }
            let Some([x, y]) = path.position_at(t) else {
                continue;
            };
            let range = x.hypot(y);
            if !(radar.min_range..=radar.max_range).contains(&range) {
                continue;
            }
            if rng.random::<f64>() >= radar.p_detection {
                continue;
            }
            let r = range + radar.sigma_range * normal(rng);
            let a = wrap_angle(y.atan2(x) + radar.sigma_azimuth * normal(rng));
            if r <= 0.0 {
                continue;
            }
            out.push(LabelledPlot {
                plot: Plot::polar(t, radar.sensor, r, a)?,
                origin: Origin::Target(target),
            });
        }
    }
    if radar.clutter_per_revolution > 0.0 {
        let poisson = Poisson::new(radar.clutter_per_revolution).map_err(|e| {
            ScenarioError::Distribution {
                what: "clutter count",
                message: e.to_string(),
            }
        })?;
        let first = ((0.0 - radar.north_time) / radar.period).floor() as i64;
        let last = ((duration - radar.north_time) / radar.period).ceil() as i64;
        let (r0, r1) = (radar.min_range.powi(2), radar.max_range.powi(2));
        for k in first..=last {
            let n: f64 = poisson.sample(rng);
            for _ in 0..(n as u64) {
                let r = (r0 + rng.random::<f64>() * (r1 - r0)).sqrt();
                let a = wrap_angle(rng.random::<f64>() * TAU);
                let t = radar.time_in_revolution(k, a);
                if (0.0..duration).contains(&t) && r > 0.0 {
                    out.push(LabelledPlot {
                        plot: Plot::polar(t, radar.sensor, r, a)?,
                        origin: Origin::Clutter,
                    });
                }
            }
        }
    }
    out.sort_by(|a, b| a.plot.time().total_cmp(&b.plot.time()));
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::super::truth::Sample;
    use super::*;
    use argus_sensors::Measurement;
    use argus_sim::run_rng;

    fn radar() -> Radar {
        Radar {
            sensor: SensorId(1),
            period: 5.0,
            rotation: Rotation::Clockwise,
            north_time: 0.0,
            sigma_range: 70.0,
            sigma_azimuth: 0.08_f64.to_radians(),
            p_detection: 1.0,
            clutter_per_revolution: 0.0,
            min_range: 500.0,
            max_range: 150_000.0,
        }
    }

    /// A path standing still at `(x, y)` over `[0, 100]` s.
    fn still(x: f64, y: f64) -> Path {
        let s = |t| Sample {
            t,
            x,
            vx: 0.0,
            y,
            vy: 0.0,
        };
        Path {
            name: "p".into(),
            samples: vec![s(0.0), s(100.0)],
        }
    }

    #[test]
    fn a_still_target_is_seen_once_a_revolution_at_its_bearing() {
        // Due east of a clockwise radar pointing north at t = 0: bearing 90°, a quarter
        // revolution after north, t = 1.25 + 5k s (exact up to the 1e-9 s bisection).
        let r = Radar {
            sigma_range: 1e-9,
            sigma_azimuth: 1e-12,
            ..radar()
        };
        let seen = plots(&r, &[still(50_000.0, 0.0)], 100.0, &mut run_rng(1, 0)).unwrap();
        assert_eq!(seen.len(), 20);
        for (k, p) in seen.iter().enumerate() {
            assert!((p.plot.time() - (1.25 + 5.0 * k as f64)).abs() < 2e-9);
            let Measurement::Polar(m) = p.plot.measurement() else {
                panic!("polar")
            };
            assert!((m.range() - 50_000.0).abs() < 1e-6);
            assert!(m.azimuth().abs() < 1e-9);
        }
        // North-west (bearing 315°) is seen at 7/8 of the revolution; counter-clockwise
        // it is seen at 1/8.
        let nw = still(-30_000.0, 30_000.0);
        let cw = plots(&r, std::slice::from_ref(&nw), 10.0, &mut run_rng(1, 0)).unwrap();
        assert!((cw[0].plot.time() - 4.375).abs() < 2e-9);
        let ccw = Radar {
            rotation: Rotation::Counterclockwise,
            ..r
        };
        let ccw = plots(&ccw, &[nw], 10.0, &mut run_rng(1, 0)).unwrap();
        assert!((ccw[0].plot.time() - 0.625).abs() < 2e-9);
    }

    #[test]
    fn clutter_comes_at_its_own_azimuths_time_and_inside_the_coverage() {
        let r = Radar {
            clutter_per_revolution: 10.0,
            ..radar()
        };
        let seen = plots(&r, &[], 3600.0, &mut run_rng(4, 0)).unwrap();
        // 720 revolutions × 10: Poisson total 7 200, σ = 85; ±5σ.
        assert!((6775..=7625).contains(&seen.len()), "{}", seen.len());
        for p in &seen {
            let Measurement::Polar(m) = p.plot.measurement() else {
                panic!("polar")
            };
            assert!((500.0..=150_000.0).contains(&m.range()));
            // The beam points at the plot's azimuth at the plot's time.
            let turned = TAU * p.plot.time() / 5.0;
            let beam = wrap_angle(FRAC_PI_2 - turned);
            assert!(wrap_angle(beam - m.azimuth()).abs() < 1e-9);
        }
        assert!(
            seen.windows(2)
                .all(|w| w[0].plot.time() <= w[1].plot.time())
        );
        assert!((r.clutter_density() - 1.4147e-10).abs() < 1e-13);
    }

    #[test]
    fn detection_probability_drops_that_share_of_crossings() {
        let r = Radar {
            p_detection: 0.9,
            ..radar()
        };
        let paths: Vec<Path> = (0..50)
            .map(|k| still(20_000.0 + 1000.0 * f64::from(k), 5_000.0))
            .collect();
        let seen = plots(&r, &paths, 100.0, &mut run_rng(2, 0)).unwrap();
        // 50 × 20 crossings, binomial(1000, 0.9): mean 900, σ 9.5; ±5σ.
        assert!((852..=948).contains(&seen.len()), "{}", seen.len());
    }
}

//! `argus track`: a configured estimator over a user's plot file (see `docs/FORMATS.md`).

use std::path::Path;

use argus_core_math::{Gaussian, Matrix, Vector};
use serde::Deserialize;
use toml::Spanned;

use crate::error::CliError;
use argus_filters::two_point_cv2;

use crate::estimator::{CvEkf, CvKf, cv_ekf, cv_kf, polar, position, step, unbiased};
use crate::output::write_atomic;
use crate::plotfile::{self, FilePlot, FileValue};

/// The TOML configuration.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Config {
    #[serde(rename = "sensor", default)]
    sensors: Vec<SensorConfig>,
    estimator: EstimatorConfig,
}

/// A sensor: id and position; polar sensors also their noise.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SensorConfig {
    id: u32,
    position: [f64; 2],
    sigma_range: Option<Spanned<f64>>,
    sigma_azimuth_deg: Option<Spanned<f64>>,
}

/// One motion model of an IMM: `kind = "cv"` or `"ct"` (with `rate_deg`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ModelConfig {
    kind: ModelKind,
    sigma_a: Spanned<f64>,
    rate_deg: Option<Spanned<f64>>,
}

/// Motion-model kinds.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "kebab-case")]
enum ModelKind {
    /// Constant velocity.
    Cv,
    /// Coordinated turn at a fixed rate.
    Ct,
}

/// Estimator kinds: later issues add theirs (multi-IMM, trackers).
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "kebab-case")]
enum EstimatorKind {
    /// KF on converted plots (polar plots: unbiased conversion; Cartesian: as reported).
    KfConverted,
    /// EKF on polar plots.
    Ekf,
    /// IMM: validated here; runs once `argus-imm` is wired in.
    Imm,
}

/// The `[estimator]` table as written (flat, so that every value keeps its position in
/// the file for error messages); [`load`] turns it into the [`Estimator`] enum.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct EstimatorConfig {
    kind: EstimatorKind,
    sigma_a: Option<Spanned<f64>>,
    models: Option<Vec<ModelConfig>>,
    markov: Option<Spanned<Vec<Vec<f64>>>>,
}

fn line_of(text: &str, offset: usize) -> u64 {
    text.get(..offset)
        .map_or(0, |s| s.matches('\n').count() as u64 + 1)
}

fn non_negative(path: &Path, text: &str, field: &str, v: &Spanned<f64>) -> Result<f64, CliError> {
    let x = *v.get_ref();
    if x.is_finite() && x >= 0.0 {
        Ok(x)
    } else {
        Err(CliError::input(
            path,
            Some(line_of(text, v.span().start)),
            Some(field),
            format!("{x} must be finite and non-negative (a standard deviation)"),
        ))
    }
}

/// Checks the Markov matrix: square, one row per model, entries in [0, 1], rows summing
/// to 1 within 1e-9.
fn check_markov(
    path: &Path,
    text: &str,
    m: &Spanned<Vec<Vec<f64>>>,
    n: usize,
) -> Result<(), CliError> {
    let line = Some(line_of(text, m.span().start));
    let rows = m.get_ref();
    if rows.len() != n || rows.iter().any(|r| r.len() != n) {
        return Err(CliError::input(
            path,
            line,
            Some("markov"),
            format!("must be {n} × {n} (one row and column per model)"),
        ));
    }
    for (i, r) in rows.iter().enumerate() {
        let sum: f64 = r.iter().sum();
        if r.iter().any(|p| !(0.0..=1.0).contains(p)) || (sum - 1.0).abs() > 1e-9 {
            return Err(CliError::input(
                path,
                line,
                Some("markov"),
                format!(
                    "row {} is not stochastic (entries in [0, 1] summing to 1; sum = {sum})",
                    i + 1
                ),
            ));
        }
    }
    Ok(())
}

/// A validated estimator.
enum Estimator {
    KfConverted(CvKf),
    Ekf(CvEkf),
}

/// A validated sensor.
struct Sensor {
    id: u32,
    position: [f64; 2],
    polar: Option<(f64, f64)>,
}

fn load(path: &Path) -> Result<(Vec<Sensor>, Estimator), CliError> {
    let text = std::fs::read_to_string(path).map_err(|e| CliError::io(path, e))?;
    let cfg: Config = toml::from_str(&text).map_err(|e| {
        let line = e.span().map(|s| line_of(&text, s.start));
        CliError::input(path, line, None, e.message().to_owned())
    })?;
    let mut sensors = Vec::new();
    for s in &cfg.sensors {
        if !s.position.iter().all(|v| v.is_finite()) {
            return Err(CliError::input(
                path,
                None,
                Some("position"),
                format!("sensor {}: position must be finite", s.id),
            ));
        }
        let polar = match (&s.sigma_range, &s.sigma_azimuth_deg) {
            (Some(r), Some(a)) => Some((
                non_negative(path, &text, "sigma_range", r)?,
                non_negative(path, &text, "sigma_azimuth_deg", a)?.to_radians(),
            )),
            _ => None,
        };
        if sensors.iter().any(|o: &Sensor| o.id == s.id) {
            return Err(CliError::input(
                path,
                None,
                Some("id"),
                format!("sensor id {} given twice", s.id),
            ));
        }
        sensors.push(Sensor {
            id: s.id,
            position: s.position,
            polar,
        });
    }
    let e = &cfg.estimator;
    let missing = |key: &str| {
        CliError::input(
            path,
            None,
            Some(key),
            format!("required by estimator kind {:?}", e.kind),
        )
    };
    let est = match e.kind {
        EstimatorKind::KfConverted => {
            let sa = e.sigma_a.as_ref().ok_or_else(|| missing("sigma_a"))?;
            Estimator::KfConverted(cv_kf(non_negative(path, &text, "sigma_a", sa)?)?)
        }
        EstimatorKind::Ekf => {
            let sa = e.sigma_a.as_ref().ok_or_else(|| missing("sigma_a"))?;
            Estimator::Ekf(cv_ekf(non_negative(path, &text, "sigma_a", sa)?)?)
        }
        EstimatorKind::Imm => {
            let models = e.models.as_ref().ok_or_else(|| missing("models"))?;
            for m in models {
                non_negative(path, &text, "sigma_a", &m.sigma_a)?;
                match (m.kind, &m.rate_deg) {
                    (ModelKind::Ct, Some(w)) if !w.get_ref().is_finite() => {
                        return Err(CliError::input(
                            path,
                            Some(line_of(&text, w.span().start)),
                            Some("rate_deg"),
                            format!("{} must be finite", w.get_ref()),
                        ));
                    }
                    (ModelKind::Ct, None) => return Err(missing("rate_deg")),
                    _ => {}
                }
            }
            let markov = e.markov.as_ref().ok_or_else(|| missing("markov"))?;
            check_markov(path, &text, markov, models.len())?;
            return Err(CliError::input(
                path,
                None,
                Some("estimator.kind"),
                "'imm' is a valid configuration but cannot run yet: it needs the argus-imm crate wired into `argus track` (a later issue)",
            ));
        }
    };
    Ok((sensors, est))
}

/// Runs `argus track`.
///
/// # Errors
/// [`CliError::Input`] for bad configuration or plots, filter errors, I/O.
pub(crate) fn run(config: &Path, plots_path: &Path, out: &Path) -> Result<usize, CliError> {
    let (sensors, est) = load(config)?;
    let plots = plotfile::read(plots_path)?;
    // Per plot: its Cartesian position and covariance (converted) or the raw polar value.
    let sensor_of = |p: &FilePlot| -> Result<&Sensor, CliError> {
        sensors.iter().find(|s| s.id == p.sensor).ok_or_else(|| {
            CliError::input(
                plots_path,
                Some(p.line),
                Some("sensor"),
                format!("unknown sensor {} (not in {})", p.sensor, config.display()),
            )
        })
    };
    let convert = |p: &FilePlot| -> Result<(Vector<2>, Matrix<2, 2>), CliError> {
        let s = sensor_of(p)?;
        match p.value {
            FileValue::Cartesian { x, y, cov } => Ok((
                Vector::<2>::new(x, y),
                Matrix::<2, 2>::new(cov[0], cov[1], cov[1], cov[2]),
            )),
            FileValue::Polar { range, azimuth } => {
                let (sr, sa) = s.polar.ok_or_else(|| CliError::input(config, None, Some("sigma_range"),
                    format!("sensor {} reports polar plots but has no sigma_range / sigma_azimuth_deg", s.id)))?;
                let (z, r) = unbiased(range, azimuth, sr, sa).map_err(|e| {
                    CliError::input(plots_path, Some(p.line), Some("range"), e.to_string())
                })?;
                Ok((z + Vector::<2>::new(s.position[0], s.position[1]), r))
            }
        }
    };
    let mut rows = String::from("t,track,x,vx,y,vy,var_x,var_vx,var_y,var_vy\n");
    let mut iter = plots.iter();
    let (Some(p1), Some(p2)) = (iter.next(), iter.next()) else {
        return Err(CliError::input(
            plots_path,
            None,
            None,
            "at least two plots are needed to start a track",
        ));
    };
    let (z1, r1) = convert(p1)?;
    let (z2, r2) = convert(p2)?;
    let mut x = two_point_cv2(&z1, &r1, &z2, &r2, p2.time - p1.time).map_err(|e| {
        CliError::input(
            plots_path,
            Some(p2.line),
            Some("t"),
            format!("two-point initialisation: {e}"),
        )
    })?;
    let mut t = p2.time;
    let mut push = |t: f64, g: &Gaussian<4>| {
        let m = g.mean();
        let c = g.cov();
        rows.push_str(&format!(
            "{t},1,{},{},{},{},{},{},{},{}\n",
            m[0],
            m[1],
            m[2],
            m[3],
            c[(0, 0)],
            c[(1, 1)],
            c[(2, 2)],
            c[(3, 3)]
        ));
    };
    push(t, &x);
    let mut n = 1;
    for p in iter {
        let dt = p.time - t;
        let at = |e: argus_filters::FilterError| {
            CliError::input(
                plots_path,
                Some(p.line),
                None,
                format!("filter update failed: {e}"),
            )
        };
        x = match (&est, p.value) {
            (Estimator::Ekf(f), FileValue::Polar { range, azimuth }) => {
                let s = sensor_of(p)?;
                let (sr, sa) = s.polar.ok_or_else(|| {
                    CliError::input(
                        config,
                        None,
                        Some("sigma_range"),
                        format!("sensor {} has no polar noise", s.id),
                    )
                })?;
                step(
                    f,
                    &x,
                    dt,
                    &polar(s.position, sr, sa)?,
                    &Vector::<2>::new(range, azimuth),
                )
                .map_err(at)?
                .0
            }
            (Estimator::Ekf(f), FileValue::Cartesian { .. }) => {
                let (z, r) = convert(p)?;
                step(f, &x, dt, &position(r)?, &z).map_err(at)?.0
            }
            (Estimator::KfConverted(f), _) => {
                let (z, r) = convert(p)?;
                step(f, &x, dt, &position(r)?, &z).map_err(at)?.0
            }
        };
        t = p.time;
        push(t, &x);
        n += 1;
    }
    write_atomic(out, rows.as_bytes())?;
    Ok(n)
}
